"""The scene registry (`sim_origami.scenes`): building, parameters and a first MuJoCo run of each scene."""

import dataclasses

import mujoco
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.errors import ParameterError
from sim_origami.geometry import wrap
from sim_origami.mjcf import ModelOptions
from sim_origami.peer_times import FREE_RUN_PEERS
from sim_origami.presets import FAST
from sim_origami.scenes.base import DEFAULT_TUNING, Tuning
from sim_origami.simulate import Bindings, compile_model

# Command-line values (degrees, metres) that keep each scene valid but differ from the defaults.
USER_VALUES = {
    "vertex4": {"alpha1": 70.0, "alpha3": 80.0, "length": 2.0},
    "miura": {"alpha1": 40.0, "alpha2": 50.0, "length": 0.5},
}


def crease_angle_deg(scene, crease_a: str, crease_b: str) -> float:
    """Angle in the flat sheet between two creases' directions (joint frame z axes), degrees."""
    mech = scene.mechanism
    za = mech.joints[mech.joint_index(crease_a)].frame_parent[:3, 2]
    zb = mech.joints[mech.joint_index(crease_b)].frame_parent[:3, 2]
    return float(np.rad2deg(np.arccos(np.clip(za @ zb, -1.0, 1.0))))


def test_registry_lists_the_shipped_scenes_sorted():
    assert scenes.names() == tuple(sorted(scenes.REGISTRY))
    assert {"vertex4", "miura"} <= set(scenes.names())


@pytest.mark.slow
@pytest.mark.parametrize("name", scenes.names())
def test_scene_builds_with_defaults_compiles_and_steps_without_mujoco_warnings(name):
    scene = scenes.get(name).build()
    assert scene.name == name
    compiled = compile_model(scene, ModelOptions())
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    branch = scene.kinematics.branches()[0].name
    start, _ = scene.branch_path(branch)
    binds.set_pose(data, scene.pose(branch, start))
    mujoco.mj_forward(model, data)
    drive = compiled.ids.drive_equalities[0]
    model.eq_data[drive, 0] = scene.drive_scale * start
    for _ in range(50):
        mujoco.mj_step(model, data)
    # As MuJoCo Menagerie's model test: no warning of any kind was raised.
    assert [w.number for w in data.warning] == [0] * len(data.warning)
    assert np.all(np.isfinite(data.qpos))
    # Held at a closed pose, the model stays there (measured drift 2e-13 rad).
    held = binds.angles(scene, data.qpos[None])[0]
    # modulo 2 pi: a crease folded flat (the twist's middle row) sits at -pi in the closed form, +pi - 1e-13 in MuJoCo
    assert np.max(np.abs(wrap(held - scene.pose(branch, start)))) <= FAST.angle_rad


@pytest.mark.parametrize("name", scenes.names())
def test_default_path_lies_inside_every_branch_domain(name):
    scene = scenes.get(name).build()
    for branch in scene.kinematics.branches():
        start, stop = scene.branch_path(branch.name)
        lo, hi = branch.domain
        assert lo < min(start, stop) < max(start, stop) < hi  # a sweep may run downwards
        assert np.all(np.isfinite(scene.pose(branch.name, stop)))


def test_unknown_scene_raises_parameter_error_naming_it():
    with pytest.raises(ParameterError, match="'origami9'"):
        scenes.get("origami9")


@pytest.mark.parametrize("name", scenes.names())
def test_unknown_parameter_raises_parameter_error_naming_it(name):
    scene_type = scenes.get(name)
    with pytest.raises(ParameterError, match="'wingspan'"):
        scene_type.build(wingspan=1.0)
    with pytest.raises(ParameterError, match="'wingspan'"):
        scene_type.build_from_user({"wingspan": 1.0})


def test_vertex4_sectors_not_summing_to_360_deg_raise_parameter_error():
    with pytest.raises(ParameterError, match="360"):
        scenes.get("vertex4").build_from_user({"alpha1": 70.0})  # 70 + 100 + 90 + 110 = 370 deg


@pytest.mark.parametrize("name", scenes.names())
def test_build_from_user_converts_degrees_to_radians_and_keeps_metres(name):
    scene_type = scenes.get(name)
    # scenes without a hand-picked set get all their defaults, given explicitly in user units
    user = USER_VALUES.get(name, {p.name: p.default for p in scene_type.params})
    scene = scene_type.build_from_user(user)
    units = {p.name: p.unit for p in scene_type.params}
    for key, value in user.items():
        expected = np.deg2rad(value) if units[key] == "deg" else value
        np.testing.assert_allclose(scene.params[key], expected, atol=1e-15, rtol=0, err_msg=key)
    # Parameters not given keep their defaults, converted the same way.
    for p in scene_type.params:
        if p.name not in user:
            np.testing.assert_allclose(scene.params[p.name], p.to_api(p.default), atol=1e-15, rtol=0)


def test_build_from_user_degrees_reach_the_geometry():
    scene = scenes.get("vertex4").build_from_user(USER_VALUES["vertex4"])
    # alpha1 is the sector between creases 1 and 2, alpha3 between creases 3 and 4.
    np.testing.assert_allclose(crease_angle_deg(scene, "crease_1", "crease_2"), 70.0, atol=1e-9, rtol=0)
    np.testing.assert_allclose(crease_angle_deg(scene, "crease_3", "crease_4"), 80.0, atol=1e-9, rtol=0)
    anchors = scene.mechanism.joints[0].anchors
    np.testing.assert_allclose(max(anchors), 2.0, atol=0, rtol=0)  # crease length in metres


@pytest.mark.parametrize("name", scenes.names())
def test_param_unit_conversion_round_trips(name):
    for p in scenes.get(name).params:
        np.testing.assert_allclose(p.to_user(p.to_api(p.default)), p.default, atol=1e-12, rtol=0)


# Scene modules that may tune their runs (issue 29: at most three, each saying why).
MOST_TUNED_MODULES = 3


def test_a_registered_scene_runs_the_default_tuning_unless_it_says_why_in_one_line():
    tuned = {}
    for name in scenes.names():
        kind = scenes.get(name)
        tuning = kind.build().tuning
        if tuning != DEFAULT_TUNING:
            assert tuning.why and "\n" not in tuning.why, name
            tuned.setdefault(kind.build_fn.__module__, []).append(name)
    assert len(tuned) <= MOST_TUNED_MODULES, tuned


def test_a_scenes_run_tuning_is_its_tuning_value_only():
    """The knobs live in `Scene.tuning` alone: no field, property or keyword of the scene by their names."""
    scene = dataclasses.replace(scenes.get("bennett").build(), tuning=Tuning(fast_step_scale=1.25, why="test"))
    assert dataclasses.replace(scene, notes="x").tuning == Tuning(fast_step_scale=1.25, why="test")
    for name in ("preset", "sweep_time_scale", "fast_step_scale", "fast_timeconst_scale", "fast_regularization_scale"):
        assert not hasattr(scene, name), name
        with pytest.raises(TypeError, match=name):
            dataclasses.replace(scene, **{name: getattr(scene.tuning, name)})


@pytest.mark.parametrize(("values", "needle"), [
    ({"sweep_time_scale": 0.0}, "sweep_time_scale = 0.0"),
    ({"fast_step_scale": float("nan")}, "fast_step_scale = nan"),
    ({"fast_regularization_scale": -1.0}, "fast_regularization_scale = -1.0"),
    ({"preset": "fast"}, "preset = 'fast'"),
])
def test_tuning_refuses_a_scale_not_above_zero_and_a_preset_by_name(values, needle):
    with pytest.raises(ParameterError, match=needle):
        Tuning(**values)


def test_a_peers_free_run_time_comes_from_the_peer_table_not_the_scene():
    assert FREE_RUN_PEERS["iftomm-a04"] == ("OpenSim", 0.258) and "bennett" not in FREE_RUN_PEERS
    assert not hasattr(scenes.get("iftomm-a04").build(), "free_run_peer")
