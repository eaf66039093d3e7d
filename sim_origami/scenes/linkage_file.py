"""A scene from a linkage file (`linkage_file.read_linkage`): the numeric paths are the reference.

The file gives the mechanism, the driven joint and its range, and optionally a start configuration; the
reference is `kinematics.linkage_path.LinkagePath` (every branch through the start input, traced over the range,
named path-1, path-2, ...). The sweep is the input range (kept clear of each branch's domain ends by
`Scene.branch_path`), or, when branches meet inside it, its widest stretch between meetings with EVENT_CLEAR of
that stretch kept clear of them (as the built-in scenes' default sweeps avoid their bifurcations: there the solve
pins the joints only to the square root of its residual and MuJoCo's soft closures lag). The bifurcation study
still seeds MuJoCo at every meeting. The sweep lasts the file's `sweep_time_scale` times the preset's duration.
Lengths are in metres (the file's unit converted); a linkage whose size lies outside `LENGTH_RANGE` is refused as a
scene's length would be.
"""

from pathlib import Path

from ..errors import ParameterError
from ..kinematics.base import Kinematics
from ..kinematics.linkage_path import LinkagePath
from ..linkage_file import read_linkage
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
    mechanism = spec.mechanism
    size = mechanism.length_scale
    if not LENGTH_RANGE[0] <= size <= LENGTH_RANGE[1]:
        raise ParameterError(f"units.length: the linkage is {size:.3g} m across; sim_origami simulates "
                             f"{LENGTH_RANGE[0]:g} .. {LENGTH_RANGE[1]:g} m (give the right unit)")  # fmt: skip
    if mechanism.idle_spins:
        raise ParameterError("joints: a link between two spherical joints spins freely about the line through their "
                             "centres, a freedom no input drives and the comparison cannot pin; make one of them "
                             "revolute")  # fmt: skip
    names = tuple(j.name for j in mechanism.joints)
    balls = mechanism.balls.values()
    kinematics = LinkagePath(mechanism.loop_system(), spec.joint_names, names.index(spec.input_joint),
                             spec.input_range, spec.start, start_input=spec.start_input,
                             ball_middles=[iy for _, iy, _ in balls],
                             compared=[not j.ball for j in mechanism.joints])  # fmt: skip
    lo, hi = sweep(kinematics, *spec.input_range)
    notes = f"from {Path(path).name} ({spec.form} form); {kinematics.summary()}"
    return Scene(
        name=f"linkage-{spec.name}", params={"length_unit_m": spec.length_m}, kinematics=kinematics,
        mechanism=mechanism, loop_joints=names, drive_joint=spec.input_joint, drive_scale=1.0, path=(lo, hi),
        contact_pairs=spec.contact_pairs, sweep_time_scale=spec.sweep_time_scale,
        notes=f"{spec.notes}; {notes}" if spec.notes else notes,
    )  # fmt: skip


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
