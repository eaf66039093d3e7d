"""Path error: simulated outputs against the closed form at the simulated input."""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ..geometry import wrap
from ..scenes.base import Scene


@dataclass(frozen=True)
class PathComparison:
    """Simulated and analytic outputs (n, k) at the simulated inputs (n,), radians."""

    input: NDArray[np.float64]
    simulated: NDArray[np.float64]
    analytic: NDArray[np.float64]

    @cached_property
    def error(self) -> NDArray[np.float64]:
        """|simulated - analytic| (n, k), modulo 2 pi; NaN where the input left the branch's domain."""
        return np.abs(wrap(self.simulated - self.analytic))

    def max_error(self) -> float:
        """Largest error over samples and joints (inf if the input ever left the domain)."""
        err = self.error
        return float(np.max(err)) if np.all(np.isfinite(err)) else float("inf")


def compare(scene: Scene, branch: str, q: NDArray[np.float64]) -> PathComparison:
    """Outputs measured from mechanism angles q (n, n_joints) against `branch`."""
    x = scene.input_of(q)
    analytic, _ = scene.kinematics.evaluate(branch, x)
    return PathComparison(x, scene.outputs(q), analytic)
