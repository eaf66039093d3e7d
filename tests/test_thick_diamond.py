"""Thick six-crease diamond vertex = plane-symmetric Bricard (`sim_origami.kinematics.thick_diamond`, scene
`thick-diamond`) against Peng 2018, §4.4.1 (eqns 4-29 to 4-50), the loop solver and MuJoCo."""

import numpy as np
import pytest
from published import check_every, peng2018

import sim_origami.scenes.thick_diamond  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.errors import DomainError, ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.dh import DHRow, dh_loop
from sim_origami.kinematics.thick_diamond import (
    COUNTER,
    DIAMOND,
    ThickDiamond,
    diamond_folds,
    hinge_heights,
    sectors,
)
from sim_origami.kinematics.thick_vertex5 import lifted_loop
from sim_origami.presets import FAST
from sim_origami.simulate import contact_distance, contact_input
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import MUJOCO_PATH_ERROR, PROJECTION_PATH_ERROR, validate

DEG = np.pi / 180
BRANCHES = (DIAMOND, COUNTER)
# (alpha deg, p, q): r = p + q
GEOMETRIES = ((30.0, 0.3, 0.5), (30.0, 0.03, 0.05), (10.0, 1.0, 0.01), (45.0, 0.01, 1.0), (20.0, 0.5, 0.5))


thick_diamond = peng2018.thick_diamond


def domain(n: int = 721) -> np.ndarray:
    return np.linspace(-np.pi, np.pi, n)


def test_thick_diamond_heights_and_main_branch_of_eqn_4_38():
    model = thick_diamond()
    assert model.heights == pytest.approx([0.0, 0.3, -0.2, -1.0, -0.2, 0.3], abs=1e-15)
    assert model.sectors == pytest.approx(np.array([30.0, 120.0, 30.0, 30.0, 120.0, 30.0]) * DEG)
    q = model.at(DIAMOND, np.pi / 2)
    # measured 1.0e-7 (rho) and 2.4e-7 rad (phi2 = pi + rho2, eqn 4-38), 6 decimals
    check_every(peng2018.NUMBERS, "test_thick_diamond_heights_and_main_branch_of_eqn_4_38")
    assert q["rho4"] == pytest.approx(np.pi / 2, abs=1e-15)


def test_thick_diamond_second_flat_branch_at_q1_0_5():
    # measured worst 3.0e-5 rad (4 decimals)
    check_every(peng2018.NUMBERS, "test_thick_diamond_second_flat_branch_at_q1_0_5")


def test_thick_diamond_line_fold_is_impossible_thick_and_possible_with_zero_thickness():
    # (psi, 0, 0, psi, 0, 0): fold about the straight line of creases 1 and 4 only.
    q = np.array([0.5, 0.0, 0.0, 0.5, 0.0, 0.0])
    thick = thick_diamond().loop_system().residual_norm(q)
    # the hinges 1 and 4 are |h4| = 1 m apart: residual |h4| sin(psi) = 0.479426 (a first check here: 0.48)
    assert thick == pytest.approx(np.sin(0.5), abs=1e-12)
    # measured 8.9e-17
    assert lifted_loop(sectors(np.pi / 6), np.zeros(6)).residual_norm(q) <= TOLERANCES.closed_form_residual


def test_thick_diamond_r_0_7_is_refused_and_moves_along_another_curve():
    with pytest.raises(ParameterError, match=r"r = 0\.7 m but p \+ q = 0\.8 m.*r = p \+ q.*misses closure by 0\.1 "):
        ThickDiamond(np.pi / 6, 0.3, 0.5, 0.7)
    # The r = 0.7 loop still moves (plane-symmetric Bricard); followed from near flat on the branch next to
    # 'diamond', at phi1 = pi/2 it reaches a non-equivalent (phi2, phi3, phi4) (worked here).
    loops = lifted_loop(sectors(np.pi / 6), hinge_heights(0.3, 0.5, 0.7))
    x = np.linspace(0.02, np.pi / 2, 80)
    q = loops.follow(diamond_folds(np.pi / 6, x[0])[0], 0, x)[-1]
    phi = np.pi - np.abs(q)
    # measured 4.5e-7 rad (6 decimals)
    check_every(peng2018.NUMBERS, "test_thick_diamond_r_0_7_is_refused_and_moves_along_another_curve")
    assert loops.residual_norm(q) < 1e-13
    assert abs(phi[3] - np.pi / 2) > 0.5  # the equivalent motion would have phi4 = phi1


@pytest.mark.parametrize(("alpha", "p", "q"), GEOMETRIES)
def test_closed_form_closes_the_lifted_loop_over_each_branch(alpha, p, q):
    model = ThickDiamond(alpha * DEG, p, q, p + q)
    for branch in BRANCHES:
        values = model.joint_angles(branch, domain())
        # measured worst 1.2e-15 over these geometries
        assert np.max(model.loop_system().residual_norm(model.loop_angles(values))) <= TOLERANCES.closed_form_residual
        # continuous over the domain (measured largest step 0.012 rad for input steps of 0.0087 rad)
        assert np.max(np.abs(wrap(np.diff(values, axis=0)))) < 0.02


@pytest.mark.parametrize(("alpha", "p", "q"), [GEOMETRIES[0], GEOMETRIES[1], GEOMETRIES[3]])
def test_closed_form_matches_numeric_continuation_on_each_branch(alpha, p, q):
    # The solver's angles are good to its stopping residual over the smallest singular value, which vanishes
    # at the flat bifurcation and shrinks with thin slabs near rho1 = +-pi: with the default 1e-14 the
    # difference reached 2.5e-12 rad at rho1 = 3.0 (p = 0.03). So 0.2 <= |rho1| <= 2.9, solved to 1e-15.
    model = ThickDiamond(alpha * DEG, p, q, p + q)
    joint, scale = model.loop_input()
    for branch in BRANCHES:
        for x in (np.linspace(-0.2, -2.9, 136), np.linspace(0.2, 2.9, 136)):
            values = model.joint_angles(branch, x)
            numeric = model.loop_system().follow(model.loop_angles(values)[0], joint, scale * x, tol=1e-15)
            # measured worst 7.9e-14 rad (p = 0.03); 3.3e-15 (Peng 2018's p = 0.3, q = 0.5), 4.0e-15 (alpha = 45 deg)
            assert np.max(np.abs(model.observe(numeric) - values)) <= TOLERANCES.closed_form_rad


@pytest.mark.parametrize("x", [0.5, -1.2, 2.5])
def test_every_assembly_is_plane_symmetric_on_one_of_the_two_factors(x):
    # Derived here: eliminating rho1 leaves (u - v)((p + q) u + p v) = 0, u = tan(rho2/2), v = tan(rho3/2).
    # The 'diamond' factor has one assembly per input, the 'counter23' factor three (a cubic in u), one
    # of which is the branch through flat: random starts find exactly those four.
    model = thick_diamond()
    found = model.loop_system().assemblies(0, x, starts=96)
    assert len(found) == 4
    assert np.max(np.abs(wrap(found[:, [1, 2]] - found[:, [5, 4]]))) < 1e-10
    u, v = np.tan(found[:, 1] / 2), np.tan(found[:, 2] / 2)
    factor = np.minimum(np.abs(u - v), np.abs(0.8 * u + 0.3 * v) / 0.8)
    # measured worst 6.0e-13 (the assemblies are solved to 1e-13)
    assert np.max(factor) < 1e-10
    for branch in BRANCHES:
        q = model.joint_angles(branch, x)[0]
        assert np.min(np.max(np.abs(wrap(found - q)), axis=1)) < 1e-10


def test_mobility_two_at_flat_one_folded_on_both_branches():
    # Simulation recipe item 6: thick Bricard (diamond, r = p + q) 2 / 1; spherical 6R 4 / 3.
    model = thick_diamond()
    loops, sphere = model.loop_system(), lifted_loop(model.sectors, np.zeros(6))
    assert loops.mobility(np.zeros(6)) == 2
    assert sphere.mobility(np.zeros(6)) == 4
    for branch in BRANCHES:
        for x in (-2.5, -0.4, 0.3, 1.5):
            q = model.joint_angles(branch, x)[0]
            assert loops.mobility(q) == 1
            assert sphere.mobility(q) == 3


def test_both_branches_leave_flat_with_different_tangents():
    model = thick_diamond()
    h = 1e-4
    slopes = [(model.joint_angles(b, h)[0] - model.joint_angles(b, -h)[0]) / (2 * h) for b in BRANCHES]
    # diamond: rho2 / rho1 = -1 / cos(alpha); counter23: -cos(alpha) (k - 1) / ... (distinct directions)
    assert slopes[0][1] == pytest.approx(-1 / np.cos(np.pi / 6), rel=1e-7)
    assert np.max(np.abs(slopes[0] - slopes[1])) > 0.5
    # both tangents lie in the 2-dimensional null space of the closure Jacobian at flat
    J = model.loop_system().jacobian(np.zeros(6))
    for s in slopes:
        assert np.max(np.abs(J @ s)) < 1e-8


@pytest.mark.parametrize(("p", "q", "rho4_with"), [(0.3, 0.5, "rho2"), (0.5, 0.5, "rho1")])
def test_counter23_fold_signs(p, q, rho4_with):
    # Creases 1, 3, 5 fold alike, 2 and 6 against them; crease 4 joins rho2 for r/p > 1 + sqrt(2) (8/3 here)
    # and rho1 for r/p < 1 + sqrt(2) (2 here), near flat.
    model = ThickDiamond(np.pi / 6, p, q, p + q)
    for x in (-0.5, -0.1, 0.1, 0.5):
        s = np.sign(model.joint_angles(COUNTER, x)[0])
        assert s[0] == s[2] == s[4] == -s[1] == -s[5] == np.sign(x)
        assert s[3] == (s[1] if rho4_with == "rho2" else s[0])


@pytest.mark.parametrize("branch", BRANCHES)
def test_thesis_twists_4_40_close_at_the_thesis_angles(branch):
    # (4-40): twists (2 pi - a, pi - 2a, a, 2 pi - a, pi + 2a, a), lengths (p, q, r, r, q, p), R = 0, at
    # theta^Br = (rho1 + pi, rho2 + pi, rho3, rho4 + pi, rho5, rho6 + pi).
    a, p, q, r = np.pi / 6, 0.3, 0.5, 0.8
    rows = (
        DHRow(0.0, p, 2 * np.pi - a),
        DHRow(0.0, q, np.pi - 2 * a),
        DHRow(0.0, r, a),
        DHRow(0.0, r, 2 * np.pi - a),
        DHRow(0.0, q, np.pi + 2 * a),
        DHRow(0.0, p, a),
    )
    rho = thick_diamond().joint_angles(branch, domain(181))
    th = rho + np.array([np.pi, np.pi, 0.0, np.pi, 0.0, np.pi])
    # measured worst 1.7e-15
    assert np.max(dh_loop(rows).residual_norm(th)) <= TOLERANCES.closed_form_residual
    if branch == DIAMOND:
        # (4-42)/(4-48): theta2 = theta6, theta3 = theta5 = pi + theta2, theta1 = theta4,
        # cos(a) tan(theta1/2) + tan(theta2/2) = 0 (as sines and cosines, finite at the half turns)
        assert np.max(np.abs(wrap(th[:, 2] - th[:, 1] - np.pi))) < 1e-15
        assert np.max(np.abs(wrap(th[:, 0] - th[:, 3]))) < 1e-15
        s1, c1, s2, c2 = np.sin(th[:, 0] / 2), np.cos(th[:, 0] / 2), np.sin(th[:, 1] / 2), np.cos(th[:, 1] / 2)
        assert np.max(np.abs(np.cos(a) * s1 * c2 + s2 * c1)) < 1e-15


def test_branches_events_gruebler_and_domain_checks():
    model = thick_diamond()
    assert [(b.name, b.domain) for b in model.branches()] == [(DIAMOND, (-np.pi, np.pi)), (COUNTER, (-np.pi, np.pi))]
    (bifurcation,) = [e for e in model.events() if e.kind == "bifurcation"]
    assert bifurcation.input == 0.0 and set(bifurcation.branches) == {DIAMOND, COUNTER}
    assert sorted((e.branches[0], e.input) for e in model.events() if e.kind == "lock") == sorted(
        (b, s * np.pi) for b in BRANCHES for s in (-1, 1)
    )
    assert model.gruebler() == 6 - 6
    assert model.joint_names == tuple(f"rho{k}" for k in range(1, 7)) and model.input_name == "rho1"
    values, valid = model.evaluate(COUNTER, [-4.0, -np.pi, 0.0, np.pi, 4.0])
    assert valid.tolist() == [False, True, True, True, False]
    assert np.all(np.isnan(values[~valid])) and np.all(np.isfinite(values[valid]))
    assert values[2] == pytest.approx(np.zeros(6), abs=1e-15)
    with pytest.raises(DomainError, match=r"rho1 = -4 rad .*'counter23'"):
        model.joint_angles(COUNTER, -4.0)
    with pytest.raises(ParameterError, match="diamond, counter23"):
        model.evaluate("mode_s", 0.5)


@pytest.mark.parametrize("alpha", [0.0, 46.0, 60.0, -30.0])
def test_alpha_outside_0_45_deg_raises_parameter_error(alpha):
    with pytest.raises(ParameterError, match=rf"alpha = {alpha:g} deg; it must be a number in \[0\.001, 45\] deg"):
        scenes.get("thick-diamond").build_from_user({"alpha": alpha})


@pytest.mark.parametrize("name", ["p", "q", "r"])
def test_non_positive_spacing_raises_parameter_error(name):
    with pytest.raises(ParameterError, match=rf"{name} = 0 m; it must be a number in \[0\.0001, 10000\] m"):
        scenes.get("thick-diamond").build_from_user({name: 0.0})


def test_scene_r_not_p_plus_q_raises_parameter_error():
    with pytest.raises(ParameterError, match=r"r = 0\.07 m but p \+ q = 0\.08 m"):
        scenes.get("thick-diamond").build_from_user({"r": 0.07})


@pytest.fixture(scope="module")
def scene():
    return scenes.get("thick-diamond").build()


def test_scene_mechanism_slabs_cut_and_closure_points(scene):
    mech = scene.mechanism
    assert scene.params == pytest.approx({"alpha": np.pi / 6, "p": 0.03, "q": 0.05, "r": 0.08, "length": 1.0})
    assert scene.kinematics.heights == pytest.approx([0.0, 0.03, -0.02, -0.1, -0.02, 0.03], abs=1e-15)
    thickness = [body.solid.extents[2] for body in mech.bodies]
    assert thickness == pytest.approx([0.03, 0.05, 0.08, 0.08, 0.05, 0.03])
    assert all(body.collision is not None for body in mech.bodies)
    assert [mech.joints[i].name for i in mech.cut_joints] == ["crease_3"]
    assert mech.root == "panel_3" and mech.joints[2].anchors == (0.0, 1.0)
    assert len(scene.contact_pairs) == 15
    for branch in BRANCHES:
        q = scene.kinematics.joint_angles(branch, domain(91))
        # measured worst 9.0e-16
        residual = mech.loop_system().residual_norm(scene.loop_to_mechanism(q))
        assert np.max(residual) <= TOLERANCES.closed_form_residual


def test_slabs_free_on_diamond_path_touch_at_mixed_creases_and_block_counter23(scene):
    start, stop = scene.branch_path(DIAMOND)
    assert np.min(contact_distance(scene, DIAMOND, np.linspace(start, stop, 25))) > 0
    # mixed-face creases 3 and 5 touch at |rho3| = pi/2: rho1 = -2 atan(cos(alpha)) = -1.427449 for slabs
    # reaching the hinges; the relief (2e-3 q) moves it to -1.429429 (measured)
    limit = -2 * np.arctan(np.cos(np.pi / 6))
    touch = contact_input(scene, DIAMOND, start, -np.pi)
    assert limit - 0.005 < touch < limit
    # 'counter23' folds crease 4 (bottom hinge) the blocked way for r/p = 8/3: slabs overlap on both sides
    assert np.max(contact_distance(scene, COUNTER, np.array([-0.4, 0.4]))) < 0


def test_validate_default_scene_passes_every_verdict(scene):
    report = validate(scene)
    every = [*report.verdicts, *(v for run in report.runs for v in run.verdicts)]
    assert report.passed, [v for v in every if not v.passed]
    assert [(run.requested, run.followed, run.flips) for run in report.runs] == [(b, b, 0) for b in BRANCHES]
    for run in report.runs:
        measured = {v.id: v.measured for v in run.verdicts}
        # Measured: fast path error 1.7e-6 (diamond) and 4.2e-7 rad (counter23), projection 7.1e-15 and
        # 6.7e-15 rad, fast closure gap 9.8e-8 and 1.9e-8 m.
        assert measured[MUJOCO_PATH_ERROR] <= FAST.angle_rad
        assert measured[PROJECTION_PATH_ERROR] <= TOLERANCES.projection_rad
        # the bifurcation at flat: mobility 2 there in the numeric loop and in MuJoCo, 1 at the start
        # truss method alike; one state of self-stress (a Bricard 6R) at the start, two at flat
        flat = {"input_rad": 0.0, "numeric": 2, "mujoco": 2, "truss": 2, "truss_self_stress": 2}
        assert run.mobility["bifurcations"] == [flat]
        start = {"input_rad": -0.4, "numeric": 1, "mujoco": 1, "truss": 1, "truss_self_stress": 1}
        assert run.mobility["start"] == start
    # blockage (branch 'diamond'): measured stop -1.429613 vs contact -1.429429 (1.8e-4 rad)
    assert report.blockage.stopped and report.blockage.error <= TOLERANCES.blockage_rad
    # bifurcation study: each branch followed once seeded (diamond from 1e-2 rad, counter23 from 1e-4)
    (study,) = report.bifurcations
    assert study["input_rad"] == 0.0 and None not in study["seed_offset_followed_rad"].values()
