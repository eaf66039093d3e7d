"""Asymmetric Miura vertex (`sim_origami.kinematics.miura`) against seed 002 (digest part A)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim_origami.errors import DomainError, ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.miura import MiuraVertex, fold_limit, spinal_crease

# Sector pairs (alpha1, alpha2) in degrees from the digest's verification list (A.6).
ASYMMETRIC = [(30, 60), (60, 30), (50, 80), (20, 70), (70, 80), (40, 50)]
SYMMETRIC = [(45, 45), (60, 60)]  # flat-foldable: the degree-4 vertex names the branch 'S'
PAIRS = ASYMMETRIC + SYMMETRIC
PHI, PSI, RHO = 0, 1, slice(2, 6)
RHO_A, RHO_B, RHO_C, RHO_D = 2, 3, 4, 5

HYPOTHESIS = settings(max_examples=40, deadline=None, derandomize=True, database=None)
MIURA_SECTOR_DEG = st.floats(1.0, 89.0)


def miura(alpha1_deg: float, alpha2_deg: float) -> MiuraVertex:
    return MiuraVertex(np.deg2rad(alpha1_deg), np.deg2rad(alpha2_deg))


def deg_outputs(vertex: MiuraVertex, branch: str, theta_deg) -> np.ndarray:
    """Outputs (n, 6) in degrees at inputs theta given in degrees."""
    return np.rad2deg(vertex.joint_angles(branch, np.deg2rad(theta_deg)))


def domain_grid(vertex: MiuraVertex, branch: str, fraction: float = 1.0, n: int = 200) -> np.ndarray:
    """n inputs spanning `fraction` of a branch's symmetric domain (an even n skips theta = 0)."""
    lo, hi = vertex.branch(branch).domain
    return np.linspace(fraction * lo, fraction * hi, n)


def assert_angles_close(actual, expected, atol: float) -> None:
    """Angles equal up to whole turns (psi = +pi and -pi name the same direction)."""
    np.testing.assert_allclose(wrap(np.asarray(actual) - np.asarray(expected)), 0.0, atol=atol, rtol=0)


# ---------------------------------------------------------------------------------------------
# Published numbers (digest seed002_004.md, Miura validation cases 1-7)
# ---------------------------------------------------------------------------------------------

CASE1_THETA = [10, 20, 30, 40, 45, 50, 54]
CASE1_PHI = [16.9774, 32.0720, 44.0307, 52.1183, 54.4567, 55.4107, 54.9574]
CASE1_PSI = [1.5418, 6.5056, 15.5928, 28.3376, 34.9864, 40.8309, 44.4588]
# Printed to 4 decimals in degrees: half a unit of the last digit. (The digest's 1e-6 deg analytic
# tolerance cannot apply to values rounded to 1e-4 deg.)
FOUR_DECIMALS_DEG = 5e-5


def test_published_projection_angles_case1():
    out = deg_outputs(miura(30, 60), "miura", CASE1_THETA)
    np.testing.assert_allclose(out[:, PHI], CASE1_PHI, atol=FOUR_DECIMALS_DEG, rtol=0)
    np.testing.assert_allclose(out[:, PSI], CASE1_PSI, atol=FOUR_DECIMALS_DEG, rtol=0)


def test_published_spinal_crease_case1():
    a = spinal_crease(np.deg2rad(30), np.deg2rad(60), np.deg2rad(30))[0]
    # Printed to 6 decimals: half a unit of the last digit.
    np.testing.assert_allclose(a, [0.704918, 0.196721, 0.681463], atol=5e-7, rtol=0)
    # Measured 1e-16 (a unit vector by construction); 1e-14 leaves 100x margin.
    np.testing.assert_allclose(np.linalg.norm(a), 1.0, atol=1e-14, rtol=0)


@pytest.mark.parametrize(
    "theta, expected",
    [
        # (rho_a, rho_b, rho_c, rho_d): a is a mountain (negative), b, c, d are valleys.
        (10, (-20, 34.4709, 20, 19.6999)),
        (30, (-60, 100.3889, 60, 52.6590)),
        (50, (-100, 164.0130, 100, 69.7434)),
    ],
)
def test_published_fold_angles_case2(theta, expected):
    out = deg_outputs(miura(30, 60), "miura", [theta])[0]
    # Stated tolerance 1e-3 deg (values printed to 4 decimals).
    np.testing.assert_allclose(out[RHO], expected, atol=1e-3, rtol=0)


def test_published_fold_angles_near_lock_case2():
    out = deg_outputs(miura(30, 60), "miura", [54])[0]
    # Stated tolerance 1e-3 deg.
    np.testing.assert_allclose(out[[RHO_B, RHO_D]], [177.4631, 70.5089], atol=1e-3, rtol=0)


def test_spinal_folds_are_twice_theta_with_opposite_assignment():
    vertex = miura(30, 60)
    theta = domain_grid(vertex, "miura")
    out = vertex.joint_angles("miura", theta)
    # Collinear pair a, c: |rho_a| = |rho_c| = 2 theta (digest A.2); measured 4e-16; 1e-14 is 25x.
    np.testing.assert_allclose(out[:, RHO_C], 2 * theta, atol=1e-14, rtol=0)
    np.testing.assert_allclose(out[:, RHO_A], -2 * theta, atol=1e-14, rtol=0)


@pytest.mark.parametrize("pair", [(30, 60), (50, 80), (45, 45)])
def test_phi_is_odd_and_psi_is_even_in_theta_case3(pair):
    vertex = miura(*pair)
    theta = domain_grid(vertex, "miura")
    plus, minus = vertex.joint_angles("miura", theta), vertex.joint_angles("miura", -theta)
    # Stated tolerance 1e-9 deg (1.7e-11 rad); measured bit-exact.
    tol = np.deg2rad(1e-9)
    np.testing.assert_allclose(minus[:, PHI], -plus[:, PHI], atol=tol, rtol=0)
    np.testing.assert_allclose(minus[:, PSI], plus[:, PSI], atol=tol, rtol=0)
    np.testing.assert_allclose(minus[:, RHO], -plus[:, RHO], atol=tol, rtol=0)  # central symmetry


@pytest.mark.parametrize(
    "pair, limit_deg",
    [
        ((30, 60), 54.7356),
        ((60, 30), 54.7356),
        ((20, 70), 48.8063),
        ((40, 50), 67.3780),
        ((50, 80), 51.0652),
        ((70, 80), 59.4884),
        ((45, 45), 90.0),
        ((60, 60), 90.0),
    ],
)
def test_published_lock_angle_case4_and_6(pair, limit_deg):
    vertex = miura(*pair)
    np.testing.assert_allclose(np.rad2deg(vertex.theta_limit), limit_deg, atol=FOUR_DECIMALS_DEG, rtol=0)
    assert vertex.branch("miura").domain == (-vertex.theta_limit, vertex.theta_limit)


@pytest.mark.parametrize("pair", ASYMMETRIC)
def test_crease_next_to_smaller_sector_folds_flat_at_lock_case4(pair):
    vertex = miura(*pair)
    crease = RHO_B if pair[0] < pair[1] else RHO_D
    out = np.rad2deg(vertex.joint_angles("miura", [vertex.theta_limit, -vertex.theta_limit]))
    # Stated tolerance 0.01 deg (measured 1e-13 deg).
    np.testing.assert_allclose(np.abs(out[:, crease]), 180.0, atol=0.01, rtol=0)


def test_phi_at_lock_equals_lock_angle_case4():
    vertex = miura(30, 60)
    phi = np.rad2deg(vertex.joint_angles("miura", vertex.theta_limit)[0, PHI])
    np.testing.assert_allclose(phi, 54.7356, atol=FOUR_DECIMALS_DEG, rtol=0)


def test_phi_is_non_monotonic_with_published_maximum_case5():
    vertex = miura(30, 60)
    theta = np.linspace(0.0, vertex.theta_limit, 100001)  # 5.5e-4 deg steps
    phi = np.rad2deg(vertex.joint_angles("miura", theta)[:, PHI])
    k = int(np.argmax(phi))
    assert 0 < k < len(theta) - 1, "the maximum of phi is interior"
    # Stated tolerance 0.01 deg, far above the grid step.
    np.testing.assert_allclose(phi[k], 55.4185, atol=0.01, rtol=0)
    np.testing.assert_allclose(np.rad2deg(theta[k]), 50.475, atol=0.01, rtol=0)


@pytest.mark.parametrize("alpha, phi30", [(45, 53.1301), (60, 81.7868)])
def test_symmetric_vertex_has_zero_psi_and_closed_form_phi_case6(alpha, phi30):
    vertex = miura(alpha, alpha)
    phi = deg_outputs(vertex, "miura", [30])[0, PHI]
    np.testing.assert_allclose(phi, phi30, atol=FOUR_DECIMALS_DEG, rtol=0)
    theta = np.linspace(-0.99, 0.99, 199) * np.deg2rad(35)  # phi < 90 deg here, so a_x > 0
    out = vertex.joint_angles("miura", theta)
    assert np.all(out[:, PSI] == 0.0)
    # phi = 2 atan(sin theta tan alpha) (digest A.3, verified there to 4e-16); measured 4e-16 here.
    expected = 2 * np.arctan(np.sin(theta) * np.tan(np.deg2rad(alpha)))
    np.testing.assert_allclose(out[:, PHI], expected, atol=1e-14, rtol=0)


def test_psi_uses_atan2_past_ninety_degrees_case7():
    out = deg_outputs(miura(50, 80), "miura", [45])[0]
    np.testing.assert_allclose(out[[PHI, PSI]], [100.4486, 105.7768], atol=FOUR_DECIMALS_DEG, rtol=0)


def test_spinal_crease_x_changes_sign_at_published_angle_case7():
    # f_x < 0 for theta > 33.6005 deg: the root lies within the rounding of the printed value.
    theta = np.deg2rad([33.6005 - FOUR_DECIMALS_DEG, 33.6005 + FOUR_DECIMALS_DEG])
    a_x = spinal_crease(np.deg2rad(50), np.deg2rad(80), theta)[:, 0]
    assert a_x[0] > 0.0 > a_x[1]


# ---------------------------------------------------------------------------------------------
# The flat state
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("branch", ["miura", "straight"])
@pytest.mark.parametrize("pair", [(30, 60), (50, 80), (45, 45)])
def test_flat_state_is_exactly_zero_and_approached_continuously(pair, branch):
    vertex = miura(*pair)
    values, valid = vertex.evaluate(branch, 0.0)
    assert valid[0] and np.array_equal(values, np.zeros((1, 6)))
    for sign in (1.0, -1.0):
        small = vertex.joint_angles(branch, sign * 1e-8)[0]
        assert np.max(np.abs(small)) < 1e-7  # of the input's scale, no 1/sin(theta) blow-up
        # Linear to O(theta^2): values(1e-8) = 1e-2 values(1e-6) up to ~2.5e-14 measured; 1e-12 is 40x.
        scaled = 1e-2 * vertex.joint_angles(branch, sign * 1e-6)[0]
        np.testing.assert_allclose(small, scaled, atol=1e-12, rtol=0)


# ---------------------------------------------------------------------------------------------
# Agreement with the degree-4 vertex and the numeric loop closure
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("pair", PAIRS)
def test_miura_closed_form_matches_vertex4_driven_at_crease_c(pair):
    vertex = miura(*pair)
    general = vertex.vertex
    name = "S" if general.flat_foldable else "odd1"
    assert [b.name for b in general.branches()] == sorted([name, "straight13"])
    # The ends are flat-folded, singular states where the general root is only sqrt(eps) accurate
    # (and psi of a symmetric vertex is undefined there), so the comparison stops at 99% of the domain.
    for branch, other in (("miura", name), ("straight", "straight13")):
        theta = domain_grid(vertex, branch, 0.99)
        values = vertex.joint_angles(branch, theta)
        rho = general.joint_angles(other, 2 * theta)
        # Measured <= 5.7e-14 (straight branch of 40/50 near the end); 1e-12 leaves 17x margin.
        assert_angles_close(values[:, RHO], rho, atol=1e-12)
        # psi = atan2(a_y, a_x) amplifies the 7e-15 fold error by 1/a_x ~ 1e4 for 45/45 near the lock:
        # measured 3.6e-11 there (<= 6e-14 elsewhere); 1e-9 leaves 28x margin.
        assert_angles_close(vertex.observe(rho), values, atol=1e-9)


@pytest.mark.parametrize("pair", ASYMMETRIC)
def test_vertex4_branch_domain_is_twice_the_fold_limit(pair):
    vertex = miura(*pair)
    # The degree-4 domain is bisected to ~1e-13; measured 4.4e-16 against eqn 40.
    np.testing.assert_allclose(
        vertex.vertex.branch("odd1").domain, 2 * np.array(vertex.branch("miura").domain), atol=1e-12, rtol=0
    )


def assert_observe_inverts_loop_angles(vertex: MiuraVertex) -> None:
    """observe(loop_angles(values)) == values on both branches, up to 99% of each domain."""
    for branch in ("miura", "straight"):
        values = vertex.joint_angles(branch, domain_grid(vertex, branch, 0.99))
        # Measured <= 2.8e-13 (psi of a symmetric vertex as a_x -> 0); 1e-11 leaves 35x margin.
        assert_angles_close(vertex.observe(vertex.loop_angles(values)), values, atol=1e-11)


def assert_loop_angles_close_the_loop(vertex: MiuraVertex) -> None:
    """The loop angles of the closed form close the loop over both whole closed domains."""
    system = vertex.loop_system()
    for branch in ("miura", "straight"):
        q = vertex.loop_angles(vertex.joint_angles(branch, domain_grid(vertex, branch)))
        # Measured <= 6.5e-16 including both locks; the required 1e-12 leaves 1500x margin.
        assert system.residual_norm(q).max() <= 1e-12


@pytest.mark.parametrize("pair", PAIRS)
def test_observe_of_loop_angles_reproduces_values(pair):
    assert_observe_inverts_loop_angles(miura(*pair))


@pytest.mark.parametrize("pair", PAIRS)
def test_loop_angles_close_the_loop_over_the_whole_domain(pair):
    assert_loop_angles_close_the_loop(miura(*pair))


def test_loop_input_is_crease_c_at_twice_theta():
    vertex = miura(30, 60)
    joint, scale = vertex.loop_input()
    theta = domain_grid(vertex, "miura")
    q = vertex.loop_angles(vertex.joint_angles("miura", theta))
    # Same arithmetic as the closed form's rho_c: measured 4e-16; 1e-14 leaves 25x margin.
    np.testing.assert_allclose(q[:, joint], scale * theta, atol=1e-14, rtol=0)


@pytest.mark.parametrize("sign", [1.0, -1.0])
@pytest.mark.parametrize("pair", PAIRS)
def test_numeric_follow_reproduces_phi_and_psi_through_observe(pair, sign):
    vertex = miura(*pair)
    joint, scale = vertex.loop_input()
    theta = sign * np.linspace(0.05, 0.95 * vertex.theta_limit, 30)
    start = vertex.loop_angles(vertex.joint_angles("miura", theta[0]))[0]
    path = vertex.loop_system().follow(start, joint, scale * theta)
    # Newton to 1e-14 residual: measured <= 5.9e-13 (psi of a symmetric vertex); 1e-11 is 17x.
    assert_angles_close(vertex.observe(path), vertex.joint_angles("miura", theta), atol=1e-11)


@HYPOTHESIS
@given(MIURA_SECTOR_DEG, MIURA_SECTOR_DEG)
def test_random_miura_vertices_close_and_observe_back(alpha1, alpha2):
    vertex = miura(alpha1, alpha2)
    assert_loop_angles_close_the_loop(vertex)
    assert_observe_inverts_loop_angles(vertex)


# ---------------------------------------------------------------------------------------------
# Fold limit, events and errors
# ---------------------------------------------------------------------------------------------


@HYPOTHESIS
@given(MIURA_SECTOR_DEG, MIURA_SECTOR_DEG)
def test_fold_limit_is_symmetric_in_the_two_sectors(alpha1, alpha2):
    a1, a2 = np.deg2rad(alpha1), np.deg2rad(alpha2)
    assert fold_limit(a1, a2) == fold_limit(a2, a1)
    assert 0.0 < fold_limit(a1, a2) <= np.pi / 2


@HYPOTHESIS
@given(MIURA_SECTOR_DEG, MIURA_SECTOR_DEG)
def test_crease_next_to_smaller_sector_folds_exactly_flat_at_the_limit(alpha1, alpha2):
    vertex = miura(alpha1, alpha2)
    crease = RHO_B if alpha1 <= alpha2 else RHO_D
    out = vertex.joint_angles("miura", [vertex.theta_limit, -vertex.theta_limit])
    # Measured <= 1.3e-15 rad over 2000 random pairs; 1e-12 leaves 750x margin.
    np.testing.assert_allclose(np.abs(out[:, crease]), np.pi, atol=1e-12, rtol=0)


@pytest.mark.parametrize(
    "pair, crease",
    [
        ((30, 60), "crease b"),
        ((60, 30), "crease d"),
        ((45, 45), "b, c and d"),
    ],
)
def test_events_are_flat_bifurcation_and_locks(pair, crease):
    vertex = miura(*pair)
    events = vertex.events()
    assert events[0].kind == "bifurcation" and events[0].input == 0.0
    assert set(events[0].branches) == {"miura", "straight"}
    miura_locks = sorted(e.input for e in events if e.kind == "lock" and e.branches == ("miura",))
    straight_locks = sorted(e.input for e in events if e.kind == "lock" and e.branches == ("straight",))
    assert miura_locks == [-vertex.theta_limit, vertex.theta_limit]
    assert straight_locks == [-np.pi / 2, np.pi / 2]
    assert all(crease in e.detail for e in events if e.branches == ("miura",))


@pytest.mark.parametrize(
    "alpha1, alpha2, bad",
    [
        (90, 30, "alpha1 = 90 deg"),
        (30, 90, "alpha2 = 90 deg"),
        (120, 30, "alpha1 = 120 deg"),
        (0, 30, "alpha1 = 0 deg"),
        (30, -10, "alpha2 = -10 deg"),
    ],
)
def test_sector_outside_zero_to_ninety_degrees_raises_parameter_error(alpha1, alpha2, bad):
    with pytest.raises(ParameterError, match=rf"{bad}; .* in \(0, 90\) deg"):
        miura(alpha1, alpha2)


@pytest.mark.parametrize("branch", ["miura", "straight"])
def test_inputs_beyond_the_domain_raise_domain_error(branch):
    vertex = miura(30, 60)
    lo, hi = vertex.branch(branch).domain
    for x in (hi + 1e-9, lo - 1e-9, 2.0):
        with pytest.raises(DomainError, match=rf"theta = {x:.6g} rad .* \[{lo:.6g}, {hi:.6g}\] rad"):
            vertex.joint_angles(branch, x)
        values, valid = vertex.evaluate(branch, x)
        assert not valid[0] and np.isnan(values).all()
    values, valid = vertex.evaluate(branch, [lo, hi])
    assert valid.all() and not np.isnan(values).any()


def test_unknown_branch_raises_parameter_error():
    with pytest.raises(ParameterError, match=r"unknown branch 'odd1'; this model has: miura, straight"):
        miura(30, 60).evaluate("odd1", 0.1)
