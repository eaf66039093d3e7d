"""`sim-origami describe SCENE` (or `--linkage FILE`): parameters, joints, input, branches and events."""

import argparse

from .. import scenes
from ..conventions import rad_to_deg
from ..errors import ParameterError
from ..scenes.linkage_file import linkage_scene
from .options import add_params, parse_params

NAME = "describe"
HELP = "show a scene's parameters (units, defaults), joints, input, branches and events"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", nargs="?", help="scene name (see list); omit with --linkage")
    parser.add_argument("--linkage", metavar="FILE", help="a linkage file (docs/linkage_files.md) instead of a scene")
    add_params(parser)


def run(args: argparse.Namespace) -> int:
    if (args.scene is None) == (args.linkage is None):
        raise ParameterError("give a SCENE or --linkage FILE")
    if args.linkage is not None:
        if args.param:
            raise ParameterError("-p sets a registered scene's parameters; a --linkage file holds its own")
        scene = linkage_scene(args.linkage)
        print(f"{scene.name}: linkage file {args.linkage}")
        print("parameters: none (the file holds the geometry)")
    else:
        kind = scenes.get(args.scene)
        scene = kind.build_from_user(parse_params(args.param))
        print(f"{kind.name}: {kind.summary}")
        print("parameters:")
        for p in kind.params:
            value = p.to_user(scene.params[p.name])
            print(f"  {p.name:10s} = {value:<10.6g} {p.unit:4s} (default {p.default:g}) {p.help}")
    kin = scene.kinematics
    deg = rad_to_deg
    print(
        f"input: {kin.input_name} (degrees here, radians in JSON); drives {scene.drive_joint} x {scene.drive_scale:g}"
    )
    print(f"joints: {', '.join(kin.joint_names)}")
    columns = [kin.input_name] + [j for j in kin.joint_names if j != kin.input_name]
    more = ",..." if len(columns) > 9 else ""  # any subset of the joints will do
    print(f"reference CSV header (validate --reference): {','.join(f'{c}[deg]' for c in columns[:9])}{more}")
    mech = scene.mechanism
    reduced = mech.reduced()  # spherical joints as one joint each, without their spacer bodies
    cut = {mech.joints[i].ball or mech.joints[i].name for i in mech.cut_joints}
    spherical = f", {len(mech.balls)} spherical" if mech.balls else ""
    print(f"mechanism: {len(reduced.bodies)} bodies, {len(reduced.joints) - len(mech.balls)} hinges{spherical}, "
          f"root {mech.root}, loops cut at {', '.join(sorted(cut)) or 'none'}")
    tuning = scene.tuning
    scaled = f"; fast at {tuning.fast_step_scale:g}x its step and time constant" if tuning.fast_step_scale != 1 else ""
    if tuning.fast_timeconst_scale != 1:
        scaled += f"; fast's time constant {tuning.fast_timeconst_scale:g}x its own"
    if tuning.fast_regularization_scale != 1:
        scaled += f"; fast's regulariser {tuning.fast_regularization_scale:g}x its own"
    slower = f" x {tuning.sweep_time_scale:g}" if tuning.sweep_time_scale != 1 else ""
    print(f"preset: {tuning.preset.name}, sweep as long as its path's joint rates ask{slower}{scaled}")
    if tuning.why:
        print(f"tuned: {tuning.why}")
    print("branches:")
    for b in kin.branches():
        lo, hi = b.domain
        print(f"  {b.name:10s} {kin.input_name} in [{deg(lo):.4f}, {deg(hi):.4f}] deg: {b.description}")
    print("events:")
    for e in kin.events():
        print(f"  {e.kind:13s} at {kin.input_name} = {deg(e.input):9.4f} deg on {', '.join(e.branches)}: {e.detail}")
    if scene.contact_pairs:
        print(f"contact pairs: {', '.join('-'.join(p) for p in scene.contact_pairs)}")
    if scene.notes:
        print(f"notes: {scene.notes}")
    return 0
