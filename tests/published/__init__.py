"""The published numbers the tests check, one module per source document, and the corrections of printed equations.

Each `Number` holds one value as the document prints it (its precision visible in the text), the function that
computes ours from the package, the tolerance the test applies (the printed precision) and the test that checks
it. Each `Correction` holds a printed equation the code corrects, with the function that measures the residual of
the corrected and of the printed form. The tests read these entries (there is one copy of each published number)
and `scripts/results_doc.py` writes `docs/results.md` from them.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike


@dataclass(frozen=True)
class Number:
    """One published value (scalar or a row of values) and how the tests reproduce it.

    where: the figure, table or equation ("Table 4-1, case 10"); quantity: what it is, in words, with the input;
    printed: the values as printed, comma separated; ours: computes our values (same shape, same unit);
    tol: the largest difference the test accepts (half a unit of the printed last place, unless stated);
    test: the test function that checks it; unit: of printed and ours; angle: differences wrapped to one turn;
    strict: the test requires difference < tol rather than <= tol; truncated: the document truncates (does not
    round), so ours - printed must lie in [0, tol) and the difference is signed; a single printed value stands
    for every value of ours (e.g. every row of a tube); relative: the difference is |ours / printed - 1| (values
    printed to significant digits); in_text: the document prints this value
    (False: a worked value, the document's equations evaluated at its own geometry and rounded to the places
    shown, where the document gives the configuration only as a figure or a table of cases).
    """

    where: str
    quantity: str
    printed: str
    ours: Callable[[], ArrayLike]
    tol: float
    test: str
    unit: str = ""
    angle: bool = False
    strict: bool = False
    truncated: bool = False
    relative: bool = False
    in_text: bool = True

    @property
    def value(self) -> np.ndarray:
        """The printed values as floats."""
        return np.array([float(v) for v in self.printed.split(",")])

    def difference(self, ours: ArrayLike | None = None) -> float:
        """Largest |ours - printed| over the values, wrapped to one turn for angles."""
        got = np.atleast_1d(np.asarray(self.ours() if ours is None else ours, dtype=float))
        if self.value.size > 1 and got.shape != self.value.shape:
            raise ValueError(f"{self.where}: ours has shape {got.shape}, printed {self.value.shape}")
        d = got / self.value - 1 if self.relative else got - self.value
        if self.angle:
            turn = 360.0 if self.unit == "deg" else 2 * np.pi
            d = (d + turn / 2) % turn - turn / 2
        if self.truncated:  # signed: a negative difference fails
            return float(np.min(d)) if np.min(d) < 0 else float(np.max(d))
        return float(np.max(np.abs(d)))

    def check(self) -> float:
        """Assert that ours matches the printed values within tol; return the difference."""
        d = self.difference()
        if self.truncated:
            ok = 0 <= d < self.tol
        else:
            ok = d < self.tol if self.strict else d <= self.tol
        assert ok, f"{self.where}, {self.quantity}: ours differs from {self.printed} by {d:.3g} > {self.tol:g}"
        return d

    def __str__(self) -> str:
        return f"{self.where}: {self.quantity}"


@dataclass(frozen=True)
class Correction:
    """A printed equation the code corrects, with the residuals that prove it.

    where: the equation; printed / corrected: the two forms in words; measure: what the residual is (and where
    it is evaluated); residuals: computes (residual of the corrected form, residual of the printed form);
    test: the test function that checks both; closes: the corrected residual stays at or below it; fails: the
    printed residual exceeds it.
    """

    where: str
    printed: str
    corrected: str
    measure: str
    residuals: Callable[[], tuple[float, float]]
    test: str
    closes: float
    fails: float

    def check(self) -> tuple[float, float]:
        """Assert that the corrected form closes and the printed one does not; return both residuals."""
        fixed, printed = self.residuals()
        assert fixed <= self.closes, f"{self.where}: the corrected form leaves {fixed:.3g} > {self.closes:g}"
        assert printed > self.fails, f"{self.where}: the printed form leaves only {printed:.3g} <= {self.fails:g}"
        return fixed, printed

    def __str__(self) -> str:
        return f"{self.where}: {self.corrected}"


def checked_by(entries: tuple[Number | Correction, ...], test: str) -> list[Number | Correction]:
    """The entries whose test is `test`: a function name, or "file::function" where two test files share the name.
    Never empty and never from two files, so a renamed test cannot check nothing or someone else's numbers."""
    found = [e for e in entries if e.test == test or ("::" not in test and e.test.split("::")[-1] == test)]
    if not found:
        raise LookupError(f"no published entry names the test {test}")
    files = {e.test.split("::")[0] for e in found}
    if len(files) > 1:
        raise LookupError(f"{test} is a test in {sorted(files)}: name it as file::function")
    return found


def check_every(entries: tuple[Number | Correction, ...], test: str) -> None:
    """Check every entry whose test is `test` (for tests that check them among other things)."""
    for entry in checked_by(entries, test):
        entry.check()
