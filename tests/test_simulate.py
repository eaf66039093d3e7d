"""MuJoCo runs (`sim_origami.simulate`): accuracy, conventions, seeding, divergence and blockage."""

import functools
from dataclasses import replace

import mujoco
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.branches import classify
from sim_origami.checks.paths import compare
from sim_origami.errors import DomainError, ParameterError, SimOrigamiError, SimulationError
from sim_origami.geometry import rotation
from sim_origami.mjcf import ModelOptions
from sim_origami.origami import crease_directions
from sim_origami.presets import ACCURATE, FAST, STIFF
from sim_origami.scenes import Tuning
from sim_origami.simulate import (
    Bindings,
    compile_model,
    contact_distance,
    contact_input,
    project,
    ramp,
    scene_xml,
    simulate,
    warn_in_python,
)
from sim_origami.studies import pareto
from sim_origami.tolerances import TOLERANCES

RUNS = [("vertex4", "odd1"), ("vertex4", "odd2"), ("miura", "miura")]
RUN_IDS = [f"{s}-{b}" for s, b in RUNS]
# Flat-foldable vertex (alpha1 + alpha3 = 180 deg): branches S and C cross at the flat state.
FLAT_FOLDABLE_DEG = (60.0, 100.0, 120.0, 80.0)
# Hinge axes and body quaternions are written with 12 significant digits: measured body-frame
# difference 3.9e-13 between MuJoCo's xmat and the mechanism's pose.
MJCF_DIGITS_ATOL = 1e-12
THICKNESS = 0.02


@functools.cache
def scene_of(name: str, thickness: float = 0.0):
    return scenes.get(name).build(**({"thickness": thickness} if thickness else {}))


@functools.cache
def fast_run(name: str, branch: str):
    return simulate(scene_of(name), branch)


@functools.cache
def flat_foldable_scene():
    alpha = dict(zip(("alpha1", "alpha2", "alpha3", "alpha4"), np.deg2rad(FLAT_FOLDABLE_DEG), strict=True))
    return scenes.get("vertex4").build(**alpha)


def drive_input(scene, q: np.ndarray) -> np.ndarray:
    """The scene's input (rad) measured from mechanism angles (n, n_joints)."""
    return q[:, scene.mechanism.joint_index(scene.drive_joint)] / scene.drive_scale


def posed(scene, q: np.ndarray):
    """A compiled model and data with hinges at mechanism angles q (n_joints,), kinematics done."""
    compiled = compile_model(scene, ModelOptions())
    model, data = compiled.fresh()
    Bindings(compiled).set_pose(data, q)
    mujoco.mj_kinematics(model, data)
    return model, data


def world_rotation(model, data, scene, panel: str) -> np.ndarray:
    """Rotation (3, 3) of a panel's body frame in MuJoCo; the root panel lives on the world body."""
    body = 0 if panel == scene.mechanism.root else model.body(panel).id
    return data.xmat[body].reshape(3, 3)


@pytest.mark.parametrize(("name", "branch"), RUNS, ids=RUN_IDS)
def test_fast_run_path_error_and_closure_residual_within_fast_tolerances(name, branch):
    run = fast_run(name, branch)
    assert compare(scene_of(name), branch, run.q).max_error() <= FAST.angle_rad
    assert np.max(run.closure_residual) <= FAST.residual_per_m


@pytest.mark.parametrize(("name", "branch"), RUNS, ids=RUN_IDS)
def test_fast_run_sweeps_the_default_path(name, branch):
    scene, run = scene_of(name), fast_run(name, branch)
    start, stop = scene.branch_path(branch)
    assert run.target[-1] == stop and run.steps == len(run.q) == len(run.time)
    # The input starts at the start pose and reaches its target in the sense of checks.blockage.assess
    # (within 1 mrad; measured end overshoot up to 1.2e-4 rad, the soft drive's lag on the ramp).
    x = drive_input(scene, run.q)
    np.testing.assert_allclose([x[0], x[-1]], [start, stop], atol=1e-3, rtol=0)


@pytest.mark.parametrize(("name", "branch"), RUNS, ids=RUN_IDS)
def test_projection_path_error_and_residual_within_projection_tolerances(name, branch):
    scene = scene_of(name)
    run = project(scene, branch, np.linspace(*scene.branch_path(branch), 50))
    assert compare(scene, branch, run.q).max_error() <= TOLERANCES.projection_rad
    assert np.max(run.closure_residual) <= TOLERANCES.projection_residual_m


@pytest.mark.slow
def test_accurate_preset_on_vertex4_within_accurate_tolerances():
    scene = scene_of("vertex4")
    run = simulate(scene, "odd2", preset=ACCURATE)
    assert compare(scene, "odd2", run.q).max_error() <= ACCURATE.angle_rad
    assert np.max(run.closure_residual) <= ACCURATE.residual_per_m


@pytest.mark.parametrize(("name", "branch"), RUNS, ids=RUN_IDS)
def test_mechanism_body_poses_equal_mujoco_body_frames_at_the_simulated_angles(name, branch):
    scene, run = scene_of(name), fast_run(name, branch)
    for q in run.q[:: len(run.q) // 4]:
        model, data = posed(scene, q)
        for panel, pose in scene.mechanism.body_poses(q).items():
            if panel == scene.mechanism.root:
                np.testing.assert_allclose(pose, np.eye(4), atol=0, rtol=0)
                continue
            b = model.body(panel).id
            np.testing.assert_allclose(data.xpos[b], pose[:3, 3], atol=MJCF_DIGITS_ATOL, rtol=0)
            np.testing.assert_allclose(data.xmat[b].reshape(3, 3), pose[:3, :3], atol=MJCF_DIGITS_ATOL, rtol=0)


@pytest.mark.parametrize(("name", "branch"), RUNS, ids=RUN_IDS)
def test_hinge_qpos_is_the_fold_angle_rotating_the_ccw_panel_about_its_crease(name, branch):
    scene, run = scene_of(name), fast_run(name, branch)
    mech = scene.mechanism
    d = crease_directions(scene.kinematics.sectors if name == "miura" else scene.kinematics.alpha)
    q = run.q[-1]
    model, data = posed(scene, q)
    for i, joint in enumerate(mech.joints):
        R_cw = world_rotation(model, data, scene, joint.parent)
        R_ccw = world_rotation(model, data, scene, joint.child)
        # Tree joints are exact; the cut joint is closed to the soft closure's residual (1 m creases).
        atol = FAST.residual_per_m if i in mech.cut_joints else MJCF_DIGITS_ATOL
        np.testing.assert_allclose(R_cw.T @ R_ccw, rotation(d[i], q[i]), atol=atol, rtol=0, err_msg=joint.name)


@pytest.mark.parametrize(("name", "branch"), RUNS, ids=RUN_IDS)
def test_closed_seed_run_is_classified_on_its_branch_without_flips(name, branch):
    scene, run = scene_of(name), fast_run(name, branch)
    path = compare(scene, branch, run.q)
    labels = classify(scene.kinematics, path.input, path.simulated)
    assert (labels.followed, labels.flips) == (branch, 0)


def test_flat_foldable_vertex_has_branches_s_and_c():
    assert {b.name for b in flat_foldable_scene().kinematics.branches()} == {"S", "C"}


@pytest.mark.slow
@pytest.mark.parametrize("branch", ["S", "C"])
def test_flat_seed_with_tangent_bias_reaches_the_requested_branch(branch):
    scene = flat_foldable_scene()
    # the fast preset cannot steer this bifurcation (soft loops take C, measured here)
    run = simulate(scene, branch, seed="flat", bias=1e-4, stop=1.0, preset=ACCURATE)
    assert run.target[0] < 1e-3  # seed 'flat' sweeps from the flat state
    path = compare(scene, branch, run.q)
    labels = classify(scene.kinematics, path.input, path.simulated)
    assert (labels.followed, labels.flips) == (branch, 0), f"final angles {run.q[-1]}"


def test_unknown_seed_raises_domain_error_naming_it():
    with pytest.raises(DomainError, match="'sideways'"):
        simulate(scene_of("vertex4"), "odd1", seed="sideways")


def test_unknown_drive_raises_a_sim_origami_error_naming_it():
    with pytest.raises(SimOrigamiError, match="'pedal'"):
        simulate(scene_of("vertex4"), "odd1", drive="pedal")


def test_diverging_run_raises_simulation_error_and_leaves_no_mujoco_log(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    handler = mujoco.get_mju_user_warning()
    # 100 rad of input in 16 ms (2 steps of 8 ms): MuJoCo reports a bad QACC (deterministic).
    # The message names the configuration that diverged.
    match = r"scene vertex4 \(alpha1=.*\), branch odd2, preset fast, equality drive .* -> 100 rad in 0.016 s.*BAD"
    with pytest.raises(SimulationError, match=match):
        simulate(scene_of("vertex4"), "odd2", duration=0.016, stop=100.0)
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
    assert list(tmp_path.iterdir()) == []
    assert mujoco.get_mju_user_warning() is handler  # warning capture undone


def test_sweep_shorter_than_half_a_step_raises_a_sim_origami_error():
    # 1 ms with the fast preset's 8 ms step rounds to zero steps.
    with pytest.raises(SimOrigamiError):
        simulate(scene_of("vertex4"), "odd2", duration=1e-3, stop=100.0)


def test_ramp_is_minimum_jerk_from_zero_to_one():
    p = np.linspace(0.0, 1.0, 101)
    s, ds = ramp(p)
    assert (s[0], s[-1], ds[0], ds[-1]) == (0.0, 1.0, 0.0, 0.0)
    assert np.all(np.diff(s) > 0)
    # ds/dp by central differences of s (step 0.01: truncation ~ 1e-4 * s''' ~ 6e-3).
    np.testing.assert_allclose(np.gradient(s, p)[1:-1], ds[1:-1], atol=6e-3, rtol=0)


@functools.cache
def thick_contact_input() -> tuple[float, float, float]:
    """(path start, contact input, theta_limit) of the thick Miura vertex on branch 'miura'."""
    scene = scene_of("miura", THICKNESS)
    start, _ = scene.branch_path("miura")
    lock = scene.kinematics.theta_limit
    return start, contact_input(scene, "miura", start, lock), lock


def test_thick_miura_contact_input_lies_before_theta_limit():
    start, touch, lock = thick_contact_input()
    assert start < touch < lock
    # The solids are apart just before the contact input and touch at it.
    before, at = contact_distance(scene_of("miura", THICKNESS), "miura", np.array([touch - 1e-6, touch]))
    assert before > 0.0 >= at


@pytest.mark.parametrize("contact", [True, False])
def test_servo_run_stops_at_contact_input_only_when_contact_is_enabled(contact):
    scene = scene_of("miura", THICKNESS)
    start, touch, lock = thick_contact_input()
    run = simulate(scene, "miura", drive="servo", contact=contact, start=start, stop=lock, hold=1.0)
    stop = drive_input(scene, run.q)[-1]
    if contact:
        assert abs(stop - touch) <= TOLERANCES.blockage_rad
        assert run.contacts[-1] > 0
    else:
        # Free servo: 1 s of hold brings it to its target (measured 1.5e-7 rad short).
        assert abs(stop - lock) <= 1e-3
        assert not np.any(run.contacts)


@pytest.mark.parametrize("branch", ["S", "C"])
def test_flat_foldable_vertex_follows_both_branches_within_fast_tolerances(branch):
    scene = flat_foldable_scene()
    run = simulate(scene, branch)
    path = compare(scene, branch, run.q)
    assert path.max_error() <= FAST.angle_rad
    assert np.max(run.closure_residual) <= FAST.residual_per_m
    labels = classify(scene.kinematics, path.input, path.simulated)
    assert (labels.followed, labels.flips) == (branch, 0)


@pytest.mark.parametrize("preset", [FAST, STIFF, ACCURATE], ids=lambda p: p.name)
def test_compiled_models_carry_the_presets_regulariser_scale(preset):
    """compile_model scales MuJoCo's inverse weights (hence every row's R) by the preset's stated factor."""
    scene = scenes.get("thick-diamond").build()
    plain = mujoco.MjModel.from_xml_string(scene_xml(scene, ModelOptions(preset=preset)))
    model = compile_model(scene, ModelOptions(preset=preset)).model
    scale = preset.regularization_scale
    assert scale == model.numeric("regularization_scale").data[0] == 0.01
    np.testing.assert_allclose(model.body_invweight0, scale * plain.body_invweight0, rtol=1e-15, atol=0)
    np.testing.assert_allclose(model.dof_invweight0, scale * plain.dof_invweight0, rtol=1e-15, atol=0)


def test_a_scenes_regulariser_scale_multiplies_the_fast_presets_and_is_written_in_the_model():
    """Tuning.fast_regularization_scale reaches the MJCF's numeric (a plain load can repeat the run) under fast only."""
    scene = replace(scenes.get("thick-diamond").build(), tuning=Tuning(fast_regularization_scale=0.01))
    for preset, expected in ((FAST, 1e-4), (STIFF, 0.01)):
        plain = mujoco.MjModel.from_xml_string(scene_xml(scene, ModelOptions(preset=preset)))
        model = compile_model(scene, ModelOptions(preset=preset)).model
        assert model.numeric("regularization_scale").data[0] == pytest.approx(expected, rel=1e-15)
        np.testing.assert_allclose(model.body_invweight0, expected * plain.body_invweight0, rtol=1e-14, atol=0)


def test_the_scaled_regulariser_is_what_makes_the_thin_loop_accurate():
    """thick-diamond's thin loop, fast on the bench's 2 s sweep: the preset against the same setting with MuJoCo's
    own regulariser (pareto.measure, one run each): measured 1.8e-8 against 1.7e-6 rad (93x)."""
    scene = scenes.get("thick-diamond").build()
    scaled = pareto.measure(scene, "diamond", pareto.PRESET_SETTINGS[FAST], repeats=1).error
    plain = pareto.measure(scene, "diamond", replace(pareto.PRESET_SETTINGS[FAST], regularization=1.0), repeats=1).error
    assert plain / scaled > 30, (scaled, plain)


def test_contact_probe_refuses_a_scene_without_collision_solids():
    scene = scenes.get("vertex4").build()
    with pytest.raises(ParameterError, match="scene 'vertex4' has no collision solids"):
        contact_distance(scene, "odd1", np.array([0.3]))


def test_a_raw_stepping_loop_warns_in_python_and_leaves_no_mujoco_log(tmp_path, monkeypatch):
    """A script's own mj_step loop (as the benches and scripts run) on a model that blows up: MuJoCo's warning
    arrives as a RuntimeWarning and no MUJOCO_LOG.TXT lands in the working directory."""
    monkeypatch.chdir(tmp_path)
    assert mujoco.get_mju_user_warning() is warn_in_python  # installed by importing the harness
    model, data = compile_model(scene_of("vertex4"), ModelOptions()).fresh()
    data.qvel[:] = 1e200  # deterministic: MuJoCo reports a bad QVEL/QACC on the first step
    with pytest.warns(RuntimeWarning, match="MuJoCo: .*"):
        for _ in range(3):
            mujoco.mj_step(model, data)
    assert not (tmp_path / "MUJOCO_LOG.TXT").exists()
