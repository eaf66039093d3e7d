"""A scene from your own closed form: `custom_scene(name, kinematics, mechanism, ...)`.

The closed form is any `kinematics.base.Kinematics` (the contract is documented there), written in your own
module; the mechanism is built from the package's blocks (`linkage.dh_mechanism` for a D-H loop,
`origami.vertex_mechanism` for a vertex, or `mechanism.Mechanism` directly). `custom_scene` checks that the two
fit together before anything is simulated and fills in the drive from `kinematics.loop_input()`. Register the
builder with `scenes.register` in a module that an installed package names under the entry point group
`sim_origami.scenes` (see `scenes.plugins` and docs/extending.md).
"""

import math

import numpy as np

from ..closure import LoopSystem
from ..errors import ParameterError
from ..kinematics.base import Kinematics
from ..mechanism import Mechanism
from .base import Scene

# Inputs per branch at which the contract is checked: evenly across the domain, ends included.
CHECK_SAMPLES = 7
# observe(loop_angles(v)) must give v back to this (rad): the two maps are inverse by the contract.
ROUND_TRIP_RAD = 1e-9


def check_kinematics(kinematics: Kinematics) -> None:
    """
    Check a closed form against the `Kinematics` contract at CHECK_SAMPLES inputs per branch: names, branch
    domains, `evaluate`'s shapes, validity and finiteness, `loop_input`, and that `observe` inverts
    `loop_angles`. Raises ParameterError naming the member and the rule.
    """
    kind = type(kinematics).__name__
    if not isinstance(kinematics, Kinematics):
        raise ParameterError(f"kinematics is a {kind}; it must subclass sim_origami.kinematics.base.Kinematics")
    name = getattr(kinematics, "input_name", None)
    joints = getattr(kinematics, "joint_names", None)
    if not isinstance(name, str) or not name:
        raise ParameterError(f"{kind}.input_name = {name!r}; it must be a non-empty string")
    if not isinstance(joints, tuple) or not joints or not all(isinstance(j, str) and j for j in joints):
        raise ParameterError(f"{kind}.joint_names = {joints!r}; it must be a non-empty tuple of strings")
    if len(set(joints)) != len(joints):
        raise ParameterError(f"{kind}.joint_names = {joints!r} names a joint twice")
    branches = kinematics.branches()
    if not branches:
        raise ParameterError(f"{kind}.branches() is empty; a closed form has at least one branch")
    if len({b.name for b in branches}) != len(branches):
        raise ParameterError(f"{kind}.branches() names a branch twice: {', '.join(b.name for b in branches)}")
    loops = kinematics.loop_system()
    if not isinstance(loops, LoopSystem):
        raise ParameterError(f"{kind}.loop_system() returned a {type(loops).__name__}, not a closure.LoopSystem")
    joint, scale = kinematics.loop_input()
    if not (0 <= joint < loops.n_joints and math.isfinite(scale) and scale != 0):
        raise ParameterError(f"{kind}.loop_input() = ({joint}, {scale}); it must be (a loop joint index in "
                             f"0..{loops.n_joints - 1}, a finite nonzero scale)")
    for b in branches:
        lo, hi = b.domain
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            raise ParameterError(f"{kind} branch {b.name!r} has domain ({lo}, {hi}); it must be finite, low < high")
        x = np.linspace(lo, hi, CHECK_SAMPLES)
        values, valid = kinematics.evaluate(b.name, x)
        values, valid = np.asarray(values), np.asarray(valid)
        if values.shape != (len(x), len(joints)) or valid.shape != (len(x),) or valid.dtype != bool:
            raise ParameterError(f"{kind}.evaluate({b.name!r}, {len(x)} inputs) returned shapes {values.shape} and "
                                 f"{valid.shape} ({valid.dtype}); they must be ({len(x)}, {len(joints)}) float and "
                                 f"({len(x)},) bool")
        if not valid.all():
            bad = float(x[~valid][0])
            raise ParameterError(f"{kind}.evaluate({b.name!r}) marks {name} = {bad:.6g} rad invalid inside the "
                                 f"branch's own domain [{lo:.6g}, {hi:.6g}] rad")
        if not np.all(np.isfinite(values)):
            raise ParameterError(f"{kind}.evaluate({b.name!r}) gives a value that is not finite inside its domain")
        q = kinematics.loop_angles(values)
        if np.shape(q) != (len(x), loops.n_joints):
            raise ParameterError(f"{kind}.loop_angles gives shape {np.shape(q)}; the loop system has "
                                 f"{loops.n_joints} joints, so it must be ({len(x)}, {loops.n_joints})")
        gap = float(np.max(np.abs(kinematics.observe(q) - values)))
        if not gap <= ROUND_TRIP_RAD:
            raise ParameterError(f"{kind}.observe(loop_angles(v)) differs from v by {gap:.3g} rad on branch "
                                 f"{b.name!r}; the two maps must be inverse (to {ROUND_TRIP_RAD:g})")


def custom_scene(
    name: str,
    kinematics: Kinematics,
    mechanism: Mechanism,
    *,
    params: dict[str, float] | None = None,
    loop_joints: tuple[str, ...] | None = None,
    drive_joint: str | None = None,
    drive_scale: float | None = None,
    path: tuple[float, float] | None = None,
    **options,
) -> Scene:
    """
    A `Scene` of your own closed form and mechanism, checked (`check_kinematics`) before anything runs.

    Parameters
    ----------
    params : the scene's parameter values (radians, metres) as the report shows them.
    loop_joints : mechanism joints that are the loop system's joints, in order (default: every mechanism joint,
      in order, when their number matches).
    drive_joint, drive_scale : the driven mechanism joint and its angle per unit input (default: the loop joint
      and scale `kinematics.loop_input()` names).
    path : default input sweep (rad); default the middle 80% of the first branch's domain.
    options : any other `Scene` field (contact_pairs, notes, ...); `tuning=Tuning(sweep_time_scale=4.0, why=...)`
      for runs tuned apart from the defaults.

    Raises
    ------
    ParameterError
      When the closed form breaks its contract or does not fit the mechanism; the message names the field.
    """
    check_kinematics(kinematics)
    n_loop = kinematics.loop_system().n_joints
    names = tuple(j.name for j in mechanism.joints)
    if loop_joints is None:
        if len(names) != n_loop:
            raise ParameterError(f"loop_joints not given and the mechanism has {len(names)} joints where the loop "
                                 f"system has {n_loop}; name the mechanism joint of each loop joint")
        loop_joints = names
    loop_joints = tuple(loop_joints)
    if len(loop_joints) != n_loop:
        raise ParameterError(f"loop_joints has {len(loop_joints)} names; the loop system has {n_loop} joints")
    unknown = [j for j in loop_joints if j not in names]
    if unknown:
        raise ParameterError(f"loop_joints {', '.join(unknown)} are not joints of the mechanism ({', '.join(names)})")
    index, scale = kinematics.loop_input()
    drive_joint = drive_joint or loop_joints[index]
    if drive_joint not in names:
        raise ParameterError(f"drive_joint {drive_joint!r} is not a joint of the mechanism ({', '.join(names)})")
    drive_scale = scale if drive_scale is None else float(drive_scale)
    if path is None:
        lo, hi = kinematics.branches()[0].domain
        path = (lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo))
    if not (len(path) == 2 and all(math.isfinite(p) for p in path) and path[0] != path[1]):
        raise ParameterError(f"path = {path!r} rad; it must be two different finite inputs (start, stop)")
    return Scene(name=name, params=dict(params or {}), kinematics=kinematics, mechanism=mechanism,
                 loop_joints=loop_joints, drive_joint=drive_joint, drive_scale=drive_scale,
                 path=(float(path[0]), float(path[1])), **options)
