"""`sim-origami bench [SCENE]`: run time against error, measured in one run (CPU time, best of repeats).

With a SCENE: the Pareto sweep of `sim_origami.pareto` (integrator, step, closure time constant, solimp, closure
type, drive) on its first branch, printed as the front with every ratio to MuJoCo's defaults and the presets,
the harness's loop against a bare `mj_step` loop, and pareto.csv / pareto.png in --out.

Without: the cases of issue 2, the general vertex (60, 100, 90, 110) deg on one branch, rho1 0.4 -> 1.6 rad,
and the Miura vertex (30, 60) deg up to 0.95 theta_limit. For each: max angle error with the
fast and accurate presets and with projection, the CPU time of the stepping loop, the ratio of
the harness's loop to a bare `mj_step` loop on the same model, and the closed form's throughput.
Times are reported, never asserted.
"""

import argparse
import json
import time
from pathlib import Path

import numpy as np

from .. import scenes
from ..checks.paths import compare
from ..files import claimed_folder, write_text
from ..mjcf import ModelOptions
from ..plots import plot_pareto
from ..presets import ACCURATE, FAST
from ..simulate import compile_model, project, simulate
from ..studies import pareto
from .options import add_params, out_folder, parse_params, whole_number_at_least

NAME = "bench"
HELP = "benchmark run time against error (fast, accurate, projection) and analytic throughput"

CASES = (
    ("vertex4", {}, "odd2", 0.4, 1.6),
    ("miura", {}, "miura", None, None),  # default sweep 0.25 -> 0.95 theta_limit
    ("miura", {}, "miura", "0.1lim", None),  # from 0.1 theta_limit: near the flat bifurcation
)


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", nargs="?", help="a scene: its Pareto sweep (default: the issue-2 cases)")
    add_params(parser)
    parser.add_argument("--quick", action="store_true", help="RK4 and Euler at 1.25, 2.5, 5 ms only")
    parser.add_argument("--out", type=out_folder,
                        help="output folder for pareto.csv / pareto.png (default runs/bench-<scene>)")
    parser.add_argument("--force", action="store_true", help="write into a folder holding files this tool did not")
    parser.add_argument("--repeats", type=whole_number_at_least("--repeats", 1), default=3,
                        help="best of this many runs per timing")
    parser.add_argument("--json", action="store_true")


def _best(fn, repeats: int):
    out, best = None, np.inf
    for _ in range(repeats):
        t = time.thread_time()
        out = fn()
        best = min(best, time.thread_time() - t)
    return out, best


def bench_case(name, params, branch, start, stop, repeats) -> dict:
    scene = scenes.get(name).build(**params)
    lo, hi = scene.branch_path(branch)
    if start == "0.1lim":
        start = 0.1 * scene.kinematics.branch(branch).domain[1]
    start = lo if start is None else start
    stop = hi if stop is None else stop
    row = {"scene": name, "branch": branch, "input_rad": [start, stop]}
    own = scene.tuning.preset
    models = {preset: compile_model(scene, ModelOptions(preset=preset)) for preset in (FAST, ACCURATE, own)}
    for preset in (FAST, ACCURATE):
        runs = [simulate(scene, branch, start=start, stop=stop, model=models[preset]) for _ in range(repeats)]
        if preset == FAST:
            runs_fast = runs
        row[f"{preset.name}_error_rad"] = compare(scene, branch, runs[0].q).max_error()
        row[f"{preset.name}_step_cpu_s"] = min(r.cpu_time_s for r in runs)
        row[f"{preset.name}_steps"] = runs[0].steps
        if preset == FAST:
            row["fast_call_cpu_s"] = _best(lambda: simulate(scene, branch, start=start, stop=stop,
                                                            model=models[own]), repeats)[1]
    row["bare_loop_cpu_s"] = pareto.bare_loop_cpu(scene, branch, runs_fast[0].target, repeats)
    row["harness_loop_over_bare"] = row["fast_step_cpu_s"] / row["bare_loop_cpu_s"]
    proj, cpu = _best(lambda: project(scene, branch, np.linspace(start, stop, 200), model=models[own]), 1)
    row["projection_error_rad"] = compare(scene, branch, proj.q).max_error()
    row["projection_cpu_s_per_sample"] = cpu / 200
    x = np.linspace(start, stop, 1_000_000)
    _, cpu = _best(lambda: scene.kinematics.evaluate(branch, x), repeats)
    row["analytic_values_per_s"] = len(x) / cpu
    return row


def pareto_table(name: str, points: list[pareto.Point], harness: float) -> str:
    """The front, MuJoCo's defaults and the presets with their ratios to the defaults, as a markdown table."""
    default = points[0]
    shown = [default, *[p for p in points if p.setting.label.startswith("preset ")], *pareto.front(points)]
    lines = [f"{name}: MuJoCo defaults {default.error:.2e} rad in {default.cpu * 1e3:.1f} ms of CPU; the harness's "
             f"loop costs {harness:.2f}x a bare mj_step loop", "",
             "| setting | max error (rad) | CPU (ms) | more accurate than the defaults | CPU vs the defaults |",
             "|---|---|---|---|---|"]
    seen = set()
    for p in shown:
        if p.setting.label in seen:
            continue
        seen.add(p.setting.label)
        front = " (front)" if p in pareto.front(points) else ""
        lines.append(f"| {p.setting.label}{front} | {p.error:.2e} | {p.cpu * 1e3:.1f} | {default.error / p.error:.3g}x "
                     f"| {p.cpu / default.cpu:.2f}x |")
    return "\n".join(lines)


def run_scene(args: argparse.Namespace) -> int:
    """The Pareto sweep of one scene: table on stdout, pareto.csv and pareto.png in --out."""
    scene = scenes.get(args.scene).build_from_user(parse_params(args.param))
    out = Path(args.out or f"runs/bench-{scene.name}")
    with claimed_folder(out, force=args.force) as stage:  # written beside the last results, swapped in at the end
        branch, points, harness = pareto.sweep(scene, quick=args.quick, repeats=args.repeats)
        rows = [
            f"{scene.name},{p.setting.label},{p.setting.integrator},{p.setting.h:g},{p.setting.tau:g},"
            f"{p.setting.solimp[0]:g},{p.setting.closure},{p.setting.drive},{p.error:.6g},{p.cpu:.6g}"
            for p in points
        ]
        write_text(stage / "pareto.csv", "scene,setting,integrator,h_s,tau_s,solimp,closure,drive,error_rad,cpu_s\n"
                   + "\n".join(rows) + "\n")
        plot_pareto({scene.name: points}, stage / "pareto.png")
    if args.json:
        print(json.dumps([{"setting": p.setting.label, "error_rad": p.error, "cpu_s": p.cpu} for p in points]))
    else:
        print(pareto_table(f"{scene.name} ({branch}, {pareto.SWEEP_S:g} s sweep)", points, harness))
        print(f"\noutputs in {out}/")
    return 0


def run(args: argparse.Namespace) -> int:
    if args.scene:
        return run_scene(args)
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
              f"| {r['analytic_values_per_s']:.2e} |")
    return 0
