"""A scene from a linkage file (`linkage_file.read_linkage`): the numeric paths are the reference.

The file gives the mechanism, the driven joint and its range, and optionally a start configuration; the
reference is `kinematics.linkage_path.LinkagePath` (every branch through the start input, traced over the range,
named path-1, path-2, ...). The sweep is the input range (kept clear of each branch's domain ends by
`Scene.branch_path`), or, when branches meet inside it, its widest stretch between meetings with EVENT_CLEAR of
that stretch kept clear of them (as the built-in scenes' default sweeps avoid their bifurcations: there the solve
pins the joints only to the square root of its residual and MuJoCo's soft closures lag). The bifurcation study
still seeds MuJoCo at every meeting. The sweep lasts the file's `sweep_time_scale` times the preset's duration.
A link between two spherical joints spins freely about the line through their centres (an idle freedom, as the
built-in rssr scene's coupler): MuJoCo leaves it free, the trace holds it by one ball hinge (`idle_spin_gauge`), the
angles it moves are not outputs and the Kutzbach count leaves it out. Lengths are in metres (the file's unit
converted); a linkage whose size lies outside `LENGTH_RANGE` is refused as a scene's length would be.

Numbers as typed: when the loops do not close at the start input, the file's geometry numbers are moved to the
nearest mobile linkage within their precision (`nearest_mobile`), which is validated, every move on the scene's
`adjustments`; beyond the precision the refusal states how far the nearest mobile linkage lies.
"""

from collections.abc import Callable
from dataclasses import replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import block_diag

from ..closure import Coupling, LoopSystem
from ..conventions import LENGTH_RANGE
from ..errors import ParameterError
from ..geometry import wrap
from ..kinematics.base import Kinematics
from ..kinematics.linkage_path import MISS_ITER, MISS_STARTS, START_SHARE, AssemblyError, LinkagePath
from ..kinematics.numeric_pattern import CLOSE_TOL
from ..linkage_file import LinkageSpec, read_linkage
from ..mechanism import Mechanism
from ..path import correct, secant
from ..precision import Adjustment
from ..presets import PRESETS
from .base import DEFAULT_TUNING, Scene, Tuning

# Share of the sweep's stretch kept clear of a bifurcation at each end it meets one. Measured on the plane-symmetric
# Bricard (case 10) over theta2 = -60 .. 60 deg, through its crossing at 0: fast path error 4.3e-5 rad, closure
# check 2.3e-12 rad (both fail); over 0 .. 60 deg with 10% clear they pass.
EVENT_CLEAR = 0.1
# The nearest mobile linkage closes its loops at SAMPLES inputs spread over the stretch of the range along which the
# file's own linkage nearly closes: least-squares poses followed from the start in steps of at most SAMPLE_STEP (rad)
# while their residual stays within SAMPLE_GROWTH times the start's or what the numbers' precision can make there,
# and no joint jumps by JUMP (rad) in a step.
SAMPLES = 6
SAMPLE_STEP = 0.1
SAMPLE_GROWTH = 100.0
JUMP = 0.5
# Gauss-Newton steps of the projection, stopped when the residual falls below PROJECTION_TOL or stops halving
# (STALLED, below: the rounding floor of the placed model). It converges quadratically: on the Bennett file with beta
# printed to 4 decimals, residual 1.7e-7 -> 5.4e-14 -> 4.4e-16.
PROJECTION_ITER = 20
POSE_STEPS = 3
# The projection stops when the residual has not halved in this many steps in a row.
STALLED = 3
# Loops whose traced nodes close no better than this (median; rad, lengths in units of the loops' size) are no exact
# linkage: the trace accepts nodes to 100 x CLOSE_TOL, so a Bennett file with beta printed to 8 and 10 decimals traced
# its whole range, closed to 1.7e-11 and 2.4e-13, and failed validation (the projection's path error 8.1e-13 against
# 1e-13 at 10). The examples' nodes close to 2.7e-16 .. 8.6e-15 (median); a spherical 4R drawn 5500 units from the
# origin to 1.5e-13, its 17-digit numbers rounded to 5e-13: refused, 1.09 precision units from a mobile one.
UNCLOSED = CLOSE_TOL
# A projection that leaves more than this residual (rad, lengths in units of the loops' size) found no mobile linkage:
# the trace accepts nodes closed to 100 x CLOSE_TOL.
CONVERGED = 10 * CLOSE_TOL
PROJECTION_TOL = 1e-15
# Central differences of the loops in a value: steps of this times the value's size (at least its unit).
VALUE_STEP = 1e-6
# Singular values below this share of the largest are dropped in the projection's least-squares steps: the closures
# at several inputs repeat the linkage's few mobility conditions, and the rest is the residual's rounding. On the
# Bennett linkage drawn as axis lines to 4 decimals the 6 kept lie within 1e-2 of the largest, the rounding's below
# 4e-7 of it; kept down to 1e-10 those made the steps wander (residual 1e-11 after 15 steps, 4e-16 after 4 at 1e-8).
PROJECTION_RCOND = 1e-8


def linkage_scene(path: str | Path) -> Scene:
    """
    Build a scene from a linkage file (JSON or TOML, docs/linkage_files.md).

    Raises
    ------
    ParameterError
      For any field that breaks the schema (named by its path), a loop that cannot be assembled (with its closure
      residual), or a start configuration that does not close.
    """
    spec = read_linkage(path)
    adjustments: tuple[Adjustment, ...] = ()
    least = max(2 * p.timestep / p.sweep_duration for p in PRESETS)  # before the trace, not at simulate
    if spec.sweep_time_scale < least:
        raise ParameterError(f"sweep_time_scale = {spec.sweep_time_scale:g}: it must be at least {least:g} (a sweep "
                             "of two time steps of every preset)")
    mechanism = spec.mechanism
    size = mechanism.length_scale
    if not LENGTH_RANGE[0] <= size <= LENGTH_RANGE[1]:
        raise ParameterError(f"units.length: the linkage is {size:.3g} m across; sim_origami simulates "
                             f"{LENGTH_RANGE[0]:g} .. {LENGTH_RANGE[1]:g} m (give the right unit)")
    names = tuple(j.name for j in mechanism.joints)
    gauge, spinning = idle_spin_gauge(mechanism)
    try:
        kinematics = _kinematics(spec, gauge, spinning)
        floor = _closed_to(kinematics)
        if floor > UNCLOSED:
            raise AssemblyError(f"joints: the loops close only to {floor:.3g} along the traced motion (median of its "
                                f"nodes; an exact linkage closes to {CLOSE_TOL:g})")
    except AssemblyError as err:
        spec, adjustments = nearest_mobile(path, spec, gauge, err)
        mechanism = spec.mechanism
        try:
            kinematics = _kinematics(spec, gauge, spinning)
        except AssemblyError as again:
            raise ParameterError(f"{err}; the nearest mobile linkage found ({len(adjustments)} values moved) does not "
                                 f"assemble either: {again}") from None
    lo, hi = sweep(kinematics, *spec.input_range)
    notes = f"from {Path(path).name} ({spec.form} form); {kinematics.summary()}"
    if adjustments:
        worst = max(adjustments, key=lambda a: a.ratio)
        notes += (f"; validated as the nearest mobile linkage within the numbers' precision: {len(adjustments)} "
                  f"value{'s' if len(adjustments) > 1 else ''} moved, the most {worst.text()}")
    if gauge:
        notes += (f"; Kutzbach {kinematics.gruebler() + len(gauge)} = {kinematics.gruebler()} + {len(gauge)} idle "
                  f"spin{'s' if len(gauge) > 1 else ''} (held by {', '.join(spec.joint_names[j] for j in gauge)} = 0 "
                  "in the trace; the angles it moves are not outputs)")
    return Scene(
        name=f"linkage-{spec.name}", params={"length_unit_m": spec.length_m}, kinematics=kinematics,
        mechanism=mechanism, loop_joints=names, drive_joint=spec.input_joint, drive_scale=1.0, path=(lo, hi),
        contact_pairs=spec.contact_pairs,
        tuning=DEFAULT_TUNING if spec.sweep_time_scale == 1.0 else Tuning(
            sweep_time_scale=spec.sweep_time_scale, why="the file's sweep_time_scale"),
        notes=f"{spec.notes}; {notes}" if spec.notes else notes, adjustments=adjustments,
    )


def _closed_to(kinematics: LinkagePath) -> float:
    """The median closure residual of the traced nodes of every branch (rad, lengths in units of the loops' size)."""
    loops = kinematics.loop_system()
    q = np.vstack([nodes for _, nodes, _ in kinematics.nodes.values()])
    return float(np.median(loops.residual_size(loops.residual(q))))


def _kinematics(spec: LinkageSpec, gauge: tuple[int, ...], spinning: NDArray[np.bool_]) -> LinkagePath:
    """The file's branches traced (raises `AssemblyError` when the loops do not close at the start)."""
    mechanism = spec.mechanism
    names = tuple(j.name for j in mechanism.joints)
    return LinkagePath(mechanism.loop_system(), spec.joint_names, names.index(spec.input_joint), spec.input_range,
                       spec.start, start_input=spec.start_input,
                       ball_middles=[iy for _, iy, _ in mechanism.balls.values()],
                       compared=[not j.ball for j in mechanism.joints], gauge=gauge, observed=~spinning)


def nearest_mobile(
    path: str | Path, spec: LinkageSpec, gauge: tuple[int, ...], why: AssemblyError
) -> tuple[LinkageSpec, tuple[Adjustment, ...]]:
    """
    The linkage nearest the file's geometry numbers, in units of each number's precision, whose loops close at
    SAMPLES inputs spread over the range (a mobile one), and the numbers it moved (file units).

    A least-squares projection by Gauss-Newton: the unknowns are the numbers (their moves weighted by 1/precision)
    and the free joints' angles at the sample inputs (unweighted); each step is the least move of the numbers that
    closes the linearised loops, the poses following. The start poses are the least-squares poses of the file's own
    linkage, followed from the start input (`_near_poses`).

    Raises
    ------
    ParameterError
      `why`, with the distance to the nearest mobile linkage found, when it moves a number by more than its precision
      or when none is found.
    """
    # a D-H number typed as 0 is held: intersecting or parallel axes and a zero offset are choices, not roundings
    # (and a length a stays >= 0)
    values = [v for v in spec.values if v.precision > 0 and not (v.given == 0 and spec.form == "dh")]
    if not values:
        raise why
    given = np.array([v.given for v in values])
    scale = np.array([v.precision for v in values])
    mechanism = spec.mechanism
    input_index = tuple(j.name for j in mechanism.joints).index(spec.input_joint)
    pins = tuple(Coupling(j, input_index, 0.0) for j in gauge)

    def system(p: NDArray[np.float64]) -> LoopSystem | None:
        """The loops at values p (file units), idle spins pinned; None where the file would refuse them (a < 0)."""
        try:
            spec = read_linkage(path, {v.field: float(x) for v, x in zip(values, p, strict=True)})
        except ParameterError:
            return None
        loops = spec.mechanism.loop_system()
        return replace(loops, couplings=loops.couplings + pins)

    loops = system(given)
    if loops is None:  # not expected: these are the file's own numbers, read once already
        raise why

    def reach(q: NDArray[np.float64]) -> float:
        """The largest closure residual at pose q that moving each value by its precision makes (to first order)."""
        base = _weights(loops) * loops.residual(q)
        total = np.zeros_like(base)
        for i in range(len(values)):
            moved = system(given + scale * (np.arange(len(values)) == i))
            total += np.abs(_weights(loops) * moved.residual(q) - base) if moved is not None else 0.0
        return float(np.max(total))

    poses = _near_poses(loops, spec, input_index, reach)
    fixed = np.zeros(loops.n_joints, dtype=bool)
    fixed[input_index] = True
    free = ~fixed
    weights = _weights(loops)
    for _ in range(POSE_STEPS):  # the samples to their least-squares poses: a first step then sees the values' part
        for q in poses:
            q[free] -= np.linalg.lstsq(weights[:, None] * loops.jacobian(q)[:, free], weights * loops.residual(q))[0]
    z = np.zeros(len(values))
    best, stalled, previous = (np.inf, z, poses), 0, np.inf
    for _ in range(PROJECTION_ITER):
        loops = system(given + z * scale)
        if loops is None:  # a step out of what a file may hold: no mobile linkage that way
            break
        weights = _weights(loops)
        r = (loops.residual(poses) * weights).ravel()
        size = float(np.max(np.abs(r)))
        # full steps, even where the residual rises: a step along the mobile linkages towards the least move may (the
        # Bennett file with every number to 4 decimals and beta 48.6000, largest move in precision units: 168 at
        # 1.8e-8, 19 at 6.1e-9, 19 at 6.9e-16; with singular values kept down to 1e-10 a step there rose from 2.4e-10
        # to 6.6e-9 before 3.0e-16, and halving such steps back stalled at 1.7e-10)
        stalled = stalled + 1 if size >= 0.5 * previous else 0
        previous = size
        if size < best[0]:
            best = (size, z, poses)
        if size <= PROJECTION_TOL or stalled >= STALLED:  # the rounding floor, or no mobile linkage near
            break
        J_poses = block_diag(*(weights[:, None] * loops.jacobian(q)[:, free] for q in poses))
        J_values = np.empty((len(r), len(values)))
        for i in range(len(values)):
            step = np.zeros(len(values))
            step[i] = VALUE_STEP * max(abs(given[i] + z[i] * scale[i]), 1.0)
            # central differences, one-sided where a side is out of what a file may hold (a length a below 0)
            ends = [(h, e.residual(poses) * weights) for h in (1.0, -1.0)
                    if (e := system(given + z * scale + h * step)) is not None]
            if len(ends) == 1:
                ends.append((0.0, r.reshape(len(poses), -1)))
            (h1, r1), (h0, r0) = ends
            J_values[:, i] = (r1 - r0).ravel() / ((h1 - h0) * step[i]) * scale[i]
        # the linearised loops J_values z' + J_poses dq = J_values z - r, z' least: the poses take what they can
        target = J_values @ z - r
        U, s, _ = np.linalg.svd(J_poses, full_matrices=False)
        U = U[:, s > PROJECTION_RCOND * s[0]]
        z = np.linalg.pinv(J_values - U @ (U.T @ J_values), rcond=PROJECTION_RCOND) @ (target - U @ (U.T @ target))
        dq = np.linalg.pinv(J_poses, rcond=PROJECTION_RCOND) @ (target - J_values @ z)
        poses = poses.copy()
        poses[:, free] += dq.reshape(len(poses), -1)
    size, z, poses = best
    moved = given + z * scale
    ratio = float(np.max(np.abs(z)))
    worst = values[int(np.argmax(np.abs(z)))]
    far = (f"{worst.field} {worst.given:.10g} -> {moved[int(np.argmax(np.abs(z)))]:.10g}"
           f"{' ' + worst.unit if worst.unit else ''}, {ratio:.3g} times its precision {worst.precision:.2g}")
    closed = size <= CONVERGED
    if ratio > 1.0 and closed:
        raise ParameterError(f"{why}; the nearest mobile linkage lies {ratio:.3g} precision units away, beyond what "
                             f"the numbers as printed allow: {far}") from None
    if ratio > 1.0:
        raise ParameterError(f"{why}; no mobile linkage within the numbers' precision: the projection towards one "
                             f"moved them {ratio:.3g} precision units ({far}) and leaves a closure residual of "
                             f"{size:.3g} at {SAMPLES} inputs") from None
    if not closed:
        raise ParameterError(f"{why}; no mobile linkage found within the numbers' precision (closure residual "
                             f"{size:.3g} left at {SAMPLES} inputs, the numbers moved as far as {far})") from None
    exact = read_linkage(path, {v.field: float(x) for v, x in zip(values, moved, strict=True)})
    adjustments = tuple(Adjustment(v.field, v.given, float(x), v.precision, v.unit)
                        for v, x in zip(values, moved, strict=True) if x != v.given)
    return exact, adjustments


def _weights(loops: LoopSystem) -> NDArray[np.float64]:
    """Residual weights of the loop solve (translations in units of the loops' `length_scale`)."""
    loop = np.r_[np.ones(3), np.full(3, 1.0 / loops.length_scale)]
    return np.r_[np.tile(loop, len(loops.loops)), np.ones(len(loops.couplings))]


def _near_poses(
    loops: LoopSystem, spec: LinkageSpec, input_index: int, reach: Callable[[NDArray[np.float64]], float]
) -> NDArray[np.float64]:
    """
    SAMPLES least-squares poses (SAMPLES, n_joints) of a linkage whose loops do not quite close, spread over the
    stretch of the input range they can be followed along from the start: the given start configuration, or the
    best of MISS_STARTS random starts at the start input.
    """
    fixed = np.zeros(loops.n_joints, dtype=bool)
    fixed[input_index] = True
    lo, hi = spec.input_range
    if spec.start is not None:
        starts = [np.asarray(spec.start, dtype=float)]
    else:
        x0 = lo + START_SHARE * (hi - lo) if spec.start_input is None else spec.start_input
        rng = np.random.default_rng(0)
        starts = [rng.uniform(-np.pi, np.pi, loops.n_joints) for _ in range(MISS_STARTS)]
        for q in starts:
            q[input_index] = x0
    closed = [correct(loops, q, fixed, CLOSE_TOL, max_iter=MISS_ITER)[0] for q in starts]
    sizes = [float(loops.residual_size(loops.residual(q))) for q in closed]
    q0 = closed[int(np.argmin(sizes))]
    x0 = float(q0[input_index])
    # followed while the residual stays within a multiple of the start's or what the numbers' precision can make one
    # step on (the drawn pose of an axes file closes whatever its numbers: their rounding shows once the input moves)
    probe = q0.copy()
    probe[input_index] += SAMPLE_STEP if hi - x0 > x0 - lo else -SAMPLE_STEP
    limit = max(SAMPLE_GROWTH * max(min(sizes), CLOSE_TOL),
                reach(correct(loops, probe, fixed, CLOSE_TOL, max_iter=MISS_ITER)[0]))
    nodes = [(x0, q0)]
    for end in (lo, hi):
        behind, (x, q) = None, (x0, q0)
        while abs(end - x) > 1e-12:
            x_new = x + float(np.clip(end - x, -SAMPLE_STEP, SAMPLE_STEP))
            guess = q.copy() if behind is None else secant(behind[0], behind[1], x, q, x_new)
            guess[input_index] = x_new
            # closed to the limit only: the projection's Gauss-Newton steps polish the samples it takes
            q_new = correct(loops, guess, fixed, limit, max_iter=MISS_ITER)[0]
            if loops.residual_size(loops.residual(q_new)) > limit or np.max(np.abs(wrap(q_new - q))) > JUMP:
                break
            behind, (x, q) = (x, q), (x_new, q_new)
            nodes.append((x, q))
    nodes.sort(key=lambda node: node[0])
    picked = np.unique(np.round(np.linspace(0, len(nodes) - 1, SAMPLES)).astype(int))
    return np.array([nodes[k][1] for k in picked])


def idle_spin_gauge(mechanism: Mechanism) -> tuple[tuple[int, ...], NDArray[np.bool_]]:
    """
    For each link held only by two spherical joints (an idle spin about the line through their centres, Yang 2017,
    section 2.2): the hinge that holds the spin in the trace, and the joints (bool mask) whose angles the spin moves.

    The hinge is the ball hinge next to the link whose axis lies closest to that line: a ball's x hinge where the
    link is the ball's first body (the spin turns the ball's triad about the line from the parent side), its z hinge
    where it is the second. In the D-H form with no offset on the link, the far ball's x axis is the line itself,
    so that hinge is the spin exactly and its angle is 0 on the motion the rows describe.
    """
    spinning = np.zeros(len(mechanism.joints), dtype=bool)
    ends: dict[str, list[tuple[int, NDArray[np.float64], NDArray[np.float64]]]] = {}
    held_by_hinge = {b for j in mechanism.joints if not j.ball for b in (j.parent, j.child)}
    for name, (ix, _, iz) in mechanism.balls.items():
        parent_side, child_side = mechanism.ball_frames(name)
        ends.setdefault(mechanism.joints[ix].parent, []).append((ix, parent_side[:3, 3], parent_side[:3, 0]))
        ends.setdefault(mechanism.joints[iz].child, []).append((iz, child_side[:3, 3], child_side[:3, 2]))
    gauge = []
    for body, held in ends.items():
        if body in held_by_hinge or len(held) != 2:
            continue
        line = held[1][1] - held[0][1]
        line = line / max(float(np.linalg.norm(line)), 1e-300)
        gauge.append(max(held, key=lambda end: abs(float(end[2] @ line)))[0])
        for hinge, _, _ in held:
            ball = mechanism.joints[hinge].name[:-2]
            spinning[list(mechanism.balls[ball])] = True
    return tuple(gauge), spinning


def sweep(kinematics: Kinematics, lo: float, hi: float) -> tuple[float, float]:
    """The input range (rad), or its widest stretch between the bifurcations inside it, EVENT_CLEAR of the stretch
    kept clear of each bifurcation end."""
    cuts = sorted(e.input for e in kinematics.events() if e.kind == "bifurcation" and lo < e.input < hi)
    if not cuts:
        return lo, hi
    ends = [lo, *cuts, hi]
    k = max(range(len(ends) - 1), key=lambda i: ends[i + 1] - ends[i])
    a, b = ends[k], ends[k + 1]
    clear = EVENT_CLEAR * (b - a)
    return a + (clear if k > 0 else 0.0), b - (clear if k < len(ends) - 2 else 0.0)
