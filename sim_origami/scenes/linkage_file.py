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
"""

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..kinematics.base import Kinematics
from ..kinematics.linkage_path import LinkagePath
from ..linkage_file import read_linkage
from ..mechanism import Mechanism
from ..mjcf import PRESETS, preset_duration, preset_timestep
from .base import LENGTH_RANGE, Scene

# Share of the sweep's stretch kept clear of a bifurcation at each end it meets one. Measured on the plane-symmetric
# Bricard (case 10) over theta2 = -60 .. 60 deg, through its crossing at 0: fast path error 4.3e-5 rad, closure
# check 2.3e-12 rad (both fail); over 0 .. 60 deg with 10% clear they pass.
EVENT_CLEAR = 0.1


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
    least = max(2 * preset_timestep(p) / preset_duration(p) for p in PRESETS)  # before the trace, not at simulate
    if spec.sweep_time_scale < least:
        raise ParameterError(f"sweep_time_scale = {spec.sweep_time_scale:g}: it must be at least {least:g} (a sweep "
                             "of two time steps of every preset)")  # fmt: skip
    mechanism = spec.mechanism
    size = mechanism.length_scale
    if not LENGTH_RANGE[0] <= size <= LENGTH_RANGE[1]:
        raise ParameterError(f"units.length: the linkage is {size:.3g} m across; sim_origami simulates "
                             f"{LENGTH_RANGE[0]:g} .. {LENGTH_RANGE[1]:g} m (give the right unit)")  # fmt: skip
    names = tuple(j.name for j in mechanism.joints)
    balls = mechanism.balls.values()
    gauge, spinning = idle_spin_gauge(mechanism)
    kinematics = LinkagePath(mechanism.loop_system(), spec.joint_names, names.index(spec.input_joint),
                             spec.input_range, spec.start, start_input=spec.start_input,
                             ball_middles=[iy for _, iy, _ in balls], compared=[not j.ball for j in mechanism.joints],
                             gauge=gauge, observed=~spinning)  # fmt: skip
    lo, hi = sweep(kinematics, *spec.input_range)
    notes = f"from {Path(path).name} ({spec.form} form); {kinematics.summary()}"
    if gauge:
        notes += (f"; Kutzbach {kinematics.gruebler() + len(gauge)} = {kinematics.gruebler()} + {len(gauge)} idle "
                  f"spin{'s' if len(gauge) > 1 else ''} (held by {', '.join(spec.joint_names[j] for j in gauge)} = 0 "
                  "in the trace; the angles it moves are not outputs)")
    return Scene(
        name=f"linkage-{spec.name}", params={"length_unit_m": spec.length_m}, kinematics=kinematics,
        mechanism=mechanism, loop_joints=names, drive_joint=spec.input_joint, drive_scale=1.0, path=(lo, hi),
        contact_pairs=spec.contact_pairs, sweep_time_scale=spec.sweep_time_scale,
        notes=f"{spec.notes}; {notes}" if spec.notes else notes,
    )  # fmt: skip


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
