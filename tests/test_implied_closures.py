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
from sim_origami.scenes.base import without_implied_closures
from sim_origami.simulate import compile_model, simulate
from sim_origami.tolerances import TOLERANCES


def test_the_300_panel_tube_keeps_six_of_its_closures_and_poses_between_the_samples_agree():
    """The 10 x 5 tube's symmetry couplings and 6 cut creases close the other 125 loops (digest B.2: the couplings
    leave one DOF); 41 poses a branch, between the 9 the scene samples, imply the same loops."""
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
    model, _ = compile_model(scene, ModelOptions())
    connects = [model.equality(i).name for i in range(model.neq) if model.eq_type[i] == mujoco.mjtEq.mjEQ_CONNECT]
    kept = [mech.joints[i].name for i in mech.cut_joints if mech.joints[i].name not in mech.implied]
    assert sorted(connects) == sorted(f"close_{name}_{k}" for name in kept for k in range(2))
    for name in mech.implied:
        model.site(f"{name}_parent_0"), model.site(f"{name}_child_1")  # KeyError if missing


def test_implied_loops_stay_closed_in_mujoco():
    """The 6 x 3 tube's default sweep with 5 of its 43 loops imposed follows the contraction, and every implied
    crease turns about its own axis. Less tightly than with every loop imposed (path 1.2e-8 rad, gaps 1.3e-8 m):
    the soft closures' error grows as the constraint's smallest singular value shrinks (0.17 -> 0.036)."""
    scene = without_implied_closures(scenes.get("waterbomb-tube").build(n=6, m=3))
    mech = scene.mechanism
    run = simulate(scene, BRANCH)
    assert compare(scene, BRANCH, run.q).max_error() <= TOLERANCES.fast_rad  # measured 4.0e-7 rad
    assert mech.hinge_mismatch(run.q, mech.implied) <= TOLERANCES.fast_residual_m  # measured 6.9e-7
    assert np.max(run.closure_residual) <= TOLERANCES.fast_residual_m  # measured 7.9e-7 m, implied loops included
