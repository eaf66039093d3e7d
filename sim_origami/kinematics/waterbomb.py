"""Symmetric waterbomb unit cell, zero thickness and thick panels (Feng 2018, ch. 5: §5.3, §5.4).

Pattern (reconstructed here; Fig. 5-1 is lost in our copy). One base is centred
on vertex A = (0, 0) with half-width t: top midpoint C = (0, h_C), h_C = t sin(beta) / (sin(alpha)
sin(alpha + beta)), top corners (+-t, t cot(alpha)), bottom midpoint (0, -h_C), bottom corners
(+-t, -t cot(alpha)). Vertex B is the top-right corner (t, t cot(alpha)). The unit cell is the six faces
round A and the six round B (two shared): ten triangles, eleven creases, two six-crease vertices.

Creases (the thesis's numbering; A's runs clockwise, B's counter-clockwise in the flat sheet):
A1 = A->C (M), A2 = A->B (V), A3 = A->bottom-right corner (V), A4 = A->bottom midpoint (M), A5, A6 the
mirrors of A3, A2 (V); B1 = B up to the next row's A (M), B2 = B->C (M), B3 = A2, B4 = B down the side
edge (M), B5 = B->the right neighbour's A (V), B6 = the mirror of B2 (M). Sectors: at A alpha, pi - 2 alpha,
alpha, alpha, pi - 2 alpha, alpha; at B pi - alpha - beta, beta, alpha, alpha, beta, pi - alpha - beta.

Angles are fold angles rho (`sim_origami.creases`: 0 flat, > 0 valley). The thesis's dihedral angles are
phi = pi - |rho| on the assigned side: rho = +(pi - phi) on a valley, -(pi - phi) on a mountain, so
tan(phi/2) = s cot(rho/2) with s = +1 (V) or -1 (M). The input is x = rho_A4 (= rho_A1 = rho_B1), in
[-pi, pi]: for x < 0 every crease folds as assigned (mountains rho < 0, valleys rho > 0); x > 0 is the
cell popped the other way, every fold reversed (all formulas are odd in x, thick cell included).

Periodicity. B1 is the next row's crease A4 and B5 the right neighbour's crease A6; in the symmetric
(periodic) folding of eqn 5-3 every base folds alike, so the cell carries the couplings B1 = A4 and
B5 = A6. The zero-thickness cell (two spherical 6R, 3 DOF each) also needs the thesis's symmetry: A line- and
plane-symmetric (A3 = A5 = A6 = A2, eqn 5-4), B plane-symmetric (B6 = B2, eqn 5-5a). The thick cell needs
none of these: each vertex is a plane-symmetric Bricard linkage (eqns 5-11, 5-12), 1 DOF on its own.

Branches, with u = tan(rho_A2 / 2) = -tan(x/2) / cos(alpha) (eqn 5-4, the A vertex, both paths):

* ``line-symmetric`` (path I, eqns 5-6 / 5-8): B4 = B1, B6 = B2 with
  tan(rho_B2 / 2) = -cos(alpha) u / cos(alpha + beta). B is line-symmetric like A.
* ``plane-symmetric`` (path II, eqns 5-7 / 5-9, 5-9c CORRECTED here: the printed 5-9c carries an extra
  cos(alpha) on the S7 term, which misses closure by about pi rad; without it 1.3e-15): B only plane-symmetric,
  tan(rho_B2 / 2) = -2 sin(alpha) u / (sin(alpha + beta) + sin(beta - alpha) u^2) and
  tan(rho_B4 / 2) = -(S7 u + 4 K u^3 - 2 cos(alpha) sin^2(beta - alpha) u^5) /
                     (2 sin^2(alpha + beta) - 4 q u^2 - 2 sin(beta - alpha) (2 sin(alpha + beta) +
                      sin(beta - alpha)) u^4),
  K = sin(alpha) sin(2 beta) + cos(alpha) sin(alpha + beta) sin(beta - alpha), S7 = sin(alpha + beta)
  (7 sin(beta) - sin(2 alpha + beta)), q = cos^2(alpha + beta) - cos(2 beta) (5-9c, so corrected, in u = 1/T).
  Crease B4 folds past flat onto its neighbour (phi_B4 < 0, blocked) where that denominator vanishes.

The symmetric zero-thickness cell has two more branches, not in the thesis (found by multistart solves of
the cell's loops, closed to 1e-15) (derived here): creases A1 and A4 are collinear, and so are B1 and B4, so

* ``A-straight-B-degree4``: A folds only about its straight line A1-A4 (A2 = A3 = A5 = A6 = 0) and B, with
  B3 = B5 = 0, is a flat-foldable degree-4 vertex: rho_B4 = -x, tan(rho_B2 / 2) = tan(x/2) / cos(alpha + beta);
* ``two-straight-lines``: the cell folds about the two parallel lines A1-A4 and B1-B4 only.

All four cross the flat state (x = 0: a bifurcation) and end where crease A1 folds flat (x = +-pi). The
thick cell (hinges on panel surfaces, heights below) follows path I only: B's second Bricard set (eqn 5-20)
is compatible with A only for mu = cos(alpha + beta) sin(alpha) / sin(beta) (where it equals path I) or for
alpha = beta with mu = 1 (where it equals path II, eqn 5-22b), so those thick cells list path II too.

Thick hinges (link lengths of eqns 5-11, 5-12; heights reconstructed here, checked by the closure): with a' the
thickness unit and s = (2 + mu) a', A's valleys A2, A3, A5, A6 lie at height s and its mountains A1, A4 at 0; B2 and B6
at (1 + mu) a', B4 at 2 a' (the heights reconstructed here for the thick waterbomb vertex W of Peng 2018, §4.4.2, (0,
1+mu, 2+mu, 2, 2+mu, 1+mu) a'). Hinge distances are then a12 = a61 = a34 = a45 = (2 + mu) a', a23 = a56 = 0 at A and (1
+ mu) a', a', mu a', mu a', a', (1 + mu) a' at B, as eqns 5-11 and 5-12 state.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Coupling, LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from ..geometry import wrap
from .base import Branch, Event, JointSpaceKinematics, as_inputs

LINE = "line-symmetric"
PLANE = "plane-symmetric"
DEGREE4 = "A-straight-B-degree4"
STRAIGHT = "two-straight-lines"
CREASES = ("A1", "A2", "A3", "A4", "A5", "A6", "B1", "B2", "B4", "B5", "B6")
FACES = ("A12", "A16", "A65", "A54", "A43", "A32", "B12", "B45", "B56", "B61")
# Couplings (crease, other): periodic copies, and the symmetry only the zero-thickness cell needs.
PERIODIC = (("B1", "A4"), ("B5", "A6"))
SYMMETRY = (("A3", "A2"), ("A5", "A2"), ("A6", "A2"), ("B6", "B2"))
# alpha = beta and mu = 1 are tested to this (rad, and relative).
EQUAL_TOL = 1e-12


def unit_cell(alpha: float, beta: float, t: float, mu: float | None = None, a: float = 0.0) -> CreasePattern:
    """
    The two-vertex cell (module docstring) with half-width t (m); thick hinge heights when mu is given,
    in units of a (m).
    """
    cot = 1.0 / np.tan(alpha)
    hc = t * np.sin(beta) / (np.sin(alpha) * np.sin(alpha + beta))
    v = np.array([
        (0.0, 0.0), (0.0, hc), (t, t * cot), (t, -t * cot), (0.0, -hc), (-t, -t * cot), (-t, t * cot),
        (t, t * cot + hc), (2 * t, 0.0), (2 * t, hc),
    ])
    A, C, B, Cr, Bb, Cl, Bl, Aup, Ar, Crt = range(10)
    faces = ((A, B, C), (A, C, Bl), (A, Bl, Cl), (A, Cl, Bb), (A, Bb, Cr), (A, Cr, B),
             (B, Aup, C), (B, Cr, Ar), (B, Ar, Crt), (B, Crt, Aup))
    s, m = ((2 + mu) * a, (1 + mu) * a) if mu is not None else (0.0, 0.0)
    low = 2 * a if mu is not None else 0.0
    creases = (
        Crease("A1", A, C, "M", 0.0), Crease("A2", A, B, "V", s), Crease("A3", A, Cr, "V", s),
        Crease("A4", A, Bb, "M", 0.0), Crease("A5", A, Cl, "V", s), Crease("A6", A, Bl, "V", s),
        Crease("B1", B, Aup, "M", 0.0), Crease("B2", B, C, "M", m), Crease("B4", B, Cr, "M", low),
        Crease("B5", B, Ar, "V", s), Crease("B6", B, Crt, "M", m),
    )
    lattice = (v[Ar] - v[A], v[Aup] - v[A])  # the next base to the right, the next row's base
    return CreasePattern(v, faces, creases, FACES, periodic_heights(v, faces, creases, lattice))


def periodic_heights(
    vertices: NDArray[np.float64],
    faces: tuple[tuple[int, ...], ...],
    creases: tuple[Crease, ...],
    lattice: tuple[NDArray[np.float64], NDArray[np.float64]],
) -> tuple[tuple[int, int, float], ...]:
    """
    (start, end, height) of every border edge of a periodic cell: the height of the crease it is a copy of,
    translated by a lattice vector i L1 + j L2 (|i|, |j| <= 2); ParameterError unless that height is unique.
    """
    inside = {frozenset((c.start, c.end)) for c in creases}
    shifts = [i * lattice[0] + j * lattice[1] for i in range(-2, 3) for j in range(-2, 3)]
    out = []
    for face in faces:
        for a, b in zip(face, face[1:] + face[:1], strict=True):
            if frozenset((a, b)) in inside:
                continue
            edge = vertices[[a, b]]
            copies = [c.height for c in creases for d in shifts for ends in ([c.start, c.end], [c.end, c.start])
                      if np.allclose(vertices[ends] + d, edge, atol=1e-9)]
            if len(set(copies)) != 1:
                raise ParameterError(f"border edge {a}-{b} of the periodic cell copies {len(copies)} creases "
                                     f"(heights {sorted(set(copies))}); it must copy exactly one height")
            out.append((a, b, copies[0]))
    return tuple(out)


def a_fold(alpha: float, x: NDArray) -> NDArray:
    """rho_A2 (= A3, A5, A6, B3, B5) in [-pi, pi] at inputs x = rho_A4 in [-pi, pi] (eqn 5-4), odd in x."""
    return 2.0 * np.arctan2(-np.sin(x / 2), np.cos(alpha) * np.cos(x / 2))


def path_folds(alpha: float, beta: float, branch: str, x: ArrayLike) -> NDArray[np.float64]:
    """Fold angles (n, 11) in CREASES order on a branch at inputs x (n,), wrapped to (-pi, pi]."""
    x = as_inputs(x)
    r3 = a_fold(alpha, x)
    s, c = np.sin(r3 / 2), np.cos(r3 / 2)  # u = s / c
    sab, sba = np.sin(alpha + beta), np.sin(beta - alpha)
    zero = np.zeros_like(x)
    if branch == DEGREE4:
        b2 = 2.0 * np.arctan2(np.sin(x / 2), np.cos(alpha + beta) * np.cos(x / 2))
        out = np.stack([x, zero, zero, x, zero, zero, x, b2, -x, zero, b2], -1)
        return wrap(out)
    if branch == STRAIGHT:
        return np.stack([x, zero, zero, x, zero, zero, x, zero, x, zero, zero], -1)
    if branch == LINE:
        b2 = -2.0 * np.arctan2(np.cos(alpha) * s, np.cos(alpha + beta) * c)
        b4 = x
    else:
        b2 = -2.0 * np.arctan2(2 * np.sin(alpha) * s * c, sab * c**2 + sba * s**2)
        K = np.sin(alpha) * np.sin(2 * beta) + np.cos(alpha) * sab * sba
        S7 = sab * (7 * np.sin(beta) - np.sin(2 * alpha + beta))
        q = np.cos(alpha + beta) ** 2 - np.cos(2 * beta)
        num = S7 * s * c**4 + 4 * K * s**3 * c**2 - 2 * np.cos(alpha) * sba**2 * s**5
        den = c * (2 * sab**2 * c**4 - 4 * q * s**2 * c**2 - 2 * sba * (2 * sab + sba) * s**4)
        b4 = -2.0 * np.arctan2(num, den)
    out = np.stack([x, r3, r3, x, r3, r3, x, b2, b4, r3, b2], -1)
    return wrap(out)


def plane_blockage(alpha: float, beta: float) -> float | None:
    """
    Input x in (-pi, 0) where path II folds crease B4 flat onto its neighbour (phi_B4 = 0), or None
    (-x on the popped-up side).

    The rho_B4 denominator 2 sin^2(a+b) - 4 q w - 2 sin(b-a)(2 sin(a+b) + sin(b-a)) w^2 in w = u^2 has a
    positive root ((T*)^2 = 1/w: a closed form, derived here, of the second half of eqn 5-10, garbled in print).
    """
    sab, sba = np.sin(alpha + beta), np.sin(beta - alpha)
    q = np.cos(alpha + beta) ** 2 - np.cos(2 * beta)
    roots = np.roots([-2 * sba * (2 * sab + sba), -4 * q, 2 * sab**2])
    w = [r.real for r in roots if abs(r.imag) < 1e-12 and r.real > 0]
    if not w:
        return None
    return float(-2.0 * np.arctan(np.sqrt(min(w)) * np.cos(alpha)))


class Waterbomb(JointSpaceKinematics):
    """
    The waterbomb cell driven by x = rho_A4 in [-pi, pi] (module docstring for frames and signs).

    Parameters
    ----------
    alpha, beta : float
      Design angles (rad), each in (0, pi/2) with alpha + beta < pi/2 (path I then folds smoothly from
      flat; at alpha + beta = pi/2 it is the thesis's two-stage motion, beyond it crease B2 starts blocked).
    t : float
      Base half-width (m).
    mu, a : float, optional
      Thick panels (eqns 5-11, 5-12): thickness ratio mu > 0 and unit a > 0 (m). None: zero thickness.
    """

    input_name = "rhoA4"
    joint_names = tuple(f"rho{c}" for c in CREASES)

    def __init__(self, alpha: float, beta: float, t: float, mu: float | None = None, a: float = 0.0):
        for name, value in (("alpha", alpha), ("beta", beta)):
            if not 0.0 < value < np.pi / 2:
                raise ParameterError(f"{name} = {np.rad2deg(value):.6g} deg; it must lie in (0, 90) deg")
        if not alpha + beta < np.pi / 2:
            raise ParameterError(
                f"alpha + beta = {np.rad2deg(alpha + beta):.6g} deg; this model needs alpha + beta < 90 deg (at 90 "
                "path I is Feng 2018's two-stage motion, above it crease B2 folds past flat: blocked, ch. 5 (d), (f))"
            )
        if not t > 0:
            raise ParameterError(f"half-width t = {t:g} m; it must be positive")
        if mu is not None and not (mu > 0 and a > 0):
            raise ParameterError(f"thick panels need mu > 0 and a > 0; got mu = {mu:g}, a = {a:g} m")
        self.alpha, self.beta, self.t, self.mu, self.a = float(alpha), float(beta), float(t), mu, float(a)
        self.pattern = unit_cell(self.alpha, self.beta, self.t, mu, self.a)
        self.thick = mu is not None
        self.couplings = PERIODIC if self.thick else PERIODIC + SYMMETRY

    def branches(self) -> tuple[Branch, ...]:
        line = Branch(LINE, "path I (eqn 5-6): B folds line-symmetric like A, rho_B4 = rho_B1", (-np.pi, np.pi))
        plane = Branch(PLANE, "path II (eqn 5-7): B only plane-symmetric, rho_B4 != rho_B1", (-np.pi, np.pi))
        if not self.thick:
            degree4 = Branch(DEGREE4, "A folds about its line A1-A4 only; B a degree-4 vertex, rho_B4 = -rho_B1",
                             (-np.pi, np.pi))
            straight = Branch(STRAIGHT, "folds about the straight lines A1-A4 and B1-B4 only", (-np.pi, np.pi))
            return (line, plane, degree4, straight)
        if abs(self.alpha - self.beta) < EQUAL_TOL and abs(self.mu - 1.0) < EQUAL_TOL:
            return (line, plane)  # eqn 5-22b
        return (line,)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        values = path_folds(self.alpha, self.beta, branch, x)
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        names = tuple(b.name for b in self.branches())
        out = [Event("lock", end, names, "crease A1 (and A4, B1) folded flat: phi1 = 0") for end in (-np.pi, np.pi)]
        if len(names) > 1:
            detail = "flat state: every branch leaves it (paths I, II: eqns 5-6, 5-7)"
            out.append(Event("bifurcation", 0.0, names, detail))
            x = plane_blockage(self.alpha, self.beta)
            if x is not None:
                detail = "crease B4 folds flat onto its neighbour (phi_B4 = 0): blocked"
                out += [Event("lock", x, (PLANE,), detail), Event("lock", -x, (PLANE,), detail)]
        return tuple(out)

    def gruebler(self) -> int:
        """Kutzbach: 11 joints - 6 per spatial (thick) or 3 per spherical loop - one per coupling."""
        return len(CREASES) - (6 if self.thick else 3) * 2 - len(self.couplings)

    def loop_system(self) -> LoopSystem:
        """Per-vertex closure of the cell's crease pattern with its couplings."""
        index = {name: k for k, name in enumerate(CREASES)}
        return self.pattern.loop_system(tuple(Coupling(index[a], index[b]) for a, b in self.couplings))

    def loop_input(self) -> tuple[int, float]:
        return CREASES.index("A4"), 1.0
