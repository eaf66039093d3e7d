"""Plane-symmetric Bricard 6R linkage (Feng 2018, ch. 4, §4.2-4.5).

Geometry (eqn 4-1): a12 = a61 = a, a23 = a56 = b, a34 = a45 = c; alpha12 = alpha, alpha61 = 2 pi - alpha,
alpha23 = beta, alpha56 = 2 pi - beta, alpha34 = gamma, alpha45 = 2 pi - gamma; R1 = R4 = 0, R6 = -R2,
R5 = -R3 (D-H rows T = Rz(theta) Tz(R) Tx(a) Rx(alpha), `kinematics.dh`). The input is theta2; every
branch but the double rocker of eqn 4-37d keeps theta5 = theta3 and theta6 = theta2 (eqn 4-3). The review
form of eqn 2-10 is not mobile in this convention (local DOF 0, found here) and is not used.

Closed form (§4.2). With m = tan(theta2/2), n = tan(theta3/2), A n^2 + B n + C = 0 (eqn 4-5), with A, B,
C of eqn 4-6 and the CORRECTED sign of C's linear term, -2 sin(alpha) (R3 sin(gamma) + R2 sin(beta +
gamma)) m (corrected here: eqn 4-6c prints "+", which misses closure by up to 0.23 on 72 random geometries with
offsets, against 2e-14 corrected; the sign is invisible when R2 = R3 = 0, as in every example of the thesis).
A, B and C are used multiplied by cos^2(theta2/2): quadratic forms in (sin(theta2/2), cos(theta2/2)),
finite at theta2 = pi. theta3 is the root of the quadratic written with both half-angle pairs (stable
at A = 0, where one root goes to theta3 = pi), theta1 from eqn 4-7 (appendix entry (1,3)) or entry
(1,4), whichever is better conditioned, theta4 from appendix entry (3,1), or from the rotation part
of the loop where (3,1) is 0/0. The A == 0 case (eqn 4-9) is the same formula with A = 0.

Following branches by continuity. The two roots are -B +/- sqrt(Delta) over 2A: the +/- labels swap
where Delta touches zero (a bifurcation where two branches cross), so a root is never named by its
sign. Delta is factored exactly (in coefficient space) as L(theta2)^2 G(theta2), L the product of
sin(theta2/2 - psi_k) over its double zeros; the signed root L sqrt(G) is then analytic through every
crossing, and each branch is the analytic continuation of one root. Common zeros of A, B and C (where
the eliminant vanishes identically, e.g. theta2 = 0 in case 5) are divided out first. Where joint
axes 1 and 4 coincide, theta1 and theta4 are 0/0 in (theta2, theta3); there the branch is interpolated
from nodes a few mrad away (the value is the branch's limit). Simple zeros of G are turning points.

Branches are named by a geometric property, checked on the branch:

* ``theta1_eq_theta4`` - path I of eqn 4-33 (case 10) and the double-root branch of case 8.
* ``theta1_plus_theta4_eq_2theta2`` - path II of eqn 4-34 (case 10) (derived here): theta1 + theta4 = 2 theta2.
* ``bennett_theta3_pi`` - theta3 = theta5 = pi, theta4 = theta1: the Bennett 4R of joints 1, 2, 4, 6
  (eqn 4-31; case 5 and the Fig. 4-5 geometry).
* ``only_joints_2_6_move`` - theta1 = theta3 = theta4 = theta5 = pi: links 12 and 61 folded together, so
  joints 2 and 6 are coaxial and the rest turns about them rigidly (case 6) (derived here).
* ``all_joints_move`` - the one branch, besides those above, on which every joint moves (A == 0 cases).
* otherwise ``theta3_<deg>_at_theta2_<deg>``: the configuration the branch passes through at the input
  where it is farthest from the other root (e.g. case 9's halves, through the Bennett bifurcations).

Case 10 family (eqn 4-32) (derived here, verified numerically): path I (eqn 4-33) closes for every a = b + c,
alpha = pi - 2 beta, gamma = -beta, R = 0 (so it is case 8's branch too); path II (eqn 4-34) needs b = c.
Both are evaluated from those explicit forms, which have no 0/0 points.

Case 7 of Table 4-1 (derived here): Delta < 0 for every finite theta2, but at theta2 = pi (m infinite) the loop
closes at the isolated configuration (0, pi, pi, 0, pi, pi), rigid to second order: an assembled structure.
The model has no branch then; `isolated_assemblies` and an 'isolated_assembly' event report the configuration.

The special case of §4.5.2 (`SPECIAL_CASE_4_36`: A == B == C == 0, eqn 4-36): eqn 4-5 is void. Of eqn 4-37
only the double rocker (d) is driven by theta2; its two halves (``double_rocker_theta6_<deg>_at_theta2_0``)
meet at |theta2| = 99.59 deg and pass the multifurcations with the chains (a), (b) at theta2 = +-60 deg.
Other A == B == C == 0 geometries are refused with ParameterError.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..errors import ParameterError
from ..geometry import rot_x, rot_z, wrap
from .base import Branch, Event, as_inputs, domain_of
from .dh import DHKinematics, DHRow, dh_loop

# Samples of the theta2 circle used to find features (zeros, arcs, singular points).
GRID = 4096
# Samples of each branch kept to lift its angles continuously (np.unwrap) over its domain.
LIFT_SAMPLES = 4097
# A coefficient below COEF_TOL * scale^k (scale = a + b + c + |R2| + |R3|) is exactly zero.
COEF_TOL = 1e-12
# |f(x0)| / max|f| below this at a critical point x0 of a form f makes x0 a double zero of f.
DOUBLE_ZERO_TOL = 1e-10
# A candidate root whose median closure residual exceeds this is spurious (not a motion).
SPURIOUS_RESIDUAL = 1e-8
# theta1 is 0/0 where |(Y, X)| of both theta1 forms falls below SINGULAR_KAPPA: there the branch is
# interpolated (degree 7, nodes at +/- 1..4 INTERP_RADIUS, 5x wider where kappa grows slowly) for
# |theta2 - x0| < INTERP_RADIUS. Measured on 9 such geometries: interpolant vs direct values 5e-14 rad
# at 1e-3 from x0, closure residual 1.5e-14 through x0 (where the direct 0/0 form is wrong by up to pi).
SINGULAR_KAPPA = 1e-3
INTERP_RADIUS = 2e-3
# (3,1) gives theta4 when its |(Y, X)| is above this; below it theta4 comes from the loop's rotation.
THETA4_KAPPA = 0.05
# A singular value of the six joint lines (over the largest) that dips below this, where it is
# nonzero along the rest of the branch, marks a singular configuration.
RANK_RATIO = 1e-7
# Two configurations closer than this (rad, every joint) coincide; identities hold to this.
SAME_CONFIG = 1e-7


@dataclass(frozen=True)
class Geometry:
    """The eight parameters of eqn 4-1 (metres, radians)."""

    a: float
    b: float
    c: float
    alpha: float
    beta: float
    gamma: float
    R2: float = 0.0
    R3: float = 0.0

    @property
    def rows(self) -> tuple[DHRow, ...]:
        """D-H rows (R_i, a_(i,i+1), alpha_(i,i+1)) of joints 1..6 (eqn 4-1)."""
        g = self
        two_pi = 2 * np.pi
        return (
            DHRow(0.0, g.a, g.alpha),
            DHRow(g.R2, g.b, g.beta),
            DHRow(g.R3, g.c, g.gamma),
            DHRow(0.0, g.c, two_pi - g.gamma),
            DHRow(-g.R3, g.b, two_pi - g.beta),
            DHRow(-g.R2, g.a, two_pi - g.alpha),
        )

    @property
    def scale(self) -> float:
        """a + b + c + |R2| + |R3| (m): the unit of the coefficient tolerances."""
        return self.a + self.b + self.c + abs(self.R2) + abs(self.R3)


_PI = np.pi
# Table 4-1 cases 5..10 (Feng 2018, §4.2), all R2 = R3 = 0.
TABLE_4_1 = {
    5: Geometry(1.0, 1.0, 2.0, _PI / 3, _PI / 2, _PI / 6),
    6: Geometry(1.5, 1.0, 2.0, _PI / 2, _PI / 4, -_PI / 4),
    7: Geometry(1.0, 2.0, 1.0, _PI / 6, _PI / 2, _PI / 6),
    8: Geometry(3.0, 2.0, 1.0, 2 * _PI / 3, _PI / 6, -_PI / 6),
    9: Geometry(3.0, 2.0, 1.0, _PI / 12, _PI / 3, _PI / 4),
    10: Geometry(2.0, 1.0, 1.0, 2 * _PI / 3, _PI / 6, -_PI / 6),
}
# Fig. 4-5: A == 0 with a Bennett branch theta3 = theta5 = pi (Feng 2018, §4.3-4.4).
FIG_4_5 = Geometry(1.0, 3.0, 2.0, _PI / 4, _PI / 3, 7 * _PI / 12)
# The special case of Feng 2018, §4.5.2 (eqn 4-36): A == B == C == 0, so eqn 4-5 is void; its motions are those
# of eqn 4-37.
SPECIAL_CASE_4_36 = Geometry(3.0, 2.0, 4.0, _PI / 2, 0.0, _PI / 2)
# The double rocker (eqn 4-37d) is real for |tan(theta2/2)| <= sqrt(7/5), |theta2| <= 99.59 deg.
DOUBLE_ROCKER_LIMIT = 2 * np.arctan(np.sqrt(7 / 5))


# ---------------------------------------------------------------------------------------------
# Eqns 4-6, 4-7, 4-15 and appendix entries (1,4), (3,1)
# ---------------------------------------------------------------------------------------------


def closure_forms(g: Geometry, *, printed_c: bool = False) -> NDArray[np.float64]:
    """
    A, B, C of eqn 4-6 times cos^2(theta2/2), as quadratic forms in (s, c) = (sin, cos)(theta2/2).

    Returns
    -------
    forms : (3, 3) float
      Rows A, B, C; column k multiplies s^k c^(2-k).
    printed_c : bool
      Use the printed sign "+2 sin(alpha)(R3 sin(gamma) + R2 sin(beta + gamma)) m" of eqn 4-6c (wrong,
      kept to demonstrate the correction).
    """
    a, b, c, al, be, ga, R2, R3 = g.a, g.b, g.c, g.alpha, g.beta, g.gamma, g.R2, g.R3
    sa, sg = np.sin(al), np.sin(ga)
    sign = 1.0 if printed_c else -1.0
    A = (
        (a + b - c) * np.sin(al + be - ga),
        2 * sa * (R3 * sg + R2 * np.sin(ga - be)),
        (a - b + c) * np.sin(al - be + ga),
    )
    B = (
        -2 * sg * (R2 * sa + R3 * np.sin(al + be)),
        2 * ((a - c) * np.sin(al - ga) - (a + c) * np.sin(al + ga)),
        2 * sg * (R2 * sa + R3 * np.sin(al - be)),
    )
    C = (
        (a + b + c) * np.sin(al + be + ga),
        sign * 2 * sa * (R3 * sg + R2 * np.sin(be + ga)),
        (a - b - c) * np.sin(al - be - ga),
    )
    return np.array([A, B, C], dtype=float)


def closure_coefficients(
    g: Geometry, theta2: ArrayLike, *, printed_c: bool = False
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """A, B, C of eqn 4-6 (polynomials in m = tan(theta2/2)) at finite theta2, each (n,)."""
    m = np.tan(np.atleast_1d(np.asarray(theta2, dtype=float)) / 2)
    powers = np.stack([np.ones_like(m), m, m * m])
    A, B, C = closure_forms(g, printed_c=printed_c) @ powers
    return A, B, C


def discriminant(g: Geometry, theta2: ArrayLike) -> NDArray[np.float64]:
    """Delta = B^2 - 4 A C of eqn 4-15 (m form) at finite theta2, (n,)."""
    A, B, C = closure_coefficients(g, theta2)
    return B * B - 4 * A * C


def _twist_trig(g: Geometry) -> tuple[float, ...]:
    """sin and cos of alpha, beta, gamma: (sa, ca, sb, cb, sg, cg)."""
    return tuple(float(f(t)) for t in (g.alpha, g.beta, g.gamma) for f in (np.sin, np.cos))


def theta1_fractions(g: Geometry, theta2: ArrayLike, theta3: ArrayLike) -> NDArray[np.float64]:
    """
    tan(theta1/2) = Y13 / X13 (eqn 4-7, appendix (1,3)) = Y14 / X14 (appendix (1,4)).

    Returns
    -------
    (4, n) float : Y13, X13, Y14, X14 (the last two in metres).
    """
    t2 = np.asarray(theta2, dtype=float)
    t3 = np.asarray(theta3, dtype=float)
    sa, ca, sb, cb, sg, cg = _twist_trig(g)
    s2, c2, s3, c3 = np.sin(t2), np.cos(t2), np.sin(t3), np.cos(t3)
    Y13 = sg * (c2 * s3 + cb * s2 * c3) + sb * cg * s2
    X13 = sa * sb * sg * c3 - ca * sb * cg * c2 - sa * cb * cg - ca * cb * sg * c2 * c3 + ca * sg * s2 * s3
    Y14 = g.a + g.b * c2 + g.c * (c2 * c3 - cb * s2 * s3) + g.R3 * sb * s2
    X14 = (
        g.c * (ca * s2 * c3 + ca * cb * c2 * s3 - sa * sb * s3)
        + g.b * ca * s2
        - g.R3 * ca * sb * c2
        - g.R2 * sa
        - g.R3 * sa * cb
    )
    return np.array([Y13, X13, Y14, X14])


def theta4_fraction(g: Geometry, theta2: ArrayLike, theta3: ArrayLike) -> NDArray[np.float64]:
    """tan(theta4/2) = Y31 / X31 (appendix entry (3,1); eqn 4-8 is garbled). Returns (2, n)."""
    t2 = np.asarray(theta2, dtype=float)
    t3 = np.asarray(theta3, dtype=float)
    sa, ca, sb, cb, sg, cg = _twist_trig(g)
    s2, c2, s3, c3 = np.sin(t2), np.cos(t2), np.sin(t3), np.cos(t3)
    Y31 = sa * s2 * c3 + s3 * (sa * cb * c2 + ca * sb)
    X31 = cg * (sa * s2 * s3 - sa * cb * c2 * c3 - ca * sb * c3) + sg * (sa * sb * c2 - ca * cb)
    return np.array([Y31, X31])


def theta4_from_rotation(g: Geometry, theta1: ArrayLike, theta2: ArrayLike, theta3: ArrayLike) -> NDArray[np.float64]:
    """
    theta4 from the rotation part of the loop given theta1, theta2, theta3 (theta5 = theta3,
    theta6 = theta2): Rz(theta4) = (Q P)^T with P = Rz(t1) Rx(a12) Rz(t2) Rx(a23) Rz(t3) Rx(a34) and
    Q = Rx(a45) Rz(t3) Rx(a56) Rz(t2) Rx(a61). Never 0/0; exact wherever the loop closes.
    """
    t1, t2, t3 = (np.atleast_1d(np.asarray(v, dtype=float)) for v in (theta1, theta2, theta3))
    twists = [r.alpha for r in g.rows]
    rx = [rot_x(al) for al in twists]
    P = rot_z(t1) @ rx[0] @ rot_z(t2) @ rx[1] @ rot_z(t3) @ rx[2]
    Q = rx[3] @ rot_z(t3) @ rx[4] @ rot_z(t2) @ rx[5]
    QP = Q @ P
    return np.arctan2(QP[:, 0, 1], QP[:, 0, 0])


def path_one(beta: float, theta2: ArrayLike) -> NDArray[np.float64]:
    """
    Path I of eqn 4-33 (theta1 = theta4), written without infinite tangents; (n, 6) joints 1..6.

    tan(theta2/2) = -1 / (cos(2 beta) tan(theta1/2)), tan(theta3/2) = -cos(beta) tan(theta1/2).
    Closes for every a = b + c, alpha = pi - 2 beta, gamma = -beta, R = 0 (case 10 and case 8).
    """
    t2 = np.atleast_1d(np.asarray(theta2, dtype=float))
    s, c = np.sin(t2 / 2), np.cos(t2 / 2)
    c2b = np.cos(2 * beta)
    t1 = 2 * np.arctan2(-c, c2b * s)
    t3 = 2 * np.arctan2(np.cos(beta) * c, c2b * s)
    return np.stack([t1, t2, t3, t1, t3, t2], -1)


def path_two(beta: float, theta2: ArrayLike) -> NDArray[np.float64]:
    """
    Path II of eqn 4-34; (n, 6). With T = tan(theta2/2): tan(theta1/2) = -1 / (cos^2(beta) T),
    tan(theta3/2) = 1 / (cos(beta) T), tan(theta4/2) = -(cos(2 beta) T^2 + 1) / (T (cos^2(beta) T^2 + 2 - cos^2(beta))).
    Needs b = c as well (eqn 4-32).
    """
    t2 = np.atleast_1d(np.asarray(theta2, dtype=float))
    s, c = np.sin(t2 / 2), np.cos(t2 / 2)
    cb2 = np.cos(beta) ** 2
    t1 = 2 * np.arctan2(-c, cb2 * s)
    t3 = 2 * np.arctan2(c, np.cos(beta) * s)
    t4 = 2 * np.arctan2(-(np.cos(2 * beta) * s * s + c * c) * c, s * (cb2 * s * s + (2 - cb2) * c * c))
    return np.stack([t1, t2, t3, t4, t3, t2], -1)


def double_rocker(theta2: ArrayLike, sign: int) -> NDArray[np.float64]:
    """
    The double rocker of eqn 4-37d (geometry 4-36), not plane-symmetric; (n, 6) joints 1..6, |theta2| <= 99.59 deg.

    theta1 = theta4 = 0; with m = tan(theta2/2): tan(theta6/2) = (-4m + sign sqrt(3(7m^2 + 3)(7 - 5m^2))) /
    (15m^2 + 7); theta2 + theta3 = pi - arcsin((sin(theta6) - sin(theta2))/4) (the principal arcsin does not
    close: error about 15, found here); theta5 = -(theta2 + theta3 + theta6).
    """
    t2 = np.atleast_1d(np.asarray(theta2, dtype=float))
    m = np.tan(t2 / 2)
    root = np.sqrt(np.maximum(3 * (7 * m * m + 3) * (7 - 5 * m * m), 0.0))
    t6 = 2 * np.arctan2(-4 * m + sign * root, 15 * m * m + 7)
    t3 = np.pi - np.arcsin(np.clip((np.sin(t6) - np.sin(t2)) / 4, -1.0, 1.0)) - t2
    zero = np.zeros_like(t2)
    return np.stack([zero, t2, t3, zero, -(t2 + t3 + t6), t6], -1)


# ---------------------------------------------------------------------------------------------
# Homogeneous forms in (s, c) = (sin(x/2), cos(x/2)): coefficient k multiplies s^k c^(d-k)
# ---------------------------------------------------------------------------------------------


def _form_eval(f: NDArray[np.float64], x: NDArray[np.float64]) -> NDArray[np.float64]:
    s, c = np.sin(x / 2), np.cos(x / 2)
    d = len(f) - 1
    out = np.zeros_like(x, dtype=float)
    for k, coef in enumerate(f):
        if coef != 0.0:
            out = out + coef * s**k * c ** (d - k)
    return out


def _form_diff(f: NDArray[np.float64]) -> NDArray[np.float64]:
    """d/dx of a form: d(s^k c^(d-k))/dx = (k s^(k-1) c^(d-k+1) - (d-k) s^(k+1) c^(d-k-1)) / 2."""
    d = len(f) - 1
    g = np.zeros(d + 1)
    for k, coef in enumerate(f):
        if k > 0:
            g[k - 1] += 0.5 * k * coef
        if k < d:
            g[k + 1] -= 0.5 * (d - k) * coef
    return g


def _deflate(f: NDArray[np.float64], x0: float) -> tuple[NDArray[np.float64], float]:
    """f = sin(x/2 - x0/2) q + remainder: q (degree d-1) by least squares, and |remainder|."""
    d = len(f) - 1
    lin = np.array([-np.sin(x0 / 2), np.cos(x0 / 2)])
    M = np.zeros((d + 1, d))
    for j in range(d):
        M[j : j + 2, j] = lin
    q = np.linalg.lstsq(M, f, rcond=None)[0]
    return q, float(np.max(np.abs(M @ q - f), initial=0.0))


def _bisect_zero(fun, lo: float, hi: float, iterations: int = 80) -> float:
    """A sign change of fun inside [lo, hi], by bisection."""
    flo = fun(np.array([lo]))[0]
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        fm = fun(np.array([mid]))[0]
        if (fm > 0) == (flo > 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _double_zeros(f: NDArray[np.float64], grid: NDArray[np.float64]) -> list[float]:
    """Zeros x0 in [-pi, pi) of a form f where f' changes sign too (even multiplicity)."""
    values = _form_eval(f, grid)
    big = float(np.max(np.abs(values)))
    if big == 0.0:
        return []
    fp = _form_diff(f)
    slope = _form_eval(fp, grid)
    out = []
    n = len(grid)
    for i in range(n):
        j = (i + 1) % n
        lo, hi = grid[i], grid[j] + (2 * np.pi if j == 0 else 0.0)
        if slope[i] == 0.0:
            x0 = grid[i]
        elif (slope[i] > 0) != (slope[j] > 0):
            x0 = _bisect_zero(lambda x: _form_eval(fp, x), lo, hi)
        else:
            continue
        if abs(_form_eval(f, np.array([x0]))[0]) <= DOUBLE_ZERO_TOL * big:
            x0 = float(wrap(x0))
            if not any(abs(float(wrap(x0 - y))) < 1e-9 for y in out):
                out.append(x0)
    return out


def _zoom_min(fun, lo: float, hi: float, rounds: int = 14, samples: int = 33) -> float:
    """Minimiser of a vectorised function (n,) -> (n,) near a single dip in [lo, hi], by zooming grids."""
    for _ in range(rounds):
        x = np.linspace(lo, hi, samples)
        i = int(np.argmin(fun(x)))
        lo, hi = x[max(i - 1, 0)], x[min(i + 1, samples - 1)]
        if hi - lo < 1e-15 * max(1.0, abs(lo)):
            break
    return float(0.5 * (lo + hi))


# ---------------------------------------------------------------------------------------------
# The model
# ---------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Classification:
    """
    Table 4-1 character of a geometry.

    a_identically_zero : A == 0 for every theta2 (eqns 4-13/4-14; eqn 4-9 applies).
    delta : 'zero' (Delta == 0), 'negative' (< 0 except at isolated points), 'positive' (>= 0), 'mixed'.
    delta_range : min and max of Delta (eqn 4-15, m form) over theta2 sampled in (-pi, pi).
    structure : no motion driven by theta2 exists, but the loop closes at isolated configurations.
    """

    a_identically_zero: bool
    delta: str
    delta_range: tuple[float, float]
    structure: bool


@dataclass(frozen=True)
class _Candidate:
    """One root of the quadratic on one arc (eps = +1/-1, 0 for a double root), or an explicit path."""

    eps: int
    domain: tuple[float, float]
    explicit: str = ""  # "one" / "two": eqn 4-33 / 4-34


class PlaneSymmetricBricard(DHKinematics):
    """
    Plane-symmetric Bricard 6R (eqn 4-1) driven by theta2; outputs theta1..theta6.

    Parameters
    ----------
    a, b, c : float
      Link lengths (m), >= 0, not all zero.
    alpha, beta, gamma : float
      Twists alpha12, alpha23, alpha34 (rad); alpha61 = 2 pi - alpha etc.
    R2, R3 : float
      Offsets (m); R6 = -R2, R5 = -R3, R1 = R4 = 0.
    explicit : bool
      Evaluate the case-10 family (eqn 4-32) from eqns 4-33/4-34 (default); False forces the general
      solution everywhere (used to cross-check it).

    Notes
    -----
    Inputs are taken modulo 2 pi into each branch's domain, whose ends may exceed pi (a domain through
    theta2 = pi). Output angles are continuous along a branch (lifted), so they may leave (-pi, pi].
    """

    input_joint = 2
    input_name = "theta2"
    joint_names = ("theta1", "theta2", "theta3", "theta4", "theta5", "theta6")

    def __init__(
        self,
        a: float,
        b: float,
        c: float,
        alpha: float,
        beta: float,
        gamma: float,
        R2: float = 0.0,
        R3: float = 0.0,
        *,
        explicit: bool = True,
    ):
        for name, value in (("a", a), ("b", b), ("c", c)):
            if not value >= 0:
                raise ParameterError(f"link length {name} = {value:g} m; it must not be negative")
        if a + b + c <= 0:
            raise ParameterError("a = b = c = 0: every link has zero length; give at least one positive length")
        for name, value in (("alpha", alpha), ("beta", beta), ("gamma", gamma), ("R2", R2), ("R3", R3)):
            if not np.isfinite(value):
                raise ParameterError(f"{name} = {value!r} is not a finite number")
        self.geometry = Geometry(*(float(v) for v in (a, b, c, alpha, beta, gamma, R2, R3)))
        self._explicit = explicit
        self._grid = np.linspace(-np.pi, np.pi, GRID, endpoint=False)
        self._prepare_forms()
        self._candidates = self._find_candidates()
        self._zones: dict[int, list] = {}
        self._zones = {k: self._singular_zones(k) for k in range(len(self._candidates))}
        self._lift = {k: self._lift_table(k) for k in range(len(self._candidates))}
        self._names = self._name_candidates()

    # -- geometry ---------------------------------------------------------------------------

    @property
    def rows(self) -> tuple[DHRow, ...]:
        return self.geometry.rows

    @property
    def family(self) -> str:
        """'II' for eqn 4-32 (paths I and II), 'I' for a = b + c with its twists (path I only), else ''."""
        g = self.geometry
        tol = 1e-12 * g.scale
        twists = abs(float(wrap(g.alpha - (np.pi - 2 * g.beta)))) < 1e-12 and abs(float(wrap(g.gamma + g.beta))) < 1e-12
        if not (twists and g.R2 == 0.0 and g.R3 == 0.0 and abs(g.a - g.b - g.c) < tol):
            return ""
        return "II" if abs(g.b - g.c) < tol else "I"

    @property
    def is_special_case_4_36(self) -> bool:
        """The special geometry of eqn 4-36 (Feng 2018, §4.5.2)."""
        g, ref = self.geometry, SPECIAL_CASE_4_36
        lengths = max(abs(g.a - ref.a), abs(g.b - ref.b), abs(g.c - ref.c), abs(g.R2), abs(g.R3)) < 1e-12 * g.scale
        twists = max(
            abs(float(wrap(u - v)))
            for u, v in zip((g.alpha, g.beta, g.gamma), (ref.alpha, ref.beta, ref.gamma), strict=True)
        )
        return lengths and twists < 1e-12

    @property
    def bennett_theta2_pi(self) -> bool:
        """Eqn 4-30: theta2 = theta6 = pi leaves a Bennett 4R (a = b + c, beta = alpha + gamma or b = a + c,
        alpha = beta + gamma; R = 0)."""
        g = self.geometry
        tol = 1e-12 * g.scale
        if g.R2 != 0.0 or g.R3 != 0.0:
            return False
        first = abs(g.a - g.b - g.c) < tol and abs(float(wrap(g.beta - g.alpha - g.gamma))) < 1e-12
        second = abs(g.b - g.a - g.c) < tol and abs(float(wrap(g.alpha - g.beta - g.gamma))) < 1e-12
        return first or second

    # -- the quadratic in theta3 --------------------------------------------------------------

    def _prepare_forms(self) -> None:
        """Snap A, B, C; divide out their common zeros; factor Delta = L^2 G."""
        g = self.geometry
        forms = closure_forms(g)
        forms[np.abs(forms) < COEF_TOL * g.scale] = 0.0
        self._raw_forms = forms.copy()
        # Common zeros of A, B, C: double zeros of A^2 + B^2 + C^2.
        common = []
        for _ in range(2):
            squares = sum(np.convolve(f, f) for f in forms)
            zeros = _double_zeros(squares, self._grid)
            if not zeros or len(forms[0]) == 1:
                break
            x0 = zeros[0]
            common.append(x0)
            forms = np.array([_deflate(f, x0)[0] for f in forms])
            forms[np.abs(forms) < COEF_TOL * g.scale] = 0.0
        self._common = tuple(common)
        self._forms = forms
        A, B, C = forms
        delta = np.convolve(B, B) - 4 * np.convolve(A, C)
        delta[np.abs(delta) < COEF_TOL * g.scale**2] = 0.0
        self._delta_zero = not np.any(delta)
        isolated, factors = [], []
        G = delta
        if not self._delta_zero:
            for _ in range(len(delta) // 2):
                zeros = _double_zeros(G, self._grid)
                if not zeros:
                    break
                x0 = zeros[0]
                G = _deflate(_deflate(G, x0)[0], x0)[0]
                G[np.abs(G) < COEF_TOL * g.scale**2] = 0.0
                factors.append(x0)
            # A double zero with G < 0 around it is an isolated real configuration (case 7 at theta2 = pi);
            # with G > 0 it is a crossing of two branches, through which L sqrt(G) stays analytic.
            isolated = [x0 for x0 in sorted(set(factors)) if _form_eval(G, np.array([x0]))[0] < 0]
        self._G = G
        self._factors = tuple(factors)
        self._isolated = tuple(isolated)

    def _signed_root(self, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """L(x) sqrt(G(x)), analytic through the crossings, and where G >= 0."""
        if self._delta_zero:
            return np.zeros_like(x), np.ones(x.shape, dtype=bool)
        G = _form_eval(self._G, x)
        L = np.ones_like(x)
        for x0 in self._factors:
            L = L * np.sin(x / 2 - x0 / 2)
        return L * np.sqrt(np.maximum(G, 0.0)), G >= 0.0

    def _theta3(self, eps: int, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """theta3 of root eps (+1, -1; 0 for the double root): n = (-B + eps w) / 2A = 2C / (-B - eps w)."""
        A, B, C = (_form_eval(f, x) for f in self._forms)
        w, _ = self._signed_root(x)
        num1, den1 = -B + eps * w, 2 * A
        num2, den2 = 2 * C, -B - eps * w
        first = np.hypot(num1, den1) >= np.hypot(num2, den2)
        return 2 * np.arctan2(np.where(first, num1, num2), np.where(first, den1, den2))

    def _complete(self, t2: NDArray[np.float64], t3: NDArray[np.float64]) -> tuple[NDArray, NDArray, NDArray]:
        """theta1 (eqn 4-7 or (1,4)), theta4 ((3,1) or the loop's rotation) and theta1's conditioning."""
        g = self.geometry
        Y13, X13, Y14, X14 = theta1_fractions(g, t2, t3)
        n13 = np.hypot(Y13, X13)
        n14 = np.hypot(Y14, X14) / g.scale
        use13 = n13 >= n14
        t1 = 2 * np.arctan2(np.where(use13, Y13, Y14), np.where(use13, X13, X14))
        Y31, X31 = theta4_fraction(g, t2, t3)
        t4 = 2 * np.arctan2(Y31, X31)
        weak = np.hypot(Y31, X31) < THETA4_KAPPA
        if np.any(weak):
            t4[weak] = theta4_from_rotation(g, t1[weak], t2[weak], t3[weak])
        return t1, t4, np.maximum(n13, n14)

    def _raw_candidate(self, cand: _Candidate, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Joints 1..6 (n, 6) of a candidate at inputs x inside its domain (not lifted)."""
        if cand.explicit == "one":
            return path_one(self.geometry.beta, x)
        if cand.explicit == "two":
            return path_two(self.geometry.beta, x)
        if cand.explicit == "rocker":
            return double_rocker(x, cand.eps)
        t3 = self._theta3(cand.eps, x)
        t1, t4, _ = self._complete(x, t3)
        return np.stack([t1, x, t3, t4, t3, x], -1)

    def _raw(self, k: int, x: NDArray[np.float64], interpolate: bool = True) -> NDArray[np.float64]:
        """As `_raw_candidate` for candidate k, interpolated where theta1 is 0/0 (see `_singular_zones`)."""
        out = self._raw_candidate(self._candidates[k], x)
        if interpolate:
            for x0, radius, nodes, node_values in self._zones.get(k, ()):
                near = np.abs(x - x0) < radius
                if np.any(near):
                    out[near] = _barycentric(nodes, node_values, x[near])
        return out

    def _kappa(self, k: int, x: NDArray[np.float64]) -> NDArray[np.float64]:
        t3 = self._theta3(self._candidates[k].eps, x)
        return self._complete(x, t3)[2]

    # -- candidates, arcs and domains ----------------------------------------------------------

    def _find_candidates(self) -> list[_Candidate]:
        family = self.family if self._explicit else ""
        full = (-np.pi, np.pi)
        if not np.any(self._forms):
            if not self.is_special_case_4_36:
                raise ParameterError(
                    "A = B = C = 0 for every theta2: eqn 4-5 says nothing about theta3 (Feng 2018, §4.5.2); only the "
                    "eqn 4-36 geometry a = 3, b = 2, c = 4 m, alpha = 90, beta = 0, gamma = 90 deg is modelled"
                )
            ends = (-DOUBLE_ROCKER_LIMIT, DOUBLE_ROCKER_LIMIT)
            return [_Candidate(1, ends, "rocker"), _Candidate(-1, ends, "rocker")]
        if family:
            out = [_Candidate(0, full, "one")]
            if family == "II":
                out.append(_Candidate(0, full, "two"))
            return out
        valid_at = lambda x: self._signed_root(np.asarray(x, dtype=float))[1]  # noqa: E731
        ok = valid_at(self._grid)
        if self._delta_zero:
            arcs, signs = [full], (0,)
        elif np.all(ok):
            # Forms of degree d change sign by (-1)^d over one turn and the signed root by (-1)^m (m
            # factors in L): if m - d is odd the roots swap after one turn, one branch over 4 pi.
            periodic = (len(self._factors) - (len(self._forms[0]) - 1)) % 2 == 0
            arcs = [full] if periodic else [(-np.pi, 3 * np.pi)]
            signs = (1, -1) if periodic else (1,)
        elif not np.any(ok):
            arcs, signs = [], ()
        else:
            arcs, signs = [], (1, -1)
            start = int(np.argmin(ok))  # an invalid sample: runs never wrap past it
            rolled = np.roll(ok, -start)
            i = 0
            while i < GRID:
                if rolled[i]:
                    j = i
                    while j + 1 < GRID and rolled[j + 1]:
                        j += 1
                    anchor = self._grid[(start + (i + j) // 2) % GRID]
                    lo, hi = domain_of(valid_at, anchor - np.pi, anchor + np.pi, anchor)
                    shift = 2 * np.pi * np.floor((lo + np.pi) / (2 * np.pi))
                    arcs.append((lo - shift, hi - shift))
                    i = j + 1
                else:
                    i += 1
        out = []
        for arc in arcs:
            for eps in signs:
                cand = _Candidate(eps, arc)
                xs = np.linspace(arc[0], arc[1], 67)[1:-1]
                q = self._raw_candidate(cand, xs)
                if np.median(self.loop_system().residual_norm(q)) <= SPURIOUS_RESIDUAL:
                    out.append(cand)
        return out

    def _singular_zones(self, k: int) -> list[tuple[float, float, NDArray, NDArray]]:
        """
        Where theta1 is 0/0 on candidate k (joint axes 1 and 4 coincide): (x0, radius, nodes (8,),
        node values (8, 6)). Inputs within the radius of x0 are interpolated from the nodes.
        """
        cand = self._candidates[k]
        if cand.explicit:
            return []
        lo, hi = cand.domain
        full = hi - lo >= 2 * np.pi - 1e-9
        xs = np.linspace(lo, hi, LIFT_SAMPLES)
        kappa = self._kappa(k, xs)
        zones: list[tuple[float, float, NDArray, NDArray]] = []
        for i in range(1, len(xs) - 1):
            if not (kappa[i] <= kappa[i - 1] and kappa[i] <= kappa[i + 1] and kappa[i] < 100 * SINGULAR_KAPPA):
                continue
            x0 = _zoom_min(lambda v: self._kappa(k, v), xs[i - 1], xs[i + 1])
            if self._kappa(k, np.array([x0]))[0] >= SINGULAR_KAPPA:
                continue
            # Nodes where theta1 is well conditioned again (kappa grows linearly away from x0).
            radius = INTERP_RADIUS
            if np.min(self._kappa(k, x0 + radius * np.array([-1.0, 1.0]))) < SINGULAR_KAPPA:
                radius *= 5
            nodes = x0 + radius * np.array([-4.0, -3.0, -2.0, -1.0, 1.0, 2.0, 3.0, 4.0])
            if not full and (nodes[0] < lo or nodes[-1] > hi):
                continue  # next to a turning point: left as computed
            values = np.unwrap(self._raw(k, nodes, interpolate=False), axis=0)
            # On a full-circle branch the same point recurs one period away (inputs are taken modulo it).
            shifts = (-(hi - lo), 0.0, hi - lo) if full else (0.0,)
            for shift in shifts:
                centre = x0 + shift
                if lo - radius <= centre <= hi + radius and not any(abs(centre - z[0]) < 1e-9 for z in zones):
                    zones.append((centre, radius, nodes + shift, values))
        return zones

    def _lift_table(self, k: int) -> tuple[NDArray, NDArray]:
        lo, hi = self._candidates[k].domain
        xs = np.linspace(lo, hi, LIFT_SAMPLES)
        values = np.unwrap(self._raw(k, xs), axis=0)
        # The lift is anchored so that the value nearest theta2 = 0 (mod 2 pi) lies in (-pi, pi].
        i = int(np.argmin(np.abs(wrap(xs))))
        values -= 2 * np.pi * np.round((values[i] - wrap(values[i])) / (2 * np.pi))
        return xs, values

    # -- naming -----------------------------------------------------------------------------

    def _name_candidates(self) -> list[str]:
        names: list[str | None] = []
        for k, cand in enumerate(self._candidates):
            if cand.explicit == "rocker":
                t6 = float(np.rad2deg(double_rocker(0.0, cand.eps)[0, 5]))
                names.append(f"double_rocker_theta6_{'m' if t6 < 0 else ''}{abs(round(t6))}_at_theta2_0")
                continue
            lo, hi = cand.domain
            x = np.linspace(lo, hi, 257)
            q = self._raw(k, x)
            t1, t3, t4 = q[:, 0], q[:, 2], q[:, 3]

            def holds(v):
                return bool(np.all(np.abs(wrap(v)) < SAME_CONFIG))

            if holds(t3 - np.pi) and holds(t1 - np.pi) and holds(t4 - np.pi):
                names.append("only_joints_2_6_move")
            elif holds(t3 - np.pi) and holds(t1 - t4):
                names.append("bennett_theta3_pi")
            elif holds(t1 - t4):
                names.append("theta1_eq_theta4")
            elif holds(t1 + t4 - 2 * x):
                names.append("theta1_plus_theta4_eq_2theta2")
            else:
                names.append(None)
        open_ = [k for k, n in enumerate(names) if n is None]
        degenerate = any(n in ("only_joints_2_6_move", "bennett_theta3_pi") for n in names)
        if len(open_) == 1 and degenerate:
            names[open_[0]] = "all_joints_move"
        elif open_:
            for k in open_:
                names[k] = self._configuration_name(k)
        seen: dict[str, int] = {}
        out = []
        for n in names:
            seen[n] = seen.get(n, 0) + 1
            out.append(n if seen[n] == 1 else f"{n}_{seen[n]}")
        return out

    def _configuration_name(self, k: int) -> str:
        """theta3_<deg>_at_theta2_<deg>: at the multiple of 10 deg where it is farthest from the other root."""
        cand = self._candidates[k]
        lo, hi = cand.domain
        x = np.deg2rad(np.arange(np.ceil(np.rad2deg(lo) / 10) * 10, np.rad2deg(hi) + 1e-9, 10.0))
        x = x[(x >= lo) & (x <= hi)]
        if x.size == 0:
            x = np.array([0.5 * (lo + hi)])
        t3 = self._raw(k, x)[:, 2]
        other = self._theta3(-cand.eps, x) if cand.eps else t3
        gap = np.abs(wrap(t3 - other))
        i = int(np.argmax(np.round(gap, 9) - 1e-12 * np.abs(wrap(x))))  # ties: nearest theta2 = 0
        x_deg, t3_deg = float(np.rad2deg(wrap(x[i]))), float(np.rad2deg(wrap(t3[i])))
        if abs(x_deg + 180.0) < 1e-6:
            x_deg = 180.0
        if abs(t3_deg + 180.0) < 0.5:
            t3_deg = 180.0

        def fmt(v: float) -> str:
            r = round(v)
            return f"m{-r}" if r < 0 else f"{r}"

        return f"theta3_{fmt(t3_deg)}_at_theta2_{fmt(x_deg)}"

    # -- contract -----------------------------------------------------------------------------

    def _index(self, name: str) -> int:
        if name in self._names:
            return self._names.index(name)
        self.branch(name)  # raises ParameterError listing the names
        raise AssertionError  # pragma: no cover

    def _describe(self, k: int) -> str:
        name = self._names[k]
        lo, hi = self._candidates[k].domain
        text = {
            "theta1_eq_theta4": "theta1 = theta4 (path I, eqn 4-33; case 8's double root)",
            "theta1_plus_theta4_eq_2theta2": "theta1 + theta4 = 2 theta2 (path II, eqn 4-34)",
            "bennett_theta3_pi": "theta3 = theta5 = pi, theta4 = theta1: Bennett 4R of joints 1, 2, 4, 6 (eqn 4-31)",
            "only_joints_2_6_move": "theta1 = theta3 = theta4 = theta5 = pi: joints 2 and 6 coaxial, the rest rigid",
            "all_joints_move": "the 6R motion: every joint turns (eqn 4-9, A = 0)",
        }.get(name, "a plane-symmetric 6R motion (theta5 = theta3, theta6 = theta2)")
        if self._candidates[k].explicit == "rocker":
            text = "the four-bar double rocker of eqn 4-37d: theta1 = theta4 = 0, not plane-symmetric"
        if hi - lo < 2 * np.pi - 1e-9:
            share = (hi - lo) / (2 * np.pi)
            text += (
                f"; theta2 is not fully rotatable: only [{np.rad2deg(lo):.4f}, {np.rad2deg(hi):.4f}] deg "
                f"({100 * share:.1f} % of the circle, inputs taken modulo 360 deg)"
            )
        elif hi - lo > 2 * np.pi + 1e-9:
            text += "; the branch covers the theta2 circle twice (the two roots swap after one turn)"
        return text

    @cached_property
    def _branches(self) -> tuple[Branch, ...]:
        return tuple(
            Branch(name, self._describe(k), cand.domain)
            for k, (name, cand) in enumerate(zip(self._names, self._candidates, strict=True))
        )

    def branches(self) -> tuple[Branch, ...]:
        return self._branches

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        k = self._index(branch)
        lo, hi = self._candidates[k].domain
        x = as_inputs(x)
        # Valid exactly on the domain `describe` prints: a full-turn branch is not continued periodically beyond it
        # (at |x| = 1e10 the wrapped input had lost every digit: loop residual 3.0).
        valid = (x >= lo) & (x <= hi)
        values = np.full((x.size, 6), np.nan)
        if np.any(valid):
            raw = self._raw(k, x[valid])
            xs, table = self._lift[k]
            ref = np.stack([np.interp(x[valid], xs, table[:, j]) for j in range(6)], -1)
            lifted = ref + wrap(raw - ref)
            lifted[:, 1] = x[valid]
            if self._candidates[k].explicit != "rocker":  # theta6 = theta2 on the plane-symmetric branches
                lifted[:, 5] = x[valid]
            values[valid] = lifted
        return values, valid

    @cached_property
    def _events(self) -> tuple[Event, ...]:
        events: list[Event] = []
        # Turning points: the two roots of one arc meet where G = 0.
        by_arc: dict[tuple[float, float], list[str]] = {}
        for name, cand in zip(self._names, self._candidates, strict=True):
            lo, hi = cand.domain
            if hi - lo < 2 * np.pi - 1e-9:
                by_arc.setdefault(cand.domain, []).append(name)
        for (lo, hi), names in by_arc.items():
            for end in (lo, hi):
                detail = "Delta = 0: the two roots meet and theta2 turns back (eqn 4-15)"
                if self.is_special_case_4_36:
                    detail = "7 - 5 tan^2(theta2/2) = 0: the two theta6 roots of eqn 4-37d meet and theta2 turns back"
                events.append(Event("turning_point", end, tuple(names), detail))
        # Singular configurations: the six joint lines lose rank (bifurcations, incl. with motions
        # that theta2 does not drive, e.g. case 9's Bennett 4R at theta2 = pi).
        found: list[tuple[float, NDArray[np.float64]]] = []
        for k in range(len(self._candidates)):
            for x0 in self._singular_inputs(k):
                q0 = self._raw(k, np.array([x0]))[0]
                if not any(abs(float(wrap(x0 - y))) < 1e-6 and np.all(np.abs(wrap(q0 - q)) < 1e-6) for y, q in found):
                    found.append((x0, q0))
        for x0, q0 in found:
            through = []
            for name in self._names:
                values, valid = self.evaluate(name, x0)
                if valid[0] and np.all(np.abs(wrap(values[0] - q0)) < 1e-6):
                    through.append(name)
            mobility = self.loop_system().mobility(q0)
            conf = _degrees(q0)
            if len(through) > 1:
                detail = f"{len(through)} branches cross at theta = ({conf}) deg"
            elif self.is_special_case_4_36:
                sign, eqn = ("", "4-37a") if x0 > 0 else ("-", "4-37b")
                detail = (
                    f"multifurcation (Fig. 4-8) at theta = ({conf}) deg: the rocker meets eqn {eqn}, theta1 = -theta4 "
                    f"free with theta2 = theta6 = {sign}60, theta3 = theta5 = {sign}120 deg (theta2 fixed)"
                )
            elif self.bennett_theta2_pi and abs(float(wrap(x0 - np.pi))) < 1e-9:
                detail = (
                    f"meets the Bennett 4R theta2 = theta6 = pi, theta4 = theta1, theta5 = theta3 (eqn 4-30; not "
                    f"driven by theta2) at theta = ({conf}) deg"
                )
            else:
                detail = (
                    f"singular configuration theta = ({conf}) deg: a motion that theta2 does not drive "
                    f"(theta2 fixed) meets this branch"
                )
            detail += f"; instantaneous mobility {mobility}"
            events.append(Event("bifurcation", float(x0), tuple(through), detail))
        # Isolated assemblies (a double zero of Delta with no real roots around it).
        for x0, q in self.isolated_assemblies():
            conf = _degrees(q)
            events.append(
                Event("isolated_assembly", float(x0), (), f"the loop closes only at theta = ({conf}) deg: rigid")
            )
        return tuple(sorted(events, key=lambda e: (e.input, e.kind)))

    def _singular_inputs(self, k: int) -> list[float]:
        """Inputs where the rank of the joint lines drops below its value along candidate k."""
        lo, hi = self._candidates[k].domain
        xs = np.linspace(lo, hi, 1025)
        s = _line_singular_values(self._links, self.geometry.scale, self._raw(k, xs))
        ratios = s / s[:, :1]
        # The rank along the branch: 5 on a regular branch, less on a double root (case 8: 4).
        rank = int(np.sum(np.median(ratios, axis=0) > 1e-6))
        if rank < 2:
            return []

        def ratios_at(v: NDArray[np.float64]) -> NDArray[np.float64]:
            sv = _line_singular_values(self._links, self.geometry.scale, self._raw(k, v))
            return sv[:, rank - 1] / sv[:, 0]

        def ratio(v: float) -> float:
            return float(ratios_at(np.array([v]))[0])

        r = ratios[:, rank - 1]
        out = []
        for i in range(len(xs)):
            left = r[i - 1] if i > 0 else np.inf
            right = r[i + 1] if i + 1 < len(xs) else np.inf
            if r[i] <= left and r[i] <= right and r[i] < 1e-2:
                x0 = _zoom_min(ratios_at, xs[max(i - 1, 0)], xs[min(i + 1, len(xs) - 1)])
                if ratio(x0) >= RANK_RATIO:
                    continue
                # Snap to a multiple of 15 deg (theta2 = 0, pi: the collinear configurations; +-60 deg:
                # the multifurcations of eqn 4-36's geometry) when it is one; +pi over -pi.
                nearest = float(np.round(x0 * 12 / np.pi)) * np.pi / 12 + 0.0
                if abs(x0 - nearest) < 1e-7:
                    targets = [nearest, nearest + 2 * np.pi, nearest - 2 * np.pi]
                    if abs(float(wrap(nearest - np.pi))) < 1e-9:
                        targets = [np.pi, -np.pi, 3 * np.pi]
                    inside = [float(t) for t in targets if lo <= t <= hi and ratio(t) < RANK_RATIO]
                    x0 = inside[0] if inside else x0
                if not any(abs(x0 - y) < 1e-6 for y in out):
                    out.append(float(x0))
        return out

    def events(self) -> tuple[Event, ...]:
        return self._events

    def isolated_assemblies(self) -> list[tuple[float, NDArray[np.float64]]]:
        """(theta2, configuration (6,)) where the loop closes but cannot move (a double zero of Delta)."""
        out = []
        for x0 in self._isolated:
            x = np.array([x0])
            A, B, C = (_form_eval(f, x)[0] for f in self._forms)
            t3 = 2 * np.arctan2(-B, 2 * A) if abs(A) >= abs(C) else 2 * np.arctan2(2 * C, -B)
            t1, t4, _ = self._complete(x, np.array([t3]))
            q = np.array([t1[0], x0, t3, t4[0], t3, x0])
            if self.loop_system().residual_norm(q) < 1e-9:
                out.append((x0, q))
        return out

    def classification(self) -> Classification:
        """A == 0 or not and the sign of Delta, as Table 4-1 states them."""
        A_forms = self._raw_forms[0]
        A, B, C = self._raw_forms
        delta = np.convolve(B, B) - 4 * np.convolve(A, C)
        values = _form_eval(delta, self._grid)
        tol = 1e-12 * self.geometry.scale**2
        if not np.any(np.abs(delta) > tol):
            sign = "zero"
        elif np.max(values) <= tol:
            sign = "negative"
        elif np.min(values) >= -tol:
            sign = "positive"
        else:
            sign = "mixed"
        finite = self._grid[1:]  # theta2 in (-pi, pi): m finite
        m_delta = discriminant(self.geometry, finite)
        structure = not self._candidates and bool(self.isolated_assemblies())
        return Classification(not np.any(A_forms), sign, (float(np.min(m_delta)), float(np.max(m_delta))), structure)

    def loop_system(self) -> LoopSystem:
        return self._loop  # cached: the solver evaluates it at every sample

    @cached_property
    def _loop(self) -> LoopSystem:
        return dh_loop(self.rows)

    @cached_property
    def _links(self) -> NDArray[np.float64]:
        return self._loop.loops[0].links


def _degrees(q: NDArray[np.float64]) -> str:
    """Joint angles (rad) as '180.0000, 0.0000, ...' degrees in (-180, 180]."""
    return ", ".join(f"{v + 0.0:.4f}" for v in np.round(np.rad2deg(wrap(q)), 4))


def _barycentric(nodes: NDArray, values: NDArray, x: NDArray) -> NDArray:
    """Polynomial interpolation (barycentric form) of values (m, k) at nodes (m,), evaluated at x (n,)."""
    w = np.array([1.0 / np.prod(nodes[i] - np.delete(nodes, i)) for i in range(len(nodes))])
    diff = x[:, None] - nodes[None, :]
    exact = diff == 0.0
    diff[exact] = 1.0
    terms = w[None, :] / diff
    out = (terms @ values) / np.sum(terms, axis=1, keepdims=True)
    hit = np.any(exact, axis=1)
    if np.any(hit):
        out[hit] = values[np.argmax(exact[hit], axis=1)]
    return out


def _line_singular_values(links: NDArray[np.float64], scale: float, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    Singular values (n, 6), descending, of the six joint lines (Pluecker (z, o x z / scale)) of
    configurations q (n, 6), for the loop's link transforms (6, 4, 4).
    """
    lines = np.empty((len(q), 6, 6))
    T = np.broadcast_to(np.eye(4), (len(q), 4, 4))
    rz = np.zeros((len(q), 4, 4))
    rz[:, 2, 2] = rz[:, 3, 3] = 1.0
    for j in range(6):
        z, o = T[:, :3, 2], T[:, :3, 3]
        lines[:, :3, j] = z
        lines[:, 3:, j] = np.cross(o, z) / scale
        c, s = np.cos(q[:, j]), np.sin(q[:, j])
        rz[:, 0, 0], rz[:, 0, 1], rz[:, 1, 0], rz[:, 1, 1] = c, -s, s, c
        T = T @ rz @ links[j]
    return np.linalg.svd(lines, compute_uv=False)
