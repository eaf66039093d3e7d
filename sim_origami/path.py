"""Numeric path following over any `LoopSystem`: k driven joints moved along a polyline in their space.

The follower is a predictor-corrector: a secant predictor through the last two closed configurations, a damped
Newton (Levenberg-Marquardt) corrector with the driven joints held, and step control (halving on failure,
growth by 1.5 on success). Along the path it records the instantaneous mobility (joints minus the numerical rank
of the closure Jacobian) at every node; a change is reported as an event (a bifurcation or the end of one).

Where it stops, and why (`PathStop.kind`):
- "end": the polyline's end was reached;
- "stall": the corrector converges to a stationary point of the residual that is not closed (a least-squares
  minimum above the tolerance, |J^T r| << |J| |r|) at STALL_CONFIRM successively halved steps, or the step
  fell below `min_step`: no rigid configuration beyond, with the driven joints moved that way;
- "bound": a joint would leave its bounds (a crease reaching +-pi, a crease whose sign would flip), `joint` says
  which; the path ends at the last node inside them;
- "bifurcation": the mobility rose above the path's (only with `stop_at_bifurcation`);
- "contact": `stop_when` (e.g. a self-contact test) gave a reason at a node; the first such configuration is
  located by bisection on s between that node and the last one to STOP_WHEN_TOL, and the path ends just before it.

Open chains (no loops, no couplings) close trivially: every node is exact and the mobility is the joint count.
Units: radians for joints and the path parameter s; the residual in radians and the loops' length unit.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import sparse as sp

from .closure import LoopSystem, _levenberg_marquardt
from .errors import ParameterError

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
# Sparse (large) systems rank every this many nodes and the last (480 creases: one rank 0.1-1 s, a corrector step
# a few ms); a mobility change is then placed between two ranked nodes.
SPARSE_RANK_STRIDE = 10
# A `stop_when` reason is located to this (path parameter, rad) by bisection between two nodes.
STOP_WHEN_TOL = 1e-9


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
    """Where a trace ended or something happened on it: `kind`, parameter `s`, the joint concerned, why."""

    kind: str
    s: float
    joint: int | None
    detail: str


@dataclass(frozen=True)
class TracedPath:
    """Closed configurations q (n, n_joints) at parameters s (n,), their mobility and residual; stop and events."""

    s: NDArray[np.float64]
    q: NDArray[np.float64]
    mobility: NDArray[np.int64]
    residual: NDArray[np.float64]
    stop: PathStop
    events: tuple[PathStop, ...]


def rank(J, rtol: float = RANK_RTOL) -> int:
    """Numerical rank of a Jacobian, dense or sparse (rows may be empty). A sparse one is ranked by the eigenvalues
    of its Gram matrix J^T J (n_joints square, far smaller than J for big patterns; eigenvalue errors of
    1e-16 |J|^2 leave singular values near rtol = 1e-6 resolved)."""
    if not J.shape[0] or not J.shape[1]:
        return 0
    if sp.issparse(J):
        sv = np.sqrt(np.clip(np.linalg.eigvalsh((J.T @ J).toarray()), 0.0, None))
    else:
        sv = np.linalg.svd(J, compute_uv=False)
    return int(np.sum(sv > rtol * max(sv.max(initial=0.0), 1.0)))


def jacobian(loops: LoopSystem, q: ArrayLike):
    """The closure Jacobian, sparse when the loop system solves sparse."""
    return loops.jacobian_sparse(q) if loops.sparse else loops.jacobian(q)


def mobility(loops: LoopSystem, q: ArrayLike) -> int:
    """Instantaneous mobility at q: joints minus the closure Jacobian's numerical rank."""
    return loops.n_joints - rank(jacobian(loops, q))


def independent_joints(loops: LoopSystem, q: ArrayLike, k: int | None = None, among: ArrayLike | None = None,
                       first: tuple[int, ...] = ()) -> tuple[int, ...]:  # fmt: skip
    """
    Joints that can be driven independently at q: k (default: the mobility) rows of the closure Jacobian's null
    space picked by pivoted elimination (largest remaining row norm first, `first` before any other), among
    `among` (bool mask) if given. Returned in the order picked.
    """
    J = loops.jacobian(q)
    if J.size:
        _, sv, vt = np.linalg.svd(J)
        r = int(np.sum(sv > RANK_RTOL * max(sv.max(initial=0.0), 1.0)))
        null = vt[r:].T  # (n_joints, mobility)
    else:
        null = np.eye(loops.n_joints)
    k = null.shape[1] if k is None else k
    allowed = np.ones(loops.n_joints, dtype=bool) if among is None else np.array(among, dtype=bool)
    basis, picked = null.copy(), []
    queue = list(first)
    while len(picked) < min(k, null.shape[1]):
        norms = np.where(allowed, np.linalg.norm(basis, axis=1), -1.0)
        j = queue.pop(0) if queue else int(np.argmax(norms))
        if np.linalg.norm(basis[j]) <= 1e-9:
            if queue or j in first:
                continue
            break
        picked.append(j)
        allowed[j] = False
        v = basis[j] / np.linalg.norm(basis[j])
        basis = basis - np.outer(basis @ v, v)  # remove that direction: the next pick is independent of it
    return tuple(picked)


def correct(loops: LoopSystem, guess: NDArray[np.float64], fixed: NDArray[np.bool_], tol: float,
            max_iter: int = CORRECTOR_ITER) -> tuple[NDArray[np.float64], float, bool]:  # fmt: skip
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

    u, r = _levenberg_marquardt(lambda u: loops.residual(q_of(u)), lambda u: jacobian(loops, q_of(u))[:, free],
                                guess[free], tol, max_iter)  # fmt: skip
    q = q_of(u)
    worst = float(np.max(np.abs(r), initial=0.0))
    if worst <= tol:
        return q, worst, False
    J = jacobian(loops, q)[:, free]
    size = sp.linalg.norm(J) if sp.issparse(J) else np.linalg.norm(J)
    gradient = float(np.linalg.norm(J.T @ r))
    return q, worst, gradient <= STATIONARY * max(size, 1.0) * float(np.linalg.norm(r))


def trace(
    loops: LoopSystem,
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
) -> TracedPath:
    """
    Follow the closed configurations of `loops` from q0 (closed, or nearly, at `path.at(s0)`) while the driven
    joints (k indices) move along `path` from s0 (default its first knot) to s_end (default its last).

    Steps are in path parameter (rad); `lower`/`upper` (n_joints,) bound the joints (default +-inf); `names`
    label joints in the details; `previous` (s, q) is a closed configuration behind the start that the first
    step's secant predictor uses (e.g. the flat state, when the start lies just off it on the wanted branch);
    `stop_when(q)` returns why the path must end at configuration q (a contact), or None; it is asked at every
    node. See the module docstring for the stops.
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
    h, failures, stop = first_step, 0, None
    behind = None if previous is None else (float(previous[0]), np.asarray(previous[1], dtype=float))
    if r0 > 100 * tol:
        why = f"no rigid configuration beyond: the start does not close (residual {r0:.3g})"
        stop = PathStop("stall", s, None, why)
    elif stop_when is not None and (why := stop_when(q)) is not None:
        stop = PathStop("contact", s, None, f"{why} already at the start")
    while stop is None:
        if (end - s) * direction <= 1e-15:
            stop = PathStop("end", s, None, "the path's end")
            break
        s_new = s + direction * min(h, abs(end - s))
        if len(nodes_q) >= 2:
            guess = q + (q - nodes_q[-2]) * (s_new - s) / (s - nodes_s[-2])
        elif behind is not None and behind[0] != s:
            guess = q + (q - behind[1]) * (s_new - s) / (s - behind[0])
        else:
            guess = q.copy()
        guess[driven] = path.at(s_new)
        q_new, r, stationary = correct(loops, guess, fixed, tol)
        jumped = r <= 100 * tol and np.max(np.abs(q_new - q)) > JUMP
        if r > 100 * tol or jumped:
            failures = failures + 1 if stationary else 0
            h /= 2
            if failures >= STALL_CONFIRM or h < min_step:
                why = (f"the residual stops at {r:.3g} (a least-squares minimum) as the steps shrink to {2 * h:.3g}"
                       if stationary else f"no closing step down to {2 * h:.3g} rad (last residual {r:.3g})")
                stop = PathStop("stall", s, None, f"no rigid configuration beyond: {why}")
            continue
        out = np.flatnonzero((q_new < lower) | (q_new > upper))
        if len(out):
            h /= 2
            if h < min_step:
                j = int(out[0])
                bound = upper[j] if q_new[j] > upper[j] else lower[j]
                stop = PathStop("bound", s, j, f"{names[j]} reaches its bound {bound:.6g} rad")
            continue
        failures = 0
        why = None if stop_when is None else stop_when(q_new)
        if why is not None:
            s_new, q_new, s_hit, why = _first(loops, stop_when, driven, path, fixed, tol, (s, q), (s_new, q_new, why))
            stop = PathStop("contact", s_new, None, f"{why} (at s = {s_hit:.10g})")
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
        h = min(1.5 * h, max_step)
    return TracedPath(np.array(nodes_s), np.array(nodes_q), np.array(mob), np.array(res), stop, tuple(events))


def _first(
    loops: LoopSystem,
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
