"""`sim-origami mobility SCENE [-p NAME=VALUE] [--branch B] [--at DEG]`: truss method vs Jacobian rank.

At the branch's start pose (or at --at) and at each of its bifurcation events: the truss counts (Yang 2017,
§2.3: nodes j, bars b, couplings c, rank r, mobility m = 3j - 6 - r, states of self-stress s, Maxwell's
3j - 6 - b - c) next to the instantaneous mobility from the numeric loop closure's Jacobian and from
MuJoCo's constraint Jacobian, then the redundant bars (those carrying self-stress) at each pose. The idle spins of
links held by two spherical joints are free in the loop system and in MuJoCo but not in the truss: they are taken
off the numeric and MuJoCo counts, as validation does. Exit 0 when the three mobilities agree at every pose, 1
otherwise, 2 on bad input.
"""

import argparse

import numpy as np

from .. import scenes
from ..conventions import deg_to_rad, rad_to_deg
from ..errors import ParameterError
from ..simulate import mujoco_mobility
from ..truss import truss_mobility
from .options import add_params, parse_params

NAME = "mobility"
HELP = "truss mobility, self-stress and redundant bars next to the Jacobian-rank mobility (Yang 2017)"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene")
    add_params(parser)
    parser.add_argument("--branch", help="branch (default: the first; describe lists them)")
    parser.add_argument("--at", type=float, metavar="DEG", help="input in degrees instead of the branch's start")


def _poses(scene, branch: str, at: float | None) -> list[tuple[str, float]]:
    """(label, input in rad): the start (or --at) and the branch's bifurcation events."""
    kin = scene.kinematics
    kin.branch(branch)
    if at is not None and not np.isfinite(at):
        raise ParameterError(f"--at {at} deg is not a finite angle")
    first = ("at", float(deg_to_rad(at))) if at is not None else ("start", scene.branch_path(branch)[0])
    events = [("bifurcation", e.input) for e in kin.events() if e.kind == "bifurcation" and branch in e.branches]
    return [first, *events]


def run(args: argparse.Namespace) -> int:
    scene = scenes.get(args.scene).build_from_user(parse_params(args.param))
    kin = scene.kinematics
    branch = args.branch or kin.branches()[0].name
    rows, stresses = [], []
    loops = kin.loop_system()
    idle = scene.mechanism.idle_spins
    for label, x in _poses(scene, branch, args.at):
        q = scene.pose(branch, x)
        truss = truss_mobility(scene, q)
        numeric = loops.mobility(scene.mechanism_to_loop(q)[0]) - idle
        rows.append((label, x, truss, numeric, mujoco_mobility(scene, q) - idle))
        stresses.append((label, x, truss.redundant))
    print(f"{scene.name}, branch {branch}: truss method (Yang 2017, §2.3) vs Jacobian rank; input {kin.input_name}")
    if idle:
        print(f"  {idle} idle spin(s) of links held by two spherical joints taken off the numeric and MuJoCo counts")
    print(f"  {'pose':12s} {'input deg':>10s} {'j':>4s} {'b':>4s} {'c':>3s} {'r':>4s} {'truss m':>7s} {'s':>3s} "
          f"{'Maxwell':>7s} {'numeric m':>9s} {'MuJoCo m':>8s}")
    for label, x, t, numeric, mujoco in rows:
        print(f"  {label:12s} {rad_to_deg(x):10.4f} {t.nodes:4d} {t.bars:4d} {t.couplings:3d} {t.rank:4d} "
              f"{t.mobility:7d} {t.self_stress:3d} {t.maxwell:7d} {numeric:9d} {mujoco:8d}")
    for label, x, redundant in stresses:
        names = ", ".join(redundant) or "none"
        print(f"redundant bars at {label} {rad_to_deg(x):.4f} deg ({len(redundant)}): {names}")
    agree = all(t.mobility == numeric == mujoco for _, _, t, numeric, mujoco in rows)
    print("mobilities agree" if agree else "MOBILITIES DIFFER")
    return 0 if agree else 1
