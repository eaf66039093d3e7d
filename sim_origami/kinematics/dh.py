"""Denavit-Hartenberg loops in the sources' convention (Yang 2017, eqn 1-2; Feng 2018, eqns 2-1 to 2-5).

T_(i,i+1) = Rz(theta_i) Tz(R_i) Tx(a_(i,i+1)) Rx(alpha_(i,i+1)); the loop closes when the product of
all rows is the identity. A row holds the constant part (R_i, a_(i,i+1), alpha_(i,i+1)) of joint i.
"""

from dataclasses import dataclass

import numpy as np

from ..closure import Loop, LoopSystem
from ..geometry import rot_x, signed_angle, transform
from .base import JointSpaceKinematics


@dataclass(frozen=True)
class DHRow:
    """Offset R along z_i, length a and twist alpha to the next joint (metres, radians)."""

    R: float
    a: float
    alpha: float

    def link(self) -> np.ndarray:
        """Tz(R) Tx(a) Rx(alpha), (4, 4): joint i's frame (after Rz(theta_i)) to joint i+1's."""
        return transform(None, [self.a, 0.0, self.R]) @ transform(rot_x(self.alpha))


def dh_loop(rows: tuple[DHRow, ...]) -> LoopSystem:
    """The closed chain Rz(theta_1) L_1 ... Rz(theta_n) L_n = I over joints 1..n."""
    links = np.stack([r.link() for r in rows])
    return LoopSystem(len(rows), (Loop(tuple(range(len(rows))), links, (1,) * len(rows)),))


class DHKinematics(JointSpaceKinematics):
    """
    A single D-H loop whose joint angles are the outputs theta1..thetan. Subclasses give `rows`
    and `input_joint` (1-based, default 1); the Kutzbach count of one spatial loop is n - 6.
    """

    input_joint: int = 1
    rows: tuple[DHRow, ...]

    def loop_system(self) -> LoopSystem:
        return dh_loop(self.rows)

    def loop_input(self) -> tuple[int, float]:
        return self.input_joint - 1, 1.0

    def gruebler(self) -> int:
        return len(self.rows) - 6


def dh_from_axes(points: np.ndarray, dirs: np.ndarray) -> tuple[tuple[DHRow, ...], np.ndarray]:
    """
    D-H rows and joint angles of a closed loop of revolute axes (Yang 2017, eqns 1-2, 1-3: x_(i+1) along the
    common normal from z_i to z_(i+1)).

    Parameters
    ----------
    points, dirs : (n, 3) float
      A point on each axis and its unit direction, in loop order.

    Returns
    -------
    rows : D-H rows of joints 1..n; angles : (n,) theta_i of this configuration (rad).
    """
    P, s = np.asarray(points, float), np.asarray(dirs, float)
    s = s / np.linalg.norm(s, axis=1, keepdims=True)
    n = len(P)
    foot_out, foot_in, x_axis, a, alpha = [None] * n, [None] * n, [None] * n, np.zeros(n), np.zeros(n)
    for i in range(n):
        j = (i + 1) % n
        w, b = P[i] - P[j], s[i] @ s[j]
        d, e, den = s[i] @ w, s[j] @ w, 1.0 - b * b
        if den < 1e-12:
            raise ValueError(f"axes {i + 1} and {j + 1} are parallel: their common normal is not unique")
        foot_out[i] = P[i] + (b * e - d) / den * s[i]
        foot_in[j] = P[j] + (e - b * d) / den * s[j]
        gap = foot_in[j] - foot_out[i]
        a[i] = np.linalg.norm(gap)
        x_axis[j] = gap / a[i] if a[i] > 1e-12 else np.cross(s[i], s[j]) / np.linalg.norm(np.cross(s[i], s[j]))
        alpha[i] = float(signed_angle(s[i], s[j], x_axis[j]))  # both axes are normal to x
    theta = np.array([float(signed_angle(x_axis[i], x_axis[(i + 1) % n], s[i])) for i in range(n)])
    R = np.array([(foot_out[i] - foot_in[i]) @ s[i] for i in range(n)])
    return tuple(DHRow(float(R[i]), float(a[i]), float(alpha[i])) for i in range(n)), theta
