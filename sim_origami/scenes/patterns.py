"""Scenes built on a crease pattern: mechanism, loop joints and FOLD export all come from the pattern.

The loop joints are the pattern's creases in their order (the kinematics' loop-joint order must be the same),
the drive crease stays in the spanning tree, and the fixed body defaults to the face on its right.
"""

from ..creases import CreasePattern
from ..kinematics.base import Kinematics
from ..origami import pattern_mechanism
from .base import DEFAULT_TUNING, Scene, Tuning


def pattern_scene(
    name: str,
    params: dict[str, float],
    kinematics: Kinematics,
    pattern: CreasePattern,
    *,
    drive: str,
    path: tuple[float, float],
    root: str | None = None,
    couplings: tuple[tuple[str, str, float], ...] = (),
    notes: str = "",
    collision_inset: float | None = None,
    self_contact: bool = False,
    contact_pairs: tuple[tuple[str, str], ...] = (),
    breadth_first: bool = False,
    tuning: Tuning = DEFAULT_TUNING,
) -> Scene:
    """A Scene whose mechanism is `pattern_mechanism(pattern)`, driven at crease `drive` (input = its fold angle)."""
    root = root or pattern.crease_faces(pattern.crease(drive))[0]
    mechanism = pattern_mechanism(
        pattern, root=root, keep=(drive,), couplings=couplings, collision_inset=collision_inset,
        breadth_first=breadth_first,
    )
    return Scene(
        name=name, params=params, kinematics=kinematics, mechanism=mechanism,
        loop_joints=tuple(c.name for c in pattern.creases), drive_joint=drive, drive_scale=1.0, path=path,
        notes=notes, pattern=pattern, self_contact=self_contact, contact_pairs=contact_pairs, tuning=tuning,
    )
