"""`sim-origami bench`: run time against error, measured in one run (CPU time, best of repeats).

Cases of issue 2: the general vertex (60, 100, 90, 110) deg on one branch, rho1 0.4 -> 1.6 rad,
and the Miura vertex (30, 60) deg up to 0.95 theta_limit. For each: max angle error with the
fast and accurate presets and with projection, the CPU time of the stepping loop, the ratio of
the harness's loop to a bare `mj_step` loop on the same model, and the closed form's throughput.
Times are reported, never asserted.
"""

import argparse
import json
import time

import mujoco
import numpy as np

from .. import scenes
from ..checks.paths import compare
from ..mjcf import ModelOptions
from ..simulate import Bindings, compile_model, project, simulate, start_pose

NAME = "bench"
HELP = "benchmark run time against error (fast, accurate, projection) and analytic throughput"

CASES = (
    ("vertex4", {}, "odd2", 0.4, 1.6),
    ("miura", {}, "miura", None, None),  # default sweep 0.25 -> 0.95 theta_limit
    ("miura", {}, "miura", "0.1lim", None),  # from 0.1 theta_limit: near the flat bifurcation
)


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--repeats", type=int, default=3, help="best of this many runs per timing")
    parser.add_argument("--json", action="store_true")


def _best(fn, repeats: int):
    out, best = None, np.inf
    for _ in range(repeats):
        t = time.thread_time()
        out = fn()
        best = min(best, time.thread_time() - t)
    return out, best


def bare_loop_cpu(scene, branch: str, run, repeats: int) -> float:
    """
    CPU time of the minimal loop driving the same path: one eq_data write and one mj_step per
    step from the same start pose, with no logging, checks or feed-forward bookkeeping.
    """
    model, data = compile_model(scene, ModelOptions(preset="fast"))
    binds = Bindings(scene, model)
    setpoint = model.eq_data[model.equality(f"drive_{scene.drive_joint}").id]
    targets = (scene.drive_scale * run.target).tolist()
    pose = start_pose(scene, branch, float(run.target[0]))

    def loop():
        mujoco.mj_resetData(model, data)
        binds.set_pose(data, pose)
        mujoco.mj_forward(model, data)
        t = time.thread_time()
        for value in targets:
            setpoint[0] = value
            mujoco.mj_step(model, data)
        return time.thread_time() - t

    return min(loop() for _ in range(repeats))


def bench_case(name, params, branch, start, stop, repeats) -> dict:
    scene = scenes.get(name).build(**params)
    lo, hi = scene.branch_path(branch)
    if start == "0.1lim":
        start = 0.1 * scene.kinematics.branch(branch).domain[1]
    start = lo if start is None else start
    stop = hi if stop is None else stop
    row = {"scene": name, "branch": branch, "input_rad": [start, stop]}
    for preset in ("fast", "accurate"):
        runs = [simulate(scene, branch, preset=preset, start=start, stop=stop) for _ in range(repeats)]
        if preset == "fast":
            runs_fast = runs
        row[f"{preset}_error_rad"] = compare(scene, branch, runs[0].q).max_error()
        row[f"{preset}_step_cpu_s"] = min(r.cpu_time_s for r in runs)
        row[f"{preset}_steps"] = runs[0].steps
        if preset == "fast":
            row["fast_call_cpu_s"] = _best(lambda: simulate(scene, branch, start=start, stop=stop), repeats)[1]
    row["bare_loop_cpu_s"] = bare_loop_cpu(scene, branch, runs_fast[0], repeats)
    row["harness_loop_over_bare"] = row["fast_step_cpu_s"] / row["bare_loop_cpu_s"]
    proj, cpu = _best(lambda: project(scene, branch, np.linspace(start, stop, 200)), 1)
    row["projection_error_rad"] = compare(scene, branch, proj.q).max_error()
    row["projection_cpu_s_per_sample"] = cpu / 200
    x = np.linspace(start, stop, 1_000_000)
    _, cpu = _best(lambda: scene.kinematics.evaluate(branch, x), repeats)
    row["analytic_values_per_s"] = len(x) / cpu
    return row


def run(args: argparse.Namespace) -> int:
    rows = [bench_case(*case, args.repeats) for case in CASES]
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    print(
        "| scene | input (rad) | fast err | fast step CPU | loop/bare | fast call CPU | accurate err "
        "| accurate CPU | projection err | analytic values/s |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['scene']} {r['branch']} | {r['input_rad'][0]:.3f}-{r['input_rad'][1]:.3f} "
              f"| {r['fast_error_rad']:.1e} | {r['fast_step_cpu_s'] * 1e3:.1f} ms | {r['harness_loop_over_bare']:.2f} "
              f"| {r['fast_call_cpu_s'] * 1e3:.1f} ms | {r['accurate_error_rad']:.1e} "
              f"| {r['accurate_step_cpu_s']:.2f} s | {r['projection_error_rad']:.1e} "
              f"| {r['analytic_values_per_s']:.2e} |")  # fmt: skip
    return 0
