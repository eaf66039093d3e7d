"""The closed forms' API takes one input or a 1-D array of them: anything else is a typed DomainError naming what
was given (a 2-D array and an empty `at` were IndexErrors, a 3-D array a bare ValueError)."""

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.errors import DomainError

# Kinematics families whose scenes build in about a second with their defaults.
CHEAP = ("vertex4", "miura", "bennett", "myard", "bricard-threefold", "bricard-plane", "thick-vertex4",
         "waterbomb-vertex", "waterbomb-sheet", "square-twist")
# Their closed forms take a few seconds to build.
SLOW = ("waterbomb-tube", "kokotsakis")


@pytest.mark.parametrize("name", CHEAP + tuple(pytest.param(name, marks=pytest.mark.slow) for name in SLOW))
def test_inputs_of_the_wrong_shape_or_type_are_typed_errors(name):
    kinematics = scenes.get(name).build().kinematics
    branch = kinematics.branches()[0]
    middle = 0.5 * (branch.domain[0] + branch.domain[1])
    with pytest.raises(DomainError, match=r"inputs of shape \(1, 2\)"):
        kinematics.evaluate(branch.name, np.array([[1.0, 2.0]]))
    with pytest.raises(DomainError, match=r"inputs of shape \(2, 2, 2\)"):
        kinematics.joint_angles(branch.name, np.zeros((2, 2, 2)))
    with pytest.raises(DomainError, match="at takes one input; 0 given"):
        kinematics.at(branch.name, [])
    with pytest.raises(DomainError, match="are not numbers"):
        kinematics.evaluate(branch.name, "abc")
    assert set(kinematics.at(branch.name, middle)) == set(kinematics.joint_names)
