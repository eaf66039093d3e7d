"""Symmetric waterbomb cell (`kinematics.waterbomb`, scenes `waterbomb-vertex` and `waterbomb-thick`) against
Feng 2018, ch. 5 (§5.3, §5.4), the loop solver and MuJoCo."""

import numpy as np
import pytest
from published import check_every, checked_by, feng2018

from sim_origami import scenes
from sim_origami.checks.blockage import assess
from sim_origami.checks.branches import classify
from sim_origami.checks.paths import compare
from sim_origami.errors import ParameterError
from sim_origami.fold import read_fold
from sim_origami.geometry import triangles_cross, wrap
from sim_origami.kinematics.dh import DHRow, dh_loop
from sim_origami.kinematics.waterbomb import (
    CREASES,
    DEGREE4,
    LINE,
    PLANE,
    STRAIGHT,
    Waterbomb,
    plane_blockage,
)
from sim_origami.kinematics.waterbomb_sheet import WaterbombSheet
from sim_origami.origami import hinge_gap
from sim_origami.presets import FAST
from sim_origami.report import FOLD_FRAMES, write
from sim_origami.simulate import contact_distance, contact_input, simulate
from sim_origami.studies.poisson import vertex_positions
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import BLOCKAGE_HOLD, run_blockage, validate

DEG = np.pi / 180
dihedrals = feng2018.dihedrals


# Worked values of Feng 2018, chapter 5 (§5.3, §5.4): tests/published/feng2018.py


@pytest.mark.parametrize(
    "entry", checked_by(feng2018.NUMBERS, "test_waterbomb_vertex_b_dihedrals_on_paths_i_and_ii"), ids=str
)
def test_waterbomb_vertex_b_dihedrals_on_paths_i_and_ii(entry):
    entry.check()


@pytest.mark.parametrize("entry", checked_by(feng2018.NUMBERS, "test_waterbomb_vertex_a_of_section_5_3"), ids=str)
def test_waterbomb_vertex_a_of_section_5_3(entry):
    entry.check()


@pytest.mark.parametrize(
    "entry", checked_by(feng2018.NUMBERS, "test_waterbomb_vertex_b_sweeps_including_blocked_phi4"), ids=str
)
def test_waterbomb_vertex_b_sweeps_including_blocked_phi4(entry):
    entry.check()


def test_waterbomb_blockage_onsets_of_path_two():
    # phi1* = pi + x* (deg) for 35/45, 50/50, 40/55 (alpha + beta = 90 is outside the model, formula only)
    check_every(feng2018.NUMBERS, "test_waterbomb_blockage_onsets_of_path_two")
    assert plane_blockage(40 * DEG, 40 * DEG) is None  # (a): alpha = beta < 45 deg, path II smooth
    events = [e for e in Waterbomb(35 * DEG, 45 * DEG, 0.5).events() if e.branches == (PLANE,)]
    assert [e.kind for e in events] == ["lock", "lock"] and events[0].input == -events[1].input


@pytest.mark.slow
@pytest.mark.parametrize(("alpha", "beta"), [(40, 40), (35, 45), (20, 30), (10, 70), (44, 45)])
@pytest.mark.parametrize("mu", [None, 0.5, 2.0])
def test_closed_forms_close_the_cell_and_match_the_numeric_solve(alpha, beta, mu):
    model = Waterbomb(alpha * DEG, beta * DEG, 0.5, mu, 0.03)
    loops = model.loop_system()
    for branch in model.branches():
        q = model.joint_angles(branch.name, np.linspace(-np.pi + 0.01, -0.01, 301))
        assert np.max(loops.residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured <= 1.4e-15
        # the numeric solve stops at 1e-14 residual, so it is good to 1e-14 / sigma_min: within the default
        # sweep (-1.8..-0.5) measured <= 1.4e-13; towards -2.8 and -0.3 up to 7.9e-12 (sigma_min -> 0.005)
        x = np.linspace(-1.8, -0.5, 201)
        q = model.joint_angles(branch.name, x)
        numeric = loops.follow(q[0], CREASES.index("A4"), x)
        assert np.max(np.abs(wrap(numeric - q))) <= TOLERANCES.closed_form_rad


@pytest.mark.parametrize(("alpha", "beta", "mu"), [(35, 45, 0.5), (40, 40, 1.0), (20, 30, 2.0)])
def test_thick_cell_matches_feng2018_dh_linkages(alpha, beta, mu):
    """Eqns 5-11 and 5-12 (the thesis's D-H Bricard loops of A and B) close at our path I through the thesis's
    joint maps: the hinge heights of the cell are an independent, equivalent reconstruction."""
    a, b, ap = alpha * DEG, beta * DEG, 0.03
    A = (DHRow(0, (2 + mu) * ap, 2 * np.pi - a), DHRow(0, 0, np.pi - 2 * a), DHRow(0, (2 + mu) * ap, a),
         DHRow(0, (2 + mu) * ap, 2 * np.pi - a), DHRow(0, 0, np.pi + 2 * a), DHRow(0, (2 + mu) * ap, a))
    B = (DHRow(0, (1 + mu) * ap, np.pi - a - b), DHRow(0, ap, b), DHRow(0, mu * ap, 2 * np.pi - a),
         DHRow(0, mu * ap, a), DHRow(0, ap, 2 * np.pi - b), DHRow(0, (1 + mu) * ap, np.pi + a + b))
    model = Waterbomb(a, b, 0.5, mu, ap)
    for phi1 in (30, 90, 150):
        fa = dihedrals(model, LINE, phi1, order=("A1", "A2", "A3", "A4", "A5", "A6")) * DEG
        fb = dihedrals(model, LINE, phi1) * DEG
        delta = (2 * np.pi - fa[0], fa[1], np.pi + fa[2], 2 * np.pi - fa[3], np.pi + fa[4], fa[5])
        omega = (2 * np.pi - fb[0], np.pi - fb[1], fb[2], 2 * np.pi - fb[3], fb[4], np.pi - fb[5])
        assert dh_loop(A).residual_norm(delta) <= 1e-14  # measured <= 4e-16
        assert dh_loop(B).residual_norm(omega) <= 1e-14


def test_thick_waterbomb_vertex_b_dh_angles_of_eqn_5_12():
    check_every(feng2018.NUMBERS, "test_thick_waterbomb_vertex_b_dh_angles_of_eqn_5_12")


def test_branches_by_thickness():
    assert [b.name for b in Waterbomb(0.7, 0.7, 0.5).branches()] == [LINE, PLANE, DEGREE4, STRAIGHT]
    assert [b.name for b in Waterbomb(0.7, 0.7, 0.5, 0.5, 0.05).branches()] == [LINE]
    # eqn 5-22b: alpha = beta and mu = 1 keeps path II in the thick cell (Fig 5-13)
    model = Waterbomb(40 * DEG, 40 * DEG, 0.5, 1.0, 0.05)
    assert [b.name for b in model.branches()] == [LINE, PLANE]
    q = model.joint_angles(PLANE, np.linspace(-3.0, -0.1, 50))
    assert np.max(model.loop_system().residual_norm(q)) <= 1e-14


def test_other_branches_are_not_motions_of_the_thick_cell():
    zero, thick = Waterbomb(0.7, 0.7, 0.5), Waterbomb(0.7, 0.7, 0.5, 0.5, 0.05)
    loops = thick.loop_system()
    for branch in (PLANE, DEGREE4, STRAIGHT):
        # measured >= 1.7e-3 at x = -0.05 (and growing with x)
        assert loops.residual_norm(zero.joint_angles(branch, -0.05))[0] >= 1e-3


def test_mobility_drops_at_flat_with_thickness():
    zero, thick = Waterbomb(0.7, 0.7, 0.5), Waterbomb(0.7, 0.7, 0.5, 0.5, 0.05)
    assert zero.loop_system().mobility(np.zeros(11)) == 3
    assert thick.loop_system().mobility(np.zeros(11)) == 2
    for model in (zero, thick):
        assert model.loop_system().mobility(model.joint_angles(LINE, -1.0)[0]) == 1


def test_thick_mujoco_follows_path_one_from_every_zero_thickness_branch():
    """The thick cell, started at a pose of each zero-thickness branch near flat, ends on path I."""
    zero = scenes.get("waterbomb-vertex").build()
    thick = scenes.get("waterbomb-thick").build()
    drive = thick.mechanism.joint_index(thick.drive_joint)
    for branch in (LINE, PLANE, DEGREE4, STRAIGHT):
        run = simulate(thick, LINE, initial=zero.pose(branch, -0.05), stop=-1.0)
        labels = classify(zero.kinematics, run.q[:, drive], thick.outputs(run.q))
        assert (labels.followed, labels.flips) == (LINE, 0)
        path = compare(thick, LINE, run.q)
        assert np.max(np.abs(path.error[len(path.error) // 2 :])) <= FAST.angle_rad  # measured 2.4e-8


def test_zero_thickness_mujoco_follows_each_branch_and_thick_equals_path_one():
    zero = scenes.get("waterbomb-vertex").build()
    thick = scenes.get("waterbomb-thick").build()
    for branch in zero.kinematics.branches():
        path = compare(zero, branch.name, simulate(zero, branch.name).q)
        assert path.max_error() <= FAST.angle_rad  # measured <= 2.4e-8 (stiff, 16x)
    thick_path = compare(thick, LINE, simulate(thick, LINE).q)
    # the thick run against the ZERO-thickness closed form: kinematic equivalence, measured 2.4e-8
    zero_values = zero.kinematics.joint_angles(LINE, thick_path.input)
    assert np.max(np.abs(thick_path.simulated - zero_values)) <= FAST.angle_rad


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"alpha": 45 * DEG, "beta": 45 * DEG}, "alpha \\+ beta = 90"),
        ({"alpha": 0.0}, "alpha = 0 deg"),
        ({"t": -1.0}, "t = -1 m; it must be a number"),
    ],
)
def test_bad_geometry_is_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("waterbomb-vertex").build(**kwargs)


def test_bad_thickness_is_refused():
    with pytest.raises(ParameterError, match=r"mu = 0; it must be a number in \[0\.001, 100\]"):
        scenes.get("waterbomb-thick").build(mu=0.0)


def test_thick_panels_carry_every_hinge_line_on_their_surface():
    """Each face is the hull of its hinge lines: both ends of every hinge are vertices of both panels' solids
    (a slab between a face's lowest and highest hinge buries B2 inside face A12)."""
    scene = scenes.get("waterbomb-thick").build()
    assert hinge_gap(scene.pattern, scene.mechanism) <= 1e-12


def _closest_approach(alpha_deg: float, beta_deg: float) -> float:
    scene = scenes.get("waterbomb-thick").build(alpha=alpha_deg * DEG, beta=beta_deg * DEG)
    return float(np.min(contact_distance(scene, LINE, np.linspace(-0.005, -3.14, 315))))


def test_thick_panels_interfere_only_for_alpha_above_45_degrees():
    """Feng 2018, §5.4: "to avoid the interference at vertex A, 0 < alpha <= pi/4" (a collision claim that needs
    the panels' geometry to test). Faces sharing no vertex, down to rho_A4 = -3.14 on path I: closest approach
    measured 7.1e-2 m at the defaults (40/40), 1.35e-2 at 44.5/30, 5.7e-4 at 45/30, overlap -3.2e-3 at 45.5/30
    (faces A43 and B12), the same threshold for beta 20-40, mu 0.5-2 and a 0.005-0.05."""
    assert _closest_approach(40.0, 40.0) > 0.05
    assert _closest_approach(44.5, 30.0) > 0.01
    assert _closest_approach(45.5, 30.0) < -0.002


@pytest.mark.slow
def test_thick_interference_stops_a_force_limited_drive_at_the_contact():
    """alpha = 50 deg: the panels touch at rho_A4 = -2.2289 on path I, where the servo stops (measured
    1.5e-4 rad from it); at the defaults it folds on to the stacked end, -pi (stopped 3e-5 past it)."""
    blocked, _ = run_blockage(scenes.get("waterbomb-thick").build(alpha=50 * DEG, beta=30 * DEG), LINE)
    assert blocked.stopped and blocked.drive_saturated
    assert blocked.contact_input == pytest.approx(-2.2289, abs=1e-3)
    assert blocked.error <= TOLERANCES.blockage_rad
    free, _ = run_blockage(scenes.get("waterbomb-thick").build(), LINE)
    assert not free.stopped and np.isnan(free.contact_input)
    assert free.stop_input == pytest.approx(-np.pi, abs=1e-3)


@pytest.mark.slow
def test_report_exports_the_simulated_motion_as_a_multi_frame_fold_file():
    scene = scenes.get("waterbomb-thick").build()
    report = validate(scene)
    path = write(report, "out")["fold"]
    fold = read_fold(path)
    assert fold.frames.shape == (FOLD_FRAMES, len(CREASES))
    q = report.runs[0].dynamic.q
    columns = [scene.mechanism.joint_index(c) for c in CREASES]
    # creases come back in the pattern's order (named e<k>) with the hinge heights of the thick cell
    np.testing.assert_allclose(fold.frames[-1], q[-1, columns], atol=1e-12, rtol=0)
    assert [c.height for c in fold.pattern.creases] == [c.height for c in scene.pattern.creases]

    # and the border edges' hinge heights (the periodic neighbours' creases), which shape the panels
    def borders(pattern):
        return {frozenset((a, b)): h for a, b, h in pattern.border_heights}

    assert len(scene.pattern.border_heights) == 8 and borders(fold.pattern) == borders(scene.pattern)
    assert fold.pattern.loop_system().residual_norm(fold.frames).max() <= FAST.residual_per_m


@pytest.mark.parametrize(("rows", "cols"), [(2, 2), (3, 3), (2, 4)])
def test_tessellation_closes_on_every_cell_branch_including_its_c_vertices(rows, cols):
    sheet = WaterbombSheet(40 * DEG, 40 * DEG, 0.5, rows, cols)
    kinds = set(sheet.kinds)
    assert kinds == {"A1", "A2", "A3", "A4", "A5", "A6", "B2", "B6", "B4"}
    plain = sheet.pattern.loop_system()  # per-vertex closure only (A, B and C vertices), no couplings
    x = np.linspace(-3.0, 3.0, 61)
    for branch in sheet.branches():
        q = sheet.joint_angles(branch.name, x)
        assert np.max(plain.residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured <= 8.9e-16
        coupled = sheet.loop_system()
        assert coupled.mobility(q[20]) == 1  # symmetric folding: one DOF
    assert sheet.loop_system().mobility(np.zeros(len(sheet.joint_names))) == 3  # flat: four branches meet


def test_waterbomb_sheet_scene_follows_path_one_in_mujoco():
    scene = scenes.get("waterbomb-sheet").build()
    path = compare(scene, LINE, simulate(scene, LINE).q)
    assert path.max_error() <= FAST.angle_rad  # measured 4.5e-8 worst branch (stiff, 16x)


def sheet_triangles_cross(scene, branch: str, x: float) -> bool:
    """Whether any two of the sheet's zero-thickness triangles that share no vertex cross at input x (rad)."""
    pattern = scene.pattern
    positions, _ = vertex_positions(pattern, scene.mechanism.body_poses(scene.pose(branch, x)))
    tri = positions[0][np.array(pattern.faces)]
    index = {n: k for k, n in enumerate(pattern.face_names)}
    pairs = np.array([(index[a], index[b]) for a, b in scene.colliding_pairs])
    return bool(np.any(triangles_cross(tri[pairs[:, 0]], tri[pairs[:, 1]])))


@pytest.mark.slow
def test_waterbomb_sheet_self_contact_finds_the_straight_line_branch_folding_into_itself():
    """Issue 4's tessellations with contact between panels that share no vertex. On the two-straight-lines branch
    the sheet's straight crease lines fold alike, so its cross-section is an equiangular polygon whose end strips
    meet at rho = 2 pi / 5 on the 2 x 2 sheet (72.0000 deg at alpha, beta = 40/40, 30/40, 40/30, 35/45): the bare
    triangles cross from there, the inset solids touch a little later and a force-limited servo stops there. The
    other branches stay clear on their default sweep."""
    scene = scenes.get("waterbomb-sheet").build()
    branch = "two-straight-lines"
    onset = -2 * np.pi / 5
    assert not sheet_triangles_cross(scene, branch, onset + 1e-6) and sheet_triangles_cross(scene, branch, onset - 1e-6)
    touch = contact_input(scene, branch, -0.5, -1.8)
    assert touch == pytest.approx(-1.313122, abs=1e-6)  # measured -1.3131225 (inset 0.05 t)
    run = simulate(scene, branch, drive="servo", contact=True, start=-0.5, stop=-1.8, hold=BLOCKAGE_HOLD)
    x = run.q[:, scene.mechanism.joint_index(scene.drive_joint)]
    blocked = assess(x, run.target, run.drive_force, 20.0, touch, -1.8)
    assert blocked.stopped and blocked.error <= TOLERANCES.blockage_rad  # measured 1.7e-5 rad past the touch
    for other in ("line-symmetric", "plane-symmetric", "A-straight-B-degree4"):
        start, stop = scene.branch_path(other)
        assert np.min(contact_distance(scene, other, np.linspace(start, stop, 14))) > 0.0  # first touch |x| >= 2.86
    line = compare(scene, LINE, simulate(scene, LINE, contact=True).q).max_error()
    assert line == pytest.approx(compare(scene, LINE, simulate(scene, LINE).q).max_error(), rel=1e-9)  # no contact


def test_waterbomb_sheet_bad_size():
    with pytest.raises(ParameterError, match="rows = 1"):
        scenes.get("waterbomb-sheet").build(rows=1)
