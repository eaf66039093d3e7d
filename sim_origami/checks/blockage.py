"""Blockage: where a force-limited drive stopped, against the kinematic contact angle."""

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray


@dataclass(frozen=True)
class Blockage:
    """Angles in radians (input units). `stopped` is False when the drive reached its target."""

    stop_input: float
    contact_input: float
    analytic_limit: float
    stopped: bool
    drive_saturated: bool

    @property
    def error(self) -> float:
        """
        |stop - kinematic contact| (rad); where the solids never touch on the way (contact nan), how far the
        drive fell short of the end, 0 when it got there.
        """
        if np.isnan(self.contact_input):
            return abs(self.stop_input - self.analytic_limit) if self.stopped else 0.0
        return abs(self.stop_input - self.contact_input)


def assess(
    input_sim: NDArray[np.float64],
    target: NDArray[np.float64],
    force: NDArray[np.float64],
    force_limit: float,
    contact_input: float,
    analytic_limit: float,
) -> Blockage:
    """The run stopped if its final input falls short of the final target by more than 1 mrad."""
    stop = float(input_sim[-1])
    stopped = bool(abs(target[-1] - stop) > 1e-3)
    saturated = bool(np.max(np.abs(force)) >= 0.999 * force_limit)
    return Blockage(stop, contact_input, analytic_limit, stopped, saturated)
