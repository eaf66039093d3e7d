"""Myard 5R linkage (Yang 2017, eqns 1-19/1-20; Peng 2018, §4.3).

D-H rows (Yang 2017's convention, eqn 1-19): a_12 = a_51 = a_23 sin(alpha12), a_23 = a_45, a_34 = 0;
alpha_23 = alpha_45 = pi/2, alpha_51 = pi - alpha12, alpha_34 = pi - 2 alpha12; all R = 0.
Closure (eqn 1-20): theta1 + theta3 + theta4 = 2 pi, theta2 + theta5 = 2 pi,
tan(theta4/2) tan(theta5/2) = K, tan(theta2/2) = K tan(theta3/2), K = sin((pi/2 + alpha12)/2) / sin((pi/2 - alpha12)/2);
hence theta4 = theta3 + pi and theta1 = pi - 2 theta3 (derived here).

The input is theta3 (chosen here): every other joint is a single-valued, smooth function of it,
whereas theta1 = pi - 2 theta3 meets each value twice per cycle. theta2 is written as
2 atan2(K sin(theta3/2), cos(theta3/2)), continuous over the whole input circle, and theta5 = -theta2
(eqn 1-20 writes theta2 + theta5 = 2 pi). The motion is fully rotatable: one assembly per input
(random-start solves) and closure Jacobian rank 4 along the whole circle, so the single branch
'plane_symmetric' has domain [-pi, pi] and no bifurcation, lock or turning point. Along it, axis 1
lies in a mirror plane that swaps axes 2 <-> 5 and 3 <-> 4 (measured to 1e-15).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ParameterError
from .base import Branch, Event
from .dh import DHKinematics, DHRow

BRANCH = "plane_symmetric"


class Myard(DHKinematics):
    """
    Myard linkage driven by theta3.

    Parameters
    ----------
    a23 : float
      Link length a_23 = a_45 (m), > 0; a_12 = a_51 = a23 sin(alpha12), a_34 = 0.
    alpha12 : float
      Twist alpha_12 (rad), in (0, pi/2): at 0 links 12 and 51 vanish, at pi/2 axes 3 and 4 coincide
      (alpha_34 = 0) and K is infinite.
    """

    input_name = "theta3"
    input_joint = 3
    joint_names = ("theta1", "theta2", "theta3", "theta4", "theta5")

    def __init__(self, a23: float, alpha12: float):
        if not a23 > 0:
            raise ParameterError(f"link length a23 = {a23:g} m; it must be positive")
        if not 0 < alpha12 < np.pi / 2:
            raise ParameterError(
                f"twist alpha12 = {np.rad2deg(alpha12):.6g} deg; it must lie in (0, 90) deg "
                "(a12 = a23 sin(alpha12) > 0 and alpha34 = 180 - 2 alpha12 > 0)"
            )
        self.a23, self.alpha12 = float(a23), float(alpha12)
        self.a12 = self.a23 * np.sin(self.alpha12)
        self.K = np.sin((np.pi / 2 + alpha12) / 2) / np.sin((np.pi / 2 - alpha12) / 2)

    @property
    def rows(self) -> tuple[DHRow, ...]:
        """D-H rows of joints 1..5 (eqn 1-19)."""
        a12, a23, al = self.a12, self.a23, self.alpha12
        return (
            DHRow(0.0, a12, al),
            DHRow(0.0, a23, np.pi / 2),
            DHRow(0.0, 0.0, np.pi - 2 * al),
            DHRow(0.0, a23, np.pi / 2),
            DHRow(0.0, a12, np.pi - al),
        )

    def branches(self) -> tuple[Branch, ...]:
        return (
            Branch(
                BRANCH,
                "the single, fully rotatable motion of the Myard linkage (eqn 1-20); axis 1 stays in the plane "
                "of symmetry that mirrors axes 2 <-> 5 and 3 <-> 4",
                (-np.pi, np.pi),
            ),
        )

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        t3, valid = self.in_domain(branch, x)
        t2 = 2 * np.arctan2(self.K * np.sin(t3 / 2), np.cos(t3 / 2))
        values = np.stack([np.pi - 2 * t3, t2, t3, t3 + np.pi, -t2], -1)
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        return ()
