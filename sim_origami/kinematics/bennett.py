"""Bennett 4R linkage (Yang 2017, eqns 1-17/1-18; Peng 2018, §4.2).

D-H rows (the theses' convention: Yang 2017, eqn 1-2): a_12 = a_34 = a, a_23 = a_41 = b; alpha_12 = alpha_34 = alpha,
alpha_23 = alpha_41 = beta; all R = 0; Bennett condition sin(alpha)/a = sin(beta)/b.
Closure: tan(theta1/2) tan(theta2/2) = K = sin((beta + alpha)/2) / sin((beta - alpha)/2),
theta3 = -theta1, theta4 = -theta2 (mod 2 pi; eqn 1-18 writes theta1 + theta3 = 2 pi).

theta2 is written as 2 atan2(K cos(theta1/2), sin(theta1/2)), continuous over the whole input circle
(it passes pi at theta1 = 0), so the single branch 'bennett' has domain [-pi, pi] and no bifurcation.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import AssemblyError, ParameterError
from .base import Branch, Event
from .dh import DHKinematics, DHRow

# |a sin(beta) - b sin(alpha)| above this (m) breaks the Bennett condition.
CONDITION_TOL = 1e-9


class Bennett(DHKinematics):
    """
    Bennett linkage driven by theta1.

    Parameters
    ----------
    a, b : float
      Link lengths a_12 = a_34 and a_23 = a_41 (m), > 0.
    alpha, beta : float
      Twists alpha_12 = alpha_34 and alpha_23 = alpha_41 (rad), in (0, pi), alpha != beta.
    check : bool
      Refuse parameters that break the Bennett condition with AssemblyError naming the loop's
      closure residual (MuJoCo would silently run a compromise motion, measured here).
    """

    input_name = "theta1"
    joint_names = ("theta1", "theta2", "theta3", "theta4")

    def __init__(self, a: float, alpha: float, b: float, beta: float, *, check: bool = True):
        for name, value in (("a", a), ("b", b)):
            if not value > 0:
                raise ParameterError(f"link length {name} = {value:g} m; it must be positive")
        for name, value in (("alpha", alpha), ("beta", beta)):
            if not 0 < value < np.pi:
                raise ParameterError(f"twist {name} = {np.rad2deg(value):.6g} deg; it must lie in (0, 180) deg")
        if abs(alpha - beta) < 1e-12:
            raise ParameterError("alpha = beta: K = sin((beta + alpha)/2) / sin((beta - alpha)/2) is infinite")
        self.a, self.alpha, self.b, self.beta = float(a), float(alpha), float(b), float(beta)
        self.K = np.sin((beta + alpha) / 2) / np.sin((beta - alpha) / 2)
        gap = a * np.sin(beta) - b * np.sin(alpha)
        if check and abs(gap) > CONDITION_TOL:
            residual = float(self.loop_system().residual_norm(self.evaluate("bennett", 1.0)[0])[0])
            closing = np.rad2deg(np.arcsin(min(1.0, b * np.sin(alpha) / a)))
            raise AssemblyError(
                f"this 4R cannot be assembled as a Bennett linkage: sin(alpha)/a = {np.sin(alpha) / a:.9g} but "
                f"sin(beta)/b = {np.sin(beta) / b:.9g} 1/m; the loop misses closure by {residual:.3g} at "
                f"theta1 = 1 rad (beta = {closing:.9g} deg would close it)"
            )

    @property
    def rows(self) -> tuple[DHRow, ...]:
        """D-H rows of joints 1..4."""
        a, b, al, be = self.a, self.b, self.alpha, self.beta
        return (DHRow(0.0, a, al), DHRow(0.0, b, be), DHRow(0.0, a, al), DHRow(0.0, b, be))

    def branches(self) -> tuple[Branch, ...]:
        return (Branch("bennett", "the single motion of the Bennett linkage (eqn 1-18)", (-np.pi, np.pi)),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        t1, valid = self.in_domain(branch, x)
        t2 = 2 * np.arctan2(self.K * np.cos(t1 / 2), np.sin(t1 / 2))
        values = np.stack([t1, t2, -t1, -t2], -1)
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        return ()
