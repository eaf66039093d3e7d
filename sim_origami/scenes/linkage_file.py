"""A scene from a linkage file (`linkage_file.read_linkage`): the numeric paths are the reference.

The file gives the mechanism, the driven joint and its range, and optionally a start configuration; the
reference is `kinematics.linkage_path.LinkagePath` (every branch through the start input, traced over the range,
named path-1, path-2, ...). The sweep is the input range (kept clear of each branch's domain ends by
`Scene.branch_path`), at the file's `sweep_time_scale` times the preset's duration. Lengths are in metres (the
file's unit converted); a linkage whose size lies outside `LENGTH_RANGE` is refused as a scene's length would be.
"""

from pathlib import Path

from ..errors import ParameterError
from ..kinematics.linkage_path import LinkagePath
from ..linkage_file import read_linkage
from .base import LENGTH_RANGE, Scene


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
    names = tuple(j.name for j in mechanism.joints)
    kinematics = LinkagePath(mechanism.loop_system(), spec.joint_names, names.index(spec.input_joint),
                             spec.input_range, spec.start, start_input=spec.start_input,
                             idle_spins=mechanism.idle_spins)  # fmt: skip
    lo, hi = spec.input_range
    notes = f"from {Path(path).name} ({spec.form} form); {kinematics.summary()}"
    return Scene(
        name=f"linkage-{spec.name}", params={"length_unit_m": spec.length_m}, kinematics=kinematics,
        mechanism=mechanism, loop_joints=names, drive_joint=spec.input_joint, drive_scale=1.0, path=(lo, hi),
        contact_pairs=spec.contact_pairs, sweep_time_scale=spec.sweep_time_scale,
        notes=f"{spec.notes}; {notes}" if spec.notes else notes,
    )  # fmt: skip
