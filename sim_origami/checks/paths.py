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
    """
    Outputs measured from mechanism angles q (n, n_joints) against `branch`. With several driven joints, the
    reference holds them where q has them: their dynamic lags differ, so they leave the drive path a little, and
    the reference at the path's nearest point would count that tracking gap, geared up by the mechanism, as error
    (docs/fold_motion.md, the waterbomb cell driven by five creases).
    """
    x = scene.input_of(q)
    if scene.drive_path is None:
        analytic, _ = scene.kinematics.evaluate(branch, x)
    else:
        joints, _ = scene.kinematics.loop_inputs(x[:1])
        analytic, _ = scene.kinematics.evaluate_held(branch, x, scene.mechanism_to_loop(q)[:, list(joints)])
    return PathComparison(x, scene.outputs(q), analytic)
