"""Myard 5R linkage (`sim_origami.kinematics.myard`, scene `myard`) against Yang 2017 (eqns 1-19,
1-20, Sec. 3.4) and Peng 2018 (§4.3), the loop solver and MuJoCo."""

import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from published import checked_by, yang2017

import sim_origami.scenes.myard  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.errors import DomainError, ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.dh import DHRow, dh_loop
from sim_origami.kinematics.myard import BRANCH, Myard
from sim_origami.presets import FAST
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import (
    CLOSED_FORM_RESIDUAL,
    CLOSED_FORM_VS_NUMERIC,
    MUJOCO_PATH_ERROR,
    PROJECTION_PATH_ERROR,
    validate,
)

DEG = np.pi / 180
HYPOTHESIS = settings(max_examples=25, deadline=None, derandomize=True, database=None)


def circle(n: int = 721) -> np.ndarray:
    """n inputs over the whole domain [-pi, pi] (the motion is fully rotatable)."""
    return np.linspace(-np.pi, np.pi, n)


@pytest.mark.parametrize("entry", checked_by(yang2017.NUMBERS, "test_yang2017_example_theta3_40_deg"), ids=str)
def test_yang2017_example_theta3_40_deg(entry):
    # Yang 2017 ch. 2: theta3 = 40 deg gives theta1 = 100, theta4 = 220 (= -140) for every alpha12.
    entry.check()


def test_yang2017_dh_product_is_identity():
    # Yang 2017's Myard example: the D-H product is I to 1e-12 at the published angles (degrees, exact here).
    al = 50 * DEG
    rows = (
        DHRow(0.0, np.sin(al), al),
        DHRow(0.0, 1.0, 90 * DEG),
        DHRow(0.0, 0.0, 80 * DEG),
        DHRow(0.0, 1.0, 90 * DEG),
        DHRow(0.0, np.sin(al), 130 * DEG),
    )
    assert Myard(1.0, al).rows == pytest.approx(rows)
    q = np.deg2rad([100.0, 90.0, 40.0, 220.0, 270.0])
    # measured 2.2e-16
    assert dh_loop(rows).residual_norm(q) <= 1e-12


@pytest.mark.parametrize("alpha12", [30.0, 50.0, 70.0])
def test_eqn_1_20_holds_over_the_whole_circle(alpha12):
    al = alpha12 * DEG
    model = Myard(1.0, al)
    K = np.sin((np.pi / 2 + al) / 2) / np.sin((np.pi / 2 - al) / 2)
    t1, t2, t3, t4, t5 = model.joint_angles(BRANCH, circle()).T
    # The tangents are written as products of sines and cosines, finite at the half turns.
    # Measured worst 0 (sums) and 7.8e-16 (tangent relations, K up to 5.7).
    assert np.max(np.abs(wrap(t1 + t3 + t4 - 2 * np.pi))) < 1e-13
    assert np.max(np.abs(wrap(t2 + t5 - 2 * np.pi))) < 1e-13
    c = np.cos
    s = np.sin
    assert np.max(np.abs(s(t4 / 2) * s(t5 / 2) - K * c(t4 / 2) * c(t5 / 2))) < 1e-13
    assert np.max(np.abs(s(t2 / 2) * c(t3 / 2) - K * s(t3 / 2) * c(t2 / 2))) < 1e-13


@HYPOTHESIS
@given(alpha12=st.floats(1.0, 89.0), a23=st.floats(0.1, 10.0))
def test_closed_form_closes_the_dh_loop_over_the_whole_circle(alpha12, a23):
    model = Myard(a23, alpha12 * DEG)
    q = model.loop_angles(model.joint_angles(BRANCH, circle()))
    # measured worst 5.3e-15 over 40 random (a23, alpha12) in this range (translation scales with a23)
    assert np.max(model.loop_system().residual_norm(q)) <= TOLERANCES.closed_form_residual


@pytest.mark.parametrize("alpha12", [30.0, 50.0, 70.0])
def test_closed_form_matches_numeric_continuation_over_the_whole_circle(alpha12):
    model = Myard(1.0, alpha12 * DEG)
    x = circle(361)
    values = model.joint_angles(BRANCH, x)
    joint, scale = model.loop_input()
    numeric = model.loop_system().follow(model.loop_angles(values)[0], joint, scale * x)
    # measured worst 4.7e-14 rad (alpha12 = 70 deg, K = 5.7); 3.1e-14 at 50, 3.4e-14 at 30
    assert np.max(np.abs(model.observe(numeric) - values)) <= TOLERANCES.closed_form_rad


@pytest.mark.parametrize("theta3", [-2.5, 0.0, 1.2, np.pi])
def test_one_assembly_per_input_and_mobility_one(theta3):
    # One branch with no events: random-start solves find only the closed form, and the closure
    # Jacobian has rank 4 (mobility 1) even at the folded poses theta3 = 0 and pi.
    model = Myard(1.0, 50 * DEG)
    loops = model.loop_system()
    found = loops.assemblies(model.loop_input()[0], theta3, starts=24)
    q = model.loop_angles(model.joint_angles(BRANCH, theta3))
    assert len(found) == 1
    # measured worst 1.8e-15 (at theta3 = pi); assemblies solve to 1e-13
    assert np.max(np.abs(wrap(found[0] - q[0]))) < 1e-10
    assert loops.mobility(q[0]) == 1


def test_motion_is_plane_symmetric():
    # The branch's name: axis 1 lies in a plane that mirrors axis 2 onto 5 and axis 3 onto 4. The
    # plane is found from joints 2 and 5, which coincide at the folded pose theta3 = 0 (not sampled).
    model = Myard(1.0, 50 * DEG)
    for q in model.loop_angles(model.joint_angles(BRANCH, np.linspace(-3.0, 3.0, 12))):
        T = np.eye(4)
        frames = []
        for k, row in enumerate(model.rows):
            c, s = np.cos(q[k]), np.sin(q[k])
            T = T @ np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
            frames.append(T.copy())
            T = T @ row.link()
        P = [F[:3, 3] for F in frames]
        Z = [F[:3, 2] for F in frames]
        n = (P[1] - P[4]) / np.linalg.norm(P[1] - P[4])
        mid = (P[1] + P[4]) / 2
        M = np.eye(3) - 2 * np.outer(n, n)
        # measured worst 1.1e-15 (points in metres, axis directions)
        assert abs((P[0] - mid) @ n) < 1e-12 and abs(Z[0] @ n) < 1e-12
        assert np.linalg.norm(np.cross(M @ Z[1], Z[4])) < 1e-12
        assert np.linalg.norm(mid + M @ (P[2] - mid) - P[3]) < 1e-12
        assert np.linalg.norm(np.cross(M @ Z[2], Z[3])) < 1e-12


def test_peng2018_myard_vertex_is_the_mirror_image_of_alpha12_30_deg():
    # Peng 2018, §4.3 (sector alpha = pi/6): its Myard has twists (4-24)
    # (pi - alpha, pi/2, pi + 2 alpha, pi/2, alpha), i.e. eqn 1-19 with alpha12 = 150 deg, and its
    # angles are theta^My = (q1 + pi, -q2, q3, q4 + pi, q5) of the published q.
    a = np.pi / 6
    q = np.array([1.570796, -1.244669, -0.785398, -0.785398, -1.244669])
    theta_my = np.array([q[0] + np.pi, -q[1], q[2], q[3] + np.pi, q[4]])
    rows = (
        DHRow(0.0, 0.5, np.pi - a),
        DHRow(0.0, 1.0, np.pi / 2),
        DHRow(0.0, 0.0, np.pi + 2 * a),
        DHRow(0.0, 1.0, np.pi / 2),
        DHRow(0.0, 0.5, a),
    )
    # q has 6 decimals (rounding <= 5e-7 rad per angle); measured residual 1.0e-6
    assert dh_loop(rows).residual_norm(theta_my) < 3e-6
    # Mirroring negates every twist and angle; reversing axes 2 and 5 then restores the twists of
    # alpha12 = 30 deg and flips theta2, theta5 back: theta(30) = (-t1, t2, -t3, -t4, t5)(150).
    mirrored = theta_my * np.array([-1, 1, -1, -1, 1])
    got = Myard(1.0, 30 * DEG).joint_angles(BRANCH, mirrored[2])[0]
    # measured 5.8e-7 rad: rounding of q, 5e-7 on the output plus 5e-7 on the input times
    # d theta2 / d theta3 <= K = 1.73, at most 1.4e-6
    assert np.max(np.abs(wrap(got - mirrored))) < 1.5e-6


def test_branch_domain_events_and_gruebler():
    model = Myard(1.0, 50 * DEG)
    (branch,) = model.branches()
    assert branch.name == BRANCH == "plane_symmetric"
    assert branch.domain == (-np.pi, np.pi)
    assert model.events() == ()
    assert model.gruebler() == 5 - 6
    assert model.input_name == "theta3"
    assert model.joint_names == ("theta1", "theta2", "theta3", "theta4", "theta5")
    assert model.loop_input() == (2, 1.0)
    # theta2 is continuous through the half turn (it passes pi with theta3)
    t2 = model.joint_angles(BRANCH, circle(20001))[:, 1]
    assert np.max(np.abs(np.diff(t2))) < 0.01


def test_evaluate_marks_inputs_outside_the_domain_and_joint_angles_refuses_them():
    model = Myard(1.0, 50 * DEG)
    values, valid = model.evaluate(BRANCH, [-4.0, 0.5, 4.0])
    assert valid.tolist() == [False, True, False]
    assert np.all(np.isnan(values[~valid])) and np.all(np.isfinite(values[valid]))
    with pytest.raises(DomainError, match=r"theta3 = 4 rad .*'plane_symmetric'"):
        model.joint_angles(BRANCH, 4.0)
    with pytest.raises(ParameterError, match="plane_symmetric"):
        model.evaluate("folded", 0.5)


@pytest.mark.parametrize("alpha12", [0.0, 90.0, 95.0, -10.0, 180.0])
def test_alpha12_outside_0_90_deg_raises_parameter_error_naming_value_and_rule(alpha12):
    with pytest.raises(ParameterError, match=rf"alpha12 = {alpha12:g} deg; it must be a number in \[0\.001, 89\.999\]"):
        scenes.get("myard").build_from_user({"alpha12": alpha12})
    with pytest.raises(ParameterError, match=rf"alpha12 = {alpha12:g} deg.*\(0, 90\) deg"):
        Myard(1.0, alpha12 * DEG)


@pytest.mark.parametrize("a23", [0.0, -1.0])
def test_non_positive_a23_raises_parameter_error(a23):
    with pytest.raises(ParameterError, match=re.escape(f"a23 = {a23:g} m")):
        scenes.get("myard").build_from_user({"a23": a23})


def test_build_from_user_alpha12_30_deg_derives_eqn_1_19():
    scene = scenes.get("myard").build_from_user({"alpha12": 30})
    assert scene.params == pytest.approx({"a23": 1.0, "alpha12": np.pi / 6})
    a12, a23, a34, a45, a51 = (row.a for row in scene.kinematics.rows)
    twists = np.rad2deg([row.alpha for row in scene.kinematics.rows])
    assert (a12, a23, a34, a45, a51) == pytest.approx((0.5, 1.0, 0.0, 1.0, 0.5))
    assert twists == pytest.approx([30.0, 90.0, 120.0, 90.0, 150.0])
    assert all(row.R == 0.0 for row in scene.kinematics.rows)
    q = scene.loop_to_mechanism(scene.kinematics.loop_angles(scene.kinematics.joint_angles(BRANCH, circle())))
    # The mechanism's own loop (tree path + cut joint 5), not the D-H product: measured 1.4e-15.
    assert np.max(scene.mechanism.loop_system().residual_norm(q)) <= TOLERANCES.closed_form_residual


def test_mechanism_zero_length_link_and_cut_joint_anchors():
    scene = scenes.get("myard").build()
    mech = scene.mechanism
    # a34 = 0: link 3 is a bar of the minimum length, a cube of the bar width (0.05 m).
    link3 = next(b for b in mech.bodies if b.name == "link_3")
    assert link3.solid.extents == pytest.approx([0.05, 0.05, 0.05])
    assert link3.solid.volume == pytest.approx(0.05**3)
    # The drive (joint 3) stays in the tree; joint 5 is cut and closed at two points 1 m apart.
    assert [mech.joints[i].name for i in mech.cut_joints] == ["joint_5"]
    assert scene.drive_joint == "joint_3"
    parent, child = mech.anchor_points(mech.joint_index("joint_5"))
    assert np.linalg.norm(parent[1] - parent[0]) == pytest.approx(1.0)
    assert np.linalg.norm(child[1] - child[0]) == pytest.approx(1.0)
    lo, hi = scene.path
    assert -np.pi < lo < hi < np.pi and min(abs(lo), abs(hi), np.pi - abs(lo), np.pi - abs(hi)) >= 0.5


def test_validate_default_scene_passes_every_verdict():
    report = validate(scenes.get("myard").build())
    assert report.passed, [v for v in report.verdicts if not v.passed]
    (run,) = report.runs
    assert run.followed == BRANCH and run.flips == 0
    measured = {v.id: v.measured for v in (*report.verdicts, *run.verdicts)}
    # Measured: fast path error 3.9e-7 rad (tolerance 2e-6), projection 2.2e-15 rad (1e-13),
    # closure residual 9.0e-16 (1e-12), closed form vs numeric 2.0e-14 rad (1e-12).
    assert measured[MUJOCO_PATH_ERROR] <= FAST.angle_rad
    assert measured[PROJECTION_PATH_ERROR] <= TOLERANCES.projection_rad
    assert measured[CLOSED_FORM_RESIDUAL] <= TOLERANCES.closed_form_residual
    assert measured[CLOSED_FORM_VS_NUMERIC] <= TOLERANCES.closed_form_rad
    # measured 1.3e-15 m
    assert run.projection_residual_m <= TOLERANCES.projection_residual_m
