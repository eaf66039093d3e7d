"""
Numbers as people type them: the precision a printed number carries, and the nearest exact model within it.

A value printed as '48.5904' stands for any value within half a unit in its last digit (5e-5): a measurement, or
the rounding of the tool that wrote it. Exact conditions (the Bennett condition, the closure of a loop) are tested
against that precision: where the values as typed lie within their precision of a model that meets the condition
exactly, that nearest model is validated and every value it moved is reported (`Adjustment`).

The nearest model is the least-squares projection onto the conditions in units of each value's precision: it
minimises sum(((p_i - typed_i) / precision_i)^2) subject to c(p) = 0, so the values typed with the fewest digits
move the most. It is within the input's precision when no value moves by more than its own precision.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

# Exact values as the API takes them: a float is held to a few units in its last place.
EXACT_ULPS = 4.0
# Gauss-Newton steps of the projection; it converges quadratically from within the precision.
PROJECTION_STEPS = 30
# Central differences of a condition step each value by this fraction of its size (or precision, if larger).
DIFFERENCE_STEP = 1e-6


def half_unit(text: str) -> float:
    """Half a unit in the last printed digit of a number as written ('12.50' -> 0.005, '1.5e-3' -> 5e-5); inf or 0
    where that is beyond a float ('0e400', an exponent of thousands of digits)."""
    mantissa, _, exponent = text.strip().lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    if len(exponent.lstrip("+-").lstrip("0")) > 5:  # beyond every float, and int() refuses over 4,300 digits
        return 0.0 if exponent.startswith("-") else np.inf
    power = (int(exponent) if exponent else 0) - decimals
    return 0.5 * 10.0**power if power <= 308 else np.inf  # 10.0 ** 309 raises OverflowError


def exact_precision(value: ArrayLike) -> NDArray[np.float64]:
    """The precision of values given as exact floats: EXACT_ULPS units in their last place."""
    return EXACT_ULPS * np.spacing(np.abs(np.asarray(value, dtype=float)))


class Typed(float):
    """A float as typed, carrying `precision`: half a unit in its last printed digit, in the same unit."""

    precision: float

    def __new__(cls, text: str) -> "Typed":
        number = super().__new__(cls, text)
        number.precision = half_unit(text)
        return number


@dataclass(frozen=True)
class Adjustment:
    """
    One value the nearest exact model moved.

    `given` and `value` are what was typed and what was validated, `precision` the typed value's precision, all in
    `unit` (the unit the user gave it in: deg, m, or the file's own).
    """

    name: str
    given: float
    value: float
    precision: float
    unit: str

    @property
    def moved(self) -> float:
        """How far the value moved, in `unit`."""
        return self.value - self.given

    @property
    def ratio(self) -> float:
        """How far it moved as a fraction of its precision (<= 1: within what its printing allows)."""
        return abs(self.moved) / self.precision if self.precision > 0 else np.inf

    def text(self) -> str:
        """One line: 'beta 48.5904 -> 48.5903779 deg (moved -2.2e-05 deg, 0.44 of its precision 5e-05)'."""
        unit = f" {self.unit}" if self.unit else ""
        return (f"{self.name} {self.given:.10g} -> {self.value:.10g}{unit} (moved {self.moved:.2g}{unit}, "
                f"{self.ratio:.2g} of its precision {self.precision:.2g})")

    def as_dict(self) -> dict[str, float | str]:
        """JSON form: the values in the user's unit, with the move and its ratio to the precision."""
        return {"name": self.name, "given": self.given, "value": self.value, "moved": self.moved,
                "precision": self.precision, "ratio": self.ratio, "unit": self.unit}


@dataclass(frozen=True)
class Projection:
    """The nearest exact model: `values` with `residual` = |c(values)| left, `ratio` the largest move over its
    precision (<= 1: within the input's precision)."""

    values: NDArray[np.float64]
    residual: float
    ratio: float


def nearest_exact(
    condition: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    given: ArrayLike,
    precision: ArrayLike,
    tol: float,
) -> Projection:
    """
    The values nearest `given` in units of `precision` at which `condition` (vector, zero when exact) is below `tol`.

    Minimum-norm Gauss-Newton in the scaled values z = (p - given) / precision: each step solves the linearised
    condition for the least z (the pseudo-inverse of the scaled Jacobian, by central differences), which converges to
    the projection for residuals small against the condition's curvature. A value of precision 0 is held.
    """
    p0 = np.asarray(given, dtype=float)
    scale = np.asarray(precision, dtype=float)
    free = scale > 0
    z = np.zeros_like(p0)
    best = Projection(p0, float(np.linalg.norm(condition(p0))), 0.0)
    for _ in range(PROJECTION_STEPS):
        p = p0 + z * scale
        r = np.atleast_1d(condition(p))
        norm = float(np.linalg.norm(r))
        if norm < best.residual or norm <= tol:
            best = Projection(p, norm, float(np.max(np.abs(z), initial=0.0)))
        if norm <= tol:
            break
        J = np.zeros((len(r), len(p0)))
        for i in np.flatnonzero(free):
            # The derivative in the value's own unit, then scaled: a precision of a few ulps is no step size.
            step = np.zeros_like(p0)
            step[i] = DIFFERENCE_STEP * max(abs(p[i]), scale[i], np.finfo(float).tiny)
            J[:, i] = (np.atleast_1d(condition(p + step)) - np.atleast_1d(condition(p - step))) / (2 * step[i])
        J *= scale
        z = np.linalg.pinv(J) @ (J @ z - r)
    return best
