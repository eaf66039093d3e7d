"""The one numeric path engine: every numeric path of the package is followed here.

Three modes share one set of parts (predictor, correctors, step control, numerical rank):

- `sweep`: natural-parameter continuation at given parameter values, a secant predictor through the last two
  solutions and the caller's corrector at each value (`LoopSystem.follow`: validation's numeric reference, the
  user-curve check, the rigid-foldability test of `kinematics.numeric_pattern`);
- `trace`: natural-parameter continuation of a `ClosureSystem` while k driven joints move along a `Polyline`, with
  step control, stall, bound and mobility-change reports (`kinematics.numeric_pattern.PatternPath`);
- `follow_arc`: pseudo-arc-length continuation of an `ArcSystem` along its mechanism mode (Yang 2017, Sec. 2.4, eqns
  2-12 to 2-18, after Kumar and Pellegrino 2000), through turning points of the input, with bifurcation detection (the
  second singular value of the Jacobian and the orientation of its bordered form), location (golden section), branch
  directions at second order and branch switching (`truss.follow`).

A traced path is then read between its nodes by `ChordPolish`: interpolated poses (straight or cubic Hermite
guesses) closed by the chord method, Gauss-Newton steps with the Jacobian of each pose's nearest node factorised
once (a band LU of its normal matrix or a dense pseudo-inverse), all poses at once, and the full solve for any the
chord does not close (`evaluate` of `kinematics.numeric_pattern.PatternPath` and `kinematics.linkage_path.LinkagePath`).
The sparse corrector's and the chord's normal equations share one band layout per sparsity pattern (`BandedNormal`).

Correctors: damped Gauss-Newton (`levenberg_marquardt`, tolerant of the rank-deficient Jacobians of overconstrained
loops) for `sweep` and `trace`; Newton with the rank-truncated pseudo-inverse (`ArcSystem.correct`) for
`follow_arc`. Step control (`Step`): halving on a rejected step, growth by GROWTH on an accepted one.

Where `trace` stops, and why (`PathStop.kind`):
- "end": the polyline's end was reached;
- "stall": the corrector converges to a stationary point of the residual that is not closed (a least-squares
  minimum above the tolerance, |J^T r| << |J| |r|) at STALL_CONFIRM successively halved steps, or the step
  fell below `min_step`: no rigid configuration beyond, with the driven joints moved that way;
- "bound": a joint would leave its bounds (a crease reaching +-pi, a crease whose sign would flip), `joint` says
  which; the path ends at the last node inside them;
- "bifurcation": the mobility rose above the path's (only with `stop_at_bifurcation`);
- "contact": `stop_when` (e.g. a self-contact test) gave a reason at a node; the first such configuration is
  located by bisection on s between that node and the last one to STOP_WHEN_TOL, and the path ends just before it.

Along the path `trace` records the instantaneous mobility (joints minus the numerical rank of the closure
Jacobian) at every node; a change is reported as an event (a bifurcation or the end of one). Open chains (no
loops, no couplings) close trivially: every node is exact and the mobility is the joint count.

Units: radians for joints and `trace`'s path parameter s; residuals in radians and the system's length unit;
`follow_arc`'s arc length in the system's length unit (steps given in units of `ArcSystem.scale`).
"""

from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import sparse as sp
from scipy.linalg import solve_banded
from scipy.linalg.lapack import dgbtrf, dgbtrs
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.sparse.linalg import LinearOperator, eigsh, splu

from .errors import AssemblyError, ConvergenceError, ParameterError

# Step control: an accepted step grows by this factor (up to the mode's largest step).
GROWTH = 1.5

# Band layouts of sparse normal equations kept (one per sparsity pattern of a corrector's Jacobian, FIFO).
BAND_LAYOUTS = 32

# -- trace --
# Corrector iterations per step, and a failed corrector's |J^T r| / (|J| |r|) below which it sits at a stationary
# point of the residual (a least-squares minimum that does not close), not merely short of iterations.
CORRECTOR_ITER = 40
STATIONARY = 1e-6
# Halved steps, each ending at such a minimum, before a stall is declared.
STALL_CONFIRM = 3
# A corrector whose result differs from the last node by more than this (rad) jumped to another branch.
JUMP = 0.2
# Numerical rank: singular values above this times the largest (at least 1) count (as `LoopSystem.mobility`).
RANK_RTOL = 1e-6
# Null-space rows this close (relative) to the largest are a tie in `independent_joints`: the earlier joint is picked,
# not the one rounding favours (the bird base's mirror creases e10 and e11 swapped with a unit in the last place of
# the loop residual).
PIVOT_TIE = 1e-9
# Sparse (large) systems rank every this many nodes and the last (480 creases: one rank 0.1-1 s, a corrector step
# a few ms); a mobility change is then placed between two ranked nodes.
SPARSE_RANK_STRIDE = 10
# Sparse matrices with more columns than this get their rank and condition from the ends of their spectrum
# (`small_spectrum`), asking first for this many of the smallest singular values.
SPARSE_SPECTRUM_FROM = 400
SMALL_SPECTRUM_FIRST = 8
SMALL_SPECTRUM_BASIS = 32  # Lanczos vectors kept (ARPACK's ncv)
SHIFT_FLOOR = 1e-8
MULTIPLICITY_BLOCK = 4
# The toward predictor's sparse least squares stops at this relative residual: a predictor, closed by the corrector
# after it (1e-15 cost 0.13 s a call on the 16 x 16 Miura sheet near flat).
PREDICTOR_TOL = 1e-8
# A `stop_when` reason is located to this (path parameter, rad) by bisection between two nodes.
STOP_WHEN_TOL = 1e-9

# -- ChordPolish --
# Chord steps before the full solve takes over (and Gauss-Newton steps to the rounding floor).
CHORD_ITER = 30

# -- follow_arc --
# Newton corrector: at most this many iterations to bring every residual component below `ArcSystem.tol`.
ARC_CORRECTOR_ITER = 12
# Step control on the arc length (x `ArcSystem.scale`): first step, largest step, smallest before giving up.
# A step is rejected (and halved) when the corrector fails, moves the point by more than MAX_CORRECTION x the
# step, or the tangent turns by more than MAX_TURN rad; a step that converged in <= FAST_ITER iterations grows.
FIRST_STEP = 0.02
MAX_STEP = 0.25
MIN_STEP = 1e-9
MAX_CORRECTION = 0.3
MAX_TURN = 0.4
FAST_ITER = 3
# Bifurcations. A branch crosses one between two points when the orientation sign (`ArcSystem.orientation`)
# flips; it touches one near a point that is a local minimum of sigma_2 below DIP x the larger of its two
# neighbours. The minimum of sigma_2 is then located on the path (golden-section rounds over spans shrinking
# REFINE_SHRINK times, down to REFINE_FLOOR x scale); it is a bifurcation, and its mobility is counted, with
# BIFURCATION_RTOL x sigma_max as zero. A double point is only located to about the square root of the
# corrector tolerance: located sigma_2 measured 3.7e-13 .. 3.7e-9, input within 5.5e-7 rad, on 44 crossings of
# the registered scenes' simple bifurcations (Bricard bundle, plane-symmetric Bricard, Miura, vertex4, thick
# diamond), against sigma_2 >= 3.5e-5 anywhere on every scene's default paths (triangle-twist-6r).
DIP = 0.5
REFINE_SHRINK = 4.0
REFINE_FLOOR = 1e-10
BIFURCATION_RTOL = 1e-6
# Second differences of the residual along a branch direction, step in units of `ArcSystem.scale`.
CURVATURE_STEP = 1e-3
# A golden-section search stops when its bracket is this fraction of the first.
GOLDEN_STOP = 0.05


# -- parts shared by the modes ---------------------------------------------------------------------------------


def levenberg_marquardt(residual, jacobian, u: NDArray[np.float64], tol: float, max_iter: int,
                        damping: float = 1e-6):
    """
    Damped Gauss-Newton (Levenberg-Marquardt, tolerant of rank-deficient Jacobians) on residual(u), from u; stops
    below `tol` (largest component), after `max_iter` steps, or when the damping needed exceeds 1e8. `damping` is the
    first, relative to J^T J's diagonal, cut tenfold on an accepted step and grown tenfold on a rejected one. A sparse
    Jacobian's normal equations are solved in band storage (`BandedNormal`). Returns (u, residual).
    """
    r, J = residual(u), None
    for _ in range(max_iter):
        if np.max(np.abs(r), initial=0.0) < tol:  # an open chain (no residual) is closed
            break
        if J is None:  # after a rejected step u has not moved: its Jacobian is the same
            J = jacobian(u)
        if sp.issparse(J):  # large patterns: a few nonzeros per row, so the normal equations stay banded
            J = J.tocsc()
            trial = u + _band_layout(J).step(J.data, r, damping)
        else:
            JtJ = J.T @ J
            trial = u + np.linalg.solve(JtJ + damping * np.diag(np.diag(JtJ) + 1e-12), -J.T @ r)
        r_trial = residual(trial)
        if np.sum(r_trial**2) < np.sum(r**2):
            u, r, J = trial, r_trial, None
            damping = max(damping * 0.1, 1e-12)
        else:
            damping *= 10.0
            if damping > 1e8:
                break
    return u, r


class BandedNormal:
    """
    The damped normal equations (J^T J + damping diag(J^T J + 1e-12)) step = -J^T r of one sparsity pattern of a
    CSC Jacobian J, assembled straight into LAPACK band storage after a reverse Cuthill-McKee ordering of the
    unknowns and solved by band LU with partial pivoting (gbsv). The layout depends on the pattern only, so it is
    built once per pattern (`_band_layout`) and each step costs a bincount and the band solve: a 16 x 16 Miura
    sheet's 479 unknowns have band 32, 0.36 ms a step against 1.5 ms for building J^T J and SuperLU (spsolve).
    """

    def __init__(self, J: sp.csc_matrix) -> None:
        m, n = J.shape
        at = sp.csc_matrix((np.arange(J.nnz, dtype=float), J.indices, J.indptr), shape=J.shape).tocsr()
        ones = sp.csc_matrix((np.ones(J.nnz), J.indices, J.indptr), shape=J.shape)
        self.order = reverse_cuthill_mckee((ones.T @ ones).tocsr(), symmetric_mode=True)
        position = np.empty(n, dtype=np.int64)
        position[self.order] = np.arange(n)
        # Every ordered pair (a, b) of entries sharing a row adds J[row, a] J[row, b] to (J^T J)[col a, col b].
        count = np.diff(at.indptr)
        pairs = count**2
        owner = np.repeat(np.arange(m), pairs)
        local = np.arange(int(pairs.sum())) - np.repeat(np.cumsum(pairs) - pairs, pairs)
        self.a = at.data[at.indptr[owner] + local // count[owner]].astype(np.int64)
        self.b = at.data[at.indptr[owner] + local % count[owner]].astype(np.int64)
        self.column = np.repeat(np.arange(n), np.diff(J.indptr))  # of each entry of J.data
        self.row = J.indices
        i, j = position[self.column[self.a]], position[self.column[self.b]]
        self.band = int(np.max(np.abs(i - j), initial=0))
        self.flat = (self.band + i - j) * n + j  # solve_banded's ab[band + i - j, j] = A[i, j]
        self.diagonal = self.band * n + np.arange(n)
        self.n = n

    def factor(self, data: NDArray[np.float64]) -> "BandLU":
        """
        The LU factorisation of J^T J for the Jacobian values `data`, to solve J^T J x = b again and again
        (`ChordPolish`). A singular one (fewer inputs than the motion's freedoms, --input: a pivot at rounding, n eps
        of the largest, or zero) is factored with 1e-12 of its largest diagonal added: the steps then leave the
        undriven directions where they are.
        """
        n, band = self.n, self.band
        # dgbtrf's storage: band rows of fill-in above solve_banded's layout
        normal = np.bincount(self.flat + band * n, weights=data[self.a] * data[self.b], minlength=(3 * band + 1) * n)
        lu, pivots, info = dgbtrf(normal.reshape(3 * band + 1, n), band, band)
        pivot = np.abs(lu[2 * band])  # U's diagonal
        if info > 0 or pivot.min(initial=np.inf) <= n * np.finfo(float).eps * pivot.max(initial=0.0):
            shifted = normal.copy()
            shifted[self.diagonal + band * n] += 1e-12 * max(float(normal[self.diagonal + band * n].max()), 1.0)
            lu, pivots, info = dgbtrf(shifted.reshape(3 * band + 1, n), band, band, overwrite_ab=True)
        if info < 0:
            raise ValueError(f"dgbtrf: argument {-info} is illegal")
        return BandLU(lu, pivots, band, self.order)

    def step(self, data: NDArray[np.float64], r: NDArray[np.float64], damping: float) -> NDArray[np.float64]:
        """The damped Gauss-Newton step (n,) for the Jacobian values `data` (in J.data's order) and residual r."""
        n, band = self.n, self.band
        ab = np.bincount(self.flat, weights=data[self.a] * data[self.b], minlength=(2 * band + 1) * n)
        ab[self.diagonal] += damping * (ab[self.diagonal] + 1e-12)
        gradient = np.bincount(self.column, weights=data * r[self.row], minlength=n)
        out = np.empty(n)
        out[self.order] = solve_banded((band, band), ab.reshape(2 * band + 1, n), -gradient[self.order],
                                       overwrite_ab=True, overwrite_b=True, check_finite=False)
        return out


@dataclass(frozen=True)
class BandLU:
    """A band LU factorisation (LAPACK dgbtrf) of a normal matrix in `BandedNormal`'s ordering."""

    lu: NDArray[np.float64]
    pivots: NDArray[np.int32]
    band: int
    order: NDArray[np.int32]

    def solve(self, b: NDArray[np.float64]) -> NDArray[np.float64]:
        """x with (J^T J) x = b, for b (n,) or (n, m)."""
        x, info = dgbtrs(self.lu, self.band, self.band, b[self.order], self.pivots, overwrite_b=True)
        if info < 0:
            raise ValueError(f"dgbtrs: argument {-info} is illegal")
        out = np.empty_like(x)
        out[self.order] = x
        return out


_band_layouts: dict[tuple, BandedNormal] = {}


def _band_layout(J: sp.csc_matrix) -> BandedNormal:
    """The `BandedNormal` of J's sparsity pattern, kept (the last BAND_LAYOUTS patterns): a corrector's Jacobian
    keeps one pattern from step to step and from solve to solve."""
    key = (J.shape, J.indptr.tobytes(), J.indices.tobytes())
    if key not in _band_layouts:
        if len(_band_layouts) >= BAND_LAYOUTS:
            del _band_layouts[next(iter(_band_layouts))]
        _band_layouts[key] = BandedNormal(J)
    return _band_layouts[key]


def hermite(v0: ArrayLike, v1: ArrayLike, d0: ArrayLike, d1: ArrayLike, w: ArrayLike) -> NDArray[np.float64]:
    """Cubic Hermite interpolation at w in [0, 1] between values v0, v1 with end slopes d0, d1 (per unit w)."""
    v0, v1, d0, d1, w = (np.asarray(a, dtype=float) for a in (v0, v1, d0, d1, w))
    return (2 * w**3 - 3 * w**2 + 1) * v0 + (w**3 - 2 * w**2 + w) * d0 + (3 * w**2 - 2 * w**3) * v1 + (w**3 - w**2) * d1


def secant(s_prev: float, x_prev: NDArray, s: float, x: NDArray, s_new: float) -> NDArray[np.float64]:
    """Secant predictor: the line through (s_prev, x_prev) and (s, x), at parameter s_new."""
    return x + (x - x_prev) / (s - s_prev) * (s_new - s)


@dataclass
class Step:
    """Step control: `size` halves on a rejected step and grows by GROWTH (up to `largest`) on an accepted one."""

    size: float
    largest: float
    smallest: float

    def reject(self) -> bool:
        """Halve the step; True when it fell below `smallest` (give up)."""
        self.size /= 2
        return self.size < self.smallest

    def accept(self) -> None:
        self.size = min(GROWTH * self.size, self.largest)


def rank(J, rtol: float = RANK_RTOL) -> int:
    """Numerical rank of a Jacobian, dense or sparse (rows may be empty): singular values above rtol times the
    largest (at least 1)."""
    if not J.shape[0] or not J.shape[1]:
        return 0
    if sp.issparse(J) and J.shape[1] > SPARSE_SPECTRUM_FROM:
        return J.shape[1] - small_spectrum(J, rtol)[1]
    return rank_of(singular_values(J), rtol)


def condition(J, rtol: float = RANK_RTOL) -> float:
    """Condition number of a Jacobian over its rank (`rank`): its largest singular value over its smallest above
    rtol times the largest (at least 1); 1 when it has none."""
    if sp.issparse(J) and J.shape[1] > SPARSE_SPECTRUM_FROM:
        largest, _, least = small_spectrum(J, rtol)
        return largest / least if least else 1.0
    s = singular_values(J)
    r = rank_of(s, rtol)
    return float(s[0] / s[r - 1]) if r else 1.0


def small_spectrum(J: sp.spmatrix, rtol: float = RANK_RTOL) -> tuple[float, int, float]:
    """
    A large sparse matrix's largest singular value, how many are at most rtol times it (at least 1: `rank_of`'s
    cut) and the smallest above that (0 when none is), from the extreme eigenvalues of its Gram matrix J^T J alone
    (`_smallest`); where its null space is too wide for that, from the whole spectrum (`singular_values`). A dense
    eigendecomposition of the Gram matrix costs n^3 (0.92 s at 1,512 creases, once per sample and rank); this grows
    about as its sparse factor.
    """
    found = _smallest(J, rtol)
    if found is not None:
        largest, cut, values, _ = found
        return largest, int(np.sum(values <= cut)), float(values[values > cut].min())
    s = singular_values(J)  # a null space this wide (many freedoms): the whole spectrum
    r = rank_of(s, rtol)
    return float(s[0]), J.shape[1] - r, float(s[r - 1]) if r else 0.0


def null_space(J, rtol: float = RANK_RTOL, expected: int | None = None) -> NDArray[np.float64]:
    """An orthonormal basis (n, k) of a matrix's null space: its right singular vectors for singular values at most
    rtol times the largest (at least 1); a large sparse one's from `_smallest` (asking for a few more than the
    `expected` width) when that finds it all, otherwise from a dense SVD."""
    if sp.issparse(J) and J.shape[1] > SPARSE_SPECTRUM_FROM and (found := _smallest(J, rtol, expected)) is not None:
        _, cut, values, V = found
        return V[:, values <= cut]
    M = J.toarray() if sp.issparse(J) else np.asarray(J)
    _, s, Vt = np.linalg.svd(M)
    return Vt[int(np.sum(s > rtol * max(s.max(initial=0.0), 1.0))) :].T


def _smallest(J: sp.spmatrix, rtol: float, expected: int | None = None) -> tuple[float, float, NDArray, NDArray] | None:
    """
    A sparse matrix's largest singular value by Lanczos, its cut (rtol times that, at least rtol), and its
    SMALL_SPECTRUM_FIRST (or `expected` + SMALL_SPECTRUM_FIRST) smallest singular values with their right singular
    vectors, by Lanczos on (J^T J + c^2 I)^-1, factored once by sparse LU, c the cut (at least SHIFT_FLOOR of the
    largest, where a smaller shift would leave the factor singular to rounding). None when they do not reach above
    the cut, or when a block of inverse iterations orthogonal to the null vectors found finds another: Lanczos keeps
    one copy of an eigenvalue repeated exactly, as a null space of several dimensions is (a test matrix with 3
    repeated columns gave 1).
    """
    n = J.shape[1]
    G = (J.T @ J).tocsc()
    largest = float(np.sqrt(max(eigsh(G, k=1, which="LA", return_eigenvectors=False)[0], 0.0)))
    cut = rtol * max(largest, 1.0)
    shift = max(cut, SHIFT_FLOOR * max(largest, 1.0)) ** 2
    lu = splu((G + shift * sp.identity(n, format="csc")).tocsc())
    inverse = LinearOperator((n, n), matvec=lu.solve, dtype=float)
    k = min(SMALL_SPECTRUM_FIRST + (expected or 0), n - 2)
    inv, V = eigsh(inverse, k=k, ncv=min(n - 1, max(2 * k + 1, SMALL_SPECTRUM_BASIS)), which="LA")
    # eigenvalues of the inverse, 1 / (lambda + shift): its largest are the Gram matrix's smallest
    values = np.sqrt(np.clip(1.0 / inv - shift, 0.0, None))
    if not np.any(values > cut):
        return None
    # one more inverse iteration on the null vectors found: their part outside the null space (1.5e-7 on a 12 x 16
    # waterbomb tessellation's 53 freedoms) shrinks by the shift over the smallest non-zero eigenvalue
    null = np.linalg.qr(lu.solve(V[:, values <= cut]))[0]
    V = np.column_stack([null, V[:, values > cut]])
    values = np.concatenate([values[values <= cut], values[values > cut]])
    return None if least_outside(G, lu.solve, null) <= cut**2 else (largest, cut, values, V)


def least_outside(G: sp.spmatrix, solve: Callable[[NDArray], NDArray], V: NDArray[np.float64]) -> float:
    """
    The least eigenvalue of a symmetric positive semidefinite G outside the span of orthonormal V, as far as two
    inverse iterations (`solve` applies G's shifted inverse) of a random block kept orthogonal to V see it: the check
    that Lanczos, which keeps one copy of an eigenvalue repeated exactly, found every near-null vector.
    """
    W = np.random.default_rng(0).standard_normal((G.shape[0], MULTIPLICITY_BLOCK))
    for _ in range(2):
        W = solve(W - V @ (V.T @ W))
        W = np.linalg.qr(W - V @ (V.T @ W))[0]
    return float(max(np.linalg.eigvalsh(W.T @ (G @ W)).min(), 0.0))


def singular_values(J) -> NDArray[np.float64]:
    """Singular values of a matrix, largest first, padded by zeros to its column count when it has fewer rows. A
    sparse one's come from the eigenvalues of its Gram matrix J^T J (columns square, far smaller than J for big
    patterns and trusses); their errors of 1e-16 |J|^2 leave singular values above about 1e-8 |J| resolved, and
    rank's rtol = 1e-6 well inside that."""
    if sp.issparse(J):
        return np.sqrt(np.clip(np.linalg.eigvalsh((J.T @ J).toarray()), 0.0, None))[::-1]
    sv = np.linalg.svd(J, compute_uv=False)
    return np.concatenate([sv, np.zeros(J.shape[1] - len(sv))])


def rank_of(sv: NDArray[np.float64], rtol: float = RANK_RTOL) -> int:
    """Numerical rank from singular values: those above rtol times the largest (at least 1)."""
    return int(np.sum(sv > rtol * max(sv.max(initial=0.0), 1.0)))


def padded_svd(M: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """Full SVD with the singular values padded by zeros to the column count: (U, s (n,), Vt)."""
    U, s, Vt = np.linalg.svd(M, full_matrices=True)
    return U, np.concatenate([s, np.zeros(M.shape[1] - len(s))]), Vt


# -- sweep: given parameter values -----------------------------------------------------------------------------


def sweep(close: Callable[[NDArray[np.float64], int], NDArray[np.float64]], x0: ArrayLike,
          s: ArrayLike) -> NDArray[np.float64]:
    """
    Natural-parameter continuation at the parameter values s (n,) in turn: at each, the secant through the last
    two solutions predicts (the last solution alone at the first two values and after a repeated value), and
    close(guess, k) corrects, setting the driven coordinates of value k itself (and raising when it cannot).
    The branch is so kept through crossings. x0 (dim,) starts the first prediction. Returns (n, dim).
    """
    s = np.asarray(s, dtype=float)
    x = np.array(x0, dtype=float)
    out = np.empty((len(s), len(x)))
    for k in range(len(s)):
        guess = secant(s[k - 2], out[k - 2], s[k - 1], out[k - 1], s[k]) if k >= 2 and s[k - 1] != s[k - 2] \
            else x.copy()
        x = close(guess, k)
        out[k] = x
    return out


# -- trace: driven joints along a polyline ---------------------------------------------------------------------


class ClosureSystem(Protocol):
    """What `trace` follows and `ChordPolish` closes (a `closure.LoopSystem` is one): residual, Jacobian and solve
    over `n_joints` coordinates."""

    n_joints: int
    n_residuals: int
    sparse: bool  # solve with sparse normal equations; then `jacobian_sparse` is used

    def residual(self, q: ArrayLike) -> NDArray[np.float64]: ...

    def jacobian(self, q: ArrayLike) -> NDArray[np.float64]: ...

    def jacobian_sparse(self, q: ArrayLike) -> sp.csc_matrix: ...

    def residual_size(self, r: ArrayLike) -> NDArray[np.float64]: ...

    def solve(self, q0: ArrayLike, fixed: ArrayLike, *, tol: float) -> NDArray[np.float64]: ...


@dataclass(frozen=True)
class Polyline:
    """
    A path through knots (m, k) (rad) in the space of k driven joints, with parameter values `s` (m,), strictly
    monotone. `through` makes s the arc length from the first knot, or, for one joint along a monotone path,
    that joint's value itself (so a single input keeps its own angle as the parameter).
    """

    s: NDArray[np.float64]
    points: NDArray[np.float64]

    @classmethod
    def through(cls, points: ArrayLike) -> "Polyline":
        points = np.atleast_2d(np.asarray(points, dtype=float))
        if points.shape[0] == 1:
            points = points.T
        if points.shape[0] < 2 or not np.all(np.isfinite(points)):
            raise ParameterError(f"a path needs at least two finite knots; got {points.tolist()}")
        steps = np.diff(points, axis=0)
        if points.shape[1] == 1 and (np.all(steps > 0) or np.all(steps < 0)):
            return cls(points[:, 0].copy(), points)
        lengths = np.linalg.norm(steps, axis=1)
        if np.any(lengths == 0.0):
            raise ParameterError(f"a path's knots must differ in turn; got {points.tolist()}")
        return cls(np.concatenate([[0.0], np.cumsum(lengths)]), points)

    @property
    def k(self) -> int:
        return self.points.shape[1]

    def at(self, s: ArrayLike) -> NDArray[np.float64]:
        """Driven joint values (..., k) at parameters s (...), linear between knots, clamped at the ends."""
        s = np.asarray(s, dtype=float)
        order = np.argsort(self.s)
        return np.stack([np.interp(s, self.s[order], self.points[order, j]) for j in range(self.k)], axis=-1)

    def parameter_of(self, values: ArrayLike) -> NDArray[np.float64]:
        """The parameter (n,) of the point of the path nearest each of `values` (n, k) (rad)."""
        v = np.atleast_2d(np.asarray(values, dtype=float))[:, None, :]
        a, b = self.points[:-1], self.points[1:]
        d = b - a
        t = np.clip(np.sum((v - a) * d, axis=-1) / np.sum(d * d, axis=-1), 0.0, 1.0)
        gap = np.linalg.norm(a + t[..., None] * d - v, axis=-1)
        seg = np.argmin(gap, axis=1)
        rows = np.arange(len(seg))
        return self.s[seg] + t[rows, seg] * (self.s[seg + 1] - self.s[seg])


@dataclass(frozen=True)
class PathStop:
    """
    Where a trace ended or something happened on it: `kind`, parameter `s`, the joint concerned, why; for a contact,
    `hit`: the parameter (beyond `s`, the last configuration clear of it) where the contact was first found.
    """

    kind: str
    s: float
    joint: int | None
    detail: str
    hit: float | None = None


@dataclass(frozen=True)
class TracedPath:
    """Closed configurations q (n, n_joints) at parameters s (n,), their mobility and residual; stop and events."""

    s: NDArray[np.float64]
    q: NDArray[np.float64]
    mobility: NDArray[np.int64]
    residual: NDArray[np.float64]
    stop: PathStop
    events: tuple[PathStop, ...]


def jacobian(loops: ClosureSystem, q: ArrayLike):
    """The closure Jacobian, sparse when the loop system solves sparse."""
    return loops.jacobian_sparse(q) if loops.sparse else loops.jacobian(q)


def mobility(loops: ClosureSystem, q: ArrayLike) -> int:
    """Instantaneous mobility at q: joints minus the closure Jacobian's numerical rank."""
    return loops.n_joints - rank(jacobian(loops, q))


def independent_joints(loops: ClosureSystem, q: ArrayLike, k: int | None = None, among: ArrayLike | None = None,
                       first: tuple[int, ...] = ()) -> tuple[int, ...]:
    """
    Joints that can be driven independently at q: k (default: the mobility) rows of the closure Jacobian's null
    space picked by pivoted elimination (largest remaining row norm first, ties within PIVOT_TIE to the earlier
    joint, `first` before any other), among `among` (bool mask) if given. Returned in the order picked.
    """
    J = jacobian(loops, q)
    null = null_space(J, expected=k) if J.shape[0] else np.eye(loops.n_joints)  # (n_joints, mobility)
    k = null.shape[1] if k is None else k
    allowed = np.ones(loops.n_joints, dtype=bool) if among is None else np.array(among, dtype=bool)
    basis, picked = null.copy(), []
    queue = list(first)
    while len(picked) < min(k, null.shape[1]):
        norms = np.where(allowed, np.linalg.norm(basis, axis=1), -1.0)
        top = norms.max()
        j = queue.pop(0) if queue else int(np.flatnonzero(norms >= top - PIVOT_TIE * abs(top))[0])
        if np.linalg.norm(basis[j]) <= 1e-9:
            if queue or j in first:
                continue
            break
        picked.append(j)
        allowed[j] = False
        v = basis[j] / np.linalg.norm(basis[j])
        basis = basis - np.outer(basis @ v, v)  # remove that direction: the next pick is independent of it
    return tuple(picked)


def correct(loops: ClosureSystem, guess: NDArray[np.float64], fixed: NDArray[np.bool_], tol: float,
            max_iter: int = CORRECTOR_ITER) -> tuple[NDArray[np.float64], float, bool]:
    """
    Close the loops from `guess` moving the joints not `fixed`. Returns (q, largest |residual|, stationary): the
    last is True when the result is a least-squares minimum of the residual (its gradient vanishes) that does
    not close.
    """
    free = ~fixed

    def q_of(u: NDArray[np.float64]) -> NDArray[np.float64]:
        out = guess.copy()
        out[free] = u
        return out

    u, r = levenberg_marquardt(lambda u: loops.residual(q_of(u)), lambda u: jacobian(loops, q_of(u))[:, free],
                               guess[free], tol, max_iter)
    q = q_of(u)
    worst = float(np.max(np.abs(r), initial=0.0))
    if worst <= tol:
        return q, worst, False
    J = jacobian(loops, q)[:, free]
    size = sp.linalg.norm(J) if sp.issparse(J) else np.linalg.norm(J)
    gradient = float(np.linalg.norm(J.T @ r))
    return q, worst, gradient <= STATIONARY * max(size, 1.0) * float(np.linalg.norm(r))


def trace(
    loops: ClosureSystem,
    q0: ArrayLike,
    driven: ArrayLike,
    path: Polyline,
    *,
    s0: float | None = None,
    s_end: float | None = None,
    lower: ArrayLike | None = None,
    upper: ArrayLike | None = None,
    first_step: float = 0.02,
    max_step: float = 0.05,
    min_step: float = 1e-6,
    tol: float = 1e-13,
    stop_at_bifurcation: bool = False,
    names: tuple[str, ...] | None = None,
    previous: tuple[float, ArrayLike] | None = None,
    stop_when: Callable[[NDArray[np.float64]], str | None] | None = None,
    toward: ArrayLike | None = None,
) -> TracedPath:
    """
    Follow the closed configurations of `loops` from q0 (closed, or nearly, at `path.at(s0)`) while the driven
    joints (k indices) move along `path` from s0 (default its first knot) to s_end (default its last).

    Steps are in path parameter (rad); `lower`/`upper` (n_joints,) bound the joints (default +-inf); `names`
    label joints in the details; `previous` (s, q) is a closed configuration behind the start that the first
    step's secant predictor uses (e.g. the flat state, when the start lies just off it on the wanted branch);
    `stop_when(q)` returns why the path must end at configuration q (a contact), or None; it is asked at every
    node. `toward` (n_joints, NaN: no preference) is a state the joints fold towards where the path has more
    freedoms than driven joints: the predictor is then the tangent step nearest in least squares to moving every
    joint towards it in proportion (`toward_step`), so the spare freedoms follow the state's direction, not the
    last secant (which takes a flat, singular start's direction from the start guess alone). See the module
    docstring for the stops.
    """
    driven = np.atleast_1d(np.asarray(driven, dtype=int))
    if len(driven) != path.k:
        raise ParameterError(f"{len(driven)} driven joints for a path in {path.k} inputs")
    n = loops.n_joints
    names = names or tuple(f"joint {j}" for j in range(n))
    lower = np.full(n, -np.inf) if lower is None else np.asarray(lower, dtype=float)
    upper = np.full(n, np.inf) if upper is None else np.asarray(upper, dtype=float)
    s = float(path.s[0] if s0 is None else s0)
    end = float(path.s[-1] if s_end is None else s_end)
    fixed = np.zeros(n, dtype=bool)
    fixed[driven] = True
    q = np.array(q0, dtype=float)
    q[driven] = path.at(s)
    q, r0, _ = correct(loops, q, fixed, tol, max_iter=200)
    direction = 1.0 if end >= s else -1.0
    nodes_s, nodes_q, mob, res = [s], [q], [mobility(loops, q)], [r0]
    events: list[PathStop] = []
    step, failures, stop = Step(first_step, max_step, min_step), 0, None
    behind = None if previous is None else (float(previous[0]), np.asarray(previous[1], dtype=float))
    leaning: dict[tuple[int, bytes], NDArray[np.float64] | None] = {}  # `toward_step` at the last node, per direction
    if r0 > 100 * tol:
        why = f"no rigid configuration beyond: the start does not close (residual {r0:.3g})"
        stop = PathStop("stall", s, None, why)
    elif stop_when is not None and (why := stop_when(q)) is not None:
        stop = PathStop("contact", s, None, f"{why} already at the start")
    while stop is None:
        if (end - s) * direction <= 1e-15:
            stop = PathStop("end", s, None, "the path's end")
            break
        s_new = s + direction * min(step.size, abs(end - s))
        if len(nodes_q) >= 2:
            guess = secant(nodes_s[-2], nodes_q[-2], s, q, s_new)
        elif behind is not None and behind[0] != s:
            guess = secant(behind[0], behind[1], s, q, s_new)
        else:
            guess = q.copy()
        dx = path.at(s_new) - q[driven]
        if toward is not None and mob[-1] > len(driven) and np.any(dx):
            size = float(np.linalg.norm(dx))
            key = (len(nodes_q), (dx / size).round(12).tobytes())  # one solve per node and direction, scaled
            if key not in leaning:
                leaning = {key: toward_step(loops, q, driven, dx / size, np.asarray(toward, dtype=float))}
            if leaning[key] is not None:
                guess = q + size * leaning[key]
        guess[driven] = path.at(s_new)
        q_new, r, stationary = correct(loops, guess, fixed, tol)
        jumped = r <= 100 * tol and np.max(np.abs(q_new - q)) > JUMP
        if r > 100 * tol or jumped:
            failures = failures + 1 if stationary else 0
            small = step.reject()
            if failures >= STALL_CONFIRM or small:
                h = 2 * step.size
                why = (f"the residual stops at {r:.3g} (a least-squares minimum) as the steps shrink to {h:.3g}"
                       if stationary else f"no closing step down to {h:.3g} rad (last residual {r:.3g})")
                stop = PathStop("stall", s, None, f"no rigid configuration beyond: {why}")
            continue
        out = np.flatnonzero((q_new < lower) | (q_new > upper))
        if len(out):
            if step.reject():
                j = int(out[0])
                bound = upper[j] if q_new[j] > upper[j] else lower[j]
                stop = PathStop("bound", s, j, f"{names[j]} reaches its bound {bound:.6g} rad")
            continue
        failures = 0
        why = None if stop_when is None else stop_when(q_new)
        if why is not None:
            s_new, q_new, s_hit, why = _first(loops, stop_when, driven, path, fixed, tol, (s, q), (s_new, q_new, why))
            stop = PathStop("contact", s_new, None, why, s_hit)
            if s_new == s:
                break
        last = abs(end - s_new) <= 1e-15 or stop is not None
        ranked = not loops.sparse or len(nodes_s) % SPARSE_RANK_STRIDE == 0 or last
        m = mobility(loops, q_new) if ranked else mob[-1]
        if m != mob[-1]:
            kind = "bifurcation" if m > mob[-1] else "rank"
            events.append(PathStop(kind, s_new, None, f"mobility {mob[-1]} -> {m}"))
            if stop_at_bifurcation and m > mob[-1] and len(mob) > 1:
                stop = PathStop("bifurcation", s, None, f"the mobility rises from {mob[-1]} to {m}: a branch point")
                break
        nodes_s.append(s_new)
        nodes_q.append(q_new)
        mob.append(m)
        res.append(r)
        s, q = s_new, q_new
        step.accept()
    return TracedPath(np.array(nodes_s), np.array(nodes_q), np.array(mob), np.array(res), stop, tuple(events))


def toward_step(loops: ClosureSystem, q: NDArray[np.float64], driven: NDArray[np.int64], dx: NDArray[np.float64],
                toward: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """
    dq, the first-order closed step (J dq = 0) that moves the driven joints by dx and the others as near as least
    squares allows to lam * (toward - q), lam the driven joints' share of their way (NaN entries of `toward`: no
    preference, held). This is "every crease towards its target at once" in the tangent space. Linear in dx (for a
    positive scale); None when the drive does not head towards `toward` (lam <= 0).
    """
    d = np.nan_to_num(toward - q)
    share = float(d[driven] @ d[driven])
    lam = float(d[driven] @ dx) / share if share > 0 else 0.0
    if lam <= 0:
        return None
    dq = lam * d
    dq[driven] = dx
    return first_order_closed(loops, q, dq, driven, PREDICTOR_TOL)


def first_order_closed(loops: ClosureSystem, q: NDArray[np.float64], dq: NDArray[np.float64], driven: NDArray[np.int64],
                       tol: float) -> NDArray[np.float64]:
    """
    `dq` with its free joints (all but `driven`) changed by the least-norm amount that closes it to first order at q
    (J(q) dq = 0): the part of a wished step that would open the loops, removed. Sparse systems by lsqr to `tol`,
    dense ones by lstsq.
    """
    free = np.ones(len(q), dtype=bool)
    free[driven] = False
    J = jacobian(loops, q)
    rhs = J @ dq
    out = np.array(dq, dtype=float)
    if sp.issparse(J):
        out[free] -= sp.linalg.lsqr(J[:, free], rhs, atol=tol, btol=tol, iter_lim=20 * len(q))[0]
    else:
        out[free] -= np.linalg.lstsq(J[:, free], rhs, rcond=None)[0]
    return out


def _first(
    loops: ClosureSystem,
    stop_when: Callable,
    driven: NDArray,
    path: Polyline,
    fixed: NDArray,
    tol: float,
    before: tuple[float, NDArray],
    hit: tuple[float, NDArray, str],
) -> tuple[float, NDArray, float, str]:
    """
    Bisection on s between a node without a `stop_when` reason (`before`: s, q) and one with (`hit`: s, q, why),
    each midpoint closed by the corrector from the chord between them. Returns (s, q) of the last configuration
    without a reason and (s, why) of the first with one, STOP_WHEN_TOL apart (or where the corrector fails).
    """
    (s0, q0), (s1, q1, why) = before, hit
    while abs(s1 - s0) > STOP_WHEN_TOL:
        sm = 0.5 * (s0 + s1)
        guess = q0 + (q1 - q0) * 0.5
        guess[driven] = path.at(sm)
        qm, r, _ = correct(loops, guess, fixed, tol)
        if r > 100 * tol:
            break
        reason = stop_when(qm)
        if reason is None:
            s0, q0 = sm, qm
        else:
            s1, q1, why = sm, qm, reason
    return s0, q0, s1, why


# -- polish: closing poses near a traced path ------------------------------------------------------------------


def nearest_nodes(s_nodes: NDArray[np.float64], x: ArrayLike) -> NDArray[np.int64]:
    """Index of the node nearest each parameter x (n,) among ascending `s_nodes` (the upper one on a tie)."""
    x = np.asarray(x, dtype=float)
    i = np.clip(np.searchsorted(s_nodes, x), 0, len(s_nodes) - 1)
    return np.where((i > 0) & (np.abs(s_nodes[i - 1] - x) < np.abs(s_nodes[i] - x)), i - 1, i)


class ChordPolish:
    """
    Close poses near a traced path by the chord method: Gauss-Newton steps with the closure Jacobian of each pose's
    nearest trace node (the `fixed` joints held), all poses at once (one batched residual a step), then a full
    solve for any pose the chord does not close in CHORD_ITER steps. The chord contracts by about the distance to
    the node per step, so nodes a trace step apart close an interpolated pose in a few steps.

    The Jacobian of a node is factorised once and kept: a sparse system (`loops.sparse`) keeps the band LU of its
    normal matrix (`BandedNormal.factor`; 480 creases: one factorisation 0.3 ms, a dense one 0.2 s), a dense one the
    pseudo-inverse with singular values below RANK_RTOL of the largest dropped (as in the rank count).

    Residuals are measured as `loops.residual_size` weighs them (that of the full solve). A pose is closed below `tol`.
    With `floor`, the rounding floor of large systems (about 4e-15 on the 16 x 16 Miura sheet, above a `tol` of 1e-15)
    is accepted below `close_tol` (or twice the residual at the nodes, the loops' own floor): a pose stops where its
    residual stops falling, one left above it or 10 x the batch's median gets Gauss-Newton with fresh Jacobians from its
    best, and the full solve if still above it. Without, a pose not closed below `tol` is solved again from its guess (a
    singular pose, where the chord need not contract: the solve, and `correct` to `close_tol` where Newton converges
    only linearly).
    """

    def __init__(self, loops: ClosureSystem, nodes: NDArray[np.float64], fixed: NDArray[np.bool_], *, tol: float,
                 close_tol: float, floor: bool = False):
        self.loops, self.nodes, self.fixed = loops, nodes, np.asarray(fixed, dtype=bool)
        self.tol, self.close_tol, self.floor = tol, close_tol, floor
        if floor and loops.n_residuals and len(nodes):
            # the floor is the loops' own: twice the residual the trace's nodes sit at (their median). A file whose
            # coordinates lie near (700, -300) with 0.067-wide panels has 1.1e-13 at every node, from the coordinates'
            # rounding; held to 1e-13, each pose went on to the full solve and `correct` (20 s for a 3 x 3 sheet)
            at_nodes = loops.residual_size(loops.residual(nodes))
            self.close_tol = max(close_tol, 2.0 * float(np.median(at_nodes)))
        self._factors: dict[int, tuple] = {}  # node -> (free columns of J, factorisation, fixed columns of J)

    def _factor(self, q: NDArray[np.float64]) -> tuple:
        free = ~self.fixed
        if self.loops.sparse:
            full = self.loops.jacobian_sparse(q)
            J = full[:, free]
            return J, _band_layout(J).factor(J.data), full[:, ~free]
        full = self.loops.jacobian(q)
        return full[:, free], np.linalg.pinv(full[:, free], rcond=RANK_RTOL), full[:, ~free]

    def factor(self, node: int) -> tuple:
        """(free columns of the Jacobian, its factorisation, fixed columns) at trace node `node`, kept."""
        if node not in self._factors:
            self._factors[node] = self._factor(self.nodes[node])
        return self._factors[node]

    def _solve(self, factor: tuple, r: NDArray[np.float64]) -> NDArray[np.float64]:
        """The least-squares step (m, n_free) of the free joints that cancels residuals r (m, rows) to first order."""
        J, f, _ = factor
        return f.solve(np.asarray(J.T @ r.T)).T if self.loops.sparse else r @ f.T

    def _step(self, nodes: NDArray[np.int64], r: NDArray[np.float64]) -> NDArray[np.float64]:
        """Chord steps (m, n_free) for residuals r (m, rows) with the Jacobians of `nodes` (m,)."""
        if not self.loops.sparse:  # small pseudo-inverses: one batched product
            return np.einsum("mij,mj->mi", np.stack([self.factor(int(k))[1] for k in nodes]), r)
        out = np.empty((len(nodes), int(np.sum(~self.fixed))))
        for node in np.unique(nodes):
            mine = nodes == node
            out[mine] = self._solve(self.factor(int(node)), r[mine])
        return out

    def tangent(self, node: int) -> NDArray[np.float64]:
        """The path's tangent dq/dx at a node when one fixed joint is the input x: the free joints' least-squares
        rates, the fixed one's 1."""
        J, f, J_fixed = self.factor(node)
        out = np.ones(len(self.fixed))
        rhs = np.asarray(J_fixed @ out[self.fixed]).ravel()
        out[~self.fixed] = -(f.solve(np.asarray(J.T @ rhs).ravel()) if self.loops.sparse else f @ rhs)
        return out

    def hermite(self, s_nodes: NDArray[np.float64], x: NDArray[np.float64]) -> NDArray[np.float64]:
        """
        Guesses at inputs x (one fixed joint, the input its value) by cubic Hermite interpolation between the nodes
        (at `s_nodes`) with their tangents. On the 16 x 16 Miura sheet (nodes up to 0.05 rad apart) the guesses'
        median residual is 2.5e-9 instead of 7.3e-5 from straight lines, and the chord takes 6.4 steps a guess
        instead of 9.4. A trace that stopped at its first node has no interval: its node is every guess.
        """
        if len(s_nodes) < 2:
            out = np.repeat(self.nodes[:1], len(x), axis=0)
            out[:, self.fixed] = x[:, None]
            return out
        i = np.clip(np.searchsorted(s_nodes, x) - 1, 0, len(s_nodes) - 2)
        h = s_nodes[i + 1] - s_nodes[i]
        t = ((x - s_nodes[i]) / h)[:, None]
        tangents = {int(k): self.tangent(int(k)) for k in np.unique(np.r_[i, i + 1])}
        d0 = np.array([tangents[int(k)] for k in i]) * h[:, None]
        d1 = np.array([tangents[int(k)] for k in i + 1]) * h[:, None]
        out = hermite(self.nodes[i], self.nodes[i + 1], d0, d1, t)
        out[:, self.fixed] = x[:, None]
        return out

    def polish(self, guesses: NDArray[np.float64], nearest: NDArray[np.int64]) -> NDArray[np.float64]:
        """The guesses (m, n_joints) closed, each by chord steps with the Jacobian of its node `nearest` (m,)."""
        if not self.loops.n_residuals:
            return guesses.copy()
        columns = np.flatnonzero(~self.fixed)
        q = guesses.copy()
        best_q, best = q.copy(), np.full(len(q), np.inf)
        active = np.ones(len(q), dtype=bool)
        bar = self.close_tol if self.floor else self.tol  # below it, a residual that stops falling is the floor
        for _ in range(CHORD_ITER):
            index = np.flatnonzero(active)
            r = self.loops.residual(q[index])
            size = self.loops.residual_size(r)
            better = size < best[index]
            best_q[index[better]], best[index[better]] = q[index[better]], size[better]
            done = (size < self.tol) | (~better & (best[index] < bar))
            active[index[done]] = False
            if not np.any(active):
                break
            q[index[~done][:, None], columns[None, :]] -= self._step(nearest[index[~done]], r[~done])
        if self.floor:
            # the floor is the loops' rounding, the same for every pose: a pose above 10x the batch's median sat
            # where the chord's node is far in conditioning (16 x 16 Miura near its folded end, cond 4100: 9.3e-14
            # against 3.6e-15)
            for k in np.flatnonzero((best >= self.close_tol) | (best > max(10 * np.median(best), self.tol))):
                q_k, size_k = self._newton(best_q[k])
                best_q[k] = q_k if size_k < self.close_tol else self._full(q_k)
        else:
            for k in np.flatnonzero(best >= self.tol):
                best_q[k] = self._full(guesses[k])
        return best_q

    def _newton(self, q: NDArray[np.float64]) -> tuple[NDArray[np.float64], float]:
        """Gauss-Newton with a fresh Jacobian each step, to the residual's rounding floor (9 of 1000 inputs on the
        16 x 16 Miura sheet): (q, its residual size)."""
        best_q, best = q.copy(), float(self.loops.residual_size(self.loops.residual(q)))
        for _ in range(CHORD_ITER):
            q = q.copy()
            q[~self.fixed] -= self._solve(self._factor(q), self.loops.residual(q)[None])[0]
            size = float(self.loops.residual_size(self.loops.residual(q)))
            if size >= best:
                break
            best_q, best = q, size
        return best_q, best

    def _full(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """The full solve from q; `correct` to `close_tol` where it does not converge (at a singular pose Newton
        converges only linearly)."""
        try:
            return self.loops.solve(q, self.fixed, tol=self.tol)
        except ConvergenceError:
            return correct(self.loops, q, self.fixed, self.close_tol, max_iter=200)[0]


# -- follow_arc: along the mechanism mode, through turning points and bifurcations ------------------------------


class ArcSystem(ABC):
    """
    Equations F(x) = 0 of a one-degree-of-freedom motion, followed by `follow_arc`: x is the system's coordinate
    array, moved over `n_free` free coordinates; `chart` observes it (e.g. joint angles, continued along the path
    next to a reference). Subclasses give the residual, its Jacobian (rows, n_free), the move and the chart; the
    corrector, spectrum, self-stresses, orientation and tangent are the engine's.

    `scale` is the characteristic length (arc lengths are in its units), `tol` the residual the corrector reaches,
    `rtol` the relative singular value below which the corrector does not invert.
    """

    def __init__(self, n_free: int, n_rows: int, scale: float, tol: float, rtol: float):
        self.n_free, self.scale, self.tol, self.rtol = n_free, scale, tol, rtol
        # a fixed generic projection of the rows onto n_free - 1 (the Jacobian may have more, redundant rows)
        self.projection = np.random.default_rng(0).standard_normal((n_free - 1, n_rows)) / np.sqrt(n_rows)

    @abstractmethod
    def residual(self, x: NDArray, ref: NDArray) -> NDArray:
        """F(x), with `ref` the chart of a nearby point (angles are continued next to it)."""

    @abstractmethod
    def jacobian(self, x: NDArray) -> NDArray:
        """dF/dx over the free coordinates, (rows, n_free)."""

    @abstractmethod
    def move(self, x: NDArray, d: NDArray) -> NDArray:
        """x displaced by d (n_free,) over the free coordinates."""

    @abstractmethod
    def chart(self, x: NDArray, ref: NDArray) -> NDArray:
        """The observed coordinates at x, continued next to `ref`."""

    @abstractmethod
    def chart_rate(self, x: NDArray, k: int) -> NDArray:
        """The gradient (n_free,) of chart coordinate k at x over the free coordinates."""

    def correct(self, x: NDArray, ref: NDArray) -> tuple[NDArray, int] | None:
        """
        Newton with the rank-truncated pseudo-inverse (Yang 2017, Eq. 2-18), which never inverts the smallest
        singular value of the full-column system (the path's own mechanism mode): (x, iterations), None if it fails.
        """
        for it in range(ARC_CORRECTOR_ITER):
            F = self.residual(x, ref)
            if np.max(np.abs(F)) < self.tol:
                return x, it
            U, s, Vt = np.linalg.svd(self.jacobian(x), full_matrices=False)
            keep = (s > self.rtol * s.max()) & (np.arange(len(s)) < self.n_free - 1)
            x = self.move(x, -Vt[keep].T @ ((U[:, keep].T @ F) / s[keep]))
        return None

    def spectrum(self, x: NDArray) -> tuple[NDArray, NDArray]:
        """(singular values ascending, relative to the largest, padded with zeros; matching right vectors as rows)."""
        _, s, Vt = padded_svd(self.jacobian(x))
        order = np.argsort(s)
        return s[order] / s.max(), Vt[order]

    def stresses(self, x: NDArray, mobility: int) -> NDArray:
        """Orthonormal self-stresses (rows, columns): the left null space at a point of this mobility."""
        U = np.linalg.svd(self.jacobian(x), full_matrices=True)[0]
        return U[:, self.n_free - mobility :]

    def orientation(self, x: NDArray, t: NDArray) -> float:
        """
        Sign of det [P J(x); t^T], P the fixed projection onto n_free - 1 rows: constant along a smooth branch with
        a continuously oriented tangent t, it flips where the branch crosses a simple bifurcation (Allgower and
        Georg, Numerical Continuation Methods, ch. 8).
        """
        return float(np.sign(np.linalg.det(np.vstack([self.projection @ self.jacobian(x), t]))))

    def tangent(self, x: NDArray, near: NDArray) -> tuple[NDArray, float]:
        """(unit mechanism mode at x oriented along `near`, relative sigma_2)."""
        s, V = self.spectrum(x)
        return V[0] * (np.sign(V[0] @ near) or 1.0), float(s[1])


@dataclass(frozen=True)
class ArcPoint:
    """A point of an arc path: coordinates x, chart, relative sigma_2, unit tangent, the step that reached it."""

    x: NDArray[np.float64]
    chart: NDArray[np.float64]
    sigma2: float
    tangent: NDArray[np.float64]  # over the free coordinates
    arc: float


@dataclass(frozen=True)
class ArcEvent:
    """A located bifurcation: its index in the path, the point, the mobility there, real branch directions found."""

    index: int
    point: ArcPoint
    mobility: int
    directions: int


@dataclass(frozen=True)
class ArcPath:
    """`follow_arc`'s points, the bifurcations met, and whether chart coordinate k reached the target."""

    points: tuple[ArcPoint, ...]
    events: tuple[ArcEvent, ...]
    reached: bool


def _arc_step(f: ArcSystem, p: ArcPoint, eta: float) -> tuple[ArcPoint, int] | None:
    """Predictor eta along the tangent, corrector; None when step control rejects it."""
    guess = f.move(p.x, eta * p.tangent)
    got = f.correct(guess, p.chart)
    if got is None or np.linalg.norm(got[0] - guess) > MAX_CORRECTION * eta:
        return None
    t, s2 = f.tangent(got[0], p.tangent)
    if t @ p.tangent < np.cos(MAX_TURN):
        return None
    return ArcPoint(got[0], f.chart(got[0], p.chart), s2, t, eta), got[1]


def _land(f: ArcSystem, p: ArcPoint, eta: float, k: int, target: float) -> ArcPoint:
    """The point at which chart coordinate k equals `target`, between p and p + eta (secant on the predictor step)."""
    lo, g_lo = 0.0, p.chart[k] - target
    hi, point = eta, None
    for _ in range(60):
        got = _arc_step(f, p, hi)
        if got is None:
            raise ConvergenceError(f"corrector failed landing on the stop input {target:.6g} rad")
        point = got[0]
        g = point.chart[k] - target
        if abs(g) < 1e-14 * max(1.0, abs(target)):
            break
        lo, g_lo, hi = hi, g, hi - g * (hi - lo) / (g - g_lo)
    return point


def _golden(f: ArcSystem, p: ArcPoint, lo: float, hi: float) -> ArcPoint:
    """Golden-section search (to GOLDEN_STOP of the bracket) for the minimum of sigma_2 over the predictor steps h
    in [lo, hi] from p; a step the corrector cannot close counts as no minimum."""
    g = (np.sqrt(5.0) - 1) / 2
    span = hi - lo

    def at(h: float) -> ArcPoint:
        got = f.correct(f.move(p.x, h * p.tangent), p.chart)
        if got is None:
            return ArcPoint(p.x, p.chart, np.inf, p.tangent, h)
        t, s2 = f.tangent(got[0], p.tangent)
        return ArcPoint(got[0], f.chart(got[0], p.chart), s2, t, h)

    a, b = at(hi - g * span), at(lo + g * span)
    while hi - lo > GOLDEN_STOP * span:
        if a.sigma2 < b.sigma2:
            hi, b = b.arc, a
            a = at(hi - g * (hi - lo))
        else:
            lo, a = a.arc, b
            b = at(lo + g * (hi - lo))
    return min(a, b, key=lambda q: q.sigma2)


def _locate(f: ArcSystem, p: ArcPoint, before: float, after: float) -> ArcPoint:
    """
    The minimum of sigma_2 on the path from `before` (arc length) behind p to `after` ahead of it. Near a
    crossing the corrector, started about curvature x h^2 off the branch, may land on the other branch, which
    hides a gap of that size around the bifurcation; so the search is repeated around the best point so far,
    with predictor steps from it, over a span REFINE_SHRINK times shorter each round, down to the rounding
    floor (REFINE_FLOOR x scale).
    """
    best = _golden(f, p, -before, after)
    span = before + after
    while span > REFINE_FLOOR * f.scale:
        span /= REFINE_SHRINK
        best = min(best, _golden(f, best, -span / 2, span / 2), key=lambda q: q.sigma2)
    return best


def _branch_directions(f: ArcSystem, p: ArcPoint, null: NDArray) -> list[NDArray]:
    """
    Branch tangents at a simple bifurcation p (null space of dimension 2, rows of `null`): t = cos(a) n1 +
    sin(a) n2 with w . d2F(t) = 0 for every state of self-stress w (no second-order strain that the
    self-stress would resist), d2F the second derivative of the residual along t (central differences).
    None real (an isolated point at second order): an empty list.
    """
    W = f.stresses(p.x, 2)
    h = CURVATURE_STEP * f.scale
    F0 = f.residual(p.x, p.chart)

    def form(t: NDArray) -> NDArray:
        return W.T @ (f.residual(f.move(p.x, h * t), p.chart) - 2 * F0 + f.residual(f.move(p.x, -h * t), p.chart))

    n1, n2 = null
    A, C = form(n1), form(n2)
    B = (form(n1 + n2) - A - C) / 2
    a, b, c = np.linalg.svd(np.stack([A, B, C], axis=1))[2][0]  # the dominant quadratic a x^2 + 2 b x y + c y^2
    R = np.hypot((a - c) / 2, b)
    if R < 1e-12 or abs(a + c) / 2 > R:
        return []
    psi, spread = np.arctan2(b, (a - c) / 2), np.arccos(-(a + c) / (2 * R))
    return [np.cos(u) * n1 + np.sin(u) * n2 for u in ((psi + spread) / 2, (psi - spread) / 2)]


def _leave(f: ArcSystem, p: ArcPoint, t_in: NDArray, rate: NDArray, choice: str) -> tuple[ArcPoint, int, int]:
    """
    Step off the bifurcation p along the chosen branch: 'keep' = the direction closest to the incoming
    tangent t_in, 'switch' = the other, oriented so the drive keeps its sense (`rate`: the drive's rate).
    Returns (p with that direction as its tangent, mobility at p, number of branch directions found).
    """
    s, V = f.spectrum(p.x)
    m = int(np.sum(s < BIFURCATION_RTOL))
    directions = _branch_directions(f, p, V[:2]) if m == 2 else []
    if len(directions) == 2:
        closest = int(np.argmax([abs(d @ t_in) for d in directions]))
        if choice == "keep":
            t = directions[closest] * np.sign(directions[closest] @ t_in)
        else:
            t = directions[1 - closest]
            t = t * (np.sign(t @ rate) * np.sign(t_in @ rate) or np.sign(t @ t_in) or 1.0)
    elif choice == "keep":
        t = V[:m].T @ (V[:m] @ t_in)
        t /= np.linalg.norm(t)
    else:
        raise AssemblyError(f"cannot switch branch where the mobility jumps to {m} "
                            f"({len(directions)} real branch directions at second order)")
    return replace(p, tangent=t), m, len(directions)


def _is_dip(points: list[ArcPoint], events: list[ArcEvent]) -> bool:
    """Whether the second-last point is a deep local minimum of sigma_2 (not at an event)."""
    if len(points) < 3 or (events and events[-1].index >= len(points) - 3):
        return False
    a, b, c = (p.sigma2 for p in points[-3:])
    return b < a and b < c and b < DIP * max(a, c)


def follow_arc(f: ArcSystem, x0: NDArray, ref: NDArray, k: int, target: float, *, step: float | None = None,
               choice: str = "keep", max_points: int = 20000, unit: float = 1.0) -> ArcPath:
    """
    Follow the one-degree-of-freedom motion of `f` from x0 (chart continued next to `ref`) until chart coordinate
    k reaches `target`: predictor along the mechanism mode (the Jacobian's null vector), corrector `f.correct`,
    step control on the arc length (`step`: first step, length units, default FIRST_STEP x scale). The arc
    length is the natural parameter, so the path passes turning points of every chart coordinate.

    At a dip of sigma_2, or where the orientation flips, its minimum is located on the path; where the mobility
    jumps there (a bifurcation) the branch directions are found at second order and `choice` picks one: 'keep'
    (closest to the incoming tangent: straight through a transversal crossing) or 'switch' (the other branch,
    with the drive's sense kept). The path ends early, with reached = False, after `max_points` points. `unit`
    divides chart coordinate k in messages (rad of the input). ConvergenceError when the step falls below
    MIN_STEP x scale (a stall: the corrector closes no step).
    """
    if choice not in ("keep", "switch"):
        raise ParameterError(f"branch choice {choice!r}; it must be 'keep' or 'switch'")
    eta = FIRST_STEP * f.scale if step is None else float(step)
    if not (np.isfinite(eta) and eta > 0):
        raise ParameterError(f"step = {step!r}; it must be a positive length")
    chart = f.chart(x0, ref)
    sense = np.sign(target - chart[k]) or 1.0
    s, V = f.spectrum(x0)
    if s[1] < f.rtol:
        raise ParameterError(f"path following needs mobility 1 at the start; sigma_2 = {s[1]:.3g} (mobility >= 2)")
    rate = f.chart_rate(x0, k)
    points = [ArcPoint(x0.copy(), chart, float(s[1]), V[0] * (np.sign(V[0] @ rate) * sense or 1.0), 0.0)]
    events: list[ArcEvent] = []
    signs = [f.orientation(points[0].x, points[0].tangent)]
    control = Step(eta, MAX_STEP * f.scale, MIN_STEP * f.scale)
    landed = False
    while len(points) < max_points and not landed:
        got = _arc_step(f, points[-1], control.size)
        if got is None:
            if control.reject():
                raise ConvergenceError(f"step fell below {MIN_STEP:g} x scale at input "
                                       f"{points[-1].chart[k] / unit:.6g} rad")
            continue
        new, iterations = got
        landed = (new.chart[k] - target) * sense >= 0
        if landed:
            new = _land(f, points[-1], control.size, k, target)
        points.append(new)
        signs.append(f.orientation(new.x, new.tangent))
        if iterations <= FAST_ITER:
            control.accept()
        if signs[-1] != signs[-2]:  # crossed between the last two points
            found, replace_from = _locate(f, points[-2], 0.0, new.arc), -1
        elif _is_dip(points, events):  # touched near the second-last point
            found, replace_from = _locate(f, points[-2], points[-2].arc, new.arc), -2
        else:
            continue
        if found.sigma2 < BIFURCATION_RTOL:
            leaving, m, n_dir = _leave(f, found, points[replace_from - 1].tangent, f.chart_rate(found.x, k), choice)
            got = _arc_step(f, leaving, control.size)
            if got is None:
                raise ConvergenceError(
                    f"corrector failed stepping off the bifurcation at {found.chart[k] / unit:.6g} rad"
                )
            after = got[0]
            landed = (after.chart[k] - target) * sense >= 0
            if landed:
                after = _land(f, leaving, control.size, k, target)
            points[replace_from:] = [found, after]
            signs[replace_from:] = [f.orientation(after.x, after.tangent)] * 2
            events.append(ArcEvent(len(points) - 2, found, m, n_dir))
    return ArcPath(tuple(points), tuple(events), landed)
