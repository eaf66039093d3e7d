"""A crease pattern without a closed form: the numeric loop closure is the reference (numpy only).

The motion is traced by `sim_origami.path` (predictor-corrector with step control, stall and rank monitoring)
with k driven creases (the inputs) moved along a path in their space. Two ways to give the motion:

- anchored: one input and an exact folded state (finite, every |rho| < pi, closing within TARGET_TOL with the
  input held): the state is closed, then traced inwards to FLAT_END of its input and outwards until a crease
  folds flat; the input x is the driven crease's angle;
- directed: anything else (several inputs, frames, a state with NaN (free) entries, creases at +-180 deg, a state
  off the rigid path, M/V letters only): the inputs move from flat along a straight line to the state's inputs
  (or through the frames' inputs; from the first frame, back to flat and on, when it is an exact rigid state),
  and the trace goes as far as the rigid motion does. It stops at the path's end, at a stall (no rigid
  configuration beyond), where a crease reaches +-(pi - LOCK_MARGIN), with `signs` where a crease would take the
  other sign than its M/V letter, or at the first self-contact of two faces (`self_contact`, zero thickness).
  With one input x is its angle;
  with several, the arc length (rad) along the inputs' path from flat.

`evaluate` polishes an interpolated guess with the solver at each input (above SPARSE_FROM creases by chord steps
on the trace's nodes, `path.ChordPolish`, to the residual's rounding floor), so values close the loops to the
solver's 1e-15 wherever the path is regular. F creases are locked flat by couplings (`lock_flat`); U creases
and NaN entries are free.

Signs and frames are those of `sim_origami.creases` (rho > 0 valley seen from +z, radians).
"""

from collections.abc import Sequence
from dataclasses import replace
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Coupling, LoopSystem
from ..conventions import MIN_SWEEP_RAD
from ..creases import CreasePattern
from ..errors import ParameterError
from ..path import ChordPolish, PathStop, Polyline, TracedPath, correct, first_order_closed, nearest_nodes, trace
from .base import Branch, Event, JointSpaceKinematics
from .self_contact import SelfContact

BRANCH = "through-target"
# Patterns with more creases than this solve with sparse normal equations (16 x 16 Miura, 480 creases: a corrector
# iteration 0.2 s dense, a few ms sparse), and start a letters-only trace of one input on the first-order closure
# plane; smaller ones keep the dense solve and the sign-held start.
SPARSE_FROM = 100
# Continuation: first step (fraction of the target input), how close to flat the trace goes (fraction of the
# target input), how near pi a crease counts as folded flat (rad), and the largest step (rad of input).
FIRST_STEP = 0.02
FLAT_END = 0.02
LOCK_MARGIN = 1e-3
MAX_STEP = 0.05
# The smallest step (fraction of the path's length) before a stall is declared.
STALL_STEP = 1e-6
# A crease held to the sign of its M/V letter may cross zero by this much (rad) before it counts as flipping.
SIGN_SLACK = 1e-9
# A directed trace's start guess is put on the first-order closure plane at flat to this relative residual.
START_TOL = 1e-15
# `evaluate` keeps the values of this many input arrays (a validation asks for about four different ones).
EVALUATE_MEMO = 8
# Residual (rad, m) to which the target and the trace's nodes are closed, and to which `evaluate` polishes
# (MuJoCo's projection is compared with these values at 1e-13 rad).
CLOSE_TOL = 1e-13
# A lettered crease that never turns beyond this (rad) along a letters trace is left flat by it: the trace holds a
# crease its motion does not fold at its letter's bound, within SIGN_SLACK of 0, where a folding one turns by
# radians.
UNFOLDED = 1e-6
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


def lock_flat(pattern: CreasePattern) -> tuple[Coupling, ...]:
    """Couplings rho = 0 for the pattern's F creases (a crease that must stay flat)."""
    return tuple(Coupling(k, k, 0.0) for k, c in enumerate(pattern.creases) if c.assignment == "F")


def assignment_signs(pattern: CreasePattern) -> NDArray[np.float64]:
    """Fold sign of each crease from its letter: V +1, M -1, else 0 (rho > 0 valley seen from +z)."""
    return np.array([{"V": 1.0, "M": -1.0}.get(c.assignment, 0.0) for c in pattern.creases])


class PatternPath(JointSpaceKinematics):
    """
    One branch of a crease pattern, traced numerically (anchored at or directed towards a folded state).

    Parameters
    ----------
    pattern : CreasePattern
    inputs : str or sequence of str
      Names of the driven creases.
    target : (n_creases,) float, optional
      A folded state (rad); NaN entries are free. Not needed with `frames` or `signs`.
    frames : (n_frames, n_creases) float, optional
      States the motion passes through in turn (NaN free): the inputs move from flat through theirs, traced from
      the first folded frame when it closes with the inputs held (`_frame_anchor`).
    signs : (n_creases,) float, optional
      M/V letters as -1/+1 (0: free): the trace keeps each crease on its letter's side and, without a target,
      heads for +-pi in every driven crease.
    contact : bool
      Stop each trace at the first self-contact of two faces (default); False traces through it.
    """

    def __init__(
        self,
        pattern: CreasePattern,
        inputs: str | Sequence[str],
        target: ArrayLike | None = None,
        *,
        frames: ArrayLike | None = None,
        signs: ArrayLike | None = None,
        contact: bool = True,
    ):
        names = [c.name for c in pattern.creases]
        inputs = (inputs,) if isinstance(inputs, str) else tuple(inputs)
        for name in inputs:
            if name not in names:
                raise ParameterError(f"input crease {name!r} is not a crease of the pattern; creases are {names}")
        if len(set(inputs)) != len(inputs) or not inputs:
            raise ParameterError(f"input creases {list(inputs)}: name each driven crease once")
        self.pattern = pattern
        self.joint_names = tuple(f"rho_{n}" for n in names)
        self.inputs = inputs
        self.driven = np.array([names.index(n) for n in inputs])
        self.input_index = int(self.driven[0])
        self.input_name = f"rho_{inputs[0]}" if len(inputs) == 1 else "s (arc length of the inputs' path, rad)"
        self._loops = replace(pattern.loop_system(lock_flat(pattern)), sparse=len(names) > SPARSE_FROM)
        self._contact = SelfContact(pattern) if contact else None
        for k in self.driven:
            if pattern.creases[k].assignment == "F":
                raise ParameterError(f"input crease {names[k]!r} is an F crease (kept flat): it cannot be driven")
        n = len(names)
        self.signs = np.zeros(n) if signs is None else np.asarray(signs, dtype=float)
        self.lower = np.where(self.signs > 0, -SIGN_SLACK, -(np.pi - LOCK_MARGIN))
        self.upper = np.where(self.signs < 0, SIGN_SLACK, np.pi - LOCK_MARGIN)
        self.target = None if target is None else np.asarray(target, dtype=float)
        self.frames = None if frames is None else np.atleast_2d(np.asarray(frames, dtype=float))
        self.letters_only = self.target is None and self.frames is None
        if self.letters_only:
            if signs is None:
                raise ParameterError("a pattern path needs a target state, frames or M/V signs")
            self.target = np.where(self.signs != 0, self.signs * np.pi, np.nan)
        for name, state in (("target", self.target), ("frames", self.frames)):
            if state is not None and state.shape[-1] != n:
                raise ParameterError(f"{name} has {state.shape[-1]} fold angles for {n} creases")
        self.stops: list[PathStop] = []
        self._lead_stop: PathStop | None = None  # why the lead trace of several inputs under letters ended (`_lead`)
        self._lead_path: PatternPath | None = None  # that lead trace
        self._evaluated: dict[bytes, tuple] = {}  # the last EVALUATE_MEMO inputs evaluated and their values
        self.rank_events: list[PathStop] = []
        self.path: Polyline | None = None
        self.frame_distances: list[dict] = []
        # rad: frames farther than this from the rigid motion fail validation; None = reported only
        self.frames_tolerance: float | None = None
        # the input (rad) of a target that lies on the rigid motion (the trace is anchored there), else None
        self.target_input: float | None = None
        # the file's folded form against its nearest rigid state, whose angles are the target (`fold.FormFit`), if any
        self.state_fit = None
        anchor = self._anchor()
        if anchor is not None:
            self._trace_anchored(anchor)
        else:
            self._trace_directed()
        self.stalled_at = tuple(p.s for p in self.stops if p.kind == "stall")

    # -- the two ways of tracing ------------------------------------------------------------------------------

    def _anchor(self) -> NDArray | None:
        """The closed target for an anchored trace, or None (then the trace is directed)."""
        t = self.target
        if self.frames is not None or len(self.driven) != 1 or not np.all(np.isfinite(t)):
            return None
        if np.max(np.abs(t)) >= np.pi - LOCK_MARGIN:
            return None
        x = float(t[self.input_index])
        if abs(x) < 1e-6:
            raise ParameterError(
                f"input crease {self.inputs[0]!r} is flat in the target state ({x:.3g} rad): pick a folded crease"
            )
        fixed = np.zeros(len(t), dtype=bool)
        fixed[self.input_index] = True
        q, r, _ = correct(self._loops, t.copy(), fixed, CLOSE_TOL, max_iter=200)
        outside = np.any(q < self.lower) or np.any(q > self.upper)
        if r > 100 * CLOSE_TOL or np.max(np.abs(q - t)) > TARGET_TOL or outside:
            return None  # not on the rigid motion: a direction to trace towards
        return q

    def _run(self, q0: NDArray, knots: ArrayLike, first: float) -> TracedPath:
        path = Polyline.through(knots)
        span = abs(path.s[-1] - path.s[0])
        return trace(self._loops, q0, self.driven, path, lower=self.lower, upper=self.upper, first_step=first,
                     max_step=MAX_STEP, min_step=STALL_STEP * span, tol=CLOSE_TOL,
                     names=tuple(c.name for c in self.pattern.creases), stop_when=self._contact)

    def _trace_anchored(self, q_target: NDArray) -> None:
        x = self.target_input = float(q_target[self.input_index])
        inward = self._run(q_target, [[x], [FLAT_END * x]], FIRST_STEP * abs(x))
        outward = self._run(q_target, [[x], [np.copysign(np.pi, x)]], FIRST_STEP * abs(x))
        self.stops = [inward.stop, outward.stop]
        self.rank_events = [*inward.events, *outward.events]
        s = np.concatenate([inward.s[::-1], outward.s[1:]])
        q = np.vstack([inward.q[::-1], outward.q[1:]])
        self.mobility = np.concatenate([inward.mobility[::-1], outward.mobility[1:]])
        order = np.argsort(s)
        self.s_nodes, self.nodes = s[order], q[order]
        self.target_gap = float(np.max(np.abs(q_target - self.target)))
        self.target_end, self.target_state = x, q_target

    def _knots(self) -> NDArray:
        """The inputs' path from flat: through each frame's inputs, through the lead trace's (`_lead`) for several
        inputs driven by letters, or straight to the target's."""
        lead = self._lead() if self.letters_only and len(self.driven) > 1 else None
        states = self.frames if self.frames is not None else self.target[None]
        knots = lead if lead is not None else states[:, self.driven]
        if not np.all(np.isfinite(knots)):
            bad = [self.inputs[j] for j in np.flatnonzero(~np.all(np.isfinite(knots), axis=0))]
            raise ParameterError(f"input crease(s) {bad} have no angle (null) in the file's folded state: drive "
                                 "creases whose angles are given (--input)")
        knots = knots[np.r_[True, np.any(np.diff(knots, axis=0) != 0, axis=1)]]  # repeated frames add nothing
        if np.any(knots[0] != 0):
            knots = np.vstack([np.zeros(len(self.driven)), knots])
        if len(knots) < 2:
            raise ParameterError("the folded state leaves every input crease flat: pick folded input creases")
        return knots

    def _lead(self) -> NDArray | None:
        """
        The inputs' values along the motion driven by the first input alone, every spare freedom folding towards the
        letters (`path.toward_step`), from flat: the path several inputs follow under letters. A straight line in
        the inputs to +-pi would fix how the freedoms share the motion by the inputs' letters alone, which no rigid
        motion need keep (a degree-8 vertex of alternating letters, 5 inputs: a V crease turned M at 0.09 rad).
        None when the lead does not leave flat (then the straight line, which stops where it does).
        """
        lead = PatternPath(self.pattern, self.inputs[0], signs=self.signs, contact=self._contact is not None)
        if len(lead.s_nodes) < 2:
            return None
        self._lead_stop, self._lead_path = lead.stops[-1], lead
        order = np.argsort(np.abs(lead.s_nodes))
        return np.vstack([np.zeros(len(self.driven)), lead.nodes[order][:, self.driven]])

    def _start(self, path: Polyline, s1: float) -> NDArray:
        """A configuration near the closed one at s1, a little way from flat along the path (flat is a branch point:
        the guess picks the branch heading for the folded state, or the M/V signs)."""
        n = len(self.joint_names)
        lettered = self.signs[[k for k, c in enumerate(self.pattern.creases) if c.assignment != "F"]] != 0
        if self._lead_path is not None:  # s1 is the path's first knot, the lead's first node: closed, these inputs'
            lead = self._lead_path
            return lead.nodes[int(np.argmin(np.abs(lead.s_nodes)))].copy()
        if self.letters_only and np.all(lettered) and n <= SPARSE_FROM:
            x = float(path.at(s1)[0])
            q, _ = self._loops.solve_signed(np.where(self.signs == 0, 1.0, self.signs), self.input_index, x,
                                            tol=CLOSE_TOL)
            q[self.signs == 0] = 0.0
            return q
        states = self.frames if self.frames is not None else self.target[None]
        first = np.nan_to_num(states[0])
        lead = np.max(np.abs(path.points[1]))
        q = first * (np.max(np.abs(path.at(s1))) / lead) if lead > 0 else np.zeros(n)
        q[self.driven] = path.at(s1)
        # nearest to that guess of the states that close to first order at flat (J0 q = 0, inputs held): from a
        # guess off that plane the corrector can stall at flat's saddle (a degree-5 vertex did at 4.6e-5)
        if self._loops.n_residuals:
            q = first_order_closed(self._loops, np.zeros(n), q, self.driven, START_TOL)
        return q

    def _trace_directed(self) -> None:
        path = Polyline.through(self._knots())
        span = abs(path.s[-1] - path.s[0])
        s1 = path.s[0] + np.sign(path.s[-1] - path.s[0]) * FIRST_STEP * min(span, abs(path.s[1] - path.s[0]))
        if self._lead_path is not None:
            s1 = float(path.s[1])  # the lead's first node, where its closed state is known (`_start`)
        names = tuple(c.name for c in self.pattern.creases)
        anchor = self._frame_anchor(path)
        if anchor is None:
            parts = [trace(self._loops, self._start(path, s1), self.driven, path, s0=s1, lower=self.lower,
                           upper=self.upper, first_step=FIRST_STEP * span, max_step=MAX_STEP,
                           min_step=STALL_STEP * span, tol=CLOSE_TOL, names=names,
                           previous=(path.s[0], np.zeros(len(self.joint_names))), stop_when=self._contact,
                           toward=self.target if self.letters_only else None)]
        else:  # from the first frame back to near flat, and on through the others
            s_frame, q_frame = anchor
            parts = [trace(self._loops, q_frame, self.driven, path, s0=s_frame, s_end=s_end, lower=self.lower,
                           upper=self.upper, first_step=FIRST_STEP * span, max_step=MAX_STEP,
                           min_step=STALL_STEP * span, tol=CLOSE_TOL, names=names, stop_when=self._contact)
                     for s_end in (s1, path.s[-1])]
        traced = parts[-1]
        self.path = path
        self.stops = [p.stop for p in parts]
        if self._lead_stop is not None and traced.stop.kind == "end":  # the lead's end is where its motion stopped
            self.stops[-1] = replace(self._lead_stop, s=traced.stop.s, hit=None)  # its hit is in the lead's parameter
        self.rank_events = [e for p in parts for e in p.events]
        s = np.concatenate([parts[0].s, *(p.s[1:] for p in parts[1:])])
        q = np.vstack([parts[0].q, *(p.q[1:] for p in parts[1:])])
        mobility = np.concatenate([parts[0].mobility, *(p.mobility[1:] for p in parts[1:])])
        # a start that does not close is no configuration (box.fold's, 1.35e-5 from a direction with 10 inputs): the
        # trace keeps the closed nodes, else flat, so that every state downstream (MuJoCo's poses, the truss) closes
        closed = self._loops.residual_norm(q) <= 100 * CLOSE_TOL
        if not np.any(closed):
            s, q, closed = path.s[:1], np.zeros((1, len(self.joint_names))), np.array([True])
            mobility = np.array([self._loops.mobility(q[0])])
        order = np.argsort(s[closed])
        self.s_nodes, self.nodes, self.mobility = s[closed][order], q[closed][order], mobility[closed][order]
        self.target_gap = np.nan
        self.target_end, self.target_state = float(traced.s[-1]), traced.q[-1]
        self.frame_distances = self._frame_distances() if self.frames is not None else []
        if self.target is not None and traced.stop.kind == "end":
            known = np.isfinite(self.target)
            self.target_gap = float(np.max(np.abs(traced.q[-1][known] - self.target[known]), initial=0.0))

    def _frame_anchor(self, path: Polyline) -> tuple[float, NDArray] | None:
        """
        (its parameter, the closed state) of the first folded frame, closed with the inputs held, when it is an
        exact rigid state (every angle given, within TARGET_TOL of the closed one, inside the bounds); else None.
        Traced from flat instead, the inputs alone may pick another branch at flat, a branch point (the thick
        waterbomb cell driven by e1 did, 0.79 rad from its frames).
        """
        if self.frames is None:
            return None
        folded = [f for f in self.frames if np.max(np.abs(f[self.driven])) > 0]
        if not folded or not np.all(np.isfinite(folded[0])) or np.max(np.abs(folded[0])) >= np.pi - LOCK_MARGIN:
            return None
        fixed = np.zeros(len(self.joint_names), dtype=bool)
        fixed[self.driven] = True
        q, r, _ = correct(self._loops, folded[0].copy(), fixed, CLOSE_TOL, max_iter=200)
        if r > 100 * CLOSE_TOL or np.max(np.abs(q - folded[0])) > TARGET_TOL or np.any(q < self.lower) \
                or np.any(q > self.upper):
            return None
        return float(path.parameter_of(q[self.driven][None])[0]), q

    def _frame_distances(self) -> list[dict]:
        """Each frame against the rigid motion through the frames' inputs: its closure residual (its free entries
        taken from the motion) and its largest distance (rad) from the closed configuration at its inputs; None
        where the trace ended before the frame."""
        out = []
        knots = self._knots()
        lo, hi = self.s_nodes[0], self.s_nodes[-1]
        for f, frame in enumerate(self.frames):
            s = float(self.path.parameter_of(frame[self.driven][None])[0]) if np.all(np.isfinite(frame[self.driven])) \
                else np.nan
            entry = {"frame": f, "input": s, "closure_residual": None, "distance_rad": None}
            if np.isfinite(s) and lo - 1e-12 <= s <= hi + 1e-12 and len(knots):
                closed = self.evaluate(BRANCH, [min(max(s, lo), hi)])[0][0]
                known = np.isfinite(frame)
                filled = np.where(known, frame, closed)
                entry["closure_residual"] = float(self._loops.residual_norm(filled))
                entry["distance_rad"] = float(np.max(np.abs(frame[known] - closed[known]), initial=0.0))
            out.append(entry)
        return out

    # -- Kinematics -------------------------------------------------------------------------------------------

    @property
    def path_is_input(self) -> bool:
        """The input x is the (single) driven crease's angle itself."""
        return self.path is None or (len(self.driven) == 1 and np.array_equal(self.path.s, self.path.points[:, 0]))

    def summary(self) -> str:
        """One line on the trace: inputs, mobility along it, where and why it ended, the target's distance."""
        names = [c.name for c in self.pattern.creases]
        lo, hi = float(np.min(self.mobility)), float(np.max(self.mobility))
        parts = [f"{len(self.driven)} input(s) {', '.join(names[k] for k in self.driven)}, mobility "
                 f"{lo:g}" + (f"-{hi:g}" if hi != lo else "") + " along the traced path"]
        if self.open_chain:
            parts.append("an open chain: no closed loop, the closure check is empty")
        for e in self.events():
            if e.kind in ("stall", "lock", "contact", "branch-point", "off-target"):
                parts.append(f"{e.kind} at {e.input:.6g} rad: {e.detail}")
        return "; ".join(parts)

    def state_check(self) -> tuple[float, float, str, int] | None:
        """
        The file's folded state against the nearest rigid state read in its place (`state_fit`): (its largest move
        of a value over that value's precision, 1, where it is largest and whether the rigid motion reaches the
        state, how many values were compared); None without one. Beyond 1 the file's state is not a rigid one within
        its precision.
        """
        fit = self.state_fit
        if fit is None:
            return None
        if self.target_input is not None and len(self.s_nodes) > 1:
            reach = f"the rigid motion passes through it (traced from it, input {self.target_input:.6g} rad)"
        elif self.target_input is not None:
            reach = "it closes, but no rigid motion leaves it (the trace stalls there both ways)"
        elif self.frame_distances:
            far = [d["distance_rad"] for d in self.frame_distances]
            reach = "the rigid motion ends before the last frame" if any(d is None for d in far) else \
                f"the rigid motion through the frames' inputs passes {max(far):.3g} rad from them at most"
        elif np.isfinite(self.target_gap):
            verb = "reaches" if self.target_gap <= TARGET_TOL else "ends"
            reach = f"the rigid motion {verb} {self.target_gap:.3g} rad from it at the inputs' end"
        else:
            stop = next((p for p in self.stops if p.kind != "end"), None)
            reach = "the rigid motion does not reach it" + (f": it stops at {stop.s:.6g} rad ({stop.kind})" if stop
                                                            else "")
        return fit.ratio, 1.0, f"{fit.text()}; {reach}", fit.values

    def start_check(self) -> tuple[float, float, str] | None:
        """
        (1, 0, where and why it stopped) when the trace never left its start (a single node, or nodes within
        MIN_SWEEP_RAD of it: a stall, lock or contact at once), else None. Such a motion gives MuJoCo a drive of no
        length to sweep, so this stop is the run's first real cause of failure (`validation.validate` then runs no
        MuJoCo).
        """
        span = float(self.s_nodes[-1] - self.s_nodes[0])
        if span >= MIN_SWEEP_RAD:
            return None
        stop = next((e for e in self.events() if e.kind in ("stall", "lock", "contact")), None)
        why = f"{stop.kind} at {stop.input:.6g} rad: {stop.detail}" if stop is not None else \
            f"no node beyond {self.s_nodes[0]:.6g} rad"
        moved = f" after {span:.3g} rad" if span > 0 else ""
        return 1.0, 0.0, (f"{why}{moved}; the pattern does not fold rigidly from there, so there is no motion to "
                          "simulate")

    def target_check(self) -> tuple[float, float, str, int] | None:
        """
        A folded state given as the motion's target (not letters, not frames) against the rigid motion: (the largest
        distance, rad, of a given angle from the traced state at the target's inputs, TARGET_TOL, what was compared, how
        many angles);
        None when there is no such state or the trace stopped before the target's inputs (its stall, lock or contact
        event says where and why). A file giving a folded state asks whether the pattern folds rigidly to it, so a
        state beyond TARGET_TOL, the rounding allowed to FOLD writers' angles as to exact frames, fails.
        """
        if self.letters_only or self.frames is not None or not np.isfinite(self.target_gap):
            return None
        names = [c.name for c in self.pattern.creases]
        known = np.flatnonzero(np.isfinite(self.target))
        worst = int(known[np.argmax(np.abs(self.target_state[known] - self.target[known]))]) if known.size else 0
        at = f"the inputs' end {self.target_end:.6g} rad" if self.target_input is None else \
            f"its input {self.target_input:.6g} rad (traced from it)"
        detail = (f"the file's folded state is {self.target_gap:.3g} rad ({np.rad2deg(self.target_gap):.3g} deg) from "
                  f"the rigid motion's state at {at}, largest at crease {names[worst]}; {len(known)} given "
                  f"angles of {len(names)} creases compared")
        if self.target_gap > TARGET_TOL:
            detail += ": the pattern does not fold rigidly to it"
        return self.target_gap, TARGET_TOL, detail, len(known)

    def unfolded_letters(self) -> tuple[str, ...] | None:
        """
        Names of the M/V creases that the traced motion leaves flat (never beyond UNFOLDED rad), when the trace
        follows the letters (None otherwise, or when it never left its start): such a motion is that of another
        assignment, those creases F. A Yoshimura sheet with flat diamond panels (two families of crossing
        lines, all M) folds one family and leaves the other flat: its letters do not fold rigidly.
        """
        if not self.letters_only or len(self.s_nodes) < 2:
            return None
        still = (self.signs != 0) & (np.max(np.abs(self.nodes), axis=0) <= UNFOLDED)
        return tuple(self.pattern.creases[k].name for k in np.flatnonzero(still))

    @property
    def open_chain(self) -> bool:
        """No closed loop and no coupling: nothing to close (MuJoCo on a tree)."""
        return not self._loops.loops

    def driven_values(self, x: ArrayLike) -> NDArray[np.float64]:
        """The driven creases' angles (n, k) at inputs x (n,)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return x[:, None] if self.path_is_input else self.path.at(x)

    def branches(self) -> tuple[Branch, ...]:
        lo, hi = float(self.s_nodes[0]), float(self.s_nodes[-1])
        return (Branch(BRANCH, "the branch through (or towards) the given folded state, traced by continuation",
                       (lo, hi)),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        return self.evaluate_held(branch, x, self.driven_values(x))

    def evaluate_held(
        self, branch: str, x: ArrayLike, held: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """The closed configurations (n, n_creases) with the inputs at `held` (n, k) (rad), from the trace's
        state at x (n,) as the guess; NaN where x is off the traced domain."""
        x, valid = self.in_domain(branch, x)
        held = np.asarray(held, dtype=float).reshape(len(x), len(self.driven))
        key = x.tobytes() + held.tobytes()  # validation asks for the same inputs several times (path error, labels)
        if key not in self._evaluated:
            if len(self._evaluated) >= EVALUATE_MEMO:
                self._evaluated.pop(next(iter(self._evaluated)))
            self._evaluated[key] = self._evaluate(x, valid, held)
        values, valid = self._evaluated[key]
        return values.copy(), valid.copy()

    @cached_property
    def _polisher(self) -> ChordPolish:
        """`evaluate`'s polish: chord steps on the trace's nodes (their factorisations kept), dense and sparse systems
        alike, to the residual's rounding floor (near a singular end a residual of 1e-13 still left the angles 3.7e-12
        rad off, the Jacobian's smallest singular value 3.7e-3 there; at the floor they are 1e-13 from MuJoCo's
        projection)."""
        fixed = np.zeros(len(self.joint_names), dtype=bool)
        fixed[self.driven] = True
        return ChordPolish(self._loops, self.nodes, fixed, tol=POLISH_TOL, close_tol=CLOSE_TOL, floor=True)

    def _evaluate(self, x: NDArray, valid: NDArray, held: NDArray) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        values = np.full((len(x), len(self.joint_names)), np.nan)
        if not np.any(valid):
            return values, valid
        if self._loops.n_residuals and self.path_is_input and len(self.driven) == 1:
            guesses = self._polisher.hermite(self.s_nodes, x[valid])
        else:
            guesses = np.stack([np.interp(x[valid], self.s_nodes, self.nodes[:, j])
                                for j in range(self.nodes.shape[1])], axis=-1)
        guesses[:, self.driven] = held[valid]
        if not self._loops.n_residuals:
            values[valid] = guesses
        else:
            values[valid] = self._polisher.polish(guesses, nearest_nodes(self.s_nodes, x[valid]))
        return values, valid

    def events(self) -> tuple[Event, ...]:
        out = []
        names = [c.name for c in self.pattern.creases]
        for stop in self.stops:
            if stop.kind == "end":
                continue
            what = {"stall": "stall", "bound": "lock", "bifurcation": "branch-point", "contact": "contact"}[stop.kind]
            detail = stop.detail
            if stop.kind == "bound" and stop.joint is not None:
                j = stop.joint
                flips = self.signs[j] != 0 and abs(self.nodes[np.argmin(np.abs(self.s_nodes - stop.s)), j]) < 0.5
                detail = (f"crease {names[j]} would fold against its {self.pattern.creases[j].assignment} letter"
                          if flips else f"crease {names[j]} folds flat (|rho| -> pi)") + f": {stop.detail}"
            if stop.hit is not None:
                detail += f" (at s = {stop.hit:.10g})"
            out.append(Event(what, float(stop.s), (BRANCH,), detail))
        for e in self.rank_events:
            out.append(Event("mobility-change", float(e.s), (BRANCH,), e.detail))
        for d in self.frame_distances:
            if d["distance_rad"] is None:
                detail = f"frame {d['frame']}: beyond the traced motion"
            else:
                detail = (f"frame {d['frame']}: {d['distance_rad']:.3g} rad from the rigid motion, closure residual "
                          f"{d['closure_residual']:.3g}")
            out.append(Event("frame", float(d["input"]) if np.isfinite(d["input"]) else float("nan"), (BRANCH,),
                             detail))
        if self.target_gap > TARGET_TOL:
            out.append(Event("off-target", self.target_end, (BRANCH,),
                             f"the target state is off the rigid motion: at the inputs' end the traced state differs "
                             f"from it by {self.target_gap:.3g} rad"))
        if self.open_chain:
            out.append(Event("open-chain", float(self.s_nodes[0]), (BRANCH,),
                             "no closed loop: every crease is free but the inputs; the closure check is empty"))
        return tuple(out)

    def gruebler(self) -> int:
        """Kutzbach: creases - 3 per spherical vertex (6 per vertex with lifted hinges) - F locks."""
        spatial = any(c.height != 0.0 for c in self.pattern.creases)
        return len(self.joint_names) - (6 if spatial else 3) * len(self._loops.loops) - len(self._loops.couplings)

    def loop_system(self) -> LoopSystem:
        return self._loops

    def loop_input(self) -> tuple[int, float]:
        return self.input_index, 1.0

    def loop_inputs(self, x: ArrayLike) -> tuple[tuple[int, ...], NDArray[np.float64]]:
        return tuple(int(j) for j in self.driven), self.driven_values(x)


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
