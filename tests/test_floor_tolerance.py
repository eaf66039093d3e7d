"""Agreement at a rounding floor held to max(base, factor eps cond) per sample (`checks.paths.floor_verdict_values`):
the tolerance follows the closure Jacobian's conditioning where the error exceeds the base, and nowhere else."""

import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import PathComparison, closure_conditions, floor_verdict_values
from sim_origami.tolerances import TOLERANCES

EPS = np.finfo(float).eps


def _path(name: str):
    scene = scenes.get(name).build()
    branch = scene.kinematics.branches()[0].name
    x = np.linspace(*scene.branch_path(branch), 20)
    values = scene.kinematics.joint_angles(branch, x)
    return scene, x, values


def test_errors_within_the_base_tolerance_are_held_to_it():
    scene, x, values = _path("miura")
    path = PathComparison(x, values + 5e-14, values)
    error, tol, where = floor_verdict_values(scene, path, 1e-13, TOLERANCES.projection_cond_factor)
    assert abs(error - 5e-14) < 1e-15 and tol == 1e-13 and "within the base" in where


def test_an_error_above_the_base_is_held_to_the_conditioning_at_its_sample():
    """The registered 4 x 4 Miura sheet: cond 7.3 .. 52 along its sweep, 40 eps cond 4.7e-13 rad at the worst."""
    scene, x, values = _path("miura-sheet")
    conds = closure_conditions(scene, x, values)
    k = int(np.argmax(conds))
    scaled = 40.0 * EPS * conds[k]
    assert scaled > 2e-13  # well above the base, so the sample's conditioning decides
    for size, passed in ((0.9 * scaled, True), (1.1 * scaled, False)):
        simulated = values.copy()
        simulated[k, 0] += size
        error, tol, where = floor_verdict_values(scene, PathComparison(x, simulated, values), 1e-13, 40.0)
        assert abs(tol - scaled) <= 1e-9 * scaled and f"{x[k]:.6g} rad" in where
        assert (error <= tol) == passed


def test_a_sample_off_the_domain_fails():
    scene, x, values = _path("miura")
    simulated = values.copy()
    simulated[3] = np.nan  # compare's value off the branch's domain
    error, _, _ = floor_verdict_values(scene, PathComparison(x, simulated, values), 1e-13, 40.0)
    assert error == np.inf
