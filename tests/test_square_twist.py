"""Square twist (`kinematics.square_twist`, scene `square-twist`) against Peng 2018, §3.3
(eqns 3-29 to 3-32, Figs 3-15 and 3-18), the signed and unsigned loop solvers and MuJoCo."""

import numpy as np
import pytest
from published import check_every, checked_by, peng2018

import sim_origami.scenes.square_twist  # noqa: F401  (registers `square-twist`)
from sim_origami import scenes
from sim_origami.checks.blockage import assess
from sim_origami.checks.paths import compare
from sim_origami.errors import DomainError, ParameterError
from sim_origami.fold import read_fold
from sim_origami.geometry import wrap
from sim_origami.kinematics.numeric_pattern import FOLDABLE_TOL
from sim_origami.kinematics.square_twist import (
    CREASES,
    EDGES,
    RIGID,
    VERTICES,
    SquareTwist,
    assignment,
    crease_pattern,
    edge_multipliers,
    loop_gain,
    metamaterial_unit,
    mode_classes,
    tan_ratios,
    verdict_table,
)
from sim_origami.kinematics.vertex4 import flat_foldable_multipliers
from sim_origami.presets import FAST
from sim_origami.report import write
from sim_origami.scenes.square_twist import assigned
from sim_origami.simulate import simulate
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import validate

ALPHA = 5 * np.pi / 6  # Fig 3-15
# The 6-decimal values (printed, or computed independently here): half a unit of the last digit.
PRINTED = 5e-7
# The servo's force range (mjcf_templates/defaults.xml, class servo), N m.
SERVO_LIMIT = 20.0


def vertex_folds(q: np.ndarray, k: int) -> np.ndarray:
    """Fold angles (n, 4) of vertex k's creases 1..4 from joint angles (n, 12) in CREASES order."""
    v = VERTICES[k]
    names = (f"{v}1", EDGES[k], EDGES[(k - 1) % 4], f"{v}4")
    return q[:, [CREASES.index(n) for n in names]]


@pytest.mark.parametrize("alpha_deg", [100.0, 150.0, 170.0])
def test_pattern_has_four_flat_foldable_vertices_with_peng2018_sectors(alpha_deg):
    alpha = np.deg2rad(alpha_deg)
    pattern = crease_pattern(alpha, 1.0, 0.7)
    assert (len(pattern.faces), len(pattern.creases), len(pattern.interior_vertices())) == (9, 12, 4)
    for k, v in enumerate(pattern.interior_vertices()):
        around = pattern.vertex_creases(v)
        names = [pattern.creases[i].name for i, _ in around]
        first = names.index(f"{VERTICES[k]}1")
        d = [around[(first + i) % 4][1] for i in range(4)]  # creases 1..4, counter-clockwise
        sectors = [np.arctan2(np.cross(d[i], d[(i + 1) % 4])[2], d[i] @ d[(i + 1) % 4]) % (2 * np.pi) for i in range(4)]
        np.testing.assert_allclose(sectors, [alpha, np.pi / 2, np.pi - alpha, np.pi / 2], atol=1e-14, rtol=0)


@pytest.mark.parametrize("modes", [m for members in mode_classes().values() for m in members])
def test_every_assignment_obeys_maekawa_and_big_little_big(modes):
    pattern = crease_pattern(ALPHA, modes=modes)
    letters = {c.name: c.assignment for c in pattern.creases}
    assert "".join(letters[c] for c in CREASES) == assignment(ALPHA, modes)
    for k, v in enumerate(VERTICES):
        mv = [letters[n] for n in (f"{v}1", EDGES[k], EDGES[(k - 1) % 4], f"{v}4")]
        assert abs(mv.count("M") - mv.count("V")) == 2  # Maekawa (1-12)
        assert mv[2] != mv[3]  # Big-Little-Big: creases 3 and 4 bound the smallest sector, pi - alpha


def test_multipliers_against_peng2018():
    m = edge_multipliers(ALPHA)
    # m_C 1.732051 vs ours 1.7320508, m_S -0.577350 vs -0.5773503
    check_every(peng2018.NUMBERS, "test_multipliers_against_peng2018")
    vertex = flat_foldable_multipliers([ALPHA, np.pi / 2, np.pi - ALPHA, np.pi / 2])
    assert (m["C"], m["S"]) == pytest.approx((vertex["C"][1], vertex["S"][1]), abs=1e-15)  # eqn 3-3 = §3.3's
    for alpha in np.linspace(0.51 * np.pi, 0.99 * np.pi, 25):
        m = edge_multipliers(alpha)
        assert m["C"] * m["S"] == pytest.approx(-1.0, abs=1e-13)  # identically; measured <= 1.1e-14 (alpha -> 90)


def test_verdict_table_has_two_rigid_classes_of_four():
    table = {v.name: v for v in verdict_table(ALPHA)}
    assert {name: len(v.members) for name, v in table.items()} == {"adjacent": 4, "opposite": 2, "all-C": 1, "all-S": 1}
    # Peng 2018, §3.3: two classes rigid, two locked; here K = 9 (CCCC) and 1/9 (SSSS), CCSS and CSCS K = 1
    gains = {name: v.loop_gain for name, v in table.items()}
    assert gains == pytest.approx({"adjacent": 1.0, "opposite": 1.0, "all-C": 9.0, "all-S": 1 / 9}, abs=1e-13)
    for name, v in table.items():
        assert v.rigid_analytic == v.rigid_numeric == (name in ("adjacent", "opposite"))
        if v.rigid_numeric:
            assert v.residual <= FOLDABLE_TOL  # a sign-kept 1-DOF path over 0.1..2 rad; measured 6.6e-16
        else:
            assert v.residual >= 1e-4  # the sign-held solve stalls: measured 1.15e-4 (both classes)
    assert sum(v.rigid_numeric for v in table.values()) == 2


@pytest.mark.parametrize("alpha_deg", [110.0, 135.0])
def test_two_of_four_rigid_at_other_twist_angles(alpha_deg):
    table = verdict_table(np.deg2rad(alpha_deg), 1.0, 0.5)
    assert [v.rigid_numeric for v in table] == [v.rigid_analytic for v in table] == [True, True, False, False]


def test_branches_are_the_rigid_mode_strings_with_vertex_mode_relations():
    model = SquareTwist(ALPHA)
    assert tuple(b.name for b in model.branches()) == RIGID
    x = np.linspace(-np.pi, np.pi, 401)
    for modes in RIGID:
        q = model.joint_angles(modes, x)
        for k, mode in enumerate(modes):
            r1, r2, r3, r4 = vertex_folds(q, k).T
            sign = 1.0 if mode == "C" else -1.0  # C: rho3 = rho1, rho4 = -rho2; S: rho3 = -rho1, rho4 = rho2
            assert np.max(np.abs(wrap(r3 - sign * r1))) <= 1e-14  # measured <= 8.9e-16
            assert np.max(np.abs(wrap(r4 + sign * r2))) <= 1e-14
        assert np.max(np.abs(np.abs(q[[0, -1]]) - np.pi)) <= 1e-15  # every crease folds flat at x = +-pi


def test_closed_form_closes_and_matches_the_numeric_solve():
    model = SquareTwist(ALPHA, 1.0, 0.6)
    loops = model.loop_system()
    for modes in RIGID:
        q = model.joint_angles(modes, np.linspace(-np.pi, np.pi, 1001))
        assert np.max(loops.residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured <= 1.2e-15
        x = np.linspace(0.1, 3.0, 30)
        q = model.joint_angles(modes, x)
        numeric = loops.follow(q[0], CREASES.index("AB"), x)
        assert np.max(np.abs(wrap(numeric - q))) <= TOLERANCES.closed_form_rad  # measured <= 1.2e-13


def test_locked_mode_strings_do_not_close():
    loops = SquareTwist(ALPHA).loop_system()
    for modes in ("CCCC", "SSSS"):
        k = tan_ratios(ALPHA, modes)
        for x in (0.05, 1.0):
            chained = 2 * np.arctan(k * np.tan(x / 2))  # per-vertex folds chained round the square (K != 1)
            assert loops.residual_norm(chained) >= 1e-2  # misses at B: measured >= 3.8e-2
            # the sign-held solve stalls: measured >= 1e-4
            assert loops.solve_signed(np.sign(k), CREASES.index("AB"), x)[1] >= 1e-4
    assert loop_gain(ALPHA, "CCCC") * loop_gain(ALPHA, "SSSS") == pytest.approx(1.0, abs=1e-14)


def test_events_mobility_and_kutzbach():
    model = SquareTwist(ALPHA)
    kinds = {(e.kind, e.input): e.branches for e in model.events()}
    assert kinds == {("bifurcation", 0.0): RIGID, ("lock", -np.pi): RIGID, ("lock", np.pi): RIGID}
    loops = model.loop_system()
    assert model.gruebler() == 0  # overconstrained: 12 creases, 4 spherical loops
    assert loops.mobility(np.zeros(12)) == 4  # flat: 12 - rank 8
    for modes in RIGID:
        assert loops.mobility(model.joint_angles(modes, 1.0)[0]) == 1


@pytest.mark.parametrize("alpha", [5 * np.pi / 6, 3 * np.pi / 4, 2 * np.pi / 3])
def test_square_twist_metamaterial_tables_of_eqns_3_30_to_3_32(alpha):
    # phi, L, S, H, nu_SL, nu_HL at a = b = c = 1, 6 decimals
    for entry in checked_by(peng2018.NUMBERS, "test_square_twist_metamaterial_tables_of_eqns_3_30_to_3_32"):
        if entry.where.endswith(f"alpha = {round(np.rad2deg(alpha))} deg"):
            entry.check()
    theta = np.deg2rad([30.0, 60.0, 90.0, 120.0, 150.0])
    unit = metamaterial_unit(alpha, theta)
    # phi is crease DA of vertex A in mode C at rho_AB = theta: the square twist's own closed form
    np.testing.assert_allclose(unit.phi, SquareTwist(alpha).joint_angles("CCSS", theta)[:, 3], atol=1e-15, rtol=0)
    ca, sa = np.cos(alpha), np.sin(alpha)
    c31 = -ca * np.cos(unit.theta) + ca * np.cos(unit.phi) - sa * np.sin(unit.theta) * np.sin(unit.phi)
    assert np.max(np.abs(c31)) <= 1e-12  # eqn 3-31 on the C branch, measured 5.6e-16
    # eqn 3-32 against central differences of eqn 3-30 (step 1e-5): measured relative <= 4.3e-10
    h = 1e-5
    up, down = metamaterial_unit(alpha, unit.theta + h), metamaterial_unit(alpha, unit.theta - h)
    dL, dS, dH = up.L - down.L, up.S - down.S, up.H - down.H
    np.testing.assert_allclose(unit.nu_sl, -(unit.S / unit.L) * dL / dS, rtol=1e-8, atol=0)
    np.testing.assert_allclose(unit.nu_hl, -(unit.L / unit.H) * dH / dL, rtol=1e-8, atol=0)


def height_peak(alpha: float) -> float:
    """theta (rad) where H peaks: nu_HL (proportional to dH/dtheta) changes sign, by bisection."""
    lo, hi = 0.3, 2.5
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if metamaterial_unit(alpha, mid).nu_hl[0] > 0 else (lo, mid)
    return lo


@pytest.mark.parametrize(
    ("alpha", "theta_sampled", "h_sampled", "theta_ours", "corrected"),
    [(5 * np.pi / 6, 1.2999, 0.9634, 1.299533, True), (3 * np.pi / 4, 1.1437, 1.2872, 1.143718, False),
     (2 * np.pi / 3, 0.9548, 1.4142, np.arccos(1 / np.sqrt(3)), True)],
)
def test_square_twist_metamaterial_height_peak(alpha, theta_sampled, h_sampled, theta_ours, corrected):
    theta = height_peak(alpha)
    assert theta == pytest.approx(theta_ours, abs=5e-7)
    # the text: nu_SL < 0 always; nu_HL > 0 before H peaks and < 0 after
    grid = metamaterial_unit(alpha, np.linspace(0.01, np.pi - 0.01, 2001))
    assert np.all(grid.nu_sl < 0)
    assert np.all(np.sign(grid.nu_hl) == np.where(grid.theta < theta, 1.0, -1.0))
    assert metamaterial_unit(alpha, theta).H[0] == pytest.approx(h_sampled, abs=5e-5)  # 4 decimals: all agree
    # a first, sampled reproduction of eqns 3-30 to 3-32 put the peak at 1.2999, 1.1437, 0.9548 (4 decimals); ours
    # 1.299533 and 0.955317 (= arccos(1/sqrt(3)), H = sqrt(2)) differ; 1.1437 agrees
    assert (abs(theta - theta_sampled) > 5e-5) == corrected
    if corrected:
        # corrected here: at the sampled theta nu_HL has already (or not yet) changed sign, |nu_HL| 8.9e-4, 7.3e-4
        nu = metamaterial_unit(alpha, theta_sampled).nu_hl[0]
        assert np.sign(nu) == np.sign(theta - theta_sampled) and abs(nu) >= 5e-4


def test_locked_assignment_cannot_leave_flat_in_mujoco():
    """Vertex modes imposed by couplings: the all-C and all-S sheets stay flat against a saturated servo."""
    for modes in ("CCCC", "SSSS"):
        scene = assigned(modes, ALPHA)
        run = simulate(scene, "CCSS", start=0.0, stop=1.0, drive="servo", hold=1.0)  # "CCSS": the flat start pose
        x = run.q[:, scene.mechanism.joint_index("AB")]
        result = assess(x, run.target, run.drive_force, SERVO_LIMIT, float("nan"), 0.0)
        assert result.stopped and result.drive_saturated
        # the soft couplings give way under 20 N m: input measured 2.4e-5 (CCCC), 7.2e-5 (SSSS) rad, any hinge 8.7e-5
        assert np.max(np.abs(run.q)) <= 1e-3


def test_rigid_assignment_folds_from_flat_in_mujoco():
    """The same servo and couplings with a rigid mode string reach the target on the closed-form branch."""
    for modes in ("CCSS", "CSCS"):
        scene = assigned(modes, ALPHA)
        run = simulate(scene, modes, start=0.0, stop=1.0, drive="servo", hold=1.0)
        x = run.q[:, scene.mechanism.joint_index("AB")]
        result = assess(x, run.target, run.drive_force, SERVO_LIMIT, float("nan"), 0.0)
        assert not result.stopped and not result.drive_saturated  # force measured <= 0.14 N m
        # from flat, where the free sheet bifurcates: couplings are soft, measured 6.5e-8 (CCSS), 1.6e-7 (CSCS)
        assert compare(scene, modes, run.q).max_error() <= FAST.angle_rad


@pytest.mark.slow
def test_validate_square_twist_every_branch():
    scene = scenes.get("square-twist").build()
    report = validate(scene)
    assert report.passed, [v.name for r in report.runs for v in r.verdicts if not v.passed]
    for run in report.runs:
        # fast preset, the path's sweep time (sweep_rate, timed for 2e-7) over 0.5..2.4 rad: measured <= 1.1e-7
        # (CSSC), projection <= 2.7e-15
        assert run.dynamic_path.max_error() <= 2.5e-7
        assert run.followed == run.requested and run.flips == 0
        flat = run.mobility["bifurcations"][0]
        assert (flat["input_rad"], flat["numeric"], flat["mujoco"]) == (0.0, 4, 4)
    (study,) = report.bifurcations
    assert all(d is not None for d in study["seed_offset_followed_rad"].values())
    fold = read_fold(write(report, "out")["fold"])
    assert fold.pattern.loop_system().residual_norm(fold.frames).max() <= FAST.residual_per_m


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"alpha": np.deg2rad(80.0)}, r"alpha = 80 deg; it must be a number in \[90\.001, 179\.999\] deg"),
        ({"alpha": np.pi}, "alpha = 180 deg"),
        ({"side": 0.0}, r"side = 0 m; it must be a number in \[0\.0001, 10000\] m"),
        ({"pleat": -1.0}, r"pleat = -1 m; it must be a number in \[0\.0001, 10000\] m"),
    ],
)
def test_bad_geometry_is_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("square-twist").build(**kwargs)


@pytest.mark.parametrize(
    ("modes", "match"),
    [("CCX", "one mode, S or C, for each of the vertices"), ("CCCS", "1 vertices in mode S; .* even number")],
)
def test_bad_modes_are_refused(modes, match):
    with pytest.raises(ParameterError, match=match):
        assigned(modes, ALPHA)


def test_bad_inputs_are_refused():
    model = SquareTwist(ALPHA)
    with pytest.raises(ParameterError, match="unknown branch 'CCCC'"):
        model.joint_angles("CCCC", 0.5)  # a locked string is no branch
    with pytest.raises(DomainError, match=r"rhoAB = 3.2 rad is outside branch 'CSCS'"):
        model.joint_angles("CSCS", 3.2)
    with pytest.raises(ParameterError, match="theta = 0 rad; eqn 3-32 needs 0 < theta < pi"):
        metamaterial_unit(ALPHA, [0.0, 1.0])
    with pytest.raises(ParameterError, match="a = -1 m; it must be positive"):
        metamaterial_unit(ALPHA, 1.0, a=-1.0)
