"""The outcome of one check: a measured number against a tolerance."""

from dataclasses import dataclass


@dataclass(frozen=True)
class Verdict:
    """
    `passed` is `measured <= tolerance` over a comparison of `compared` values (samples, poses, steps): a check that
    compared none cannot pass (None: the check is no comparison of samples, e.g. a count of events). Units are in
    the name (e.g. angle_error_max_rad).
    """

    name: str
    measured: float
    tolerance: float
    detail: str = ""
    compared: int | None = None

    @property
    def passed(self) -> bool:
        return bool(self.measured <= self.tolerance) and self.compared != 0
