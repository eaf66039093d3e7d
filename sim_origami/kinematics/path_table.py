"""Batched path solving shared by the polyhedra models (numpy only): a table of a path's unknowns dense at the
ends of its domain, cubic interpolation from it, and a vectorised Newton polish of every input at once."""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ConvergenceError
from ..geometry import wrap


def polish(y: NDArray[np.float64], residual: Callable, correction: Callable, what: str, floor: float) -> NDArray:
    """
    Newton-type iteration on every row of y (n,) or (n, k) at once. residual(y_rows, rows) gives the residuals
    (shaped as y_rows) of the rows still moving (first rows = slice(None): all); correction(y_rows, rows, r) the
    steps of those among them whose largest residual is >= `floor` (the rounding of the residuals): the others
    stop there, unchanged (near a turning point a step would be rounding over a vanishing slope), and so does a
    row once its largest step is below 1e-15. ConvergenceError naming `what` when a residual is still >= 1e-14
    after 12 steps, or NaN (a row that has no real solution).
    """
    y, rows = y.copy(), np.arange(len(y))
    r = residual(y, slice(None))
    for _ in range(12):
        need = ~(_largest(r) < floor)  # a NaN residual (no real state) keeps its row open, to be reported
        rows, r = rows[need], r[need]
        if not len(rows):
            return y
        dy = correction(y[rows], rows, r)
        y[rows] -= dy
        rows = rows[~(_largest(dy) < 1e-15)]
        r = residual(y[rows], rows)
    open_rows = np.flatnonzero(~(_largest(r) < 1e-14))
    if open_rows.size:
        k = int(open_rows[0])
        raise ConvergenceError(f"the closure of {what} did not converge at {y[rows[k]]} (residual "
                               f"{_largest(r)[k]:.3g} m^2)")
    return y


def _largest(a: NDArray[np.float64]) -> NDArray[np.float64]:
    """Largest |entry| of each row of a (n,) or (n, k) array (NaN where a row holds NaN)."""
    return np.abs(a) if a.ndim == 1 else np.max(np.abs(a), axis=1)


@dataclass(frozen=True)
class PathTable:
    """
    Values (N, m) of a path's unknowns (and what else helps to solve for them) at N inputs equally spaced in mu
    over the domain [lo, hi] (rad), x = lo + (hi - lo) (1 - cos(pi mu)) / 2: dense at both ends, where an unknown
    may go as sqrt(x - end) (a turning point) and is still smooth in mu. `at` interpolates them cubically in mu.
    """

    lo: float
    hi: float
    values: NDArray[np.float64]

    @staticmethod
    def inputs(lo: float, hi: float, size: int) -> NDArray[np.float64]:
        """The N = size inputs (rad) of a table over [lo, hi]."""
        return lo + 0.5 * (hi - lo) * (1.0 - np.cos(np.pi * np.linspace(0.0, 1.0, size)))

    def locate(self, x: NDArray[np.float64]) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
        """For inputs x (n,) in [lo, hi]: the second of the four nodes around each (n,) and their weights (4, n)."""
        w = np.arccos(np.clip(1.0 - 2.0 * (x - self.lo) / (self.hi - self.lo), -1.0, 1.0)) * (
            (len(self.values) - 1) / np.pi
        )
        k = np.clip(w.astype(np.intp), 1, len(self.values) - 3)
        f = w - k
        g, h, e = f + 1.0, f - 1.0, f - 2.0
        return k, np.stack([-f * h * e / 6.0, 0.5 * g * h * e, -0.5 * g * f * e, g * f * h / 6.0])

    def at(
        self, where: tuple[NDArray[np.intp], NDArray[np.float64]], columns: int | slice, rows: NDArray | None = None
    ) -> NDArray:
        """Values (n,) or (n, c) of `columns` at the inputs `locate` found (those of `rows` only, if given)."""
        k, w = where
        if rows is not None:
            k, w = k[rows], w[:, rows]
        v = self.values[:, columns]
        w = w.reshape(4, -1, *(1,) * (v.ndim - 1))
        return w[0] * v[k - 1] + w[1] * v[k] + w[2] * v[k + 1] + w[3] * v[k + 2]


def wrap_if_needed(angle: NDArray[np.float64]) -> NDArray[np.float64]:
    """`wrap` (rad, to (-pi, pi]), skipping the work when every angle already lies there (as on the path)."""
    return angle if angle.size == 0 or (angle.max() <= np.pi and angle.min() > -np.pi) else wrap(angle)
