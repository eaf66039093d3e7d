"""Patterns of flat-foldable vertices held in fixed modes: every crease folds as tan(rho_i/2) = k_i tan(x/2).

On such a branch (the mode multipliers of Peng 2018, §3.2.1, chained over the pattern) each fold angle is a fixed
tan-half multiple of the input x, so the whole pattern folds flat together at x = +-pi. Subclasses set `ratios`: branch
name -> (n_creases,) multipliers k_i (k_input = 1), in their loop-joint order.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .base import JointSpaceKinematics


class FixedModeKinematics(JointSpaceKinematics):
    """Branches whose folds are tan-half multiples of the input; domain [-pi, pi] (module docstring)."""

    ratios: dict[str, NDArray[np.float64]]

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        # tan(rho/2) = k tan(x/2) written as an angle: finite at x = +-pi, where every crease reaches +-pi
        values = 2.0 * np.arctan2(np.outer(np.sin(x / 2), self.ratios[branch]), np.cos(x / 2)[:, None])
        values[~valid] = np.nan
        return values, valid
