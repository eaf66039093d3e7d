"""Denavit-Hartenberg loops in the seeds' convention (seed 001 §2.0, seed 000 §1.1).

T_(i,i+1) = Rz(theta_i) Tz(R_i) Tx(a_(i,i+1)) Rx(alpha_(i,i+1)); the loop closes when the product of
all rows is the identity. A row holds the constant part (R_i, a_(i,i+1), alpha_(i,i+1)) of joint i.
"""

from dataclasses import dataclass

import numpy as np

from ..closure import Loop, LoopSystem
from ..geometry import rot_x, transform


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
