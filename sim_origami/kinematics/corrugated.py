"""Double-corrugated units P and Q: rigid foldability against the mountain-valley assignment (Peng 2018,
§3.2.1-3.2.2; the §3.2.3 metamaterials are stacks of these units).

Geometry (reconstructed here from eqns 3-16, 3-22 and the text; Fig. 3-1 is lost in our copy). Design angles are
the sectors (alpha, beta, gamma, delta) of a type-I vertex, counter-clockwise; every vertex is
flat-foldable (alpha + gamma = beta + delta = pi) and gamma is the strict minimum (the thesis's case,
which the M/V counts assume). A type-II vertex has the same sectors clockwise: (alpha, delta, gamma, beta).

* P: the parallelogram A = (0, 0), B = L1 e(alpha), C = B + D, D = L2 e(0) (angles alpha, gamma).
* Q: the parallelogram A, B, E = B + F, F = L3 e(alpha + beta) (angles beta, delta).

e(t) = (cos t, sin t). Each unit is a 3 x 3 Kokotsakis mesh: the central face, one side face on each
edge and one corner face at each vertex, all parallelograms; outer creases have length L3 (P) or L2 (Q),
so the side faces on AB and CD of P are copies of Q and those on AB and EF of Q copies of P. Twelve
creases, four interior degree-4 vertices (P: A, C type I and B, D type II; Q: A, E type I and B, F
type II). Crease names: the inner creases by their end points (P: AB, BC, CD, AD; Q: AB, BE, EF, AF),
the outer ones by vertex and the thesis's crease number k (a3, a4, b1, ...). VERTEX_CREASES lists each
vertex's creases in the thesis's k order (counter-clockwise, sector k
between creases k and k + 1, gamma = sector 3 at every vertex).

Signs (`sim_origami.conventions`, `sim_origami.creases`): rho > 0 is a valley seen from +z, so a crease
is V when rho > 0 and M when rho < 0. Peng 2018 reads M/V from the other side (theta > 0 =
mountain): every M/V string in the thesis's convention is ours with M and V swapped.

Kinematics (Peng 2018, §3.2.1-3.2.2, eqns 3-1 to 3-23). Near flat a flat-foldable vertex folds in mode S
(rho3 = -rho1, rho4 = rho2) or C (rho3 = rho1, rho4 = -rho2), each linear in t = tan(rho/2):
t_(k+1) = m_(k,k+1) t_k (`vertex4.flat_foldable_multipliers`, eqn 3-1). A unit with one mode per
vertex closes round its central face iff the loop gain K = prod of the multipliers along the inner
creases is 1 (P: m12(A) m34(B) m12(C) m34(D); Q: m23(F) m23(E) m23(B) m23(A)); otherwise only the flat
and the fully folded states close: the unit is locked. Every crease of a rigid mode combination is then
tan(rho/2) = g tan(x/2) with a constant gain g, for the input x = rho_AD (P, the thesis's theta_1a) or
rho_AF (Q, theta_2f).

M/V assignments (Peng 2018, §3.2.2: P1-P10, Q1-Q6). A vertex's M/V obeys Maekawa (three of one kind) and
Big-Little-Big (the creases round the smallest sector gamma differ), which leaves four per vertex: the
two modes times a global flip. The unit's assignments are the sign vectors of its twelve creases that
are valid at all four vertices, enumerated here by brute force over all 2^12 (no multiplier used); a
class is an orbit under the global M/V flip and the unit's 180 deg rotation. Each class gets the
analytic verdict (K = 1) and an independent numeric one from the crease pattern's per-vertex closure:
a least-squares solve over fold angles held to the class's signs, as M/V joint ranges would hold them
(rho = s pi sigmoid(u)), at a small input either closes (then continuation follows a 1-DOF path that
keeps the signs: rigidly foldable) or stalls at a positive residual (locked).
"""

import itertools
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from .base import Branch, Event
from .fixed_modes import FixedModeKinematics
from .numeric_pattern import foldable_with_signs
from .vertex4 import ANGLE_TOL, developable_sectors, flat_foldable_multipliers

UNITS = ("P", "Q")
# Central face corners, counter-clockwise; the outer crease direction on each central edge (from corner i
# to corner i + 1) as an angle in terms of (alpha, beta); the outer creases at corner i along the
# previous and the next edge's direction.
CENTRAL = {"P": ("A", "D", "C", "B"), "Q": ("A", "B", "E", "F")}
SIDE_DIRECTION = {
    "P": (lambda a, b: np.pi + b, lambda a, b: np.pi + a + b, lambda a, b: b, lambda a, b: a + b),
    "Q": (lambda a, b: 0.0, lambda a, b: b, lambda a, b: np.pi, lambda a, b: np.pi + b),
}
OUTER = {
    "P": (("a3", "a4"), ("d1", "d2"), ("c3", "c4"), ("b1", "b2")),
    "Q": (("a4", "a1"), ("b4", "b1"), ("e4", "e1"), ("f4", "f1")),
}
INNER = {"P": ("AD", "CD", "BC", "AB"), "Q": ("AB", "BE", "EF", "AF")}  # central edge i: corner i -> i + 1
# Each vertex's creases in the thesis's order k = 1..4 (shared creases 3-16, 3-22), in the order (A, B, C, D) /
# (F, E, B, A) in which mode combinations are named.
VERTEX_CREASES = {
    "P": {
        "A": ("AD", "AB", "a3", "a4"),
        "B": ("b1", "b2", "AB", "BC"),
        "C": ("BC", "CD", "c3", "c4"),
        "D": ("d1", "d2", "CD", "AD"),
    },
    "Q": {
        "F": ("f1", "AF", "EF", "f4"),
        "E": ("e1", "EF", "BE", "e4"),
        "B": ("b1", "BE", "AB", "b4"),
        "A": ("a1", "AB", "AF", "a4"),
    },
}
INPUT = {"P": "AD", "Q": "AF"}  # the thesis's theta_1a and theta_2f
MODES = ("S", "C")
# Loop gains within this of 1 count as closed (the multipliers carry rounding only, about 1e-15).
GAIN_TOL = 1e-9


def _e(angle: float) -> NDArray[np.float64]:
    return np.array([np.cos(angle), np.sin(angle)])


def check_sectors(sectors: ArrayLike) -> NDArray[np.float64]:
    """
    The design angles (alpha, beta, gamma, delta) in radians, checked: each in (0, pi), sum 2 pi
    (developable), alpha + gamma = pi (flat-foldable, Kawasaki) and gamma the strict minimum.
    """
    s = developable_sectors(sectors, ("alpha", "beta", "gamma", "delta"))
    if abs(s[0] + s[2] - np.pi) > ANGLE_TOL:
        raise ParameterError(
            f"alpha + gamma = {np.rad2deg(s[0] + s[2]):.12g} deg; a flat-foldable vertex (Kawasaki) needs 180"
        )
    if not s[2] < min(s[0], s[1], s[3]):
        raise ParameterError(
            f"gamma = {np.rad2deg(s[2]):.6g} deg is not the smallest design angle "
            f"(alpha, beta, delta = {', '.join(f'{np.rad2deg(v):.6g}' for v in s[[0, 1, 3]])} deg); "
            "Peng 2018's units need gamma < alpha, beta, delta"
        )
    return s


def unit_pattern(
    unit: str,
    sectors: ArrayLike,
    lengths: ArrayLike = (1.0, 1.0, 1.0),
    assignment: dict[str, str] | None = None,
) -> CreasePattern:
    """
    The 3 x 3 unit (module docstring) as a crease pattern.

    Parameters
    ----------
    unit : 'P' or 'Q'
    sectors : (4,) float
      Design angles alpha, beta, gamma, delta (rad).
    lengths : (3,) float
      L1 = |AB|, L2 = |AD|, L3 = |AF| (m).
    assignment : {crease name: 'M' | 'V' | 'U'}, optional
      Recorded on the creases (the closure does not use it); missing creases are 'U'.
    """
    if unit not in UNITS:
        raise ParameterError(f"unknown unit {unit!r}; units are P and Q")
    alpha, beta = check_sectors(sectors)[:2]
    L1, L2, L3 = (float(v) for v in lengths)
    for name, value in (("L1", L1), ("L2", L2), ("L3", L3)):
        if not value > 0:
            raise ParameterError(f"{name} = {value:g} m; lengths must be positive")
    B = L1 * _e(alpha)
    if unit == "P":
        corners = {"A": np.zeros(2), "B": B, "C": B + L2 * _e(0.0), "D": L2 * _e(0.0)}
        outer = L3
    else:
        F = L3 * _e(alpha + beta)
        corners = {"A": np.zeros(2), "B": B, "E": B + F, "F": F}
        outer = L2
    order = CENTRAL[unit]
    w = [outer * _e(f(alpha, beta)) for f in SIDE_DIRECTION[unit]]
    points = [corners[c] for c in order]
    index = {c: i for i, c in enumerate(order)}
    for i, c in enumerate(order):  # outer ends: along the previous edge's side direction, then the next's
        points += [corners[c] + w[i - 1], corners[c] + w[i]]
    for i, c in enumerate(order):  # far corners of the corner faces
        points.append(corners[c] + w[i - 1] + w[i])
    prev_end = {c: 4 + 2 * i for i, c in enumerate(order)}
    next_end = {c: 5 + 2 * i for i, c in enumerate(order)}
    faces, names = [tuple(range(4))], [unit]
    for i, c in enumerate(order):
        d = order[(i + 1) % 4]
        faces.append((index[c], next_end[c], prev_end[d], index[d]))
        names.append(f"side_{INNER[unit][i]}")
    for i, c in enumerate(order):
        faces.append((index[c], prev_end[c], 12 + i, next_end[c]))
        names.append(f"corner_{c}")
    assignment = assignment or {}
    creases = []
    for i, c in enumerate(order):
        creases.append((INNER[unit][i], index[c], index[order[(i + 1) % 4]]))
    for i, c in enumerate(order):
        creases += [(OUTER[unit][i][0], index[c], prev_end[c]), (OUTER[unit][i][1], index[c], next_end[c])]
    unknown = set(assignment) - {name for name, *_ in creases}
    if unknown:
        raise ParameterError(f"assignment names unknown creases {sorted(unknown)}")
    return CreasePattern(
        np.array(points),
        tuple(faces),
        tuple(Crease(name, a, b, assignment.get(name, "U")) for name, a, b in creases),
        tuple(names),
    )


@dataclass(frozen=True)
class ClassVerdict:
    """
    One M/V class: its mode combinations (vertex order of VERTEX_CREASES), a representative assignment
    (input crease V), its size (assignments in the orbit), the loop gain K, and both verdicts.
    `residual` is the numeric solve's closure residual (rad): <= FOLDABLE_TOL when it closed, else where
    it stalled.
    """

    modes: tuple[str, ...]
    assignment: dict[str, str]
    size: int
    gain: float
    analytic: bool
    numeric: bool
    residual: float

    @property
    def label(self) -> str:
        return "|".join(self.modes)


class UnitModel:
    """Geometry, vertex multipliers and assignments of one unit at one set of design angles."""

    def __init__(self, unit: str, sectors: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0)):
        self.unit = unit
        self.pattern = unit_pattern(unit, sectors, lengths)
        self.sectors = check_sectors(sectors)
        self.crease_names = tuple(c.name for c in self.pattern.creases)
        self.index = {name: k for k, name in enumerate(self.crease_names)}
        self.vertices = tuple(VERTEX_CREASES[unit])
        self.input = self.index[INPUT[unit]]

    def _direction(self, vertex: str, crease: str) -> NDArray[np.float64]:
        c = self.pattern.creases[self.index[crease]]
        p = self.pattern.vertices
        at = self.vertex_point(vertex)
        far = p[c.end] if np.allclose(p[c.start], at) else p[c.start]
        return far - at

    def vertex_point(self, vertex: str) -> NDArray[np.float64]:
        """Position (2,) m of a central vertex (the point shared by its four creases)."""
        names = VERTEX_CREASES[self.unit][vertex]
        ends = [self.pattern.creases[self.index[n]] for n in names]
        common = set.intersection(*({c.start, c.end} for c in ends))
        return self.pattern.vertices[common.pop()]

    def vertex_sectors(self, vertex: str) -> NDArray[np.float64]:
        """Sectors (4,) rad between creases k and k + 1 of a vertex, counter-clockwise (sum 2 pi)."""
        d = [self._direction(vertex, n) for n in VERTEX_CREASES[self.unit][vertex]]
        angles = np.array([np.arctan2(v[1], v[0]) for v in d])
        return np.mod(np.roll(angles, -1) - angles, 2 * np.pi)

    @cached_property
    def multipliers(self) -> dict[str, dict[str, NDArray[np.float64]]]:
        """{vertex: {'S': (m12, m23, m34, m41), 'C': ...}} from each vertex's own sectors (Peng 2018, eqn 3-1)."""
        return {v: flat_foldable_multipliers(self.vertex_sectors(v)) for v in self.vertices}

    def loop_gain(self, modes: str) -> float:
        """
        K: tan(rho/2) of the input carried round the central face through each vertex's multiplier from
        its first to its second inner crease (Peng 2018, §3.2.2), over tan(rho/2) of the input.
        """
        inner = set(INNER[self.unit])
        crease, gain = INPUT[self.unit], 1.0
        for _ in range(4):
            for vertex, mode in zip(self.vertices, modes, strict=True):
                names = VERTEX_CREASES[self.unit][vertex]
                k = names.index(crease) if crease in names else -1
                if k >= 0 and names[(k + 1) % 4] in inner:
                    gain *= self.multipliers[vertex][mode][k]
                    crease = names[(k + 1) % 4]
                    break
        return float(gain)

    def gains(self, modes: str) -> NDArray[np.float64]:
        """
        g (12,) with tan(rho/2) = g tan(x/2) for every crease on a mode combination, propagated from the
        input vertex by vertex. Only meaningful when loop_gain(modes) is 1.
        """
        g = np.full(len(self.crease_names), np.nan)
        g[self.input] = 1.0
        for _ in range(4):
            for vertex, mode in zip(self.vertices, modes, strict=True):
                names = VERTEX_CREASES[self.unit][vertex]
                known = [k for k, n in enumerate(names) if np.isfinite(g[self.index[n]])]
                if not known:
                    continue
                m = self.multipliers[vertex][mode]
                k0 = known[0]
                t = g[self.index[names[k0]]]
                for step in range(1, 4):
                    t *= m[(k0 + step - 1) % 4]
                    k = self.index[names[(k0 + step) % 4]]
                    if not np.isfinite(g[k]):
                        g[k] = t
        return g

    def vertex_modes(self, signs: ArrayLike) -> str:
        """Mode letters (vertex order) of a sign vector (12,): S if s3 = -s1, s4 = s2; C if s3 = s1, s4 = -s2."""
        out = []
        for vertex in self.vertices:
            s = [signs[self.index[n]] for n in VERTEX_CREASES[self.unit][vertex]]
            out.append("S" if (s[2] == -s[0] and s[3] == s[1]) else "C" if (s[2] == s[0] and s[3] == -s[1]) else "?")
        return "".join(out)

    def _vertex_valid(self, signs: NDArray[np.int8]) -> NDArray[np.bool_]:
        """Maekawa and Big-Little-Big at every vertex, for sign vectors (n, 12)."""
        ok = np.ones(len(signs), dtype=bool)
        for vertex in self.vertices:
            cols = [self.index[n] for n in VERTEX_CREASES[self.unit][vertex]]
            s = signs[:, cols]
            small = int(np.argmin(self.vertex_sectors(vertex)))
            ok &= np.abs(s.sum(axis=1)) == 2
            ok &= s[:, small] != s[:, (small + 1) % 4]
        return ok

    @cached_property
    def rotation(self) -> NDArray[np.int64]:
        """Crease permutation (12,) of the 180 deg rotation about the central face's centre."""
        p, cs = self.pattern.vertices, self.pattern.creases
        centre = p[:4].mean(axis=0)
        mids = np.array([(p[c.start] + p[c.end]) / 2 for c in cs])
        turned = 2 * centre - mids
        return np.array([int(np.argmin(np.linalg.norm(mids - t, axis=1))) for t in turned])

    def assignments(self) -> NDArray[np.int8]:
        """Every valid M/V assignment as signs (n, 12), +1 = V (rho > 0), by brute force over 2^12."""
        signs = np.array(list(itertools.product((1, -1), repeat=len(self.crease_names))), dtype=np.int8)
        return signs[self._vertex_valid(signs)]

    def classes(self) -> list[NDArray[np.int8]]:
        """Assignments grouped into orbits of the global flip and the half turn; each (k, 12)."""
        remaining = {tuple(s) for s in self.assignments().tolist()}
        out = []
        while remaining:
            s = np.array(max(remaining))
            orbit = {tuple(s), tuple(-s), tuple(s[self.rotation]), tuple(-s[self.rotation])}  # all valid
            remaining -= orbit
            out.append(np.array(sorted(orbit, reverse=True), dtype=np.int8))
        return out

    def verdicts(self) -> tuple[ClassVerdict, ...]:
        """Every class with its analytic (K = 1) and numeric (closure) verdicts, sorted rigid first."""
        loops = self.pattern.loop_system()
        rows = []
        for orbit in self.classes():
            rep = next(s for s in orbit if s[self.input] > 0)
            modes = tuple(sorted({self.vertex_modes(s) for s in orbit}))
            gain = self.loop_gain(modes[0])
            numeric, residual = foldable_with_signs(loops, rep, self.input)
            assignment = {n: "V" if s > 0 else "M" for n, s in zip(self.crease_names, rep, strict=True)}
            rows.append(ClassVerdict(modes, assignment, len(orbit), gain, abs(gain - 1) <= GAIN_TOL, numeric, residual))
        return tuple(sorted(rows, key=lambda r: (not r.analytic, r.modes)))


def verdict_table(unit: str, sectors: ArrayLike) -> tuple[ClassVerdict, ...]:
    """Every M/V class of unit 'P' or 'Q' with its analytic and numeric verdicts (UnitModel.verdicts)."""
    return UnitModel(unit, sectors).verdicts()


def format_table(rows: tuple[ClassVerdict, ...], names: tuple[str, ...]) -> str:
    """The verdict table as text: modes, size, K, analytic and numeric verdicts, residual, M/V in `names` order."""
    head = f"{'modes':<10} {'n':>2} {'K':>10} {'analytic':<9} {'numeric':<9} {'residual':>9}  M/V ({' '.join(names)})"
    lines = [head]
    for r in rows:
        mv = "".join(r.assignment[n] for n in names)
        verdict = ("rigid" if r.analytic else "locked", "rigid" if r.numeric else "locked")
        lines.append(
            f"{r.label:<10} {r.size:>2} {r.gain:>10.6f} {verdict[0]:<9} {verdict[1]:<9} {r.residual:>9.2e}  {mv}"
        )
    return "\n".join(lines)


def rigid_modes(model: UnitModel) -> tuple[str, ...]:
    """Mode combinations with loop gain 1 (every one that folds from flat, both directions)."""
    combos = ("".join(c) for c in itertools.product(MODES, repeat=4))
    return tuple(sorted(c for c in combos if abs(model.loop_gain(c) - 1) <= GAIN_TOL))


def mode_couplings(unit: str, modes: str) -> tuple[tuple[str, str, float], ...]:
    """
    Linear couplings (crease, other, scale), rho_crease = scale rho_other, that hold a vertex in its mode
    exactly: creases k and k + 2 with k the vertex's first inner crease; S: rho3 = -rho1 (rho4 = rho2),
    C: rho3 = rho1 (rho4 = -rho2). Under them the unit moves only on that mode combination (none if locked).
    Each vertex uses a different outer crease, one per corner face, so all fit in a spanning tree.
    """
    inner = set(INNER[unit])
    out = []
    for vertex, mode in zip(VERTEX_CREASES[unit], modes, strict=True):
        names = VERTEX_CREASES[unit][vertex]
        k = next(k for k in range(4) if names[k] in inner and names[(k + 1) % 4] in inner)
        odd = k % 2 == 0  # pair (1, 3) in the thesis's 1-based numbering
        scale = (-1.0 if odd else 1.0) if mode == "S" else (1.0 if odd else -1.0)
        out.append((names[(k + 2) % 4], names[k], scale))
    return tuple(out)


class CorrugatedUnit(FixedModeKinematics):
    """
    A double-corrugated unit driven by x = rho_AD (P) or rho_AF (Q), rad, without M/V limits.

    Branches: every rigid mode combination (six in P and in Q), named by its vertex modes in the order
    of VERTEX_CREASES (P: A, B, C, D; Q: F, E, B, A), e.g. 'SCSC'. Each passes through the flat state
    (x = 0, where all meet: a bifurcation) and is one M/V assignment for x > 0 and its flip for x < 0; it
    ends at x = +-pi, where every crease folds flat at once (|rho| = pi: panels stacked, a lock).

    Parameters
    ----------
    unit : 'P' or 'Q'
    sectors : (4,) float
      Design angles alpha, beta, gamma, delta (rad), `check_sectors`.
    lengths : (3,) float
      L1, L2, L3 (m).
    """

    def __init__(self, unit: str, sectors: ArrayLike, lengths: ArrayLike = (1.0, 1.0, 1.0)):
        self.model = UnitModel(unit, sectors, lengths)
        self.unit = unit
        self.pattern = self.model.pattern
        self.input_name = f"rho{INPUT[unit]}"
        self.joint_names = tuple(f"rho{n}" for n in self.model.crease_names)
        self.ratios = {m: self.model.gains(m) for m in rigid_modes(self.model)}

    def branches(self) -> tuple[Branch, ...]:
        order = ", ".join(self.model.vertices)
        return tuple(
            Branch(m, f"vertex modes ({order}) = ({', '.join(m)}); tan(rho/2) = g tan(x/2) per crease", (-np.pi, np.pi))
            for m in self.ratios
        )

    def events(self) -> tuple[Event, ...]:
        names = tuple(self.ratios)
        detail = "fully folded flat: every crease at |rho| = pi, panels stacked"
        return (
            Event("bifurcation", 0.0, names, "flat state: every rigid mode combination passes through it"),
            Event("lock", -np.pi, names, detail),
            Event("lock", np.pi, names, detail),
        )

    def gruebler(self) -> int:
        """Kutzbach: 12 creases - 3 per spherical vertex loop (4)."""
        return len(self.joint_names) - 3 * len(self.model.vertices)

    def loop_system(self) -> LoopSystem:
        """The crease pattern's per-vertex closure."""
        return self.pattern.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return self.model.input, 1.0
