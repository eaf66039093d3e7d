"""A crease pattern without a closed form: the numeric loop closure is the reference (numpy only).

The motion is traced through a given folded state (e.g. the last frame of a FOLD file): that state is closed
by the solver with the input crease held, then followed by continuation (secant predictor, damped-Newton
corrector, step halving) towards the flat state and outwards until a crease folds flat. The trace is kept as
nodes; `evaluate` polishes an interpolated guess with the solver at each input, so values close the loops to
the solver's 1e-14 wherever the branch is regular.

Rigid foldability. A trace that cannot continue although the steps shrink to STALL_STEP (relative to the
target's input) has met a configuration where no nearby closed configuration exists with the input moved
further: the residual stalls. That is reported as the branch's end (`stalled_at`), distinct from a long path
(which only costs steps). A pattern whose trace from its folded state stalls before reaching the flat state is
not rigidly foldable from flat along that path.

Signs and frames are those of `sim_origami.creases` (rho > 0 valley seen from +z, radians).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..creases import CreasePattern
from ..errors import AssemblyError, ConvergenceError, ParameterError
from .base import Branch, Event, JointSpaceKinematics

BRANCH = "through-target"
# Continuation: first step (fraction of the target input), the smallest step before a stall is declared, how
# close to flat the trace goes (fraction of the target input), and how near pi a crease counts as folded flat.
FIRST_STEP = 0.02
STALL_STEP = 1e-6
FLAT_END = 0.02
LOCK_MARGIN = 1e-3
# Residual (rad, m) to which the target and the trace's nodes are closed, and to which `evaluate` polishes
# (MuJoCo's projection is compared with these values at 1e-13 rad).
CLOSE_TOL = 1e-13
POLISH_TOL = 1e-15
# A target may be off by this much (rad) from the closed state it stands for (FOLD files round angles).
TARGET_TOL = 1e-2
# Rigid foldability from an M/V assignment: sign-held solves at PROBE_INPUTS (rad, from flat) or at FOLD_FROM
# (then inwards) close to SIGNED_TOL or stall; the path over [0.1, FOLLOW_TO] must keep its signs, close to
# FOLDABLE_TOL and have mobility 1 (double-corrugated units: rigid classes <= 9.7e-15, locked ones stall at
# >= 3.6e-5; square twist: rigid <= 8e-15, locked >= 1e-4).
PROBE_INPUTS = (0.02, 0.1)
FOLLOW_TO = 2.0
FOLD_FROM = 2.5
SIGNED_TOL = 1e-14
FOLDABLE_TOL = 1e-12


class PatternPath(JointSpaceKinematics):
    """
    One branch of a crease pattern, traced numerically through a folded state.

    Parameters
    ----------
    pattern : CreasePattern
    input_crease : str
      Name of the driven crease; its fold angle is the input x (rad).
    target : (n_creases,) float
      A folded state (rad) on the branch; it need not be closed exactly (it is closed with x held).

    Raises
    ------
    AssemblyError
      When the target cannot be closed (the pattern does not reach that state rigidly).
    """

    def __init__(self, pattern: CreasePattern, input_crease: str, target: ArrayLike):
        names = [c.name for c in pattern.creases]
        if input_crease not in names:
            raise ParameterError(f"input crease {input_crease!r} is not a crease of the pattern; creases are {names}")
        self.pattern = pattern
        self.joint_names = tuple(f"rho_{n}" for n in names)
        self.input_name = f"rho_{input_crease}"
        self.input_index = names.index(input_crease)
        self._loops = pattern.loop_system()
        target = np.asarray(target, dtype=float)
        x_target = float(target[self.input_index])
        if abs(x_target) < 1e-6:
            raise ParameterError(
                f"input crease {input_crease!r} is flat in the target state ({x_target:.3g} rad): pick a folded crease"
            )
        fixed = np.zeros(len(names), dtype=bool)
        fixed[self.input_index] = True
        try:
            q_target = self._loops.solve(target, fixed, tol=CLOSE_TOL, max_iter=200)
        except ConvergenceError as err:
            raise AssemblyError(
                f"the target state does not close with {input_crease} = {x_target:.6g} rad: {err}; the pattern does "
                "not reach it rigidly"
            ) from None
        gap = float(np.max(np.abs(q_target - target)))
        if gap > TARGET_TOL:
            raise AssemblyError(
                f"the target state does not close with {input_crease} = {x_target:.6g} rad: the nearest closed state "
                f"differs by {gap:.3g} rad (> {TARGET_TOL:g}); the pattern does not reach it rigidly"
            )
        self._stalls: list[float] = []
        inward = self._trace(q_target, x_target, 0.0)
        outward = self._trace(q_target, x_target, np.copysign(np.pi, x_target))
        nodes = np.vstack([inward[::-1], q_target[None], outward])
        order = np.argsort(nodes[:, self.input_index])
        self.nodes = nodes[order]
        self.stalled_at = tuple(self._stalls)

    def _trace(self, q0: NDArray, x0: float, toward: float) -> NDArray:
        """Closed configurations from x0 towards `toward`, stopping near flat, at a lock or at a stall."""
        fixed = np.zeros(len(q0), dtype=bool)
        fixed[self.input_index] = True
        span = abs(x0)
        step = FIRST_STEP * span * np.sign(toward - x0)
        stop = np.copysign(FLAT_END * span, x0) if toward == 0.0 else toward
        out, prev, q = [], None, q0
        while (stop - q[self.input_index]) * np.sign(step) > 1e-15:
            x = q[self.input_index] + step
            if (stop - x) * np.sign(step) < 0:
                x = stop
            guess = (
                q.copy()
                if prev is None
                else q + (q - prev) * (x - q[self.input_index]) / (q[self.input_index] - prev[self.input_index])
            )
            guess[self.input_index] = x
            try:
                nxt = self._loops.solve(guess, fixed, tol=CLOSE_TOL)
            except ConvergenceError:
                step /= 2
                if abs(step) < STALL_STEP * span:
                    self._stalls.append(float(q[self.input_index]))
                    break
                continue
            if np.max(np.abs(nxt - q)) > 0.2:  # a jump to another branch, not a step along this one
                step /= 2
                continue
            if np.max(np.abs(nxt)) > np.pi - LOCK_MARGIN:
                break
            out.append(nxt)
            prev, q = q, nxt
            step = np.copysign(min(abs(step) * 1.5, FIRST_STEP * span), step)
        return np.array(out).reshape(-1, len(q0))

    def branches(self) -> tuple[Branch, ...]:
        lo, hi = self.nodes[0, self.input_index], self.nodes[-1, self.input_index]
        return (Branch(BRANCH, "the branch through the given folded state, traced by continuation", (lo, hi)),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        values = np.full((len(x), len(self.joint_names)), np.nan)
        fixed = np.zeros(len(self.joint_names), dtype=bool)
        fixed[self.input_index] = True
        xs = self.nodes[:, self.input_index]
        for k in np.flatnonzero(valid):
            guess = np.array([np.interp(x[k], xs, self.nodes[:, j]) for j in range(self.nodes.shape[1])])
            guess[self.input_index] = x[k]
            values[k] = self._loops.solve(guess, fixed, tol=POLISH_TOL)
        return values, valid

    def events(self) -> tuple[Event, ...]:
        lo, hi = self.branch(BRANCH).domain
        out = []
        for end in (lo, hi):
            if end in self.stalled_at:
                detail = "the closure residual stalls: no closed configuration beyond (not rigidly foldable on)"
            elif abs(end) < 0.5 * FLAT_END * np.pi:
                detail = "trace stopped short of the flat state (a bifurcation point, not traced through)"
            else:
                detail = "a crease folds flat (|rho| = pi) or the input reaches pi"
            out.append(Event("lock", float(end), (BRANCH,), detail))
        return tuple(out)

    def gruebler(self) -> int:
        """Kutzbach: creases - 3 per spherical vertex (6 per vertex with lifted hinges)."""
        spatial = any(c.height != 0.0 for c in self.pattern.creases)
        return len(self.joint_names) - (6 if spatial else 3) * len(self._loops.loops)

    def loop_system(self) -> LoopSystem:
        return self._loops

    def loop_input(self) -> tuple[int, float]:
        return self.input_index, 1.0


def foldable_with_signs(loops: LoopSystem, signs: ArrayLike, input_joint: int) -> tuple[bool, float]:
    """
    (rigidly foldable with these fold signs, smallest stalled residual or largest closed one, rad or m).

    Two starts, because a sign-held solve from a uniform guess near flat misses the closed pose of patterns
    whose creases fold at very different rates (the square twist at alpha <= 135 deg stalls at 2e-4 from
    flat but closes from its folded end): sign-held solves (`LoopSystem.solve_signed`) at PROBE_INPUTS rising
    from flat, or one at FOLD_FROM followed inwards. Either must give a closed path over [PROBE_INPUTS[-1],
    FOLLOW_TO] that keeps every sign with mobility 1. No configuration with these signs near the path: the
    residual stalls, not rigidly foldable.
    """
    s = np.asarray(signs, dtype=float)
    grid = s[input_joint] * np.linspace(PROBE_INPUTS[-1], FOLLOW_TO, 40)
    stalled = np.inf
    for start in (PROBE_INPUTS, (FOLD_FROM,)):
        for x in start:
            q, residual = loops.solve_signed(s, input_joint, x * s[input_joint], tol=SIGNED_TOL)
            if residual > FOLDABLE_TOL:
                stalled = min(stalled, residual)
                break
        else:
            values = grid if start == PROBE_INPUTS else np.concatenate([[FOLD_FROM * s[input_joint]], grid[::-1]])
            path = loops.follow(q, input_joint, values, tol=SIGNED_TOL)
            worst = float(np.max(loops.residual_norm(path)))
            if np.all(np.sign(path) == s) and worst <= FOLDABLE_TOL and loops.mobility(path[-1]) == 1:
                return True, worst
            stalled = min(stalled, worst)
    return False, stalled
