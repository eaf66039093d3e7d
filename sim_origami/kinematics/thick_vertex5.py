"""Thick-panel five-crease symmetric vertex = Myard linkage (Peng 2018, §4.3).

Sectors (eqn 4-10): alpha12 = alpha51 = alpha, alpha23 = alpha45 = pi/2, alpha34 = pi - 2 alpha, 0 < alpha < pi/2.
Hinge k lies on the line through (0, 0, h_k) along its flat crease direction d_k with
h = (0, a12, a12 + a23, a12 + a23, a12) (reconstructed here): hinges 3 and 4 at one height (a34 = 0) and
a12 = a23 sin(alpha) (eqn 4-25c); b = a23 is the thickness scale. Any other a12 leaves the 5R rigid
(Kutzbach 5 - 6 = -1): with alpha = pi/6 (Fig 4-8) and a23 = 1, a12 = 0.7 misses closure by 0.2 at rho1 = pi/2.

Closed form. The hinge angles q are the fold angles of the zero-thickness vertex's plane-symmetric motion
(eqn 4-11: rho4 = rho3, rho5 = rho2), verified by the PoE closure. With the corrected (4-20)/(4-21b),

    tan^2(rho2/2) - 2 K tan(rho2/2) / tan(rho1/2) - K^2 = 0,   K = cos(alpha) / (1 - sin(alpha)) = tan(pi/4 + alpha/2)

(K^2 = (1 + sin(alpha)) / (1 - sin(alpha))), whose root through the flat state is tan(rho2/2) = -K tan(rho1/4),
and (4-18) tan(rho3/2) = tan(rho2/2) / K gives rho3 = -rho1/2. So along the single branch

    rho2 = rho5 = -2 atan(K tan(rho1/4)),   rho3 = rho4 = -rho1/2,

smooth on rho1 in [-pi, pi], where crease 1 folds flat (panels 5 and 1 face to face: a lock). The motion is
odd in rho1, so the mirrored heights -h close the same angles. Unlike the zero-thickness vertex (2 DOF,
instantaneous mobility 3 at flat), the thick loop has mobility 1 everywhere: no bifurcation at flat.

Corrected here: Peng 2018's printed (4-20) (t2/(2 t1) for 2 t2/t1; (4-21b) with 2 t2/t1 closes to 4e-13) and the middle
signs of (4-23c)/(4-28c) are wrong ((4-23c) as printed: error 6.0, corrected 5e-13), and (4-26b,c) hold only with alpha
the sector angle alpha12 (not alpha12^My = pi - alpha12); the tests prove each by a closure residual. The Myard of
(4-24) is Yang 2017's eqn 1-19 with alpha12 = pi - alpha.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Loop, LoopSystem
from ..errors import AssemblyError, ParameterError
from ..geometry import frame_along, invert
from .base import Branch, Event, JointSpaceKinematics

BRANCH = "plane_symmetric"
# |a12 - a23 sin(alpha)| above this (m) breaks the Myard condition (4-25c).
CONDITION_TOL = 1e-9


def sectors(alpha: float) -> NDArray[np.float64]:
    """Sector angles (5,) alpha12 ... alpha51 of the symmetric five-crease vertex (eqn 4-10)."""
    return np.array([alpha, np.pi / 2, np.pi - 2 * alpha, np.pi / 2, alpha])


def hinge_heights(a12: float, a23: float) -> NDArray[np.float64]:
    """Heights (5,) of the hinge lines above the sheet (m), reconstructed here."""
    return np.array([0.0, a12, a12 + a23, a12 + a23, a12])


def lifted_loop(alpha: ArrayLike, heights: ArrayLike) -> LoopSystem:
    """
    Rotations about the lifted hinge lines, F_k Rz(q_k) inv(F_k), around the vertex (PoE closure).

    F_k is the frame on the line through (0, 0, heights[k]) along the flat crease direction d_k.
    """
    alpha, heights = np.asarray(alpha, dtype=float), np.asarray(heights, dtype=float)
    n = len(alpha)
    angles = np.concatenate([[0.0], np.cumsum(alpha)[:-1]])
    frames = [frame_along((np.cos(t), np.sin(t), 0.0), (0.0, 0.0, h)) for t, h in zip(angles, heights, strict=True)]
    links = np.stack([invert(frames[k]) @ frames[(k + 1) % n] for k in range(n)])
    return LoopSystem(n, (Loop(tuple(range(n)), links, (1,) * n),))


def plane_symmetric_folds(alpha: float, rho1: ArrayLike) -> NDArray[np.float64]:
    """Fold angles (n, 5) of the plane-symmetric motion at inputs rho1 (n,), no domain check."""
    x = np.atleast_1d(np.asarray(rho1, dtype=float))
    K = np.cos(alpha) / (1.0 - np.sin(alpha))
    rho2 = -2.0 * np.arctan(K * np.tan(x / 4))
    return np.stack([x, rho2, -x / 2, -x / 2, rho2], -1)


class ThickVertex5(JointSpaceKinematics):
    """
    Thick symmetric five-crease vertex (Myard linkage) driven by crease 1.

    Parameters
    ----------
    alpha : float
      Sector angle alpha12 = alpha51 (rad), in (0, pi/2).
    b : float
      Thickness scale (m): a23 = a45 = b, the distance between hinges 2 and 3 (and 4 and 5).
    a12 : float, optional
      Distance between hinges 1 and 2 (m); default b sin(alpha), the only value that moves.
      Another value raises AssemblyError naming the closure residual.
    """

    input_name = "rho1"
    joint_names = ("rho1", "rho2", "rho3", "rho4", "rho5")

    def __init__(self, alpha: float, b: float, a12: float | None = None):
        if not 0.0 < alpha < np.pi / 2:
            raise ParameterError(
                f"sector angle alpha = {np.rad2deg(alpha):.6g} deg; it must lie in (0, 90) deg "
                "(sectors alpha, 90, 180 - 2 alpha, 90, alpha deg, eqn 4-10)"
            )
        if not b > 0:
            raise ParameterError(f"thickness scale b = {b:g} m; it must be positive")
        self.alpha, self.b = float(alpha), float(b)
        self.a23 = self.b
        self.a12 = self.b * np.sin(self.alpha) if a12 is None else float(a12)
        if not self.a12 > 0:
            raise ParameterError(f"hinge spacing a12 = {self.a12:g} m; it must be positive")
        self.sectors = sectors(self.alpha)
        self.heights = hinge_heights(self.a12, self.a23)
        want = self.a23 * np.sin(self.alpha)
        if abs(self.a12 - want) > CONDITION_TOL:
            q = plane_symmetric_folds(self.alpha, np.pi / 2)
            residual = float(self.loop_system().residual_norm(q)[0])
            raise AssemblyError(
                f"this thick five-crease vertex cannot move as a Myard linkage: a12 = {self.a12:.9g} m but "
                f"a23 sin(alpha) = {want:.9g} m (Peng 2018, eqn 4-25c); the loop misses closure by {residual:.3g} "
                "at rho1 = pi/2"
            )

    def branches(self) -> tuple[Branch, ...]:
        text = (
            "the single motion of the thick Myard vertex: plane-symmetric about crease 1 (rho5 = rho2, "
            "rho4 = rho3 = -rho1/2, tan(rho2/2) = -K tan(rho1/4)); no bifurcation at flat"
        )
        return (Branch(BRANCH, text, (-np.pi, np.pi)),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        values = plane_symmetric_folds(self.alpha, x)
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        detail = "crease 1 folds flat (|rho1| = pi): panels 5 and 1 face to face"
        return (Event("lock", -np.pi, (BRANCH,), detail), Event("lock", np.pi, (BRANCH,), detail))

    def gruebler(self) -> int:
        """Kutzbach count of a single spatial loop of 5 revolute joints: 5 - 6."""
        return -1

    def loop_system(self) -> LoopSystem:
        """Rotations about the lifted hinge lines around the vertex."""
        return lifted_loop(self.sectors, self.heights)

    def loop_input(self) -> tuple[int, float]:
        return 0, 1.0
