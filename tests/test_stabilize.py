"""Preset fast-projected (`sim_origami.stabilize`): its accuracy on Bennett and A04, and the plain presets untouched."""

import functools

import mujoco
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.errors import ParameterError
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import ACCURATE, FAST, FAST_PROJECTED, STIFF
from sim_origami.report import as_dict
from sim_origami.simulate import Bindings, compile_model, drive_targets, simulate, simulate_free, start_pose
from sim_origami.stabilize import before_projection, run_step, step_function
from sim_origami.studies.peer_model import body_poses, potential_energy, rigid_model, tree_model
from sim_origami.validation import MUJOCO_OWN_STEP_ERROR, MUJOCO_PATH_ERROR, validate

FREE_S = 10.0


@functools.cache
def scene_of(name: str):
    return scenes.get(name).build()


@pytest.mark.slow
def test_fast_projected_closes_the_bennett_sweep():
    """Measured 2.2e-15 rad and 2.4e-15 m over a 6 s sweep (fast: 6.7e-8 rad, 1.0e-7 m)."""
    scene = scene_of("bennett")
    run = simulate(scene, "bennett", preset=FAST_PROJECTED)
    assert run.steps == round(run.sweep_time_s / 0.008)  # the fast preset's 8 ms steps over the path's sweep time
    assert compare(scene, "bennett", run.q).max_error() < FAST_PROJECTED.angle_rad
    assert np.max(run.closure_residual) < FAST_PROJECTED.residual()
    # the drive is left to its equality: the input sweeps the whole path (measured 7.0e-6 rad past its end)
    x = run.q[:, scene.mechanism.joint_index(scene.drive_joint)]
    assert x[0] == pytest.approx(0.6, abs=1e-4) and x[-1] == pytest.approx(2.4, abs=1e-4)


@pytest.mark.slow
def test_fast_projected_a04_free_run_keeps_energy():
    """A04, 10 s free: measured 2.7e-15 rad off the closed form and 1.6e-6 J of energy drift at its states (fast:
    4.4e-7 rad, 1.4e-5 J)."""
    scene = scene_of("iftomm-a04")
    run = simulate_free(scene, scene.free_branch, scene.free_start, FREE_S, preset=FAST_PROJECTED)
    path = compare(scene, scene.free_branch, run.q)
    assert run.steps == 1250
    assert path.max_error() < FAST_PROJECTED.angle_rad
    assert np.max(np.abs(run.energy - run.energy[0])) < FAST_PROJECTED.energy_j
    assert np.ptp(path.input) > 0.5  # it fell: the input swept more than half a radian


@pytest.mark.parametrize("preset", [FAST, STIFF], ids=lambda p: p.name)
def test_plain_presets_step_bit_for_bit_as_mj_step(preset):
    """The plain presets run mj_step itself: the harness's Bennett sweep equals a bare mj_step loop bit for bit."""
    scene = scene_of("bennett")
    run = simulate(scene, "bennett", preset=preset)
    compiled = compile_model(scene, ModelOptions(preset=preset))
    model, data = compiled.fresh()
    assert run_step(model, data, compiled) is mujoco.mj_step
    binds = Bindings(compiled)
    start, stop = scene.branch_path("bennett")
    binds.set_pose(data, start_pose(scene, "bennett", start))
    mujoco.mj_forward(model, data)
    _, setpoints = drive_targets(scene, model, compiled.ids, start, stop, run.steps * model.opt.timestep, run.steps)
    eq = compiled.ids.drive_equalities[0]
    log = np.empty((run.steps, model.nq))
    for value, row in zip(setpoints, log, strict=True):
        model.eq_data[eq][0] = value
        mujoco.mj_step(model, data)
        row[:] = data.qpos
    np.testing.assert_array_equal(binds.angles(scene, log), run.q)


def test_plain_free_run_is_mj_step():
    """A04's fast free run equals a bare mj_step loop bit for bit, and differs from fast-projected's."""
    scene = scene_of("iftomm-a04")
    run = simulate_free(scene, scene.free_branch, scene.free_start, 1.0, preset=FAST)
    compiled = compile_model(scene, ModelOptions(preset=FAST, drive="none", gravity=True))
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    binds.set_pose(data, start_pose(scene, scene.free_branch, scene.free_start))
    mujoco.mj_forward(model, data)
    log = np.empty((run.steps, model.nq))
    for row in log:
        mujoco.mj_step(model, data)
        row[:] = data.qpos
    np.testing.assert_array_equal(binds.angles(scene, log), run.q)
    projected = simulate_free(scene, scene.free_branch, scene.free_start, 1.0, preset=FAST_PROJECTED)
    assert not np.array_equal(projected.q, run.q)


def test_free_run_energy_is_read_at_the_states():
    """The free run's energy is the state's after each step (a fresh mj_forward there), not data.energy after an RK4
    mj_step, which MuJoCo filled at the step's last internal stage: over A04's first second under fast the stage
    reading is off the state's by up to about 1e-5 J (measured), more than the drift the states hold."""
    scene = scene_of("iftomm-a04")
    run = simulate_free(scene, scene.free_branch, scene.free_start, 1.0, preset=FAST)
    compiled = compile_model(scene, ModelOptions(preset=FAST, drive="none", gravity=True))
    model, data = compiled.fresh()
    assert model.opt.enableflags & mujoco.mjtEnableBit.mjENBL_ENERGY
    Bindings(compiled).set_pose(data, start_pose(scene, scene.free_branch, scene.free_start))
    mujoco.mj_forward(model, data)
    probe = mujoco.MjData(model)
    at_states, at_stages = np.empty(run.steps), np.empty(run.steps)
    for k in range(run.steps):
        mujoco.mj_step(model, data)
        at_stages[k] = data.energy.sum()
        probe.qpos[:], probe.qvel[:] = data.qpos, data.qvel
        mujoco.mj_forward(model, probe)
        at_states[k] = probe.energy.sum()
    assert run.energy[0] == pytest.approx(-29.43, abs=1e-9)
    np.testing.assert_allclose(run.energy[1:], at_states, rtol=0, atol=1e-12)
    assert np.max(np.abs(run.energy[1:] - at_stages)) > 1e-6
    assert np.max(np.abs(run.energy - run.energy[0])) < FAST.energy_j


def test_preset_modes_and_bad_mode():
    assert [p.stabilize for p in (FAST, STIFF, ACCURATE, FAST_PROJECTED)] == ["none"] * 3 + ["position"]
    model, data = compile_model(scene_of("bennett"), ModelOptions()).fresh()
    with pytest.raises(ParameterError, match="'velocity'"):
        step_function(model, data, "velocity")


@pytest.mark.slow
def test_report_states_the_stabilisation():
    """
    validate --preset fast-projected passes on Bennett and report.json names the preset and its stabilisation, and
    gives MuJoCo's own path error before each projection (measured 6.7e-8 rad: the dynamic check, held to fast's
    1e-6) beside the path after it (3.1e-15: the projection's work, held to 1e-11). The plain preset has neither.
    """
    report = validate(scene_of("bennett"), preset=FAST_PROJECTED, branch="bennett")
    doc = as_dict(report)
    assert report.passed and doc["preset"] == "fast-projected" and doc["stabilize"] == "position"
    checks = {v["id"]: v for v in doc["branches"][0]["verdicts"]}
    before, after = checks[MUJOCO_OWN_STEP_ERROR], checks[MUJOCO_PATH_ERROR]
    assert before["tolerance"] == FAST.angle_rad and after["tolerance"] == FAST_PROJECTED.angle_rad
    assert before["compared"] == after["compared"] == report.runs[0].dynamic.steps
    assert 1e-9 < before["measured"] < FAST.angle_rad and after["measured"] < 1e-13
    plain = as_dict(validate(scene_of("bennett"), branch="bennett"))
    assert plain["stabilize"] == "none"
    assert MUJOCO_OWN_STEP_ERROR not in {v["id"] for v in plain["branches"][0]["verdicts"]}


def test_before_projection_records_mujocos_own_steps():
    """Inside the block each stabilised step logs qpos before its projection (off the closures by MuJoCo's own step,
    here up to 4e-9 rad on A04's first second), after which the state is on them (to 1e-14); plain steps log nothing."""
    scene = scene_of("iftomm-a04")
    with before_projection() as own:
        run = simulate_free(scene, scene.free_branch, scene.free_start, 1.0, preset=FAST_PROJECTED)
        simulate_free(scene, scene.free_branch, scene.free_start, 1.0, preset=FAST)
    assert len(own) == run.steps == 125
    compiled = compile_model(scene, ModelOptions(preset=FAST_PROJECTED, drive="none", gravity=True))
    raw = compare(scene, scene.free_branch, Bindings(compiled).angles(scene, np.array(own)))
    assert 1e-11 < raw.max_error() < FAST.angle_rad
    assert compare(scene, scene.free_branch, run.q).max_error() < 1e-13
    with before_projection() as outside:
        pass
    simulate_free(scene, scene.free_branch, scene.free_start, 0.1, preset=FAST_PROJECTED)
    assert outside == []


def test_peer_model_is_the_mechanism():
    """The rigid bodies and hinges other codes are built from: A04's five 1 kg rods, six hinges along the
    benchmark's axes, one cut, joint 1 driven; principal frames map back to the mechanism's angles exactly."""
    scene = scene_of("iftomm-a04")
    q = start_pose(scene, scene.free_branch, scene.free_start)
    rigid = rigid_model(scene, q)
    assert [b.mass for b in rigid.bodies] == pytest.approx([1.0] * 5, rel=1e-7)
    assert sum(h.cut for h in rigid.hinges) == 1 and [h.name for h in rigid.hinges if h.driven] == ["joint_1"]
    for b in rigid.bodies:
        # 1 x 0.1 x 0.1 m rod, 1 kg; principal axes in MuJoCo's order (a box geom lists the long axis last)
        assert sorted(b.inertia) == pytest.approx([0.02 / 12, 1.01 / 12, 1.01 / 12], rel=1e-6)
    poses = body_poses(rigid, {b.name: b.pose[None] for b in rigid.bodies})
    np.testing.assert_allclose(scene.mechanism.angles_from_poses(poses)[0], q, atol=1e-14)
    # the energy MuJoCo reports at the start: E0 = -29.43 J
    assert potential_energy(rigid, {b.name: b.pose[None, :3, 3] for b in rigid.bodies})[0] == pytest.approx(
        -29.43, abs=1e-6
    )
    balls = scene_of("cuboctahedron")
    branch = balls.kinematics.branches()[0].name
    with pytest.raises(ParameterError, match="hinges only"):
        rigid_model(balls, start_pose(balls, branch, balls.branch_path(branch)[0]))


def test_tree_model_is_the_mechanism_in_minimal_coordinates():
    """The kinematic tree the peer's minimal-coordinate model is built from: each link's frame chains from its
    parent's, carries its body's principal frame where the rigid model puts it, and tree coordinates c (a link's
    sign times its hinge's turn from q0) give back every mechanism angle, the cut hinge's included."""
    scene = scene_of("bennett")
    start, stop = scene.branch_path("bennett")
    q0, q1 = (start_pose(scene, "bennett", x) for x in (start, 0.5 * (start + stop)))
    tree = tree_model(scene, q0)
    mech = scene.mechanism
    assert len(tree.links) == len(mech.joints) - len(mech.cut_joints) == 3
    bodies = {b.name: b for b in tree.rigid.bodies}
    for k, link in enumerate(tree.links):
        base = np.eye(4) if link.parent < 0 else tree.frames[link.parent]
        np.testing.assert_allclose(base @ link.transform, tree.frames[k], atol=1e-14)
        np.testing.assert_allclose(tree.frames[k] @ link.com_frame, bodies[link.body].pose, atol=1e-14)
    np.testing.assert_allclose(tree.angles(np.zeros(3), mech)[0], q0, atol=1e-14)
    c = np.array([link.sign * (q1[link.joint] - q0[link.joint]) for link in tree.links])
    np.testing.assert_allclose(tree.angles(c, mech)[0], q1, atol=1e-13)
    assert np.ptp(q1 - q0) > 0.1  # the pose moved
