"""The RSSR linkage, the Bennett linkage's non-overconstrained form (Yang 2017 §2.2). Numpy only.

R joints at A (axis z_A) and B (z_B), ball joints at C and D; AB = CD = a1 (AB is the
common normal of z_A and z_B, twist alpha), BC = DA = a2 with BC normal to z_B and DA normal to z_A. In the D-H
frame of joint A (x along AB at theta1 = 0): D = (-a2, 0, 0), B = T12 origin, C = T12 T23 origin, and the
loop closes when |CD| = a1, i.e. (3-3)

    a1 (cos th1 + cos th2) + a2 (cos th1 cos th2 + 1 - cos(alpha) sin th1 sin th2) = 0.

With x2 = a1 / a2, (3-4) A = cos(alpha) sin th1, B = -cos th1 - x2, C = 1 + x2 cos th1 and (3-5)
th2 = 2 arctan[(A +- sqrt(A^2 + B^2 - C^2)) / (B + C)]. Exactly A^2 + B^2 - C^2 = sin^2 th1 (x2^2 - sin^2 alpha)
and B + C = (1 - cos th1)(1 - x2), so (3-5) is tan(th1/2) tan(th2/2) = K with

    K = (cos(alpha) + sigma sqrt(x2^2 - sin^2 alpha)) / (1 - x2),   sigma = sign(sin th1 cos beta) x (+-),

the two roots of the key identity (b - a) T^2 - 2 b cos(alpha) T + (a + b) = 0 (derived and checked here, not
stated in Yang 2017): the RSSR moves exactly like the Bennett linkage with beta = arcsin(a2 sin(alpha) / a1),
K = sin((beta + alpha)/2) / sin((beta - alpha)/2) (3-6a). The Bennett branch ('+' where sin th1 cos beta > 0,
Yang 2017 §2.2) is the root sigma = +1 for an acute implied beta; a fabrication error keeps the root of its
nominal design (continuity: the roots only meet at x2 = sin(alpha), where the RSSR stops being assemblable).
th2 = 2 atan2(K cos(th1/2), sin(th1/2)) is then smooth over the whole input circle (th2 = +-pi at th1 = 0 for
every K).

Units: angles in radians; lengths in any one unit.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import AssemblyError, ParameterError
from .dh import DHRow

# 1 - x2 below this: a1 = a2, where the Bennett branch degenerates (beta = alpha, K infinite).
EQUAL_LENGTH_TOL = 1e-12


def positive_length(name: str, value: float) -> float:
    """`value` as a float; ParameterError unless it is a positive finite length."""
    if not (np.isfinite(value) and value > 0):
        raise ParameterError(f"{name} = {value!r}; it must be a positive finite length")
    return float(value)


@dataclass(frozen=True)
class RSSR:
    """
    An RSSR linkage (module docstring): a1 = AB = CD, a2 = BC = DA (one length unit), alpha the twist of AB (rad,
    in (0, pi)), root +1 for the Bennett branch (3-6a) with an acute implied beta, -1 for (3-6b).

    Raises ParameterError for bad values or a1 = a2, AssemblyError when a2 sin(alpha) > a1 (no configuration).
    """

    a1: float
    a2: float
    alpha: float
    root: int = 1

    def __post_init__(self):
        positive_length("a1", self.a1)
        positive_length("a2", self.a2)
        if not (np.isfinite(self.alpha) and 0 < self.alpha < np.pi):
            raise ParameterError(f"twist alpha = {self.alpha!r} rad; it must lie in (0, pi)")
        if self.root not in (1, -1):
            raise ParameterError(f"root = {self.root!r}; it must be +1 (3-6a) or -1 (3-6b)")
        if abs(1 - self.x2) < EQUAL_LENGTH_TOL:
            raise ParameterError(f"a1 = a2 = {self.a1:g}: the Bennett branch degenerates (beta = alpha, K infinite)")
        if self.x2 < np.sin(self.alpha):
            raise AssemblyError(
                f"a2 sin(alpha) = {self.a2 * np.sin(self.alpha):.9g} > a1 = {self.a1:.9g}: (3-3) has no real "
                f"solution (A^2 + B^2 - C^2 = sin^2(theta1) (x2^2 - sin^2 alpha) < 0), the RSSR cannot be assembled"
            )

    @property
    def x2(self) -> float:
        """a1 / a2, Yang 2017's second design variable (§3.5)."""
        return self.a1 / self.a2

    @property
    def beta(self) -> float:
        """Implied Bennett twist (rad): arcsin(a2 sin(alpha) / a1) on root +1, pi minus that on root -1 (3-38)."""
        acute = float(np.arcsin(min(1.0, np.sin(self.alpha) / self.x2)))
        return acute if self.root == 1 else np.pi - acute

    @property
    def K(self) -> float:  # noqa: N802  (Yang 2017's K of (3-6a), as in kinematics.bennett)
        """tan(theta1/2) tan(theta2/2) on this root: (cos alpha + root sqrt(x2^2 - sin^2 alpha)) / (1 - x2)."""
        r = np.sqrt(self.x2**2 - np.sin(self.alpha) ** 2)
        return float((np.cos(self.alpha) + self.root * r) / (1 - self.x2))

    def coefficients(self, theta1: ArrayLike) -> tuple[NDArray, NDArray, NDArray]:
        """(A, B, C) of (3-4) at inputs theta1 (rad)."""
        t = np.asarray(theta1, dtype=float)
        return np.cos(self.alpha) * np.sin(t), -np.cos(t) - self.x2, 1 + self.x2 * np.cos(t)

    def theta2(self, theta1: ArrayLike) -> NDArray[np.float64]:
        """Exact output (3-5) on this root (rad, smooth over the circle; see the module docstring)."""
        t = np.asarray(theta1, dtype=float)
        return 2 * np.arctan2(self.K * np.cos(t / 2), np.sin(t / 2))

    def io_residual(self, theta1: ArrayLike, theta2: ArrayLike) -> NDArray[np.float64]:
        """(3-3) divided by a2 (dimensionless): zero on every configuration of the RSSR."""
        t1, t2 = np.asarray(theta1, dtype=float), np.asarray(theta2, dtype=float)
        c1, c2 = np.cos(t1), np.cos(t2)
        return self.x2 * (c1 + c2) + c1 * c2 + 1 - np.cos(self.alpha) * np.sin(t1) * np.sin(t2)

    def sensitivity(self, theta1: ArrayLike) -> tuple[NDArray, NDArray]:
        """(d theta2 / d x1, d theta2 / d x2) of (3-42) (rad per rad, rad per unit x2) at inputs theta1 (rad)."""
        t = np.asarray(theta1, dtype=float)
        s, c, x2, sa, ca = np.sin(self.alpha), np.cos(self.alpha), self.x2, np.sin(t / 2), np.cos(t / 2)
        r = np.sqrt(x2**2 - s**2)
        dK1 = (-s - self.root * s * c / r) / (1 - x2)
        dK2 = (self.root * x2 / r + self.K) / (1 - x2)
        dth = np.sin(t) / (sa**2 + (self.K * ca) ** 2)  # d theta2 / d K
        return dth * dK1, dth * dK2

    def bennett_rows(self) -> tuple[DHRow, ...]:
        """D-H rows of the implied Bennett linkage, whose motion the RSSR follows exactly (key identity)."""
        a1, a2, al, be = self.a1, self.a2, self.alpha, self.beta
        return (DHRow(0.0, a1, al), DHRow(0.0, a2, be), DHRow(0.0, a1, al), DHRow(0.0, a2, be))

    def loop_angles(self, theta1: ArrayLike) -> NDArray[np.float64]:
        """(n, 4) angles of the implied Bennett's D-H loop: theta1, theta2, -theta1, -theta2 (rad)."""
        t = np.atleast_1d(np.asarray(theta1, dtype=float))
        t2 = self.theta2(t)
        return np.stack([t, t2, -t, -t2], -1)
