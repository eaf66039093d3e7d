"""Thick-panel six-crease diamond vertex = plane-symmetric Bricard linkage (Peng 2018, §4.4.1).

Sectors (eqn 4-29): alpha12 = alpha34 = alpha45 = alpha61 = alpha, alpha23 = alpha56 = pi - 2 alpha,
0 < alpha <= pi/4 (flat-foldable). Creases 1-4, 2-5 and 3-6 are collinear in the flat sheet. Hinge k lies
on the line through (0, 0, h_k) along d_k with h = (0, p, p - q, p - q - r, p - q, p) (reconstructed here),
so the distances between neighbouring hinges are a12 = a61 = p, a23 = a56 = q, a34 = a45 = r. The
equivalence with the zero-thickness vertex REQUIRES r = p + q (eqn 4-41c, not only "for compact folding"):
with r != p + q the plane-symmetric Bricard still moves, but along another curve (checked here on
Fig 4-12's vertex, alpha = pi/6, with p = 0.3, q = 0.5, r = 0.7), so this model refuses it.

Plane symmetry about the plane of creases 1 and 4 (rho6 = rho2, rho5 = rho3) reduces the loop to two
conditions: hinge line 4, carried by the chain from panel 1 (turned by rho1/2 about hinge 1), must lie in
that plane. Both are linear in (cos(rho1/2), sin(rho1/2)); eliminating rho1 leaves, with u = tan(rho2/2),
v = tan(rho3/2) and k = r/p,

    (u - v) ((p + q) u + p v) = 0                                                 (derived here)

so exactly two plane-symmetric branches leave the flat state (instantaneous mobility 2 there):

* 'diamond' (u = v): the zero-thickness motion (4-30)/(4-37), rho4 = rho1, rho2 = rho3 = rho5 = rho6,
  tan(rho1/2) + cos(alpha) tan(rho2/2) = 0. Creases 1 and 4 fold against 2, 3, 5 and 6.
* 'counter23' (v = -k u): creases 2 and 3 fold in opposite senses (found here: a second branch from flat), with

      tan(rho1/2) = -c u (2 k^2 C u^2 - (k^2 + 2k - 1)) / ((k^2 (1 + 2C) + k) u^2 - (k - 1))
      tan(rho4/2) =  c u (2 k^2 C u^2 + (k^2 - 2k - 1)) / ((k^2 + k (1 + 2C)) u^2 + (k - 1))

  where c = cos(alpha), C = cos(2 alpha). rho1 decreases monotonically from pi to -pi as u runs over
  (-u*, u*), u*^2 = (k - 1) / (k^2 (1 + 2C) + k) (checked for alpha in (0, pi/4], k in (1, 1001)), so the
  input is inverted by bisection of that monotone map, polished by Newton on the cubic
  c cos(rho1/2) u N(u) + sin(rho1/2) D(u) = 0. Along it rho3 and rho1 fold alike, rho2 against them;
  near flat rho4 joins rho2's sense for k > 1 + sqrt(2) and rho1's for k < 1 + sqrt(2).

Both branches are odd in rho1 and span [-pi, pi], where crease 1 folds flat. Each is also a motion of the
zero-thickness vertex (the rotation part of the loop is the spherical 6R's); the zero-thickness fold about
the line of creases 1-4 alone, (psi, 0, 0, psi, 0, 0), is not (residual h4 sin(psi): 0.48 at psi = 0.5 for
p = 0.3, q = 0.5, r = 0.8). Peng 2018's twists (4-40) and lengths (p, q, r, r, q, p) close at the thesis angles
theta^Br = (rho1 + pi, rho2 + pi, rho3, rho4 + pi, rho5, rho6 + pi).
"""

from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..errors import ParameterError
from .base import Branch, Event, JointSpaceKinematics
from .thick_vertex5 import lifted_loop

DIAMOND = "diamond"
COUNTER = "counter23"
# |r - (p + q)| above this (m) breaks the equivalence condition (4-41c).
CONDITION_TOL = 1e-9
# u(x) on branch 'counter23': interpolated in a table of the monotone rho1(u) at TABLE_SIZE values of u spread
# over (-u*, u*), then Newton steps on the cubic: 4.7e6 inputs/s where a 64-step bisection ran 8.6e5/s, outputs
# within 4.4e-16 rad of it over (-pi, pi) for four designs.
TABLE_SIZE = 4097
NEWTON_STEPS = 3


def sectors(alpha: float) -> NDArray[np.float64]:
    """Sector angles (6,) alpha12 ... alpha61 of the diamond vertex (eqn 4-29)."""
    return np.array([alpha, np.pi - 2 * alpha, alpha, alpha, np.pi - 2 * alpha, alpha])


def hinge_heights(p: float, q: float, r: float) -> NDArray[np.float64]:
    """Heights (6,) of the hinge lines above the sheet (m), reconstructed here."""
    return np.array([0.0, p, p - q, p - q - r, p - q, p])


def diamond_folds(alpha: float, rho1: ArrayLike) -> NDArray[np.float64]:
    """Fold angles (n, 6) of branch 'diamond' at inputs rho1 (n,): eqn 4-37, continuous through +-pi."""
    x = np.atleast_1d(np.asarray(rho1, dtype=float))
    rho2 = -2.0 * np.arctan2(np.sin(x / 2), np.cos(alpha) * np.cos(x / 2))
    return np.stack([x, rho2, rho2, x, rho2, rho2], -1)


class _Counter:
    """The polynomials of branch 'counter23' in u = tan(rho2/2) (see the module docstring)."""

    def __init__(self, alpha: float, k: float):
        self.c, C = np.cos(alpha), np.cos(2 * alpha)
        self.k = k
        self.n2, self.n0 = 2 * k**2 * C, k**2 + 2 * k - 1  # N(u) = n2 u^2 - n0
        self.d2, self.d0 = k**2 * (1 + 2 * C) + k, k - 1  # D(u) = d2 u^2 - d0 (< 0 on the branch)
        self.m0 = k**2 - 2 * k - 1  # rho4's numerator: n2 u^2 + m0
        self.e2 = k**2 + k * (1 + 2 * C)  # rho4's denominator: e2 u^2 + d0 (> 0)
        self.u_end = np.sqrt(self.d0 / self.d2)

    def rho1(self, u: NDArray) -> NDArray:
        """Input of the branch point u in (-u*, u*); decreasing from pi to -pi."""
        return 2.0 * np.arctan2(self.c * u * (self.n2 * u**2 - self.n0), self.d0 - self.d2 * u**2)

    @cached_property
    def _table(self) -> tuple[NDArray, NDArray]:
        """(rho1, u) at TABLE_SIZE values of u, spread as a cosine over [-u*, u*], rho1 increasing."""
        u = -self.u_end * np.cos(np.linspace(0.0, np.pi, TABLE_SIZE))
        return self.rho1(u)[::-1], u[::-1]

    def u_of(self, x: NDArray) -> NDArray:
        """u in [-u*, u*] of inputs x in [-pi, pi] (interpolated in `_table`, then Newton on the cubic)."""
        u = np.interp(x, *self._table)
        cs, sn = np.cos(x / 2), np.sin(x / 2)
        for _ in range(NEWTON_STEPS):
            g = self.c * cs * u * (self.n2 * u**2 - self.n0) + sn * (self.d2 * u**2 - self.d0)
            dg = self.c * cs * (3 * self.n2 * u**2 - self.n0) + 2 * sn * self.d2 * u
            step = np.divide(g, dg, out=np.zeros_like(g), where=dg != 0)
            u = np.clip(u - step, -self.u_end, self.u_end)
        return u

    def folds(self, x: NDArray) -> NDArray:
        """Fold angles (n, 6) at inputs x (n,) in [-pi, pi]."""
        u = self.u_of(x)
        rho2 = 2.0 * np.arctan(u)
        rho3 = 2.0 * np.arctan(-self.k * u)
        rho4 = 2.0 * np.arctan2(self.c * u * (self.n2 * u**2 + self.m0), self.e2 * u**2 + self.d0)
        return np.stack([x, rho2, rho3, rho4, rho3, rho2], -1)


class ThickDiamond(JointSpaceKinematics):
    """
    Thick six-crease diamond vertex (plane-symmetric Bricard linkage) driven by crease 1.

    Parameters
    ----------
    alpha : float
      Sector angle alpha12 = alpha34 = alpha45 = alpha61 (rad), in (0, pi/4].
    p, q, r : float
      Hinge spacings a12 = a61, a23 = a56, a34 = a45 (m), > 0, with r = p + q.
    """

    input_name = "rho1"
    joint_names = ("rho1", "rho2", "rho3", "rho4", "rho5", "rho6")

    def __init__(self, alpha: float, p: float, q: float, r: float):
        if not 0.0 < alpha <= np.pi / 4 + 1e-12:
            raise ParameterError(
                f"sector angle alpha = {np.rad2deg(alpha):.6g} deg; a flat-foldable diamond vertex needs "
                "0 < alpha <= 45 deg (sectors alpha, 180 - 2 alpha, alpha, alpha, 180 - 2 alpha, alpha, eqn 4-29)"
            )
        for name, value in (("p", p), ("q", q), ("r", r)):
            if not value > 0:
                raise ParameterError(f"hinge spacing {name} = {value:g} m; it must be positive")
        self.alpha, self.p, self.q, self.r = float(alpha), float(p), float(q), float(r)
        self.sectors = sectors(self.alpha)
        self.heights = hinge_heights(self.p, self.q, self.r)
        if abs(self.r - (self.p + self.q)) > CONDITION_TOL:
            residual = float(self.loop_system().residual_norm(diamond_folds(self.alpha, np.pi / 2))[0])
            raise ParameterError(
                f"hinge spacing r = {self.r:.9g} m but p + q = {self.p + self.q:.9g} m: a thick diamond vertex "
                "follows the zero-thickness fold only with r = p + q (Peng 2018, eqn 4-41c); otherwise the "
                f"Bricard loop moves along another curve (the closed form misses closure by {residual:.3g} "
                "at rho1 = pi/2)"
            )
        self._counter = _Counter(self.alpha, self.r / self.p)

    def branches(self) -> tuple[Branch, ...]:
        return (
            Branch(
                DIAMOND,
                "the zero-thickness diamond fold (eqns 4-30, 4-37): rho4 = rho1, rho2 = rho3 = rho5 = rho6, "
                "tan(rho1/2) + cos(alpha) tan(rho2/2) = 0; creases 1, 4 fold against 2, 3, 5, 6",
                (-np.pi, np.pi),
            ),
            Branch(
                COUNTER,
                "second plane-symmetric branch from flat: rho6 = rho2, rho5 = rho3, creases 2 and 3 fold in "
                "opposite senses, tan(rho3/2) = -(r/p) tan(rho2/2)",
                (-np.pi, np.pi),
            ),
        )

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        if branch == DIAMOND:
            values = diamond_folds(self.alpha, x)
        else:
            values = np.full((x.size, 6), np.nan)
            values[valid] = self._counter.folds(x[valid])
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        detail = "crease 1 folds flat (|rho1| = pi)"
        return (
            Event(
                "bifurcation",
                0.0,
                (DIAMOND, COUNTER),
                "flat state: the thick diamond keeps a second plane-symmetric branch (instantaneous mobility 2)",
            ),
            *(Event("lock", end, (name,), detail) for name in (DIAMOND, COUNTER) for end in (-np.pi, np.pi)),
        )

    def gruebler(self) -> int:
        """Kutzbach count of a single spatial loop of 6 revolute joints: 6 - 6."""
        return 0

    def loop_system(self) -> LoopSystem:
        """Rotations about the lifted hinge lines around the vertex."""
        return lifted_loop(self.sectors, self.heights)

    def loop_input(self) -> tuple[int, float]:
        return 0, 1.0
