"""Double-corrugated tessellation: a sheet of rows x cols repeated units P or Q (Peng 2018, §3.2.2, Fig 3-9;
units in `kinematics.corrugated`).

Lattice (metres, the flat sheet's world frame). The double-corrugated pattern is a quad mesh of parallelograms:
vertex (i, j) is reached from (0, 0) by i steps along u and j along v, the steps alternating

    u: U_e = L2 e(0) (P's AD)  and  U_o = L3 e(alpha + beta - pi) (Q's FA),
    v: V_e = L1 e(alpha) (AB)  and  V_o = Lout e(beta) (the outer creases of the units),

e(t) = (cos t, sin t), Lout = L3 for P and L2 for Q (`corrugated.unit_pattern`). Faces (U_e, V_e) are copies of
P, (U_o, V_e) of Q, the other two kinds their copies turned by the other step; every vertex is flat-foldable,
type I (sectors alpha, beta, gamma, delta counter-clockwise) or type II (alpha, delta, gamma, beta). The sheet
has (2 cols + 1) x (2 rows + 1) faces: the r x c unit faces (P, or Q) at odd face positions, each with its
3 x 3 Kokotsakis mesh, overlapping on the side faces; 1 x 1 is `corrugated.unit_pattern` exactly. The first
unit's vertex A is the origin. Faces are named f<i>_<j> (lower-left vertex (i, j)), creases u<i>_<j> ((i, j) to
(i + 1, j)) and v<i>_<j> ((i, j) to (i, j + 1)).

Modes (Peng 2018, §3.2.1-3.2.2). Each vertex takes the mode, S or C, of the unit vertex it repeats: the unit vertex at
the same lattice parity (P: A (1, 1), B (1, 0), C (0, 0), D (0, 1); Q: A (0, 1), B (0, 0), E (1, 0), F (1, 1), as (i mod
2, j mod 2)). Every face then has one corner of each role, so the loop gain round every face is the unit's K up to
inversion (the magnitudes of a vertex's multipliers pair up: type I |m| = x on its alpha and gamma sectors and 1/x on
beta and delta, type II the reverse) and its sign (-1)^#S or (-1)^#C, +1 on every rigid string: the sheet folds rigidly
iff the unit does (Peng 2018: the pattern is rigid iff every unit is).

Closed form. On a rigid mode string every crease folds as tan(rho/2) = k tan(x/2) with a constant k, chained
vertex by vertex from the input x = the fold of u1_1, the first unit's AD (P, the thesis's theta_1a) or AF (Q,
theta_2f); every vertex's four folds are the unit vertex's of the same role, up to a global sign. Fold
angles follow `sim_origami.creases` (rho > 0 valley seen from +z). Branches are the unit's rigid mode strings
(`corrugated.rigid_modes`), all crossing the flat state and ending where every crease folds flat (x = +-pi).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import AssemblyError, ParameterError
from .base import Branch, Event
from .corrugated import UNITS, VERTEX_CREASES, UnitModel, check_sectors, rigid_modes
from .fixed_modes import FixedModeKinematics
from .vertex4 import flat_foldable_multipliers

INPUT = "u1_1"
ROOT = "f1_1"
# Role of a vertex by lattice parity (i mod 2, j mod 2).
ROLES = {
    "P": {(1, 1): "A", (1, 0): "B", (0, 0): "C", (0, 1): "D"},
    "Q": {(0, 1): "A", (0, 0): "B", (1, 0): "E", (1, 1): "F"},
}
# A chained gain closes when it agrees with the one already there to this (relative): rounding only, ~1e-15.
CHAIN_TOL = 1e-9


def _e(angle: float) -> NDArray[np.float64]:
    return np.array([np.cos(angle), np.sin(angle)])


def _check_size(rows: float, cols: float) -> tuple[int, int]:
    for name, value in (("rows", rows), ("cols", cols)):
        if int(value) != value or value < 1:
            raise ParameterError(f"{name} = {value:g}; a sheet needs a whole number of units, at least 1")
    return int(rows), int(cols)


def sheet_pattern(unit: str, sectors: ArrayLike, lengths: ArrayLike, rows: int, cols: int) -> CreasePattern:
    """
    The sheet (module docstring) as a crease pattern with unassigned creases.

    Parameters
    ----------
    unit : 'P' or 'Q'
    sectors : (4,) float
      Design angles alpha, beta, gamma, delta (rad), `corrugated.check_sectors`.
    lengths : (3,) float
      L1 = |AB|, L2 = |AD|, L3 = |AF| (m), > 0.
    rows, cols : int
      Units along v and along u, >= 1.
    """
    if unit not in UNITS:
        raise ParameterError(f"unknown unit {unit!r}; units are P and Q")
    rows, cols = _check_size(rows, cols)
    alpha, beta = check_sectors(sectors)[:2]
    L1, L2, L3 = (float(v) for v in lengths)
    for name, value in (("L1", L1), ("L2", L2), ("L3", L3)):
        if not value > 0:
            raise ParameterError(f"{name} = {value:g} m; lengths must be positive")
    u_e, u_o = L2 * _e(0.0), L3 * _e(alpha + beta - np.pi)
    v_e, v_o = L1 * _e(alpha), (L3 if unit == "P" else L2) * _e(beta)
    nu, nv = 2 * cols + 1, 2 * rows + 1
    u_steps = [(u_o if f % 2 == 0 else u_e) if unit == "P" else (u_e if f % 2 == 0 else u_o) for f in range(nu)]
    v_steps = [v_o if g % 2 == 0 else v_e for g in range(nv)]
    xu = np.vstack([np.zeros(2), np.cumsum(u_steps, axis=0)])
    xv = np.vstack([np.zeros(2), np.cumsum(v_steps, axis=0)])
    origin = xu[1 if unit == "P" else 2] + xv[1]
    index = {(i, j): i * (nv + 1) + j for i in range(nu + 1) for j in range(nv + 1)}
    vertices = np.array([xu[i] + xv[j] - origin for i in range(nu + 1) for j in range(nv + 1)])
    faces = tuple(
        (index[i, j], index[i + 1, j], index[i + 1, j + 1], index[i, j + 1]) for i in range(nu) for j in range(nv)
    )
    names = tuple(f"f{i}_{j}" for i in range(nu) for j in range(nv))
    creases = [Crease(f"u{i}_{j}", index[i, j], index[i + 1, j]) for i in range(nu) for j in range(1, nv)]
    creases += [Crease(f"v{i}_{j}", index[i, j], index[i, j + 1]) for i in range(1, nu) for j in range(nv)]
    return CreasePattern(vertices, faces, tuple(creases), names)


class CorrugatedSheet(FixedModeKinematics):
    """
    A rows x cols sheet of unit P or Q driven by x = rho of crease u1_1 (rad); branches are the unit's rigid
    mode strings (vertex order of `corrugated.VERTEX_CREASES`: P A, B, C, D; Q F, E, B, A).

    Parameters
    ----------
    unit, sectors, lengths, rows, cols : as `sheet_pattern`.
    """

    input_name = "rho" + INPUT

    def __init__(
        self, unit: str, sectors: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0), rows: int = 2, cols: int = 2
    ):
        self.pattern = sheet_pattern(unit, sectors, lengths, rows, cols)
        self.unit, self.rows, self.cols = unit, int(rows), int(cols)
        self.model = UnitModel(unit, sectors, lengths)
        self.joint_names = tuple(f"rho{c.name}" for c in self.pattern.creases)
        self.input = [c.name for c in self.pattern.creases].index(INPUT)
        self.vertices = self._vertices()
        self.ratios = {modes: self.gains(modes) for modes in rigid_modes(self.model)}

    def _vertices(self) -> dict[int, tuple[str, tuple[int, ...], NDArray[np.float64]]]:
        """Interior vertex -> (role, crease indices in the thesis's order k = 1..4, sectors (4,) rad)."""
        nv = 2 * self.rows + 2
        out = {}
        for v in self.pattern.interior_vertices():
            around = self.pattern.vertex_creases(v)
            d = [direction for _, direction in around]
            sectors = np.array([np.arctan2(np.cross(d[k], d[(k + 1) % 4])[2], d[k] @ d[(k + 1) % 4]) for k in range(4)])
            first = int(np.argmax(sectors))  # crease 1 opens the sector alpha, the largest (check_sectors)
            order = [(first + k) % 4 for k in range(4)]
            role = ROLES[self.unit][(v // nv) % 2, (v % nv) % 2]
            out[v] = (role, tuple(around[k][0] for k in order), sectors[order])
        return out

    def vertex_gains(self, modes: str, vertex: int) -> NDArray[np.float64]:
        """tan-half gains (4,) of an interior vertex's creases in the thesis's order k = 1..4 on `modes`."""
        return self.ratios[modes][list(self.vertices[vertex][1])]

    def gains(self, modes: str) -> NDArray[np.float64]:
        """
        k (n_creases,) with tan(rho/2) = k tan(x/2), chained vertex by vertex from the input; AssemblyError if
        two chains disagree (a mode string that is not rigid).
        """
        mode_of = dict(zip(VERTEX_CREASES[self.unit], modes, strict=True))
        g = np.full(len(self.pattern.creases), np.nan)
        g[self.input] = 1.0
        todo = set(self.vertices)
        while todo:
            ready = [v for v in sorted(todo) if np.isfinite(g[list(self.vertices[v][1])]).any()]
            if not ready:
                raise AssemblyError(f"vertices {sorted(todo)} are not connected to the input crease")
            for v in ready:
                role, creases, sectors = self.vertices[v]
                m = flat_foldable_multipliers(sectors)[mode_of[role]]
                k0 = next(k for k in range(4) if np.isfinite(g[creases[k]]))
                t = g[creases[k0]]
                for step in range(1, 4):
                    t *= m[(k0 + step - 1) % 4]
                    c = creases[(k0 + step) % 4]
                    if np.isfinite(g[c]) and abs(g[c] - t) > CHAIN_TOL * abs(t):
                        name = self.pattern.creases[c].name
                        raise AssemblyError(
                            f"modes {modes!r} do not close: crease {name} chained to gain {t:.6g}, already {g[c]:.6g}"
                        )
                    g[c] = t
                todo.discard(v)
        return g

    def branches(self) -> tuple[Branch, ...]:
        order = ", ".join(VERTEX_CREASES[self.unit])
        text = "every vertex in the mode of its unit vertex ({}) = ({}); tan(rho/2) = k tan(x/2) per crease"
        return tuple(Branch(m, text.format(order, ", ".join(m)), (-np.pi, np.pi)) for m in self.ratios)

    def events(self) -> tuple[Event, ...]:
        names = tuple(self.ratios)
        detail = "fully folded flat: every crease at |rho| = pi, panels stacked"
        return (
            Event("bifurcation", 0.0, names, "flat state: every rigid mode string passes through it"),
            Event("lock", -np.pi, names, detail),
            Event("lock", np.pi, names, detail),
        )

    def gruebler(self) -> int:
        """Kutzbach: creases - 3 per spherical vertex loop."""
        return len(self.joint_names) - 3 * len(self.vertices)

    def loop_system(self) -> LoopSystem:
        """The crease pattern's per-vertex closure."""
        return self.pattern.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return self.input, 1.0
