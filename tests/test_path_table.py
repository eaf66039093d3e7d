"""Batched Newton polish shared by the polyhedra models (`kinematics.path_table`)."""

import numpy as np
import pytest

from sim_origami.errors import ConvergenceError
from sim_origami.kinematics.path_table import polish

TARGET = np.array([2.0, 3.0])


def residual(y, rows):
    return y**2 - TARGET[rows]


def correction(y, rows, r):
    return r / (2 * y)


def test_polish_closes_every_row_at_once():
    y = polish(np.array([1.4, 1.7]), residual, correction, "sqrt", 1e-15)
    np.testing.assert_allclose(y, np.sqrt(TARGET), rtol=0, atol=4e-16)


def test_a_row_without_a_real_state_is_reported_not_returned_as_nan():
    with pytest.raises(ConvergenceError, match="closure of sqrt did not converge at nan"):
        polish(np.array([1.4, np.nan]), residual, correction, "sqrt", 1e-15)
