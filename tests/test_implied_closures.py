"""Closures that couplings imply (`Mechanism.implied_cuts`, `scenes.base.without_implied_closures`): left out of the
MJCF, still measured."""

import dataclasses

import mujoco
import numpy as np
import pytest

import sim_origami.scenes.waterbomb_tube  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.errors import ParameterError
from sim_origami.kinematics.waterbomb_tube import BRANCH
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import FAST, STIFF
from sim_origami.scenes.base import without_implied_closures
from sim_origami.simulate import compile_model, simulate


@pytest.mark.slow
def test_the_300_panel_tube_keeps_six_of_its_closures_and_poses_between_the_samples_agree():
    """The 10 x 5 tube's symmetry couplings and 6 cut creases close the other 125 loops (the couplings leave one DOF,
    measured here by rank); 41 poses a branch, between the 9 the scene samples, imply the same loops."""
    scene = without_implied_closures(scenes.get("waterbomb-tube").build(n=10))
    mech = scene.mechanism
    assert (len(mech.cut_joints), len(mech.implied)) == (131, 125)
    assert mech.implied_cuts(scene.domain_poses(41)) == mech.implied


def test_without_couplings_every_loop_is_imposed():
    """Removing the couplings removes what they implied; the free tube's own loops imply far fewer (8 of 43)."""
    scene = without_implied_closures(scenes.get("waterbomb-tube").build(n=6, m=3))
    coupled = scene.mechanism
    free = coupled.uncoupled()
    assert (free.couplings, free.implied) == ((), ())
    assert len(coupled.implied) == 38
    assert len(free.implied_cuts(scene.domain_poses(9))) == 8


@pytest.mark.parametrize("name", ["vertex4", "rssr"])
def test_a_single_loop_is_never_implied(name):
    """One loop, cut at a hinge (vertex4) or at a spherical joint (rssr)."""
    scene = scenes.get(name).build()
    assert scene.mechanism.implied_cuts(scene.domain_poses(9)) == ()


def test_an_implied_joint_must_be_a_cut_hinge():
    mech = without_implied_closures(scenes.get("waterbomb-tube").build(n=6, m=3)).mechanism
    tree_joint = mech.joints[mech.tree[0].joint].name
    with pytest.raises(ParameterError, match=f"implied closure {tree_joint!r} is not a cut hinge"):
        dataclasses.replace(mech, implied=(tree_joint,))


def test_mjcf_connects_the_kept_loops_and_measures_every_one():
    """Two connects a kept cut crease, none for an implied one; both carry their closure sites."""
    scene = without_implied_closures(scenes.get("waterbomb-tube").build(n=6, m=3))
    mech = scene.mechanism
    model = compile_model(scene, ModelOptions()).model
    connects = [model.equality(i).name for i in range(model.neq) if model.eq_type[i] == mujoco.mjtEq.mjEQ_CONNECT]
    kept = [mech.joints[i].name for i in mech.cut_joints if mech.joints[i].name not in mech.implied]
    assert sorted(connects) == sorted(f"close_{name}_{k}" for name in kept for k in range(2))
    for name in mech.implied:
        model.site(f"{name}_parent_0"), model.site(f"{name}_child_1")  # KeyError if missing


# The sweep-duration rule is set for `fast`'s lag; under `stiff` the error is Euler's step's, which the fast preset's
# rule does not size (its default sweep here: 1.39e-6 rad with all loops or 5), so this test sweeps 2x slower.
SLOWER = "stiff's step error, which the fast preset's sweep rule does not size"


@pytest.mark.slow
def test_under_stiff_leaving_out_the_implied_loops_changes_nothing():
    """stiff, the rate script's setting, whose error is the step's: the 6 x 3 tube's sweep (2x the default) with 5 of
    its 43 loops imposed follows the contraction as closely as with all 43, and the implied creases stay as closed as
    when imposed (measured: path 3.48e-7 rad against 3.47e-7; implied hinge mismatch 3.62e-7 against 3.63e-7; site
    gaps 3.92e-7 m against 3.90e-7). Under fast the soft closures set the error and it grows (6 x 3 at 10 ms: 6.4e-7
    rad against 1.8e-8)."""
    full = scenes.get("waterbomb-tube").build(n=6, m=3)
    full = dataclasses.replace(full, tuning=dataclasses.replace(full.tuning, sweep_time_scale=2.0, why=SLOWER))
    reduced = without_implied_closures(full)
    implied = reduced.mechanism.implied
    runs = [simulate(scene, BRANCH, preset=STIFF) for scene in (full, reduced)]
    paths = [compare(scene, BRANCH, run.q).max_error() for scene, run in zip((full, reduced), runs, strict=True)]
    mismatch = [full.mechanism.hinge_mismatch(run.q, implied) for run in runs]
    gaps = [np.max(run.closure_residual) for run in runs]
    assert paths[1] <= 1.1 * paths[0] and paths[1] <= FAST.angle_rad
    assert mismatch[1] <= 1.1 * mismatch[0] and mismatch[1] <= FAST.residual_per_m
    assert gaps[1] <= 1.1 * gaps[0] and gaps[1] <= FAST.residual_per_m  # implied loops' sites included
