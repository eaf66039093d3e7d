"""Fabrication errors (`sim_origami.fabrication`) and the non-overconstrained forms (`sim_origami.linkage_forms`)
against Yang 2017, ch. 3 (Secs. 3.3 to 3.5), the truss method and MuJoCo."""

import numpy as np
import pytest
from published import check_every, checked_by, yang2017

from sim_origami import scenes
from sim_origami.errors import AssemblyError, ParameterError
from sim_origami.geometry import transform_z, wrap
from sim_origami.kinematics.bennett import Bennett
from sim_origami.kinematics.dh import DHRow, dh_from_axes, dh_loop
from sim_origami.kinematics.myard import BRANCH, Myard
from sim_origami.linkage import dh_mechanism
from sim_origami.linkage_forms import chain_poses, reduced_form
from sim_origami.presets import FAST
from sim_origami.scenes.base import Scene, Tuning
from sim_origami.scenes.polyhedra import kutzbach
from sim_origami.simulate import mujoco_mobility, simulate
from sim_origami.studies.fabrication import (
    DEG,
    NOMINAL,
    RSSR,
    VERY_COARSE,
    FabricationError,
    closure_gap,
    dh_axes,
    linearised_error,
    max_waggle,
    output_error,
    peak,
    screw_mobility,
    tilted,
    waggle,
)
from sim_origami.truss import analyse, truss_of

NOMINAL_RSSR = RSSR(*NOMINAL)
D_ALPHA, D_L = VERY_COARSE
CIRCLE = np.linspace(-np.pi, np.pi, 2001)


def counts(c) -> tuple[int, ...]:
    return c.nodes, c.bars, c.rank, c.mobility, c.self_stress


# --- the RSSR: key identity, (3-3)...(3-6) ----------------------------------------------------------------------


@pytest.mark.parametrize(("a1", "a2", "alpha"), [(100, 70.72, 45), (101.5, 69.22, 45), (100, 70.72, 46)])
def test_key_identity_rssr_is_the_bennett_with_implied_beta(a1, a2, alpha):
    # beta to 4 decimals, K to 6: the two roots of (b - a) T^2 - 2 b cos(alpha) T + (a + b) = 0
    for entry in checked_by(yang2017.NUMBERS, "test_key_identity_rssr_is_the_bennett_with_implied_beta"):
        if f"= {(a1, a2, alpha)}" in entry.where:
            entry.check()
    rssr, other = RSSR(a1, a2, alpha * DEG), RSSR(a1, a2, alpha * DEG, root=-1)
    for K in (rssr.K, other.K):  # measured 1.4e-13 (terms up to 7e2)
        assert abs((a2 - a1) * K**2 - 2 * a2 * np.cos(alpha * DEG) * K + (a1 + a2)) < 1e-11
    b = rssr.beta
    assert rssr.K == pytest.approx(np.sin((b + rssr.alpha) / 2) / np.sin((b - rssr.alpha) / 2), abs=1e-14)  # (3-6a)
    # Every configuration of the Bennett linkage with the implied beta is one of the RSSR: measured 8.9e-16 rad.
    bennett = Bennett(a1, alpha * DEG, a2, b)
    assert np.abs(wrap(bennett.joint_angles("bennett", CIRCLE)[:, 1] - rssr.theta2(CIRCLE))).max() < 1e-12
    # (3-3) holds on both roots: measured 1.0e-15
    assert np.abs(rssr.io_residual(CIRCLE, rssr.theta2(CIRCLE))).max() < 1e-12
    assert np.abs(other.io_residual(CIRCLE, other.theta2(CIRCLE))).max() < 1e-12


def test_rssr_closes_the_distance_cd_and_equals_printed_3_5():
    # (3-3) is |CD| = a1 with D = (-a2, 0, 0), C = T12 T23 origin (derived here); (3-5) as printed, '+' where
    # sin(theta1) cos(beta) > 0, is our branch away from sin(theta1) = 0, where B + C = 0 and the roots meet.
    r = FabricationError(0.0, D_L, 1).built(NOMINAL_RSSR)
    t1 = CIRCLE[np.abs(np.sin(CIRCLE)) > 1e-3]
    t2 = r.theta2(t1)
    rows = r.bennett_rows()
    C = (transform_z(t1) @ rows[0].link() @ transform_z(t2) @ rows[1].link())[:, :3, 3]
    assert np.abs(np.linalg.norm(C - [-r.a2, 0, 0], axis=1) - r.a1).max() < 1e-11  # measured 4.3e-14 mm
    A, B, Cc = r.coefficients(t1)
    sign = np.sign(np.sin(t1) * np.cos(r.beta))
    printed = 2 * np.arctan((A + sign * np.sqrt(A**2 + B**2 - Cc**2)) / (B + Cc))
    assert np.abs(wrap(printed - t2)).max() < 1e-12  # measured 5.6e-14


# --- fabrication errors (Sec. 3.5): the thesis's numbers --------------------------------------------------------


@pytest.mark.parametrize("name", list(yang2017.FABRICATION_ERRORS))
def test_yang2017_output_errors(name):
    # the thesis prints 0.58, 5.06, 0.53 (k = +1); the k = -1 rows and the linearised values are ours (derived here)
    error = yang2017.FABRICATION_ERRORS[name]
    for entry in checked_by(yang2017.NUMBERS, "test_yang2017_output_errors"):
        if entry.quantity.endswith(f"{name} (3 decimals)") or entry.quantity.endswith(f"{name} (0.1 deg)"):
            entry.check()
    # the error is odd in theta1: the peak recurs at -theta1 (measured 0 difference)
    built = error.built(NOMINAL_RSSR)
    assert output_error(NOMINAL_RSSR, built, -CIRCLE) == pytest.approx(-output_error(NOMINAL_RSSR, built, CIRCLE))
    # measured here: the peak is near +-155 deg, not "around 180 deg" (Sec. 3.5)
    assert abs(output_error(NOMINAL_RSSR, built, np.pi)) < 1e-15


def test_output_error_falls_towards_the_half_turn():
    # Derived here: d_l = 1.5 mm, k = +1: 3.431 deg at theta1 = 170 deg, 0.394 at 179 deg
    check_every(yang2017.NUMBERS, "test_output_error_falls_towards_the_half_turn")


def test_linearised_error_is_printed_3_42_and_the_derivative_of_the_exact_one():
    # Our (3-42) is rewritten through K; the printed form with A', B', C' of Sec. 3.5 gives the same values
    # (away from theta1 = 0, where the printed form is 0/0, and +-pi), and both are the derivative of the exact (3-5).
    t = CIRCLE[np.abs(np.sin(CIRCLE)) > 1e-2]
    r = NOMINAL_RSSR
    f1, f2 = r.sensitivity(t)
    A, B, C = r.coefficients(t)
    root = np.sign(np.sin(t)) * np.sqrt(A**2 + B**2 - C**2)
    printed = []
    for dA, dB, dC in ((-np.sin(r.alpha) * np.sin(t), 0.0, 0.0), (0.0, -1.0, np.cos(t))):
        dN = dA + (A * dA + B * dB - C * dC) / root
        printed.append((dN * (B + C) - (A + root) * (dB + dC)) / (A**2 + B**2 + B * C + A * root))
    assert np.abs(f1 - printed[0]).max() < 1e-12 and np.abs(f2 - printed[1]).max() < 1e-12  # measured 7.4e-15, 8.7e-15
    h = 1e-6
    fd1 = (RSSR(r.a1, r.a2, r.alpha + h).theta2(t) - RSSR(r.a1, r.a2, r.alpha - h).theta2(t)) / (2 * h)
    x2 = r.x2
    fd2 = (RSSR(x2 + h, 1.0, r.alpha).theta2(t) - RSSR(x2 - h, 1.0, r.alpha).theta2(t)) / (2 * h)
    assert np.abs(f1 - fd1).max() < 1e-8 and np.abs(f2 - fd2).max() < 1e-8  # measured 6.3e-10, 6.1e-10
    error = FabricationError(0.0, D_L, 1)
    dx1, dx2 = error.increments(r)
    assert (dx1, dx2) == pytest.approx((0.0, 101.5 / 69.22 - 100 / 70.72), abs=1e-15)
    assert linearised_error(r, error, t) == pytest.approx(f2 * dx2, abs=1e-15)


@pytest.mark.parametrize(
    ("error", "printed"), [(FabricationError(-D_ALPHA, 0.0, 1), 0.821), (FabricationError(0.0, D_L, -1), 1.669)]
)
def test_waggle_corrected_3_50(error, printed):
    # Corrected (3-50) gives 0.581 / 1.224 deg (thesis 0.58 / 1.22); the printed normalisation by a2R would give
    # 0.821 / 1.669 (ours, 3 decimals). It equals the angle between CD of (3-48) and the nominal z_D.
    check_every(yang2017.NUMBERS, "test_waggle_corrected_3_50")
    check_every(yang2017.CORRECTIONS, "test_waggle_corrected_3_50")  # |CD| = a1R: 4.3e-14 mm; a2R misses by 26 mm
    nominal, built = NOMINAL_RSSR, error.built(NOMINAL_RSSR)
    w = max_waggle(nominal, built)
    # Derived here: the maximum is |beta_R - beta| (measured 1.0e-16 rad apart): the balls turn about the implied axes
    assert w.value == pytest.approx(abs(built.beta - nominal.beta), abs=1e-12)
    t1 = CIRCLE
    b = nominal.beta
    T_AD = np.array([[1, 0, 0, built.a2], [0, np.cos(b), -np.sin(b), 0], [0, np.sin(b), np.cos(b), 0], [0, 0, 0, 1]])
    t2 = built.theta2(t1)
    C_B = np.stack([built.a2 * np.cos(t2), built.a2 * np.sin(t2), 0 * t2, 1 + 0 * t2], -1)
    C_D = np.einsum("ij,njk,nk->ni", T_AD, transform_z(t1) @ built.bennett_rows()[0].link(), C_B)[:, :3]
    assert np.abs(np.linalg.norm(C_D, axis=1) - built.a1).max() < 1e-11  # (3-49): |CD| = a1R; measured 5.7e-14 mm
    vector = np.abs(np.arcsin(C_D[:, 2] / built.a1))
    assert np.abs(vector - waggle(nominal, built, t1)).max() < 1e-13  # measured 2.4e-16 rad
    wrong = np.abs(np.arcsin(C_D[:, 2] / built.a2))  # (3-49) as printed
    assert wrong.max() / DEG == pytest.approx(printed, abs=5e-4)  # the printed (3-49)'s waggle, 3 decimals


# --- the overconstrained forms with the same errors ------------------------------------------------------------


def test_perturbed_bennett_closes_only_folded_and_locks():
    nominal = NOMINAL_RSSR
    good = Bennett(nominal.a1, nominal.alpha, nominal.a2, nominal.beta)
    built = FabricationError(0.0, D_L, 1).built(nominal)
    with pytest.raises(AssemblyError, match="cannot be assembled as a Bennett linkage"):
        Bennett(built.a1, built.alpha, built.a2, nominal.beta)
    bad = Bennett(built.a1, built.alpha, built.a2, nominal.beta, check=False)
    gap = {}
    for theta in (0.0, 1.0, 2.0, np.pi):
        start = good.loop_angles(good.joint_angles("bennett", theta))
        gap[theta] = closure_gap(bad.loop_system(), start, nominal.a1, fixed=(0,)).translation
    # Derived here: measured 1.280 mm at 1 rad, 2.275 mm at 2 rad; 0 at the folded poses 0 and pi (1.6e-14, 7.6e-16 mm)
    assert gap[1.0] == pytest.approx(1.280, abs=5e-4) and gap[2.0] == pytest.approx(2.275, abs=5e-4)
    assert gap[0.0] < 1e-10 and gap[np.pi] < 1e-10
    # folded: rigid (screw rank 4); the nominal Bennett there keeps mobility 1
    assert screw_mobility(*dh_axes(bad.rows, [0.0, np.pi, 0.0, -np.pi])) == 0
    assert screw_mobility(*dh_axes(good.rows, [0.0, np.pi, 0.0, -np.pi])) == 1
    # Sec. 3.3: an axis tilted 1.5 deg at an assembled pose -> r = 18, m = 0; its RSSR form keeps m = 1, s = 0
    q = good.loop_angles(good.joint_angles("bennett", 1.0))[0]
    points, dirs = dh_axes(good.rows, q)
    assert screw_mobility(points, dirs) == 1 and screw_mobility(points, dirs, (3, 4)) == 2  # 1 + idle spin of CD
    dirs = tilted(dirs, 1, 1.5 * DEG)
    rows, angles = dh_from_axes(points, dirs)
    assert dh_loop(rows).residual_norm(angles) < 1e-12  # forced together: measured 1.4e-14 mm
    assert counts(analyse(truss_of(dh_mechanism(rows, anchor=50.0, width=5.0), angles))) == (8, 20, 18, 0, 2)
    assert screw_mobility(points, dirs) == 0 and screw_mobility(points, dirs, (3, 4)) == 2
    form = reduced_form(rows, (3, 4), anchor=50.0, width=5.0)
    q_form = form.angles_from_poses(chain_poses(rows, angles))[0]
    assert counts(analyse(truss_of(form, q_form))) == (6, 11, 11, 1, 0)


@pytest.mark.parametrize(("ball", "name"), [(1, "RRSRR"), (2, "RSRRR")])
def test_myard_forms_keep_mobility_with_errors(ball, name):
    # Sec. 3.4: Myard j = 9, b = 22, r = 20, m = 1, s = 2; RRSRR / RSRRR built with ball_joint: 8, 17, 17, 1, 0.
    model = Myard(1.0, 50 * DEG)
    q = model.loop_angles(model.joint_angles(BRANCH, 40 * DEG))[0]
    assert counts(analyse(truss_of(dh_mechanism(model.rows, anchor=0.5, input_joint=3), q))) == (9, 22, 20, 1, 2)
    form = reduced_form(model.rows, (ball,), anchor=0.5, input_joint=3)
    assert counts(analyse(truss_of(form, form.angles_from_poses(chain_poses(model.rows, q))[0]))) == (8, 17, 17, 1, 0)
    # forced together with axis 5 tilted by 1 deg: the 5R locks (m = 0), the form keeps m = 1, s = 0
    points, dirs = dh_axes(model.rows, q)
    dirs = tilted(dirs, 5, DEG)
    rows, angles = dh_from_axes(points, dirs)
    assert analyse(truss_of(dh_mechanism(rows, anchor=0.5, input_joint=3), angles)).mobility == 0
    assert screw_mobility(points, dirs) == 0 and screw_mobility(points, dirs, (ball,)) == 1
    form = reduced_form(rows, (ball,), anchor=0.5, input_joint=3)
    c = analyse(truss_of(form, form.angles_from_poses(chain_poses(rows, angles))[0]))
    assert (c.mobility, c.self_stress) == (1, 0), name
    # a twist error alpha45 + 1 deg: the 5R cannot close at theta3 = 40 deg, the form closes and moves
    perturbed = list(model.rows)
    perturbed[3] = DHRow(0.0, perturbed[3].a, perturbed[3].alpha + DEG)
    gap = closure_gap(dh_loop(tuple(perturbed)), q, 1.0, fixed=(2,))
    assert gap.rotation > 1e-3 and gap.translation > 1e-3  # measured 6.6e-3 rad, 8.5e-3 a23
    form = reduced_form(tuple(perturbed), (ball,), anchor=0.5, input_joint=3)
    loops = form.loop_system()
    q0 = form.angles_from_poses(chain_poses(model.rows, q))[0]
    fixed = np.arange(len(q0)) == form.joint_index("joint_3")
    closed = loops.solve(q0, fixed)  # converges to 1e-14 (raises otherwise)
    assert loops.mobility(closed) == 1
    assert counts(analyse(truss_of(form, closed))) == (8, 17, 17, 1, 0)


# --- MuJoCo --------------------------------------------------------------------------------------------------------


def test_mujoco_rssr_follows_the_perturbed_closed_form_and_the_bennett_does_not_close():
    # The thesis's scale 100 mm -> 1 m; d_l = 1.5 mm -> 0.015 m, k = +1 (a1 longer, a2 shorter).
    nominal = RSSR(NOMINAL[0] / 100, NOMINAL[1] / 100, NOMINAL[2])
    built = FabricationError(0.0, 0.015, 1).built(nominal)
    scene = scenes.get("rssr").build(a1=built.a1, a2=built.a2, alpha=built.alpha)
    mech = scene.mechanism
    assert (mech.idle_spins, kutzbach(mech)) == (1, 1)
    assert [mech.joints[i].name for i in mech.cut_joints] == ["ball_4_z"]  # the ball at D is one connect
    assert mujoco_mobility(scene, scene.pose("bennett", 1.0)) == 2  # the motion + the idle spin of CD
    run = simulate(scene, "bennett", preset=FAST)
    i1, i2 = mech.joint_index("joint_1"), mech.joint_index("joint_2")
    theta1 = run.q[:, i1]
    assert theta1.min() < 2.70 < theta1.max()  # the sweep covers the error's peak (154.7 deg)
    error = np.abs(wrap(run.q[:, i2] - built.theta2(theta1)))
    # measured 8.0e-8 rad (fast, the scene's 6x sweep; 3x: 3.3e-7; stiff at 1x: 2.4e-5), closure gap 1.3e-8 m
    assert error.max() <= FAST.angle_rad
    assert run.closure_residual.max() <= FAST.residual_per_m
    assert np.abs(wrap(run.q[:, i2] - nominal.theta2(theta1))).max() / DEG > 5.0  # the nominal is 5.06 deg off
    # the waggle measured on MuJoCo's bar CD against the nominal z_D (ground frame: z_A at beta_R from z_D)
    poses = mech.body_poses(run.q)
    cd = -poses["link_3"][:, :3, 3] / np.linalg.norm(poses["link_3"][:, :3, 3], axis=1, keepdims=True)
    d = built.beta - nominal.beta
    measured = np.abs(np.arcsin(cd @ [0.0, -np.sin(d), np.cos(d)]))
    assert np.abs(measured - waggle(nominal, built, theta1)).max() < 1e-6  # measured 5.5e-8 rad
    # The overconstrained Bennett with the same errors: MuJoCo's connects cannot close it (measured 7.8e-3 ..
    # 2.7e-2 m against 2.0e-8 m for the nominal Bennett on the same sweep) and its constraint rank leaves m = 0.
    bad = Bennett(built.a1, built.alpha, built.a2, nominal.beta, check=False)
    mechanism = dh_mechanism(bad.rows, anchor=0.5)
    bennett = Scene(name="bennett-built", params={}, kinematics=bad, mechanism=mechanism,
                    loop_joints=tuple(j.name for j in mechanism.joints), drive_joint="joint_1", drive_scale=1.0,
                    path=(0.5, 2.9), tuning=Tuning(sweep_time_scale=3.0))
    assert mujoco_mobility(bennett, bennett.pose("bennett", 1.0)) == 0
    assert simulate(bennett, "bennett", preset=FAST).closure_residual.min() > 5e-3


# --- bad input -------------------------------------------------------------------------------------------------------


def test_bad_input():
    with pytest.raises(ParameterError, match="a1 = -1"):
        RSSR(-1.0, 1.0, 0.5)
    with pytest.raises(ParameterError, match="twist alpha"):
        RSSR(1.0, 0.5, np.pi)
    with pytest.raises(ParameterError, match="a1 = a2"):
        RSSR(1.0, 1.0, 0.5)
    with pytest.raises(ParameterError, match="root"):
        RSSR(1.0, 0.5, 0.5, root=0)
    with pytest.raises(AssemblyError, match="cannot be assembled"):
        RSSR(0.5, 1.0, 80 * DEG)  # a2 sin(alpha) = 0.985 > a1
    with pytest.raises(ParameterError, match=r"k = 1\.5"):
        FabricationError(0.0, 1.0, 1.5)
    with pytest.raises(ParameterError, match="d_alpha = nan"):
        FabricationError(np.nan)
    with pytest.raises(ParameterError, match="lo < hi"):
        peak(np.sin, 1.0, 0.0)
    with pytest.raises(ParameterError, match="not finite"):
        peak(lambda t: np.where(t > 0.5, np.nan, t), 0.0, 1.0)
    rows = NOMINAL_RSSR.bennett_rows()
    with pytest.raises(ParameterError, match="4 finite joint angles"):
        dh_axes(rows, [0.0, 1.0])
    points, dirs = dh_axes(rows, NOMINAL_RSSR.loop_angles(1.0)[0])
    with pytest.raises(ParameterError, match="joint 5"):
        tilted(dirs, 5, 0.1)
    with pytest.raises(ParameterError, match="parallel"):
        tilted(np.array([[0, 0, 1.0], [0, 0, 1.0], [1.0, 0, 0]]), 1, 0.1)
    with pytest.raises(ParameterError, match="spherical joints \\[7\\]"):
        screw_mobility(points, dirs, (7,))
    loops = dh_loop(rows)
    with pytest.raises(ParameterError, match="fixed joints"):
        closure_gap(loops, np.zeros(4), 1.0, fixed=(4,))
    with pytest.raises(ParameterError, match="starts of shape"):
        closure_gap(loops, np.zeros(3), 1.0)
    with pytest.raises(ParameterError, match="scale"):
        closure_gap(loops, np.zeros(4), 0.0)
    with pytest.raises(ParameterError, match="input must stay a hinge"):
        reduced_form(rows, (1,))
    with pytest.raises(ParameterError, match="4 finite loop angles"):
        chain_poses(rows, np.zeros((2, 3)))
