"""Numeric loop closure (`sim_origami.closure`) against the spherical 4R closed forms of Peng 2018 (ch. 2-3)."""

import numpy as np
import pytest

from sim_origami.closure import Loop, LoopSystem
from sim_origami.errors import ConvergenceError
from sim_origami.geometry import rot_x, transform, wrap
from sim_origami.kinematics.vertex4 import Vertex4

# Peng 2018, Eq. 2-34: the generic developable vertex.
GENERIC_ALPHA = (np.pi / 2, 7 * np.pi / 18, np.pi / 3, 7 * np.pi / 9)
# Peng 2018, Fig. 2-1 (the basic linkage, not developable) and Fig. 2-5 (a linkage).
FIG_2_1_ALPHA = (np.pi / 9, 2 * np.pi / 9, 4 * np.pi / 9, 2 * np.pi / 3)
FIG_2_5_ALPHA = (2 * np.pi / 9, np.pi / 3, 13 * np.pi / 18, 5 * np.pi / 9)
# Peng 2018, Sec. 3.2.1, Fig. 3-2: the flat-foldable type I vertex.
TYPE_I_ALPHA = (3 * np.pi / 4, np.pi / 3, np.pi / 4, 2 * np.pi / 3)

INPUT_FIXED = np.array([True, False, False, False])


def spherical_loop(alpha) -> LoopSystem:
    """Spherical 4R D-H loop Rz(q1) Rx(a12) ... Rz(q4) Rx(a41) = I, any twists (Peng 2018, Eq. 2-1)."""
    links = np.stack([transform(rot_x(a)) for a in alpha])
    return LoopSystem(4, (Loop((0, 1, 2, 3), links, (1, 1, 1, 1)),))


def angle_distance(q, p) -> np.ndarray:
    """Largest wrapped joint difference between configurations (..., 4)."""
    return np.max(np.abs(wrap(np.asarray(q) - np.asarray(p))), axis=-1)


def assert_same_configurations(found, expected, atol: float) -> None:
    """`found` and `expected` (k, n) hold the same configurations up to order and 2 pi."""
    found, expected = np.atleast_2d(found), np.atleast_2d(expected)
    assert len(found) == len(expected), f"found {len(found)} configurations, expected {len(expected)}"
    for q in expected:
        nearest = np.min(angle_distance(found, q))
        assert nearest <= atol, f"no configuration within {atol:g} rad of {q}; nearest is {nearest:.3g}"


@pytest.fixture(scope="module")
def case4():
    return Vertex4(np.array(GENERIC_ALPHA))


def test_flat_state_closes_the_loop(case4):
    # Four Rx twists summing to 2 pi: measured 4.8e-16 (rounding of the sum); 1e-15 is 2x.
    np.testing.assert_allclose(case4.loop_system().residual(np.zeros(4)), 0.0, atol=1e-15, rtol=0)


def test_residual_is_batched_over_leading_axes(case4):
    system = case4.loop_system()
    q = np.random.default_rng(0).uniform(-1.0, 1.0, (3, 5, 4))
    r = system.residual(q)
    assert r.shape == (3, 5, 6)
    assert np.array_equal(r[1, 2], system.residual(q[1, 2]))


@pytest.mark.parametrize("branch", ["odd2", "odd3"])
def test_solve_closes_perturbed_vertex_loop_onto_closed_form(case4, branch):
    system = case4.loop_system()
    exact = case4.joint_angles(branch, 0.5)[0]
    start = exact + np.array([0.0, 0.05, -0.04, 0.03])
    q = system.solve(start, INPUT_FIXED)
    assert q[0] == 0.5, "the fixed input joint must not move"
    assert system.residual_norm(q) < 1e-14  # the solver's own stopping tolerance
    # A well-conditioned folded state (away from flat and locks): measured 9e-16; 1e-13 is 100x.
    np.testing.assert_allclose(q, exact, atol=1e-13, rtol=0)


@pytest.mark.parametrize("branch, other", [("odd2", "odd3"), ("odd3", "odd2")])
def test_follow_keeps_the_named_branch_through_the_flat_state(case4, branch, other):
    # From input 0.5 down to -0.5 through the flat bifurcation: continuity must land on the SAME
    # geometric branch on the far side (the +/- root label would swap there: central symmetry, Peng 2018, Eq. 2-10).
    system = case4.loop_system()
    inputs = np.linspace(0.5, -0.5, 40)  # steps straddle 0 at +/-0.0128
    path = system.follow(case4.joint_angles(branch, 0.5)[0], 0, inputs)
    assert system.residual_norm(path).max() < 1e-13  # solve tolerance 1e-14, within its 100x slack
    # Newton near the double point is least accurate: measured 4.9e-13 at |input| = 0.013; 1e-11 is 20x.
    np.testing.assert_allclose(path, case4.joint_angles(branch, inputs), atol=1e-11, rtol=0)
    # On the far side the path is nowhere near the other branch (measured separation >= 0.47 rad).
    far = inputs < -0.2
    assert np.min(angle_distance(path[far], case4.joint_angles(other, inputs[far]))) > 0.4


@pytest.mark.parametrize("x", [0.5, -1.2, 1.5])
def test_assemblies_finds_exactly_the_closed_form_roots(case4, x):
    found = case4.loop_system().assemblies(0, x, starts=16)
    expected = np.concatenate([case4.joint_angles(name, x) for name in ("odd2", "odd3")])
    # Both roots are simple at these inputs: measured <= 3e-14; 1e-11 leaves 300x margin.
    assert_same_configurations(found, expected, atol=1e-11)


@pytest.mark.parametrize(
    "alpha, x, expected",
    [
        # Peng 2018, Fig. 2-1 linkage: theta1 = 2.0 on both branches (roots computed here from Eqs. 2-2 to 2-5)
        (FIG_2_1_ALPHA, 2.0, [(0.241470, 0.711098, 2.339965), (1.751285, -0.711098, -3.015852)]),
        # Peng 2018, Fig. 2-5 linkage: theta1 = 1.0 on both branches (computed here likewise)
        (FIG_2_5_ALPHA, 1.0, [(-0.217664, 1.337066, 1.201753), (-2.237818, -1.337066, -2.525692)]),
    ],
    ids=["case1", "case3"],
)
def test_assemblies_reproduces_published_non_developable_roots(alpha, x, expected):
    found = spherical_loop(alpha).assemblies(0, x, starts=16)
    expected = np.array([(x, *q) for q in expected])
    # Given to 6 decimals: half a unit of the last digit.
    assert_same_configurations(found, expected, atol=5e-7)


def test_assemblies_is_empty_where_the_linkage_cannot_assemble():
    # Peng 2018, Fig. 2-1 linkage: no solution for |theta1| < 1.468817 (computed here).
    assert spherical_loop(FIG_2_1_ALPHA).assemblies(0, 1.0, starts=8).shape == (0, 4)


def test_solve_raises_convergence_error_on_impossible_target():
    with pytest.raises(ConvergenceError, match=r"residual .* > tolerance"):
        spherical_loop(FIG_2_1_ALPHA).solve([1.0, 0.3, 0.2, 0.1], INPUT_FIXED)


@pytest.mark.parametrize(
    "alpha, branches, x",
    [(GENERIC_ALPHA, ("odd2", "odd3"), 0.5), (TYPE_I_ALPHA, ("S", "C"), 1.0)],
    ids=["generic", "flat_foldable"],
)
def test_mobility_is_two_at_flat_state_and_one_when_folded(alpha, branches, x):
    vertex = Vertex4(np.array(alpha))
    system = vertex.loop_system()
    assert system.mobility(np.zeros(4)) == 2
    for name in branches:
        assert system.mobility(vertex.joint_angles(name, x)[0]) == 1
