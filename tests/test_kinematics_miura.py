"""Asymmetric Miura vertex (`sim_origami.kinematics.miura`) against Kamrava et al. 2021."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from published import check_every, checked_by, kamrava2021

from sim_origami.errors import DomainError, ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.miura import MiuraVertex, fold_limit, spinal_crease

# Sector pairs (alpha1, alpha2) in degrees: the paper's 30/60 (Fig. 5) and the pairs of a first check made here.
ASYMMETRIC = [(30, 60), (60, 30), (50, 80), (20, 70), (70, 80), (40, 50)]
SYMMETRIC = [(45, 45), (60, 60)]  # flat-foldable: the degree-4 vertex names the branch 'S'
PAIRS = ASYMMETRIC + SYMMETRIC
PHI, PSI, RHO = 0, 1, slice(2, 6)
RHO_A, RHO_B, RHO_C, RHO_D = 2, 3, 4, 5

HYPOTHESIS = settings(max_examples=40, deadline=None, derandomize=True, database=None)
MIURA_SECTOR_DEG = st.floats(1.0, 89.0)


miura = kamrava2021.miura
deg_outputs = kamrava2021.deg_outputs


def domain_grid(vertex: MiuraVertex, branch: str, fraction: float = 1.0, n: int = 200) -> np.ndarray:
    """n inputs spanning `fraction` of a branch's symmetric domain (an even n skips theta = 0)."""
    lo, hi = vertex.branch(branch).domain
    return np.linspace(fraction * lo, fraction * hi, n)


def assert_angles_close(actual, expected, atol: float) -> None:
    """Angles equal up to whole turns (psi = +pi and -pi name the same direction)."""
    np.testing.assert_allclose(wrap(np.asarray(actual) - np.asarray(expected)), 0.0, atol=atol, rtol=0)


# ---------------------------------------------------------------------------------------------
# Worked values of Kamrava et al. 2021's equations: tests/published/kamrava2021.py
# ---------------------------------------------------------------------------------------------

FOUR_DECIMALS_DEG = kamrava2021.FOUR_DECIMALS_DEG


@pytest.mark.parametrize(
    "entry", checked_by(kamrava2021.NUMBERS, "test_published_projection_angles_of_the_30_60_vertex"), ids=str
)
def test_published_projection_angles_of_the_30_60_vertex(entry):
    entry.check()


def test_published_spinal_crease_of_the_30_60_vertex():
    check_every(kamrava2021.NUMBERS, "test_published_spinal_crease_of_the_30_60_vertex")
    a = spinal_crease(np.deg2rad(30), np.deg2rad(60), np.deg2rad(30))[0]
    # Measured 1e-16 (a unit vector by construction); 1e-14 leaves 100x margin.
    np.testing.assert_allclose(np.linalg.norm(a), 1.0, atol=1e-14, rtol=0)


@pytest.mark.parametrize(
    "entry", checked_by(kamrava2021.NUMBERS, "test_published_fold_angles_of_the_30_60_vertex"), ids=str
)
def test_published_fold_angles_of_the_30_60_vertex(entry):
    # a is a mountain (negative), b, c, d are valleys; stated tolerance 1e-3 deg (values printed to 4 decimals).
    assert entry.value[0] < 0 < min(entry.value[1:])
    entry.check()


def test_published_fold_angles_near_the_lock():
    check_every(kamrava2021.NUMBERS, "test_published_fold_angles_near_the_lock")


@pytest.mark.parametrize("entry", checked_by(kamrava2021.CORRECTIONS, "test_corrections_of_printed_equations"), ids=str)
def test_corrections_of_printed_equations(entry):
    entry.check()


def test_spinal_folds_are_twice_theta_with_opposite_assignment():
    vertex = miura(30, 60)
    theta = domain_grid(vertex, "miura")
    out = vertex.joint_angles("miura", theta)
    # Collinear pair a, c: |rho_a| = |rho_c| = 2 theta (derived here; eqns 9-10); measured 4e-16; 1e-14 is 25x.
    np.testing.assert_allclose(out[:, RHO_C], 2 * theta, atol=1e-14, rtol=0)
    np.testing.assert_allclose(out[:, RHO_A], -2 * theta, atol=1e-14, rtol=0)


@pytest.mark.parametrize("pair", [(30, 60), (50, 80), (45, 45)])
def test_phi_is_odd_and_psi_is_even_in_theta(pair):
    vertex = miura(*pair)
    theta = domain_grid(vertex, "miura")
    plus, minus = vertex.joint_angles("miura", theta), vertex.joint_angles("miura", -theta)
    # Stated tolerance 1e-9 deg (1.7e-11 rad); measured bit-exact.
    tol = np.deg2rad(1e-9)
    np.testing.assert_allclose(minus[:, PHI], -plus[:, PHI], atol=tol, rtol=0)
    np.testing.assert_allclose(minus[:, PSI], plus[:, PSI], atol=tol, rtol=0)
    np.testing.assert_allclose(minus[:, RHO], -plus[:, RHO], atol=tol, rtol=0)  # central symmetry


@pytest.mark.parametrize("entry", checked_by(kamrava2021.NUMBERS, "test_published_lock_angles"), ids=str)
def test_published_lock_angles(entry):
    entry.check()


@pytest.mark.parametrize("pair", PAIRS)
def test_miura_branch_domain_ends_at_the_lock_angle(pair):
    vertex = miura(*pair)
    assert vertex.branch("miura").domain == (-vertex.theta_limit, vertex.theta_limit)


@pytest.mark.parametrize("pair", ASYMMETRIC)
def test_crease_next_to_smaller_sector_folds_flat_at_lock(pair):
    vertex = miura(*pair)
    crease = RHO_B if pair[0] < pair[1] else RHO_D
    out = np.rad2deg(vertex.joint_angles("miura", [vertex.theta_limit, -vertex.theta_limit]))
    # Stated tolerance 0.01 deg (measured 1e-13 deg).
    np.testing.assert_allclose(np.abs(out[:, crease]), 180.0, atol=0.01, rtol=0)


def test_phi_at_lock_equals_lock_angle():
    check_every(kamrava2021.NUMBERS, "test_phi_at_lock_equals_lock_angle")


def test_phi_is_non_monotonic_with_published_maximum():
    vertex = miura(30, 60)
    theta_max = kamrava2021.phi_maximum()[1]
    assert 0 < theta_max < np.rad2deg(vertex.theta_limit), "the maximum of phi is interior (not a grid end)"
    # Stated tolerance 0.01 deg, far above the grid step.
    check_every(kamrava2021.NUMBERS, "test_phi_is_non_monotonic_with_published_maximum")


@pytest.mark.parametrize("alpha", [45, 60])
def test_symmetric_vertex_has_zero_psi_and_closed_form_phi(alpha):
    vertex = miura(alpha, alpha)
    entries = checked_by(kamrava2021.NUMBERS, "test_symmetric_vertex_has_zero_psi_and_closed_form_phi")
    [entry] = [e for e in entries if e.where == f"sectors {alpha}/{alpha}"]
    entry.check()
    theta = np.linspace(-0.99, 0.99, 199) * np.deg2rad(35)  # phi < 90 deg here, so a_x > 0
    out = vertex.joint_angles("miura", theta)
    assert np.all(out[:, PSI] == 0.0)
    # phi = 2 atan(sin theta tan alpha) (eqn 38 at alpha1 = alpha2, derived here); measured 4e-16.
    expected = 2 * np.arctan(np.sin(theta) * np.tan(np.deg2rad(alpha)))
    np.testing.assert_allclose(out[:, PHI], expected, atol=1e-14, rtol=0)


def test_psi_uses_atan2_past_ninety_degrees():
    check_every(kamrava2021.NUMBERS, "test_psi_uses_atan2_past_ninety_degrees")


def test_spinal_crease_x_changes_sign_at_published_angle():
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
