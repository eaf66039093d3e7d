"""Threefold-symmetric Bricard 6R (`sim_origami.kinematics.bricard_threefold`, scene `bricard-threefold`)
against Yang 2017 (eqns 1-27, 2-8 to 2-11, the ch. 2 example), the loop solver and MuJoCo."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from published import check_every, checked_by, yang2017

import sim_origami.scenes.bricard_threefold  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.errors import DomainError, ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.bricard_threefold import AGAINST, ALONG, BricardThreefold
from sim_origami.kinematics.dh import DHRow
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import validate

DEG = np.pi / 180
HYPOTHESIS = settings(max_examples=25, deadline=None, derandomize=True, database=None)
# One alpha of each kind: cos^2 alpha > 1/4 (disjoint), = 1/4 (bifurcating), < 1/4 (turning).
ALPHAS = [30.0, 90.0, 120.0, 200.0, 250.0, 300.0]


def model(alpha_deg: float, a: float = 1.0) -> BricardThreefold:
    return BricardThreefold(a, alpha_deg * DEG)


def inputs(m: BricardThreefold, branch: str, n: int, shrink: float = 1.0) -> np.ndarray:
    lo, hi = m.branch(branch).domain
    return np.linspace(shrink * lo, shrink * hi, n)


frames = yang2017.joint_frames


def lean(m: BricardThreefold, q: np.ndarray) -> float:
    """z2 . u: joint 2's axis on the threefold axis u (joint 1's frame turns +120 deg about u onto joint 3's)."""
    F = frames(m, q)
    R13 = F[0, :3, :3].T @ F[2, :3, :3]
    w = np.array([R13[2, 1] - R13[1, 2], R13[0, 2] - R13[2, 0], R13[1, 0] - R13[0, 1]])
    u = w / np.sqrt(3.0)  # R - R^T = 2 sin(120 deg) [u]x for a 120 deg turn
    assert abs(np.linalg.norm(u) - 1.0) < 1e-12  # it is a 120 deg turn (measured 6.7e-16)
    assert abs(np.trace(R13)) < 1e-12  # trace = 1 + 2 cos(120 deg) = 0 (measured 1.6e-15)
    # u is the symmetry axis: joints 1, 3, 5 lie in a plane square to it (measured 6.5e-16 m)
    assert abs((F[2, :3, 3] - F[0, :3, 3]) @ u) < 1e-12
    return float(F[1, :3, 2] @ u)


# --- Yang 2017's numbers: tests/published/yang2017.py -------------------------------------------------------


@pytest.mark.parametrize("alpha", [300.0, 60.0])
def test_threefold_bricard_phi_of_the_chapter_2_example(alpha):
    # 300/60 as printed; 60/300 gives the same closure (only cos alpha and sin^2 alpha enter).
    # measured worst 4.9e-5 deg (rounding of the 4th decimal)
    for entry in checked_by(yang2017.NUMBERS, "test_threefold_bricard_phi_of_the_chapter_2_example"):
        theta = float(entry.quantity.split("theta = ")[1].split(" deg")[0])
        assert entry.difference(yang2017.threefold_phi(alpha, theta)) <= entry.tol, entry


def test_ch2_example_with_even_axes_reversed_has_phi_negated():
    # Eqn 2-9 corrected: reversing the axes at B, D, F gives twists (120, 240) deg, alpha = 2 pi/3, and by the
    # axis-reversal rule negates phi: theta = 129.31 -> phi = +19.990 / +166.208; alpha -> pi - alpha negates phi
    # and swaps the names (z2 flips against u). Measured 2.6e-5 and 2.7e-5 deg.
    check_every(yang2017.NUMBERS, "test_ch2_example_with_even_axes_reversed_has_phi_negated")


def test_ch2_joint_coordinates_are_reproduced_up_to_a_rigid_motion():
    # Eqns 2-10, 2-11: joints A..F and second axis points X' = X + 0.1 s_X, printed to 4 decimals, against ours
    # moved by the best proper rotation + translation (Kabsch)
    _, d = yang2017.ch2_fitted_points()
    assert d == 1.0  # a proper rotation: the printed linkage is this one, not its mirror image
    # measured worst 5.8e-5 m per coordinate: the 4-decimal rounding (5e-5) plus that of theta = 129.31 deg
    check_every(yang2017.NUMBERS, "test_ch2_joint_coordinates_are_reproduced_up_to_a_rigid_motion")


# The ch. 2 example's closed path, traced here by truss continuation (2 decimals): (step, theta, phi, branch).
SAMPLED_PATH = [
    (0, 129.31, -19.99, ALONG), (250, 154.41, -89.18, ALONG), (500, 174.49, -159.48, ALONG),
    (574, 179.99, -179.95, ALONG),  # bundle: theta increases through pi ...
    (750, -166.76, 131.28, AGAINST), (1000, -145.08, 60.74, AGAINST), (1250, -117.11, -5.66, AGAINST),
    (1500, -80.97, -59.37, AGAINST), (1750, -34.05, -100.34, AGAINST), (2000, 25.93, -131.84, AGAINST),
    (2250, 95.60, -156.39, AGAINST),
    (2552, -179.89, 179.97, ALONG),  # bundle again, back onto the first branch
    (2750, -124.97, 164.99, ALONG), (3000, -54.41, 142.85, ALONG), (3250, 11.09, 114.21, ALONG),
    (3500, 63.54, 77.23, ALONG), (3750, 103.53, 29.19, ALONG),
]


@pytest.mark.parametrize(("step", "theta", "phi", "branch"), SAMPLED_PATH)
def test_sampled_closed_path_crosses_to_the_other_branch_at_each_bundle(step, theta, phi, branch):
    m = model(300.0)
    x = theta * DEG
    values = m.joint_angles(branch, [x - 1e-6, x, x + 1e-6])[:, 1]
    slope = (values[2] - values[0]) / 2e-6
    err = abs(wrap(values[1] - phi * DEG)) / DEG
    # Both numbers are rounded to 0.005 deg: |error| <= 0.005 (1 + |dphi/dtheta|); measured worst
    # 0.0127 against a bound of 0.0237 (step 574, at the bundle where the slope is 3.7).
    assert err <= 0.005 * (1 + abs(slope))
    other = AGAINST if branch == ALONG else ALONG
    # and the other branch is clearly farther (measured >= 0.047 deg, at the bundle)
    assert abs(wrap(m.joint_angles(other, x)[0, 1] - phi * DEG)) / DEG > err


# --- closure: closed form, numeric continuation, multistart ----------------------------------


@pytest.mark.parametrize("alpha", ALPHAS)
@pytest.mark.parametrize("branch", [ALONG, AGAINST])
def test_closed_form_closes_the_loop_over_the_whole_domain(alpha, branch):
    m = model(alpha)
    x = inputs(m, branch, 1441)
    values, valid = m.evaluate(branch, x)
    assert valid.all() and np.all(np.isfinite(values))
    q = m.loop_angles(values)
    # measured worst 2.6e-15 (ends included: bundle and turning points)
    assert np.max(m.loop_system().residual_norm(q)) <= TOLERANCES.closed_form_residual
    # and the printed closure (5-42 = 6-48) vanishes (measured worst 1.6e-15)
    assert np.max(np.abs(m.closure(values[:, 0], values[:, 1]))) < 1e-13


@pytest.mark.parametrize("alpha", ALPHAS)
def test_tan_half_forms_6_50_to_6_52(alpha):
    m = model(alpha)
    c = np.cos(alpha * DEG)
    x = inputs(m, ALONG, 1441, shrink=0.999)
    t1 = np.tan(x / 2)
    den = 4 * c * c * t1**2 - t1**2 - 1
    root = np.sqrt((1 + t1**2) * (4 * c * c * t1**2 - t1**2 + 3))
    usable = np.abs(den) > 1e-3  # (6-51) is 0/0-prone where phi passes pi
    for branch, sign in ((ALONG, -1.0), (AGAINST, 1.0)):
        phi = m.joint_angles(branch, x)[:, 1]
        t2 = np.tan(phi / 2)
        # (6-50) on tan halves, where both are moderate (terms up to 20^4; measured worst 9.5e-12)
        small = (np.abs(t1) <= 20) & (np.abs(t2) <= 20)
        f = (4 * c * c - 1) * t1**2 * t2**2 - 8 * c * t1 * t2 - t1**2 - t2**2 + 3
        assert np.max(np.abs(f[small])) < 1e-10
        # (6-51, 6-52): along is the '-' sign, against the '+' sign (measured worst 3.2e-13 rad)
        printed = 2 * np.arctan((4 * c * t1 + sign * root) / den)
        assert np.max(np.abs(wrap(printed - phi))[usable]) < 1e-11


@HYPOTHESIS
@given(
    alpha=st.one_of(st.floats(0.5, 179.5), st.floats(180.5, 359.5)),
    a=st.floats(0.1, 10.0),
)
def test_closed_form_closes_the_loop_for_any_alpha_and_length(alpha, a):
    m = model(alpha, a)
    for branch in (ALONG, AGAINST):
        q = m.loop_angles(m.joint_angles(branch, inputs(m, branch, 241)))
        # measured worst 2.2e-14 over 200 random draws (translation residual scales with a, up to 10 m)
        assert np.max(m.loop_system().residual_norm(q)) <= TOLERANCES.closed_form_residual


@pytest.mark.parametrize("alpha", [30.0, 90.0, 120.0, 300.0])
@pytest.mark.parametrize("branch", [ALONG, AGAINST])
def test_closed_form_matches_numeric_continuation(alpha, branch):
    m = model(alpha)
    x = inputs(m, branch, 100, shrink=0.95)
    values = m.joint_angles(branch, x)
    numeric = m.loop_system().follow(m.loop_angles(values)[0], 0, x)
    # measured worst 4.8e-14 rad
    assert np.max(np.abs(m.observe(numeric) - values)) <= TOLERANCES.closed_form_rad
    # The numeric motion keeps the threefold symmetry (first check here: < 1e-11; measured 2.8e-14).
    assert np.max(np.abs(numeric[:, [0, 1]] - numeric[:, [2, 3]])) < 1e-11
    assert np.max(np.abs(numeric[:, [0, 1]] - numeric[:, [4, 5]])) < 1e-11


@pytest.mark.slow
@pytest.mark.parametrize(("alpha", "x"), [(300.0, 1.0), (90.0, 1.0), (30.0, 3.0)])
def test_multistart_finds_exactly_the_two_closed_form_assemblies(alpha, x):
    m = model(alpha)
    found = m.loop_system().assemblies(0, x, starts=64, seed=0)
    closed = np.concatenate([m.joint_angles(b, x) for b in (ALONG, AGAINST)])
    assert len(found) == 2  # no assembly without the threefold symmetry
    for q in closed:
        # measured worst 3.9e-14 rad (the solver stops at residual 1e-13)
        assert np.min(np.max(np.abs(wrap(found - q)), axis=1)) < 1e-10


# --- symmetries of the motion ----------------------------------------------------------------


@pytest.mark.parametrize("alpha", ALPHAS)
def test_symmetries_of_the_motion(alpha):
    m = model(alpha)
    # 0.1% inside a turning point: there phi moves by sqrt(rounding of theta_max), 1.6e-9 rad
    x = inputs(m, ALONG, 241, shrink=0.999)
    along, against = m.joint_angles(ALONG, x), m.joint_angles(AGAINST, x)
    # threefold: theta1 = theta3 = theta5, theta2 = theta4 = theta6 (exact by construction)
    assert np.all(along[:, [0, 1]] == along[:, [2, 3]]) and np.all(along[:, [0, 1]] == along[:, [4, 5]])
    # mirror: the branches are exchanged by negating every joint angle (measured 4.4e-16)
    assert np.max(np.abs(wrap(m.joint_angles(AGAINST, -x) + along))) < 1e-14
    # alpha and 2 pi - alpha: the same motion (measured 2.7e-15 rad)
    twin = model(360.0 - alpha)
    assert np.max(np.abs(wrap(twin.joint_angles(ALONG, x) - along))) < 1e-13
    # alpha and pi - alpha: phi negated, names swapped (measured 1.2e-14 rad)
    if alpha != 90.0:
        flip = model((180.0 - alpha) % 360.0)
        assert np.max(np.abs(wrap(flip.joint_angles(AGAINST, x)[:, 1] + along[:, 1]))) < 1e-13
    # theta = 0: phi = +/-120 deg for every alpha, since F(0, phi) = 1 + 2 cos phi (measured 1.4e-14 deg)
    assert abs(m.at(ALONG, 0.0)["theta2"] / DEG - 120.0) < 1e-12
    assert abs(m.at(AGAINST, 0.0)["theta2"] / DEG + 120.0) < 1e-12
    # swap theta <-> phi: (phi, theta, ...) closes too and lies on one of the branches at input phi
    loops = m.loop_system()
    for q in (along, against):
        swapped = q[:, [1, 0, 3, 2, 5, 4]]
        assert np.max(loops.residual_norm(swapped)) < 1e-13  # measured 2.1e-15
        # (phi reaches the turning points' inputs, where branch membership is ill-conditioned: skip those)
        t, p = wrap(swapped[:, 0]), swapped[:, 1]
        inside = np.abs(t) <= 0.999 * m.branch(ALONG).domain[1]
        gap = np.minimum(
            np.abs(wrap(m.joint_angles(ALONG, t[inside])[:, 1] - p[inside])),
            np.abs(wrap(m.joint_angles(AGAINST, t[inside])[:, 1] - p[inside])),
        )
        assert np.max(gap) < 1e-12  # measured worst 2.2e-14 rad


@pytest.mark.parametrize("alpha", ALPHAS)
def test_branch_names_match_the_lean_of_the_even_axes(alpha):
    # The names are geometric: z2 . u > 0 on 'even-axes-along', < 0 on 'even-axes-against', computed here
    # from the D-H frames (not from the closed form's root labels).
    m = model(alpha)
    for branch, sign in ((ALONG, 1.0), (AGAINST, -1.0)):
        x = inputs(m, branch, 201, shrink=0.999)
        leans = np.array([lean(m, q) for q in m.joint_angles(branch, x)])
        assert np.all(sign * leans > 0)
        # and z2 . u = (A sin phi - B cos phi) / sqrt 3, the module's claim (measured 4.4e-16)
        t, p = m.joint_angles(branch, x)[:, :2].T
        A = m.s2 + (1 + m.c**2) * np.cos(t)
        B = -2 * m.c * np.sin(t)
        assert np.max(np.abs(leans - (A * np.sin(p) - B * np.cos(p)) / np.sqrt(3))) < 1e-13


# --- domains and events ----------------------------------------------------------------------


@pytest.mark.parametrize("alpha", [60.0, 120.0, 240.0, 300.0])
def test_bifurcating_alpha_meets_at_the_bundle(alpha):
    m = model(alpha)
    assert m.kind == "bifurcating"
    for b in m.branches():
        assert b.domain == (-np.pi, np.pi)
    events = m.events()
    assert [(e.kind, e.input, e.branches) for e in events] == [
        ("bifurcation", -np.pi, (ALONG, AGAINST)),
        ("bifurcation", np.pi, (ALONG, AGAINST)),
    ]
    loops = m.loop_system()
    for e in events:
        for branch in e.branches:
            q = m.joint_angles(branch, e.input)[0]
            # every joint angle is pi (measured 0 rad) ...
            assert np.max(np.abs(wrap(q - np.pi))) < 1e-12
            # ... joints 1 = 3 = 5 and 2 = 4 = 6 coincide (measured 1.2e-16 m) ...
            P = frames(m, q)[:, :3, 3]
            assert np.max(np.abs(P[[2, 4]] - P[0])) < 1e-12 and np.max(np.abs(P[[3, 5]] - P[1])) < 1e-12
            # ... and the closure Jacobian loses one more rank: instantaneous mobility 2, against 1 elsewhere
            assert loops.mobility(q) == 2
    assert loops.mobility(m.joint_angles(ALONG, 1.0)[0]) == 1


@pytest.mark.parametrize("alpha", [60.0, 120.0, 240.0, 300.0])
def test_numeric_continuation_through_the_bundle_lands_on_the_other_branch(alpha):
    m = model(alpha)
    x = np.pi + np.linspace(-0.3, 0.3, 61) + 0.0013  # never exactly at the bundle
    start = m.loop_angles(m.joint_angles(ALONG, x[0]))[0]
    numeric = m.loop_system().follow(start, 0, x)
    before, after = x < np.pi, x > np.pi
    along = m.evaluate(ALONG, wrap(x))[0]
    against = m.evaluate(AGAINST, wrap(x))[0]
    # Near the bundle the Jacobian is nearly singular, so the solver's 1e-14 residual maps to a
    # larger angle error: measured worst 1.2e-12 rad (alpha = 240, 0.0013 rad past the bundle).
    assert np.max(np.abs(wrap(numeric[before] - along[before]))) < 1e-10
    assert np.max(np.abs(wrap(numeric[after] - against[after]))) < 1e-10
    assert np.min(np.max(np.abs(wrap(numeric[after] - along[after])), axis=1)) > 1e-3  # measured 4.5e-3


@pytest.mark.parametrize("alpha", [75.0, 90.0, 110.0, 250.0, 280.0])
def test_turning_alpha_has_a_limited_domain_joined_at_turning_points(alpha):
    m = model(alpha)
    assert m.kind == "turning"
    c = np.cos(alpha * DEG)
    # (6-51): the root is real while (4 cos^2 alpha - 1) t1^2 + 3 >= 0, t1 = tan(theta/2)
    theta_max = 2 * np.arctan(np.sqrt(3 / (1 - 4 * c * c)))
    for b in m.branches():
        lo, hi = b.domain
        # domain_of bisects to 1e-13 and pulls in by 1e-13 (measured 1.0e-13)
        assert abs(hi - theta_max) < 1e-12 and abs(lo + theta_max) < 1e-12
    events = m.events()
    assert [(e.kind, e.branches) for e in events] == [("turning_point", (ALONG, AGAINST))] * 2
    for e in events:
        ends = [m.joint_angles(b, e.input)[0] for b in e.branches]
        # the two branches join: their gap is sqrt(1e-13)-small at 1e-13 rad inside (measured 1.7e-6 rad)
        assert np.max(np.abs(wrap(ends[0] - ends[1]))) < 1e-5
        # and the even axes are square to the threefold axis there (measured 2.4e-7)
        assert abs(lean(m, ends[0])) < 1e-5
    # beyond the turning point nothing assembles
    values, valid = m.evaluate(ALONG, [theta_max + 1e-9, -theta_max - 1e-9])
    assert not valid.any() and np.isnan(values).all()


@pytest.mark.parametrize("alpha", [10.0, 30.0, 59.0, 150.0, 200.0, 330.0])
def test_disjoint_alpha_has_two_separate_full_circle_motions(alpha):
    m = model(alpha)
    assert m.kind == "disjoint" and m.events() == ()
    x = np.linspace(-np.pi, np.pi, 721)
    along, against = m.joint_angles(ALONG, x), m.joint_angles(AGAINST, x)
    # the branches never meet (measured smallest |phi gap| 55.5 deg)
    assert np.min(np.abs(wrap(along[:, 1] - against[:, 1]))) > 0.1
    # each is a closed loop: theta = -pi and pi give the same configuration (measured 0)
    for q in (along, against):
        assert np.max(np.abs(wrap(q[0] - q[-1]))) < 1e-12


def test_near_special_alpha_is_classified_by_cos_squared():
    assert model(120.0).kind == "bifurcating"  # the double nearest 120 deg: 4 cos^2 - 1 = -8.9e-16, snapped
    assert BricardThreefold(1.0, 2 * np.pi / 3).kind == "bifurcating"
    assert model(119.999).kind == "turning"
    assert model(120.001).kind == "disjoint"


# --- the Kinematics contract and the parameters -----------------------------------------------


def test_contract():
    m = model(300.0)
    assert m.gruebler() == 0  # 6 - 6
    assert m.loop_input() == (0, 1.0)
    assert m.rows == (DHRow(0.0, 1.0, 300 * DEG), DHRow(0.0, 1.0, 2 * np.pi - 300 * DEG)) * 3
    assert m.rows[1].alpha == pytest.approx(60 * DEG, abs=1e-15)
    assert [b.name for b in m.branches()] == [ALONG, AGAINST]
    x = np.array([-4.0, -np.pi, 0.3, np.pi, 4.0])
    values, valid = m.evaluate(ALONG, x)
    assert valid.tolist() == [False, True, True, True, False]
    assert np.isnan(values[~valid]).all() and np.isfinite(values[valid]).all()
    np.testing.assert_array_equal(m.observe(m.loop_angles(values[valid])), values[valid])
    with pytest.raises(DomainError, match="4 rad is outside branch 'even-axes-along'"):
        m.joint_angles(ALONG, 4.0)
    with pytest.raises(ParameterError, match="even-axes-along, even-axes-against"):
        m.evaluate("plus", 0.0)


@pytest.mark.parametrize(
    ("a", "alpha_deg", "match"),
    [
        (0.0, 300.0, r"a = 0 m; it must be positive"),
        (-1.0, 300.0, r"a = -1 m; it must be positive"),
        (float("nan"), 300.0, r"a = nan m; it must be positive"),
        (1.0, 0.0, r"alpha = 0 deg; it must lie in \(0, 360\) deg"),
        (1.0, 360.0, r"alpha = 360 deg; it must lie in \(0, 360\) deg"),
        (1.0, -60.0, r"alpha = -60 deg; it must lie in \(0, 360\) deg"),
        (1.0, 180.0, r"alpha = 180 deg; it must differ from 180 deg"),
    ],
)
def test_bad_parameters_raise(a, alpha_deg, match):
    with pytest.raises(ParameterError, match=match):
        BricardThreefold(a, alpha_deg * DEG)


def test_scene_rejects_bad_parameters():
    scene_type = scenes.get("bricard-threefold")
    with pytest.raises(ParameterError, match="alpha = 180 deg"):
        scene_type.build_from_user({"alpha": 180.0})
    with pytest.raises(ParameterError, match="a = -2 m"):
        scene_type.build_from_user({"a": -2.0})
    with pytest.raises(ParameterError, match="unknown parameter 'beta'"):
        scene_type.build(beta=1.0)


# --- scene and MuJoCo --------------------------------------------------------------------------


def test_scene_defaults():
    scene = scenes.get("bricard-threefold").build()
    assert scene.params == pytest.approx({"a": 1.0, "alpha": 300 * DEG})
    assert scene.loop_joints == tuple(f"joint_{k}" for k in range(1, 7))
    assert len(scene.mechanism.joints) == 6
    for b in scene.kinematics.branches():
        start, stop = scene.branch_path(b.name)
        assert b.domain[0] < start < stop < b.domain[1]
    # the default pose is the closed form
    q = scene.pose(ALONG, 0.5)
    assert np.max(scene.kinematics.loop_system().residual_norm(scene.mechanism_to_loop(q))) < 1e-14


@pytest.mark.slow
def test_validate_default_scene_passes():
    report = validate(scenes.get("bricard-threefold").build())
    failed = [v for v in list(report.verdicts) + [v for r in report.runs for v in r.verdicts] if not v.passed]
    assert report.passed, failed
    # Measured (MuJoCo fast preset, default sweep -1..1 rad): path error 1.2e-7 / 1.3e-7 rad,
    # closure gap 1.3e-7 / 1.4e-7 m, projection error 1.8e-15 rad, closed form vs numeric 1.1e-15 rad,
    # closed-form closure residual 1.5e-15.
    assert {r.followed for r in report.runs} == {ALONG, AGAINST}
