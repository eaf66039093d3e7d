"""The outcome of one check: a measured number against a tolerance."""

from dataclasses import dataclass, field


@dataclass(frozen=True)
class Verdict:
    """
    `passed` is `measured <= tolerance` over a comparison of `compared` values (samples, poses, steps): a check that
    compared none cannot pass (None: the check is no comparison of samples, e.g. a count of events). Units are in
    the name (e.g. angle_error_max_rad).

    `id` is the check's kind, short kebab-case and stable across releases (report.json's `verdicts[].id`): code and
    tests find a check by it, never by its display `name`, which may change. Each kind's id is a constant beside the
    code that makes it (e.g. `validation.SWEPT_RANGE`). `branch` is the branch the check is about, "" for a check of
    the whole scene.
    """

    name: str
    measured: float
    tolerance: float
    detail: str = ""
    compared: int | None = None
    id: str = field(kw_only=True)
    branch: str = field(default="", kw_only=True)

    @property
    def passed(self) -> bool:
        return bool(self.measured <= self.tolerance) and self.compared != 0
