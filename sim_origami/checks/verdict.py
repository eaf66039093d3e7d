"""The outcome of one check: a measured number against a tolerance."""

from dataclasses import dataclass


@dataclass(frozen=True)
class Verdict:
    """`passed` is `measured <= tolerance`; units are in the name (e.g. angle_error_max_rad)."""

    name: str
    measured: float
    tolerance: float
    detail: str = ""

    @property
    def passed(self) -> bool:
        return bool(self.measured <= self.tolerance)
