"""The path engine (`sim_origami.path`): its arc-length mode through a turning point and a bifurcation, its
given-values mode with several inputs, and the chord polish between a path's nodes, each against a closed form (no
stored output of earlier code)."""

from dataclasses import replace

import numpy as np
import pytest
from scipy import sparse as sp

from sim_origami import path
from sim_origami.errors import ParameterError
from sim_origami.kinematics.vertex4 import Vertex4
from sim_origami.path import (
    BIFURCATION_RTOL,
    ArcSystem,
    BandedNormal,
    ChordPolish,
    follow_arc,
    nearest_nodes,
    toward_step,
)


class Curves(ArcSystem):
    """Points (x, y, z) with F(x) = 0 over all three coordinates (no ground); the chart is x itself."""

    def __init__(self, residual, jacobian):
        self._residual, self._jacobian = residual, jacobian
        super().__init__(3, 2, 1.0, 1e-13, 1e-9)

    def residual(self, x, ref):
        return self._residual(x)

    def jacobian(self, x):
        return self._jacobian(x)

    def move(self, x, d):
        return x + d

    def chart(self, x, ref):
        return x.copy()

    def chart_rate(self, x, k):
        return np.eye(3)[k]


def crossing() -> Curves:
    """x^2 = y^2, z = x y: the branches (t, t, t^2) and (t, -t, -t^2) cross at the origin (mobility 2 there)."""
    return Curves(lambda p: np.array([p[0] ** 2 - p[1] ** 2, p[2] - p[0] * p[1]]),
                  lambda p: np.array([[2 * p[0], -2 * p[1], 0.0], [-p[1], -p[0], 1.0]]))


@pytest.mark.parametrize(("choice", "sign"), [("keep", 1.0), ("switch", -1.0)])
def test_follow_arc_locates_the_crossing_and_keeps_or_switches_branch(choice, sign):
    start = np.array([-1.0, -1.0, 1.0])
    run = follow_arc(crossing(), start, start, 0, 1.0, choice=choice)
    assert run.reached
    (event,) = run.events
    assert (event.mobility, event.directions) == (2, 2) and event.point.sigma2 < BIFURCATION_RTOL
    # located to about the square root of the corrector tolerance (as on the scenes' bifurcations)
    assert np.abs(event.point.x).max() < 1e-6
    x = np.array([p.x for p in run.points])
    before, after = x[: event.index], x[event.index + 1 :]
    # before the crossing: the branch y = x; after it: y = x ('keep') or y = -x ('switch'), z = x y (closed form)
    assert np.abs(before[:, 1] - before[:, 0]).max() < 1e-12
    assert np.abs(after[:, 1] - sign * after[:, 0]).max() < 1e-12
    assert np.abs(x[:, 2] - x[:, 0] * x[:, 1]).max() < 1e-12
    assert x[-1, 0] == pytest.approx(1.0, abs=1e-14) and np.all(np.diff(x[:, 0]) > 0)


def test_follow_arc_passes_a_turning_point_of_an_undriven_coordinate():
    # the circle x^2 + y^2 = 1, z = x driven by y from -0.5 rad of arc to y = 0.9: x turns at y = 0, where a
    # natural-parameter continuation in x could not pass
    circle = Curves(lambda p: np.array([p[0] ** 2 + p[1] ** 2 - 1.0, p[2] - p[0]]),
                    lambda p: np.array([[2 * p[0], 2 * p[1], 0.0], [-1.0, 0.0, 1.0]]))
    start = np.array([np.cos(-0.5), np.sin(-0.5), np.cos(-0.5)])
    run = follow_arc(circle, start, start, 1, 0.9)
    x = np.array([p.x for p in run.points])
    assert run.reached and not run.events and x[-1, 1] == pytest.approx(0.9, abs=1e-14)
    assert np.argmax(x[:, 0]) not in (0, len(x) - 1)  # x rose, then fell
    assert np.abs(x[:, 0] - np.sqrt(1.0 - x[:, 1] ** 2)).max() < 1e-12 and np.abs(x[:, 2] - x[:, 0]).max() < 1e-12


def test_follow_arc_rejects_bad_choice_step_and_a_start_of_mobility_two():
    start = np.array([-1.0, -1.0, 1.0])
    with pytest.raises(ParameterError, match="'sideways'"):
        follow_arc(crossing(), start, start, 0, 1.0, choice="sideways")
    with pytest.raises(ParameterError, match="positive"):
        follow_arc(crossing(), start, start, 0, 1.0, step=0.0)
    with pytest.raises(ParameterError, match="mobility 1 at the start"):
        follow_arc(crossing(), np.zeros(3), np.zeros(3), 0, 1.0)


def test_sweep_with_several_inputs_follows_the_closed_form():
    # `LoopSystem.follow` with inputs as rows (n, k) takes the secant in the inputs' arc length: a vertex driven
    # through its input as a (n, 1) path, out and back, equals the closed form (Peng 2018, Eq. 2-34 vertex)
    vertex = Vertex4(np.array([np.pi / 2, 7 * np.pi / 18, np.pi / 3, 7 * np.pi / 9]))
    x = np.r_[np.linspace(0.3, 1.2, 20), np.linspace(1.2, 0.3, 20)[1:]]
    exact = vertex.joint_angles("odd2", x)
    numeric = vertex.loop_system().follow(exact[0], (0,), x[:, None])
    np.testing.assert_allclose(numeric, exact, atol=1e-12, rtol=0)


@pytest.mark.parametrize("sparse", [False, True], ids=["dense-pinv", "sparse-lu"])
@pytest.mark.parametrize("floor", [False, True], ids=["to-tol", "to-floor"])
def test_chord_polish_closes_poses_between_nodes_to_the_closed_form(sparse, floor):
    # nodes 0.1 rad apart on a vertex's closed form (Peng 2018, Eq. 2-34 vertex); poses between them, from straight
    # and cubic Hermite guesses, closed by chord steps with either factorisation
    vertex = Vertex4(np.array([np.pi / 2, 7 * np.pi / 18, np.pi / 3, 7 * np.pi / 9]))
    s = np.linspace(0.3, 1.2, 10)
    loops = replace(vertex.loop_system(), sparse=sparse)
    fixed = np.array([True, False, False, False])
    polish = ChordPolish(loops, vertex.joint_angles("odd2", s), fixed, tol=1e-15, close_tol=1e-13, floor=floor)
    x = np.linspace(0.3, 1.2, 37)[1:-1]
    exact = vertex.joint_angles("odd2", x)
    straight = np.stack([np.interp(x, s, polish.nodes[:, j]) for j in range(4)], axis=-1)
    cubic = polish.hermite(s, x)
    assert np.max(np.abs(cubic - exact)) < 1e-2 * np.max(np.abs(straight - exact))  # measured 6.3e-8 vs 1.7e-4
    for guess in (straight, cubic):
        closed = polish.polish(guess, nearest_nodes(s, x))
        np.testing.assert_allclose(closed, exact, atol=1e-13, rtol=0)  # measured 4.3e-15
        assert np.max(loops.residual_norm(closed)) < 1e-13
    assert len(polish._factors) == len(s)  # one factorisation per node, kept


def test_banded_normal_equations_solve_as_a_dense_solve():
    # A Jacobian whose columns are scattered (the ordering must find the band), with a column no row touches.
    rng = np.random.default_rng(3)
    J = (sp.random(300, 120, density=0.03, random_state=rng) + sp.eye(300, 120)).tocsc()
    J = J[:, np.r_[0:50, 51:120]]  # column 50 of the identity part dropped: rows 50.. keep their other entries
    J = sp.hstack([J, sp.csc_matrix((300, 1))]).tocsc()
    r = rng.standard_normal(300)
    A = (J.T @ J).toarray()
    layout = BandedNormal(J)
    assert layout.band < J.shape[1] - 1
    step = layout.step(J.data, r, 1e-3)
    damped = A + 1e-3 * np.diag(np.diag(A) + 1e-12)
    assert np.allclose(damped @ step, -(J.T @ r), rtol=0, atol=1e-12)
    b = rng.standard_normal((J.shape[1], 2))
    b[-1] = 0.0  # the empty column's row of J^T J is shifted by 1e-12 of the largest diagonal: b = 0 keeps it still
    x = layout.factor(J.data).solve(b)
    assert np.allclose(A @ x, b, rtol=0, atol=1e-10) and x.shape == b.shape
    assert np.all(x[-1] == 0.0)


@pytest.mark.parametrize("sparse", [False, True])
def test_the_toward_step_is_closed_to_first_order_and_leans_every_spare_freedom_towards_the_state(sparse):
    """A degree-8 vertex (5 freedoms) driven by one crease: the step moves the driven crease by dx, keeps J dq = 0, and
    of all such steps is the one nearest the wished lam (toward - q); it scales with dx; a drive away from the state
    gives none."""
    from sim_origami.fold import read_fold
    from sim_origami.kinematics.numeric_pattern import lock_flat

    ring = [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1]]
    pattern = read_fold({"vertices_coords": [[0, 0], *ring], "edges_vertices": [[0, i] for i in range(1, 9)]
                         + [[i, i % 8 + 1] for i in range(1, 9)], "edges_assignment": ["M", "V"] * 4 + ["B"] * 8,
                         "faces_vertices": [[0, i, i % 8 + 1] for i in range(1, 9)]}).pattern
    loops = replace(pattern.loop_system(lock_flat(pattern)), sparse=sparse)
    toward = np.pi * np.array([-1.0, 1.0] * 4)
    q = np.zeros(8)
    dq = toward_step(loops, q, np.array([0]), np.array([-0.01]), toward)
    J = loops.jacobian(q)
    assert dq[0] == -0.01 and np.max(np.abs(J @ dq)) < 1e-12
    wish = dq[0] / toward[0] * toward
    null = np.linalg.svd(np.vstack([J, np.eye(8)[:1]]))[2][6:].T  # first-order steps that hold the driven crease
    assert np.max(np.abs(null.T @ (dq - wish))) < 1e-9  # nothing within them brings dq nearer the wish
    assert np.all(np.sign(dq) == np.sign(toward))  # at flat, every crease leaves on its letter's side
    assert toward_step(loops, q, np.array([0]), np.array([0.01]), toward) is None
    np.testing.assert_allclose(toward_step(loops, q, np.array([0]), np.array([-0.03]), toward), 3 * dq, atol=1e-12)


@pytest.mark.parametrize("nullity", [0, 3, 20])
def test_large_sparse_rank_and_condition_agree_with_the_full_spectrum(nullity):
    # above SPARSE_SPECTRUM_FROM columns the rank and condition come from the spectrum's ends (Lanczos on the Gram
    # matrix and on its shifted inverse) instead of a dense eigendecomposition (0.92 s a sample at 1,512 creases);
    # a null space as wide as the first request (8) or wider takes the whole spectrum
    rng = np.random.default_rng(7)
    n = path.SPARSE_SPECTRUM_FROM + 50
    A = sp.random(2 * n, n, density=0.01, random_state=rng, format="csr") + sp.identity(n, format="csr").tocsr()[
        np.arange(2 * n) % n]
    A = A.tolil()
    for k in range(nullity):  # column k repeats column k + 1 (a null direction each)
        A[:, k] = A[:, k + nullity]
    A = A.tocsr()
    s = path.singular_values(A)
    r = path.rank_of(s)
    assert r == n - nullity and path.rank(A) == r
    assert path.condition(A) == pytest.approx(s[0] / s[r - 1], rel=1e-9)


@pytest.mark.parametrize("nullity", [1, 3])
def test_a_large_sparse_null_space_is_the_full_svds(nullity):
    # model.xml's servo gain needs the closures' null space: a dense SVD of the 24 x 24 sheet's 3177 x 575 Jacobian
    # took 3.4 s, Lanczos on its shifted Gram inverse 0.04 s (the same gain)
    rng = np.random.default_rng(3)
    n = path.SPARSE_SPECTRUM_FROM + 30
    A = (sp.random(2 * n, n, density=0.01, random_state=rng) + sp.identity(n).tocsr()[np.arange(2 * n) % n]).tolil()
    for k in range(nullity):
        A[:, k] = A[:, k + nullity]
    A = A.tocsr()
    N = path.null_space(A, 1e-9)
    Vt = np.linalg.svd(A.toarray())[2]
    full = Vt[n - nullity :].T
    assert N.shape == (n, nullity) and np.abs(A @ N).max() < 1e-12
    assert np.allclose(N @ N.T, full @ full.T, atol=1e-10)  # the same subspace
