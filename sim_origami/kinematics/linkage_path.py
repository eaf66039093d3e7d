"""A linkage without a closed form: its numeric paths are the reference (numpy only).

The loops are closed at one input value (the start): either from a given start configuration, or from random
starts (`LoopSystem.assemblies`), every distinct assembly found there being a branch. Each branch is traced from its
start to both ends of the input range by `path.trace` (predictor-corrector, step control, stall and rank
monitoring) and named generically, `path-1`, `path-2`, ... (the given start, or the first assembly in a fixed
order, is `path-1`). A branch's domain is what its trace reached: the whole range, or up to a stall (a turning
point or a lock, where no closed configuration lies beyond with the input moved on).

Events: where a trace stalled, where the mobility changed along it, and, where two branches pass through one pose,
a bifurcation naming both (so the validation seeds MuJoCo on each of them there).

A link between two spherical joints spins freely about the line through their centres (an idle spin): the traced
system holds one hinge per spin at 0 (`gauge`), so it has the mechanism's true mobility, and the outputs leave out
the angles the spin moves (`observed`; `loop_angles` fills them back in by closing the loops).

`evaluate` closes interpolated poses by chord steps (all inputs at once, `path.ChordPolish`) to 1e-15, or to the
rounding floor of the placed model where that lies higher (FLOOR_SHARE times the trace nodes' median residual: a
linkage drawn rotated and offset closes its loops only to a few 1e-15), and the full solve where those do not close;
within SINGULAR_ZONE of a meeting it extrapolates from regular poses either side. Held to 1e-15 regardless, a
spherical 4R drawn 70 units from the origin sent nearly every pose to the full solve (its validation 55 s of CPU, 1.5 s
at the origin; scripts/placement_bench.py, docs/performance.md). Angles in radians; translations in the loops'
length unit.
"""

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.optimize import minimize_scalar

from ..closure import Coupling, LoopSystem
from ..errors import ParameterError
from ..geometry import wrap
from ..path import ChordPolish, Polyline, TracedPath, correct, nearest_nodes, trace
from .base import Branch, Event, Kinematics
from .numeric_pattern import CLOSE_TOL, POLISH_TOL

# Random starts of the assembly search at the start input; two assemblies closer than SAME_ASSEMBLY (rad, every
# joint, modulo 2 pi) are one. 8 starts found every assembly of the four built-in linkages written as examples
# (1, 1, 2, 2) under each of 4 random seeds; 24 keeps a margin (the threefold Bricard's scene builds in 0.60 s of
# CPU, 0.86 s with 64).
ASSEMBLY_STARTS = 24
SAME_ASSEMBLY = 1e-6
# When none closes, the smallest residual reported is the least of MISS_STARTS damped-Newton runs of MISS_ITER steps
# (a 4R that cannot close, at theta1 = 80 deg: 1.37 from 64 runs of 200 steps in 4.2 s of CPU, 1.34 from 8 of 60
# in 0.16 s).
MISS_STARTS = 8
MISS_ITER = 60
# A given start configuration may be this far (rad) from the closed one it stands for: hand-written angles are
# rounded (10 decimals of a degree are 2e-12 rad; 0.01 deg is 1.7e-4 rad).
START_TOL = 1e-2
# Without a start, the loops are assembled at this fraction of the input range from its low end: not the middle, where
# symmetric ranges put special poses (the plane-symmetric Bricard's two motions cross at theta2 = 0 of -60..60 deg).
START_SHARE = 0.382
# Continuation: first and largest step (rad of input), and the smallest before a stall is declared.
FIRST_STEP = 0.01
MAX_STEP = 0.05
STALL_STEP = 1e-7
# Two branches meet at a bifurcation where their poses differ by less than MEET_RAD (rad, every joint): searched
# near the local minima below MEET_GRID of their distance on MEET_SAMPLES inputs of the interpolated traces.
MEET_RAD = 1e-4
MEET_GRID = 0.05
MEET_SAMPLES = 2001
# A meeting found is refined by a secant between +-MEET_BRACKET (rad of input) around the distance's minimum.
MEET_BRACKET = 1e-4
# Within SINGULAR_ZONE (rad) of a meeting a pose is extrapolated (Richardson, error O(h^4)) from polished poses at
# +-SINGULAR_STEP and +-2 SINGULAR_STEP: the solve there pins the joints only to about the square root of its
# residual (5e-7 rad at the plane-symmetric Bricard's crossing, where the truss method then counted 1 freedom, not
# 2); the extrapolated poses of both branches agree with the closed forms there to 5e-11 rad (the meeting found lies
# 7.5e-11 rad from the exact theta2 = 0).
SINGULAR_ZONE = 1e-5
SINGULAR_STEP = 1e-3
# `evaluate` polishes to this multiple of the median residual of a branch's trace nodes where that exceeds POLISH_TOL
# (the rounding floor of the placed model; `path.ChordPolish`'s floor mode takes the same multiple). Its floor mode
# itself, which accepts any pose below CLOSE_TOL whose residual stops falling, located the Myard RSRRR file's
# bifurcation 4.4e-4 rad off (the chord stalls near the singular pose at about the square root of that residual).
FLOOR_SHARE = 2.0


class AssemblyError(ParameterError):
    """The loops do not close at the start input (or at the given start configuration): a linkage file's numbers may
    then lie within their precision of a mobile linkage (`scenes.linkage_file.nearest_mobile`)."""


def _check_arguments(loops: LoopSystem, joint_names: Sequence[str], input_joint: int,
                     input_range: tuple[float, float], start: ArrayLike | None) -> None:
    """Refuse arguments of the wrong type or shape with a ParameterError (not an AttributeError or IndexError deep in
    the solve)."""
    if not isinstance(loops, LoopSystem):
        raise ParameterError(f"loops = {type(loops).__name__}: it must be a closure.LoopSystem")
    n = loops.n_joints
    if isinstance(joint_names, str) or len(joint_names) != n or not all(isinstance(j, str) for j in joint_names):
        raise ParameterError(f"joint_names: give {n} names (one per loop joint)")
    if isinstance(input_joint, bool) or not isinstance(input_joint, (int, np.integer)) or not 0 <= input_joint < n:
        raise ParameterError(f"input_joint = {input_joint!r}: it must be a joint index from 0 to {n - 1}")
    span = np.asarray(input_range, dtype=object)
    if span.shape != (2,) or not all(isinstance(v, (int, float, np.number)) and not isinstance(v, bool)
                                     and np.isfinite(v) for v in span):
        raise ParameterError(f"input_range = {input_range!r}: give (lo, hi), two finite angles (rad)")
    if start is not None:
        try:
            q = np.asarray(start, dtype=float)
        except (TypeError, ValueError) as err:
            raise ParameterError("start: it must be an array of joint angles (rad)") from err
        if q.shape != (n,) or not np.all(np.isfinite(q)):
            raise ParameterError(f"start: it must hold {n} finite joint angles (rad), not shape {q.shape}")


class LinkagePath(Kinematics):
    """
    Every branch through the start input of a linkage, traced numerically over the input range.

    Parameters
    ----------
    loops : the linkage's loop system (joints in `loop_joint_names` order).
    joint_names : one name per loop joint (`loop_joint_names`); the outputs (`joint_names`) are the `observed` ones.
    input_joint : index of the driven joint; the input x is its angle (rad).
    input_range : (lo, hi), rad: the traces run from the start to both ends.
    start : a closed (or nearly closed) configuration (rad), or None to assemble at `start_input`.
    start_input : the input at which to assemble when no `start` is given (default START_SHARE of the range).
    ball_middles : the middle (y) hinge of each spherical joint: its x-y-z angles have two sets per rotation, and
      assemblies are taken with every middle angle within +-pi/2 where one is (the set MuJoCo's poses give back).
    compared : joints (bool mask) by which two assemblies are told apart (default all; a spherical joint's angles
      follow from the others').
    gauge : one hinge per idle spin (a link between two spherical joints turning freely about the line through their
      centres), held at 0 while tracing: the traced system then has the mechanism's true mobility, its corrector
      converges quadratically and the ball angles stay where the start put them. `loop_system()` stays the
      mechanism's own (the mobility report counts the idle spins and takes them off).
    observed : joints (bool mask) that are outputs (default all): the angles an idle spin moves are not, since
      MuJoCo leaves the spin free and only the pinned trace fixes it.

    Raises
    ------
    ParameterError
      A start outside the range; `AssemblyError` for a start that does not close (with its residual) or no assembly at
      the start input (with the smallest residual found).
    """

    def __init__(
        self,
        loops: LoopSystem,
        joint_names: Sequence[str],
        input_joint: int,
        input_range: tuple[float, float],
        start: ArrayLike | None = None,
        *,
        start_input: float | None = None,
        ball_middles: Sequence[int] = (),
        compared: ArrayLike | None = None,
        gauge: Sequence[int] = (),
        observed: ArrayLike | None = None,
    ):
        _check_arguments(loops, joint_names, input_joint, input_range, start)
        self._mechanism_loops = loops
        self.input_index = int(input_joint)
        self.gauge = tuple(int(j) for j in gauge)
        pins = tuple(Coupling(j, self.input_index, 0.0) for j in self.gauge)  # q[j] = 0 q[input]: j held at 0
        loops = replace(loops, couplings=loops.couplings + pins)
        self._loops = loops  # the traced system: the mechanism's loops, each idle spin pinned
        self.loop_joint_names = tuple(joint_names)
        self.observed = np.ones(loops.n_joints, dtype=bool) if observed is None else np.asarray(observed, dtype=bool)
        self.joint_names = tuple(n for n, seen in zip(joint_names, self.observed, strict=True) if seen)
        self.input_name = self.loop_joint_names[self.input_index]
        self.lo, self.hi = float(min(input_range)), float(max(input_range))
        kutzbach = self.gruebler()
        if kutzbach > 1:  # Kutzbach's count is a lower bound of the mobility: refused before any solve
            raise ParameterError(f"joints: {loops.n_joints - len(self.gauge)} joint freedoms in {len(loops.loops)} "
                                 f"loop{'s' if len(loops.loops) > 1 else ''} leave at least {kutzbach} freedoms "
                                 "(Kutzbach); a linkage file drives one input joint, so its linkage must move with "
                                 "one freedom")
        self.ball_middles = np.asarray(ball_middles, dtype=int)
        self.compared = np.ones(loops.n_joints, dtype=bool) if compared is None else np.asarray(compared, dtype=bool)
        fixed = np.zeros(loops.n_joints, dtype=bool)
        fixed[self.input_index] = True
        if start is not None:
            given = np.asarray(start, dtype=float)
            x0 = float(given[self.input_index])
            if not self.lo <= x0 <= self.hi:
                raise ParameterError(f"joints[].theta0: the start angle of the input {self.input_name}, "
                                     f"{np.rad2deg(x0):.6g} deg, lies outside input.range [{np.rad2deg(self.lo):.6g}, "
                                     f"{np.rad2deg(self.hi):.6g}] deg")
            q, residual, _ = correct(loops, given, fixed, CLOSE_TOL, max_iter=200)
            # an idle spin's angles may move to its pinned value: the start is judged by the outputs
            gap = float(np.max(np.abs(q - given)[self.observed], initial=0.0))
            if residual > 100 * CLOSE_TOL or gap > START_TOL:
                # loops that close, far from the start, are no rounding of a mobile linkage's numbers
                raise (AssemblyError if residual > 100 * CLOSE_TOL else ParameterError)(
                    f"joints[].theta0: the loops cannot be closed at the start configuration: closure residual "
                    f"{residual:.3g} with the input held, nearest closed pose {gap:.3g} rad away (allowed "
                    f"{START_TOL:g})")
            starts = [q] + [a for a in self._assemble(x0) if not self._same(a, q)]
            self.assembly = f"the given start configuration (closed to {residual:.2g}, moved {gap:.2g} rad)"
        else:
            x0 = self.lo + START_SHARE * (self.hi - self.lo) if start_input is None else float(start_input)
            starts = self._assemble(x0)
            if not starts:
                raise AssemblyError(
                    f"joints: the loops cannot be assembled at {self.input_name} = {np.rad2deg(x0):.6g} deg: no "
                    f"closed pose from {ASSEMBLY_STARTS} random starts, the smallest closure residual reached is "
                    f"{self._best_miss(x0):.3g} (rad, length units)")
            shown = ", ".join(f"{v:.4g}" for v in np.rad2deg(starts[0]))
            self.assembly = (f"assembled at {self.input_name} = {np.rad2deg(x0):.6g} deg: {len(starts)} "
                             f"assembl{'y' if len(starts) == 1 else 'ies'} found, path-1 starts at ({shown}) deg")
        mobility = [self._loops.mobility(q) for q in starts]
        if min(mobility) > 1:
            # more freedoms than the one input: the trace would stall at every step (40 D-H rows or a Goldberg 5R with
            # every axis parallel ran for minutes), and MuJoCo's sweep would not follow one path
            raise ParameterError(f"joints: the linkage moves with {min(mobility)} freedoms at {self.input_name} = "
                                 f"{np.rad2deg(x0):.6g} deg (the rank of its closure Jacobian there); a linkage file "
                                 "drives one input joint, so it must move with one freedom")
        self.start_input = x0
        self.traces: dict[str, tuple[TracedPath, TracedPath]] = {}
        self._polishers: dict[str, ChordPolish] = {}  # per branch: its nodes' factorisations, kept
        self.nodes: dict[str, tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]] = {}
        for q in starts:
            self._trace(f"path-{len(self.nodes) + 1}", q)
        self.mobility = np.concatenate([m for _, _, m in self.nodes.values()])
        self._events: tuple[Event, ...] = ()
        self._events = self._find_events()

    def _assemble(self, x: float) -> list[NDArray[np.float64]]:
        """
        Distinct closed configurations at input x, in a fixed order (lexicographic in the wrapped angles), each
        spherical joint's angles taken with the middle one inside +-pi/2 where an assembly has that set too.
        """
        found = self._loops.assemblies(self.input_index, x, starts=ASSEMBLY_STARTS, tol=CLOSE_TOL)
        order = sorted((np.asarray(q) for q in found),
                       key=lambda q: (bool(np.any(np.abs(q[self.ball_middles]) > np.pi / 2)), tuple(np.round(q, 6))))
        out: list[NDArray[np.float64]] = []
        for q in order:
            if not any(self._same(q, other) for other in out):
                out.append(q)
        return out

    def _same(self, q: NDArray[np.float64], other: NDArray[np.float64]) -> bool:
        """One assembly: the compared joints agree within SAME_ASSEMBLY (rad, modulo 2 pi)."""
        return bool(np.max(np.abs(wrap(q - other))[self.compared], initial=0.0) <= SAME_ASSEMBLY)

    def _best_miss(self, x: float) -> float:
        """The smallest closure residual reached from random starts at input x (no assembly there)."""
        rng = np.random.default_rng(0)
        fixed = np.zeros(self._loops.n_joints, dtype=bool)
        fixed[self.input_index] = True
        best = np.inf
        for _ in range(MISS_STARTS):
            guess = rng.uniform(-np.pi, np.pi, self._loops.n_joints)
            guess[self.input_index] = x
            best = min(best, correct(self._loops, guess, fixed, CLOSE_TOL, max_iter=MISS_ITER)[1])
        return float(best)

    def _trace(self, name: str, q0: NDArray[np.float64]) -> None:
        x0 = q0[self.input_index]
        runs = []
        for end in (self.lo, self.hi):
            if abs(end - x0) <= 1e-15:
                runs.append(None)
                continue
            path = Polyline(np.array([x0, end]), np.array([[x0], [end]]))
            runs.append(trace(self._loops, q0, [self.input_index], path, first_step=FIRST_STEP, max_step=MAX_STEP,
                              min_step=STALL_STEP, tol=CLOSE_TOL, names=self.loop_joint_names))
        down, up = runs
        parts = [(r.s[::-1], r.q[::-1], r.mobility[::-1]) for r in (down,) if r is not None]
        parts += [(r.s[1:] if down is not None else r.s, r.q[1:] if down is not None else r.q,
                   r.mobility[1:] if down is not None else r.mobility) for r in (up,) if r is not None]
        s = np.concatenate([p[0] for p in parts])
        q = np.vstack([p[1] for p in parts])
        m = np.concatenate([p[2] for p in parts])
        if len(s) < 2:  # rigid: an overconstrained linkage's numbers rounded (the drawn pose of an axes file closes)
            raise AssemblyError(f"input.range: the linkage does not move from its start ({self.input_name} = "
                                 f"{np.rad2deg(x0):.6g} deg): {(down or up).stop.detail}")
        for other, (s2, _, _) in self.nodes.items():
            # an assembly on a branch already traced (two starts on one curve, or the same pose): not a new branch
            gap = np.max(np.abs(wrap(self._interp(other, s) - q))[:, self.compared], initial=0.0)
            if s2[0] <= s[0] and s[-1] <= s2[-1] and gap < MEET_RAD:
                return
        self.traces[name] = (down, up)
        self.nodes[name] = (s, q, m)

    def _find_events(self) -> tuple[Event, ...]:
        out = []
        for name, runs in self.traces.items():
            for run in runs:
                if run is None:
                    continue
                if run.stop.kind != "end":
                    out.append(Event("stall", float(run.stop.s), (name,), run.stop.detail))
                for e in run.events:
                    out.append(Event("mobility-change", float(e.s), (name,), e.detail))
        names = list(self.nodes)
        for i, a in enumerate(names):
            for b in names[i + 1 :]:
                for x in self._meetings(a, b):
                    out.append(Event("bifurcation", x, (a, b), f"branches {a} and {b} meet"))
        return tuple(out)

    def _meetings(self, a: str, b: str) -> list[float]:
        """Inputs (rad) where branches a and b pass through one pose: the smallest distance (every joint, modulo
        2 pi) of each stretch of a grid of the interpolated traces where it is below MEET_GRID, refined on polished
        poses to MEET_RAD."""
        lo = max(self.nodes[a][0][0], self.nodes[b][0][0])
        hi = min(self.nodes[a][0][-1], self.nodes[b][0][-1])
        if hi <= lo:
            return []
        grid = np.linspace(lo, hi, MEET_SAMPLES)
        gap = np.max(np.abs(wrap(self._interp(a, grid) - self._interp(b, grid))), axis=1)
        out = []
        close = np.r_[False, gap < MEET_GRID, False]
        edges = np.flatnonzero(np.diff(close.astype(int)))  # each stretch below MEET_GRID: [start, stop)
        for first, stop in zip(edges[::2], edges[1::2], strict=True):
            k = first + int(np.argmin(gap[first:stop]))  # one candidate per stretch, however long

            def distance(x: float) -> float:
                return float(np.max(np.abs(wrap(self.evaluate(a, x)[0][0] - self.evaluate(b, x)[0][0]))))

            found = minimize_scalar(distance, bounds=(grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]),
                                    method="bounded", options={"xatol": 1e-12})
            if found.fun < MEET_RAD:
                out.append(self._crossing(a, b, float(found.x)))
        return out

    def _crossing(self, a: str, b: str, x: float) -> float:
        """
        A meeting input refined by the secant through x +- MEET_BRACKET of the signed difference of the joint that
        parts fastest there. Closer to the meeting the polished poses carry the singular solve's error (about the
        square root of its residual, 5e-7 rad on the plane-symmetric Bricard's crossing), which bounded the distance's
        minimiser to 6.6e-7 rad there; the secant from regular poses gives 7.5e-11 rad.
        """
        lo = max(self.nodes[a][0][0], self.nodes[b][0][0])
        hi = min(self.nodes[a][0][-1], self.nodes[b][0][-1])
        if lo <= x - MEET_BRACKET and x + MEET_BRACKET <= hi:
            ends = np.array([x - MEET_BRACKET, x + MEET_BRACKET])
        else:  # a meeting at the end of the traces: the secant from the side they cover, extrapolated
            side = 1.0 if x - lo < hi - x else -1.0
            ends = x + side * MEET_BRACKET * np.array([1.0, 2.0])
        parting = wrap(self.evaluate(a, ends)[0] - self.evaluate(b, ends)[0])
        j = int(np.argmax(np.abs(parting[1] - parting[0])))
        if not np.all(np.isfinite(parting)) or parting[1, j] == parting[0, j]:
            return x
        root = float(ends[0] - parting[0, j] * (ends[1] - ends[0]) / (parting[1, j] - parting[0, j]))
        return min(max(root, lo), hi) if abs(root - x) <= MEET_BRACKET else x  # on the traces, ends included

    def _covers(self, branch: str, x: ArrayLike) -> NDArray[np.bool_]:
        """Whether inputs x lie on the branch's traced nodes (ends included, to 1e-12 rad)."""
        s = self.nodes[branch][0]
        return (np.asarray(x) >= s[0] - 1e-12) & (np.asarray(x) <= s[-1] + 1e-12)

    def _interp(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """Linear interpolation of a branch's nodes at inputs x, (..., n_joints)."""
        s, q, _ = self.nodes[branch]
        return np.stack([np.interp(x, s, q[:, j]) for j in range(q.shape[1])], axis=-1)

    # -- Kinematics -------------------------------------------------------------------------------------------

    def summary(self) -> str:
        """One line: the assembly taken, the branches and their domains, the stops."""
        parts = [self.assembly]
        for name, (s, _, m) in self.nodes.items():
            parts.append(f"{name} over [{np.rad2deg(s[0]):.6g}, {np.rad2deg(s[-1]):.6g}] deg, mobility "
                         f"{int(m.min())}" + (f"-{int(m.max())}" if m.max() != m.min() else ""))
        for e in self._events:
            if e.kind in ("stall", "bifurcation"):
                parts.append(f"{e.kind} at {np.rad2deg(e.input):.6g} deg on {', '.join(e.branches)}: {e.detail}")
        return "; ".join(parts)

    def branches(self) -> tuple[Branch, ...]:
        return tuple(Branch(name, "traced by continuation from " + ("the start configuration" if k == 0 and
                                                                    "given" in self.assembly else
                                                                    f"assembly {k + 1} at the start input"),
                            (float(s[0]), float(s[-1])))
                     for k, (name, (s, _, _)) in enumerate(self.nodes.items()))

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        values, valid = self._full(branch, x)
        return values[:, self.observed], valid

    def _full(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Every loop joint's angle (n, n_joints) (rad) on `branch` at inputs x, and the validity mask."""
        x, valid = self.in_domain(branch, x)
        values = self._polished(branch, x, valid)
        for xb in (e.input for e in self._events if e.kind == "bifurcation" and branch in e.branches):
            near = valid & (np.abs(x - xb) < SINGULAR_ZONE)
            lo, hi = self.branch(branch).domain
            for k in np.flatnonzero(near):  # the branch is smooth through the meeting: extrapolate from regular poses
                if lo <= x[k] - 2 * SINGULAR_STEP and x[k] + 2 * SINGULAR_STEP <= hi:  # either side
                    offsets, weights = np.array([-2.0, -1.0, 1.0, 2.0]), np.array([-1.0, 4.0, 4.0, -1.0]) / 6.0
                else:  # on the side the domain lies (a meeting at its end): cubic through four poses, O(h^4)
                    side = 1.0 if x[k] - lo < hi - x[k] else -1.0
                    offsets, weights = side * np.arange(1.0, 5.0), np.array([4.0, -6.0, 4.0, -1.0])
                q = self._polished(branch, x[k] + SINGULAR_STEP * offsets, np.ones(4, dtype=bool))
                values[k] = weights @ q
        return values, valid

    def _polished(self, branch: str, x: NDArray[np.float64], valid: NDArray[np.bool_]) -> NDArray[np.float64]:
        """Interpolated poses closed with the input held (NaN where not `valid`), by `path.ChordPolish` on the
        branch's nodes (each pose to POLISH_TOL, else solved again from its guess)."""
        values = np.full((len(x), self._loops.n_joints), np.nan)
        if not np.any(valid):
            return values
        if branch not in self._polishers:
            fixed = np.zeros(self._loops.n_joints, dtype=bool)
            fixed[self.input_index] = True
            nodes = self.nodes[branch][1]
            # the placed model's rounding floor: what its trace's nodes reached (their median), FLOOR_SHARE over
            floor = FLOOR_SHARE * float(np.median(self._loops.residual_size(self._loops.residual(nodes))))
            self._polishers[branch] = ChordPolish(self._loops, nodes, fixed, tol=max(POLISH_TOL, floor),
                                                  close_tol=CLOSE_TOL)
        guess = self._interp(branch, x[valid])
        guess[:, self.input_index] = x[valid]
        values[valid] = self._polishers[branch].polish(guess, nearest_nodes(self.nodes[branch][0], x[valid]))
        return values

    def events(self) -> tuple[Event, ...]:
        return self._events

    def gruebler(self) -> int:
        """Kutzbach: joint freedoms (a spherical joint's three hinges count three) - 6 per independent loop, less the
        idle spins (as `scenes.polyhedra.kutzbach`)."""
        return self._loops.n_joints - 6 * len(self._loops.loops) - len(self.gauge)

    def loop_system(self) -> LoopSystem:
        """The mechanism's loops, idle spins free (the mobility report counts them and takes them off)."""
        return self._mechanism_loops

    def observe(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(q_loop, dtype=float).reshape(-1, self._loops.n_joints)[:, self.observed]

    def loop_angles(self, values: ArrayLike) -> NDArray[np.float64]:
        """
        Loop angles (n, n_joints) of outputs (n, k): the outputs as given, the angles an idle spin moves from the
        nearest branch's pose at the same input (by the outputs), closed with the outputs held and the spins pinned.
        """
        values = np.asarray(values, dtype=float).reshape(-1, len(self.joint_names))
        if np.all(self.observed):
            return values
        xs = values[:, self.joint_names.index(self.input_name)]
        # every branch's pose at each input it covers, in one batch per branch (NaN elsewhere)
        poses = np.full((len(self.nodes), len(values), self._loops.n_joints), np.nan)
        for m, branch in enumerate(self.nodes):
            covered = self._covers(branch, xs)
            if np.any(covered):
                poses[m, covered] = self._full(branch, xs[covered])[0]
        for k in np.flatnonzero(np.all(np.isnan(poses[:, :, 0]), axis=0)):  # outside every domain: nearest nodes
            poses[:, k] = [q[int(np.argmin(np.abs(s - xs[k])))] for s, q, _ in self.nodes.values()]
        gaps = np.max(np.abs(wrap(poses[:, :, self.observed] - values)), axis=-1)
        best = np.argmin(np.where(np.isnan(gaps), np.inf, gaps), axis=0)
        out = poses[best, np.arange(len(values))]
        for k in np.flatnonzero(gaps[best, np.arange(len(values))] > 0.0):
            out[k, self.observed] = values[k]
            out[k] = correct(self._loops, out[k], self.observed, CLOSE_TOL, max_iter=200)[0]
        return out

    def loop_input(self) -> tuple[int, float]:
        return self.input_index, 1.0
