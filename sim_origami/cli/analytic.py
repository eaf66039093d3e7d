"""`sim-origami analytic SCENE --input V1,V2,... [--json]`: closed-form joints on every branch."""

import argparse
import json

from .. import scenes
from ..conventions import rad_to_deg
from .options import add_params, parse_degrees, parse_params

NAME = "analytic"
HELP = "evaluate the closed form on every branch (input in degrees; JSON in radians)"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene")
    add_params(parser)
    parser.add_argument("--input", required=True, help="comma-separated input values in degrees")
    parser.add_argument("--json", action="store_true", help="print JSON (radians; null outside a domain)")


def run(args: argparse.Namespace) -> int:
    scene = scenes.get(args.scene).build_from_user(parse_params(args.param))
    kin = scene.kinematics
    x = parse_degrees(args.input)
    branches = []
    for b in kin.branches():
        values, valid = kin.evaluate(b.name, x)
        joints = {
            name: [float(v) if ok else None for v, ok in zip(values[:, k], valid, strict=True)]
            for k, name in enumerate(kin.joint_names)
        }
        branches.append({"name": b.name, "domain": list(b.domain), "joints": joints})
    if args.json:
        doc = {"scene": scene.name, "params": scene.params,
               "input": {"joint": kin.input_name, "values": x.tolist()}, "branches": branches}
        print(json.dumps(doc))
        return 0
    for b in branches:
        print(f"branch {b['name']}:")
        print("  " + " ".join(f"{n:>12s}" for n in (kin.input_name, *kin.joint_names)) + "  (deg)")
        for i, xi in enumerate(x):
            cells = [b["joints"][n][i] for n in kin.joint_names]
            text = " ".join(f"{rad_to_deg(c):12.6f}" if c is not None else f"{'-':>12s}" for c in cells)
            print(f"  {rad_to_deg(xi):12.6f} {text}")
    return 0
