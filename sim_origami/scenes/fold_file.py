"""A scene from a FOLD 1.2 file: any crease pattern, with the numeric loop closure as the reference.

What the motion is (`kinematics.numeric_pattern` for the trace and its stops):
- the file's frames, when it has several: the inputs move through each frame's inputs in turn (traced from the first
  frame, back to flat and on through the others);
- else its folded state (the last frame, or the key frame's `edges_foldAngle`; null = free): anchored at it when
  it is an exact rigid state with one input, otherwise a direction traced from flat as far as the rigid motion goes
  (+-180 deg targets, free entries, states off the rigid path);
- else its M/V letters: from flat with every crease on its letter's side, towards +-180 deg.
The inputs are the creases named (`--input e1,e5`), or as many as the pattern has freedoms along the motion,
picked by rank (`path.independent_joints`), the steadiest crease first (`steadiest`: the one whose rate stays the
largest fraction of the fastest crease's). F creases are locked flat.

Scale. The pattern is simulated at unit size: lengths divided by its longest edge L (`params["size_m"]`), so the
same pattern at 1 mm, 1 m or 1000 "unit" gives the same verdict and angle errors; closure residuals in the report
are then in units of L (multiply by L for metres).

The sweep runs from SWEEP_FROM of the target's input to the target when the target is a state on the rigid motion,
else from SWEEP_FROM of the traced motion's end to that end, or from the first frame to the last.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np

from .. import fold_mesh
from ..creases import CreasePattern
from ..errors import ParameterError
from ..fold import read_fold
from ..graph import breadth_first_depths, central_node
from ..kinematics.numeric_pattern import LOCK_MARGIN, SPARSE_FROM, TARGET_TOL, PatternPath, assignment_signs, lock_flat
from ..origami import pattern_mechanism
from ..path import independent_joints
from .base import Scene, Tuning

# The default sweep runs from this fraction of the motion's end to the end.
SWEEP_FROM = 0.3
# MuJoCo's regulariser R (the preset's) times this. A file's pattern may be ill-conditioned where the registered
# scenes are not, and what lets MuJoCo's lag through there, near the lock a sweep ends at, is R, not the step: thin
# panels lag in proportion to R (a 4 x 4 sheet of 50:1 panels driven by a short crease: 4.25 x the angle tolerance at
# R / 10^4, 0.42 at R / 10^5, 0.042 at R / 10^6; 10 x 10 of 25:1 panels: 9.4 at R / 100, 0.94 at R / 1000, 0.43 at
# R / 10^4, 0.23 at R / 10^6), while every other pattern measured kept its error and closure gap to 3 digits (the
# 16 x 16 sheet of the speed benchmark, near-square large sheets, the rigid gallery of tests/test_fold_gallery.py,
# the bird base: their error is the step's; docs/fold_files.md).
REGULARIZATION_SCALE = 1e-6
# Their closures (and drive) run at this times the preset's time constant, 3 steps instead of 2.5. Near-square
# letters-only Miura sheets failed at 2.5: their closure gap peaks mid-path, where the sweep is fastest, and softer
# closures lower it (12 x 12 at a zigzag of 0.2 / 0.1 edge, 16 x 16 at 0.2: 1.20 / 1.11 / 1.60 of its tolerance ->
# 0.73 / 0.68 / 0.97), while a sheet of 5:1 panels, whose error is lag near its lock, rises 0.60 -> 0.69 of the angle
# tolerance; 3.5 and 4 steps trade further the one for the other (docs/fold_files.md).
LARGE_TIMECONST_SCALE = 1.2
# ... and sweep slower than the path's rates ask (`sweep_rate`) as the square root of the sheet's flat extent (in units
# of its longest edge) beyond this: the gap grows in proportion to it and falls as 1 / T^2. With the tree rooted at
# the pattern's centre (below) at most 0.022 x the extent of the tolerance was measured at x2 (12 x 12 and 16 x 16
# sheets at a zigzag of 0.2 edge), so at most 0.65 of it at any extent (a 20 x 20 sheet, extent 27: 0.52 at x2).
# Rooted at the input crease's face the gaps were twice as large, and this extent 15.
LARGE_EXTENT = 30.0
# Why a file's scene is tuned (`Tuning.why`), as measured above and in docs/fold_files.md.
WHY = ("a file's thin panels lag near the lock a sweep ends at by what MuJoCo's regulariser R lets through "
       "(4 x 4 sheet of 50:1 panels: 4.25x the angle tolerance at R / 10^4, 0.042x at R / 10^6)")
LARGE_WHY = ("a large sheet's closure gap peaks mid-path and grows with its extent (12 x 12, 16 x 16 Miura sheets: "
             "1.1-1.6x its tolerance, 0.68-0.97x at 1.2x the time constant)")
# Exact frame angles may be this far (rad) from the rigid motion through them: FOLD writers round angles (the
# same allowance as `numeric_pattern.TARGET_TOL`).
FRAMES_TOL = TARGET_TOL
# A folded state whose every angle is within this (rad) of flat is flat: the trace could not be driven from it
# (`numeric_pattern` refuses such an input crease).
FLAT_STATE = 1e-6
# A step of the motion in which no crease turns more than this (rad) says nothing about their rates (repeated frames).
MOVING = 1e-9
# Steadiness scores (fractions of the fastest crease's rate) this close are a tie (`steadiest`).
TIE = 1e-9
# Creases along other directions tried when the first driven crease's trace cannot leave its start (`_trial`), and
# creases tied as the steadiest tried in turn (`fold_scene`): at most this many.
RETRIES = 6


def longest_edge(pattern: CreasePattern) -> float:
    """Length (m) of the pattern's longest face side."""
    v = pattern.vertices
    return max(float(np.max(np.linalg.norm(v[list(f)] - v[list(f[1:] + f[:1])], axis=1))) for f in pattern.faces)


def unit_size(pattern: CreasePattern) -> tuple[CreasePattern, float]:
    """The pattern scaled so that its longest edge is 1, and that edge's length L (m)."""
    size = longest_edge(pattern)
    creases = tuple(replace(c, height=c.height / size) for c in pattern.creases)
    border = tuple((a, b, h / size) for a, b, h in pattern.border_heights)
    return replace(pattern, vertices=pattern.vertices / size, creases=creases, border_heights=border), size


def parse_inputs(text: str | None, pattern: CreasePattern) -> tuple[str, ...] | None:
    """Crease names from a comma list (`e1,e5`); ParameterError naming an unknown one."""
    if text is None:
        return None
    if not isinstance(text, str):
        raise ParameterError(f"input crease {text!r} is a {type(text).__name__}; name creases as text, e<FOLD edge "
                             "index>[,e<FOLD edge index>...]")
    names = tuple(t.strip() for t in text.split(",") if t.strip())
    known = {c.name for c in pattern.creases}
    for name in names:
        if name not in known:
            raise ParameterError(f"input crease {name!r} is not a crease of the pattern; creases are e<FOLD edge "
                                 f"index>, e.g. {', '.join(sorted(known)[:5])}")
    if not names:
        raise ParameterError(f"--input {text!r} names no crease; give e<edge index>[,e<edge index>...]")
    return names


def fold_scene(path: str | Path, input_crease: str | None = None, frames_tolerance: float | None = None) -> Scene:
    """
    Build a scene from a FOLD file; `input_crease` is one crease name or a comma list. Frames farther than
    `frames_tolerance` (rad) from the rigid motion fail; by default FRAMES_TOL when the frames' angles are exact,
    and none (reported only) when they were measured from 3-D coordinates (panels that bend).

    Raises
    ------
    ParameterError
      For a file with neither fold angles nor M/V letters, an unknown input crease, or a driven crease without an
      angle.
    """
    fold = read_fold(path)
    pattern, size = unit_size(fold.pattern)
    names = [c.name for c in pattern.creases]
    if not names:
        raise ParameterError(f"{path}: the pattern has no crease (every edge is a border or a cut): nothing folds")
    edges = [pattern.crease_faces(c) for c in pattern.creases]
    reached = breadth_first_depths(pattern.face_names, edges, pattern.face_names[0])
    if len(reached) < len(pattern.face_names):  # before the trace: one sheet is one mechanism
        apart = [f for f in pattern.face_names if f not in reached]
        raise ParameterError(
            f"{path}: the paper is in separate pieces (no crease joins faces {', '.join(apart[:8])}"
            f"{' ...' if len(apart) > 8 else ''} to face {pattern.face_names[0]}; cut edges C or borders part them): "
            "validate each piece as a file of its own"
        )
    frames = fold.frames if fold.frames is not None and len(fold.frames) else None
    target = frames[-1] if frames is not None else fold.fold_angles
    signs = assignment_signs(pattern)
    if target is not None and not np.any(np.abs(np.nan_to_num(target)) > FLAT_STATE):
        target = None  # a flat state (a cone's nearest developable state is one) says no more than the letters
    several = frames if frames is not None and len(frames) > 1 else None
    folded = np.abs(target[np.nan_to_num(target) != 0]) if target is not None else None
    fully = several is None and folded is not None and bool(np.all(folded >= np.pi - LOCK_MARGIN))
    if fully:
        # every folded crease at +-180 deg is how most FOLD writers mark "fully folded": the same statement as M/V
        # letters, a side per crease, so it is traced as letters are (from flat, each crease kept on its side, the
        # branch picked by those sides). Traced as a direction instead, a 4 x 3 Miura sheet driven by a straight
        # crease left flat on the branch where only straight creases fold (mobility 3, one input: 0.38 rad error)
        signs, target = np.sign(np.nan_to_num(target)), None
    if target is None and not np.any(signs):
        raise ParameterError(
            f"{path}: no folded state (edges_foldAngle all zero or absent in every frame) and no M/V letters; the "
            "numeric reference traces the motion towards a folded state or from flat with the letters' signs, so "
            "the file needs one of them"
        )
    letters_only = target is None
    inputs = parse_inputs(input_crease, pattern)
    kwargs = {"frames": several, "signs": signs if letters_only else None}
    reference = None if several is not None else target
    if inputs is None:
        firsts, trial, allowed = _choose_inputs(pattern, reference, several, signs if letters_only else None)
        stopped = []
        for k in firsts:  # the steadiest creases in turn, until one's trace leaves flat
            inputs = _by_rank(trial, allowed, (names[k],))
            # the input choice's one-input trial trace is this very path when its crease is the one chosen
            kinematics = trial if trial.inputs == inputs else PatternPath(pattern, inputs, reference, **kwargs)
            if len(kinematics.s_nodes) > 1:
                break
            stopped.append((inputs, kinematics))
        else:  # none left flat: the trial's own crease when it did (`_trial`), else the steadiest's stop
            inputs, kinematics = (trial.inputs, trial) if len(trial.s_nodes) > 1 else stopped[0]
    else:
        kinematics = PatternPath(pattern, inputs, reference, **kwargs)
    # the inputs were counted on the one-input trial's motion; the motion traced may be more singular (a
    # triangulated grid folded along one line: 37 inputs, the generic count, where that motion has 109 freedoms to
    # first order, so the held inputs leave the rest undetermined and the closed-form check's continuation drifted
    # off, 0.14 rad on a 3 x 3 grid): then as many inputs as it has there, the ones picked first kept
    if input_crease is None and (more := _by_rank(kinematics, allowed, inputs)) != inputs:
        inputs, kinematics = more, PatternPath(pattern, more, reference, **kwargs)
    if frames_tolerance is not None and frames_tolerance < 0:
        raise ParameterError(f"frames tolerance {frames_tolerance:g} rad: it must be >= 0")
    kinematics.state_fit = fold.fit
    from_coords = getattr(fold, "frames_from_coords", False)
    kinematics.frames_tolerance = frames_tolerance if frames_tolerance is not None else None if from_coords \
        else FRAMES_TOL
    # MuJoCo locks the F creases of a spanning forest of them: one closing a cycle of F creases (four round a
    # vertex, as the bird base's diagonal marks) is held flat by the others, and a cut joint cannot be coupled
    flat = tuple(names[c.joint] for c in lock_flat(pattern))
    held = [names[k] for k in pattern.spanning_creases(prefer=flat) if names[k] in flat]
    # A shortest-path tree from the face at the pattern's centre: every closure row's Jacobian runs along its bodies'
    # paths to the root, so the tree's depth sets MuJoCo's cost and its lever arms the closure gap. On the 16 x 16
    # Miura sheet (depth 31 from the input crease's face, Kruskal in crease order; 16 from the centre) MuJoCo's run
    # took 3.85 -> 2.01 s and the gap halved, the angle error the same (docs/performance.md, "FOLD files").
    mechanism = pattern_mechanism(pattern, root=central_node(pattern.face_names, edges), keep=inputs,
                                  couplings=tuple((n, n, 0.0) for n in held), breadth_first=True)
    # frames: the motion they describe, from the first to the last (the trace from flat to the first only finds it)
    if several is not None:
        sweep = (kinematics.frame_distances[0]["input"], kinematics.frame_distances[-1]["input"])
    else:
        sweep = (SWEEP_FROM * motion_end(kinematics), motion_end(kinematics))
    multi = not kinematics.path_is_input
    source = "frames" if several is not None else "+-180 deg fold angles, as M/V sides" if fully else \
        "M/V letters" if letters_only else "folded state"
    large = len(pattern.creases) > SPARSE_FROM
    extent = fold_mesh.size(pattern.vertices)  # units of the longest edge (`unit_size`)
    tuning = Tuning(fast_regularization_scale=REGULARIZATION_SCALE, why=WHY)
    if large:
        tuning = replace(tuning, sweep_time_scale=max(1.0, np.sqrt(extent / LARGE_EXTENT)),
                         fast_timeconst_scale=LARGE_TIMECONST_SCALE, why=f"{WHY}; {LARGE_WHY}")
    return Scene(
        name=f"fold-{Path(path).stem}", params={"size_m": size}, kinematics=kinematics, mechanism=mechanism,
        loop_joints=tuple(names), drive_joint=inputs[0], drive_scale=1.0, path=(float(sweep[0]), float(sweep[1])),
        tuning=tuning,
        notes=f"from {Path(path).name} ({source}), lengths in units of its longest edge {size:.6g} m, inputs "
        f"{', '.join(inputs)}; {kinematics.summary()}" + "".join(f"; read: {note}" for note in fold.notes),
        pattern=pattern, drive_joints=tuple(inputs) if multi else (), drive_path=kinematics.path if multi else None,
        adjustments=fold.fit.adjustments if fold.fit is not None else (),
        source_notes=fold.notes, numbering=None if fold.numbering is None else fold.numbering.scaled(1.0 / size),
    )


def motion_end(kinematics: PatternPath) -> float:
    """
    The input (rad) a state or letters sweep ends at: a state on the rigid motion is what the file asks about, so
    its input; a direction, as far as the trace went.
    """
    lo, hi = kinematics.branches()[0].domain
    return kinematics.target_input if kinematics.target_input is not None else hi if abs(hi) >= abs(lo) else lo


def _choose_inputs(pattern: CreasePattern, target, frames, signs) -> tuple[tuple[int, ...], PatternPath, np.ndarray]:
    """
    The steadiest creases of the motion, tied ones in the order to try them (`steadiest`: over the frames, the first
    of them only, else over each crease's own sweep along the one-input trace of `_trial`); that trace; and the
    creases an input may be (not F, with an angle). Each first input is joined by as many others as the motion has
    freedoms (`_by_rank`, in `fold_scene`).
    """
    # letters only: a U crease has no direction to be driven in (free, as a null angle)
    state = frames[-1] if frames is not None else target if target is not None else np.where(signs != 0, signs, np.nan)
    given = np.all(np.isfinite(frames), axis=0) if frames is not None else np.isfinite(state)
    usable = np.array([c.assignment != "F" for c in pattern.creases]) & given & (np.nan_to_num(state) != 0)
    if not np.any(usable):
        raise ParameterError("every crease is flat, free (null) or F in the folded state: no crease to drive")
    first = int(np.argmax(np.where(usable, np.abs(np.nan_to_num(state)), -1.0)))
    if frames is not None:
        first = steadiest(frames, usable, first)[0]
    first, trial = _trial(pattern, first, usable, target, frames, signs)
    firsts = (first,)
    if frames is None:
        end = motion_end(trial)
        on = (trial.s_nodes * np.sign(end) >= 0) & (np.abs(trial.s_nodes) <= abs(end))
        nodes = trial.nodes[on][np.argsort(np.abs(trial.s_nodes[on]))]  # from flat to the end
        # driven, crease j would sweep from SWEEP_FROM of its end angle to its end angle
        inside = np.abs(nodes) >= SWEEP_FROM * np.abs(nodes[-1]) - MOVING
        firsts = steadiest(nodes, usable, first, inside[:-1] & inside[1:])[:RETRIES]
    allowed = np.array([c.assignment != "F" for c in pattern.creases]) & given
    return firsts, trial, allowed


def _by_rank(kinematics: PatternPath, allowed: np.ndarray, first: tuple[str, ...]) -> tuple[str, ...]:
    """
    As many inputs as the traced motion has freedoms at its middle node, the `first` ones kept and the others picked
    by rank among the `allowed` creases (not F, with an angle); `first` itself when it is enough.
    """
    names = [c.name for c in kinematics.pattern.creases]
    middle = len(kinematics.nodes) // 2
    m = int(kinematics.mobility[middle])
    if m <= len(first):
        return first
    picked = independent_joints(kinematics.loop_system(), kinematics.nodes[middle], m, among=allowed,
                                first=tuple(names.index(n) for n in first))
    return tuple(names[k] for k in picked)


def _trial(pattern: CreasePattern, first: int, usable: np.ndarray, target, frames, signs) -> tuple[int, PatternPath]:
    """
    The one-input trace driven by crease `first`; when it cannot leave its start (frames aside), the first of the
    usable creases along other directions whose trace can, up to RETRIES of them. A Miura sheet driven by a zigzag
    crease may stop at its first step from flat (0.063 rad: the closest closed pose folds another zigzag crease
    against its letter, as a square grid's straight-crease-only motion would), while driven by a straight crease it
    folds to its lock: a 3 x 4 sheet of 73-deg parallelograms as Rabbit Ear writes it (a zigzag crease first), 6 x 6
    sheets at 80-89.5 deg.
    """
    names = [c.name for c in pattern.creases]
    trial = PatternPath(pattern, names[first], target, frames=frames, signs=signs)
    if frames is not None or len(trial.s_nodes) > 1:
        return first, trial
    seen = {_line_direction(pattern, first)}
    for k in np.flatnonzero(usable):
        direction = _line_direction(pattern, int(k))
        if direction in seen:
            continue
        seen.add(direction)
        other = PatternPath(pattern, names[k], target, frames=frames, signs=signs)
        if len(other.s_nodes) > 1:
            return int(k), other
        if len(seen) > RETRIES:
            break
    return first, trial


def _line_direction(pattern: CreasePattern, k: int) -> int:
    """Crease k's direction in the sheet, as a whole number of milliradians in [0, pi): creases along one line share
    it."""
    d = pattern.direction(pattern.creases[k])
    return round(1000 * float(np.arctan2(d[1], d[0]) % np.pi)) % round(1000 * np.pi)


def steadiest(
    states: np.ndarray, usable: np.ndarray, default: int, swept: np.ndarray | None = None
) -> tuple[int, ...]:
    """
    The usable creases whose rate stays the largest fraction of the fastest crease's along `states` (m, n_creases)
    (rad, in the motion's order), over the steps `swept` (m - 1, n_creases) marks for each crease (default all): the
    best and every crease within TIE of its score, `default` first when it is one of them, then in crease order;
    (`default`,) when nothing moves. Driven, the steadiest crease gears every other crease up the least, so MuJoCo's
    lag behind the drive is amplified the least; a crease near a turning point (rate -> 0) scores 0 (measured scores
    and lags: docs/fold_motion.md). Ties are a set, not a pick by rounding: the creases of a regular sheet tie (the
    16 x 16 Miura sheet's trial crease is one of them, so its motion is traced once), and the bird base's mirror
    midline halves e16 and e17 score 0.840562105780293 within 2e-15, where a change of one unit in the last place of
    the loop residual picked either; driven by e16 (with the inputs picked after it) its straight line in inputs
    ends at once, e24 against its letter, so the callers try the tied creases in turn (`fold_scene`).
    """
    steps = np.nan_to_num(np.abs(np.diff(states, axis=0)))  # a free (null) entry has no rate: 0
    fastest = np.max(steps, axis=1, initial=0.0)
    counted = (fastest > MOVING)[:, None] & (np.ones(steps.shape, dtype=bool) if swept is None else swept)
    if not np.any(counted & usable):
        return (default,)
    ratio = np.where(counted, steps / np.where(fastest > MOVING, fastest, 1.0)[:, None], np.inf)
    score = np.where(usable, np.where(np.any(counted, axis=0), np.min(ratio, axis=0), 0.0), -1.0)
    tied = [int(k) for k in np.flatnonzero(score >= np.max(score) - TIE)]
    return (default, *(k for k in tied if k != default)) if default in tied else tuple(tied)
