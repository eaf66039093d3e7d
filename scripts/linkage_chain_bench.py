"""How the CPU of a linkage file grows with its joints (issue 28, item 6): chains of N Bennett loops, as a table.

A chain of Bennett loops that share only a link moves with N freedoms (each loop turns about the shared link on its
own), which a linkage file refuses; loops that share a joint, and so the two links it joins, move with one. Loop
k + 1 here is a Bennett linkage whose joint 1 is loop k's joint 3, its link 1 loop k's link 3 and its link 4 loop
k's link 2 (ternary links): 2 new bodies and 3 new joints a loop, 3 N + 1 joints, 2 N + 2 bodies, N loops. A
Bennett linkage turns its opposite joints by opposite angles (theta3 = -theta1), so every loop's joint 1 sweeps the
input range or its mirror and the chain's gain is 1 at every pose: no loop nears a fold, however long the chain.
Loops alternate two Bennett linkages (a = 1 m, alpha = 30 deg, b = 1.5 m; a = 1.2 m, alpha = 40 deg, b = 1.6 m;
beta from sin(alpha)/a = sin(beta)/b), so no joint axis of one loop repeats one of the last. The file is the axes
form, drawn at the input 0.382 of the range from its low end (the D-H poses of eqn 1-18, every number printed to
17 digits, rad), the driven joint loop 1's joint 1 over -150 .. 150 deg.

Each size, one after another: the numeric trace (`scenes.linkage_file._kinematics`, the `LinkagePath` the scene
builds, after `read_linkage`) in this process, its CPU by `time.process_time`; then `sim-origami validate --linkage
FILE` (the scene's own preset, no --render) in a child process, its CPU (user + system) from
`resource.getrusage(RUSAGE_CHILDREN)`, its exit code and report.json's failing verdicts. The growth exponent is the
slope of log(CPU) against log(joints), least squares over the `--fit` largest sizes. `--profile N` runs the
validation of size N under cProfile and prints the functions of most cumulative and own time. Timings live here and
in docs/performance.md, never in tests; CPU on the shared 2-core machine varies by about 10 % from run to run.

    python scripts/linkage_chain_bench.py [--sizes 1,2,4,8,16,32,64] [--fit 3] [--profile 64] [--keep DIR]
"""

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import sim_origami  # noqa: F401  (before numpy: one OpenBLAS thread unless set, see sim_origami/__init__.py)

# isort: split
import numpy as np

from sim_origami.geometry import rot_x, rot_z, transform
from sim_origami.linkage_file import read_linkage
from sim_origami.scenes.linkage_file import _kinematics, idle_spin_gauge

# The two Bennett linkages the loops alternate: (a, alpha, b); beta from the Bennett condition.
LOOPS = ((1.0, math.radians(30.0), 1.5), (1.2, math.radians(40.0), 1.6))
RANGE_DEG = (-150.0, 150.0)
START_SHARE = 0.382


def bennett(a: float, alpha: float, b: float, theta1: float) -> tuple[list[float], list[tuple[float, float]]]:
    """Joint angles (eqn 1-18) and D-H rows (a, alpha) of the Bennett linkage at theta1."""
    beta = math.asin(b * math.sin(alpha) / a)
    K = math.sin((beta + alpha) / 2) / math.sin((beta - alpha) / 2)
    theta2 = 2 * math.atan2(K * math.cos(theta1 / 2), math.sin(theta1 / 2))
    return [theta1, theta2, -theta1, -theta2], [(a, alpha), (b, beta), (a, alpha), (b, beta)]


def chain(n: int) -> dict:
    """The linkage file (a dict, axes form) of a chain of n Bennett loops, each sharing a joint with the last."""
    lo, hi = (math.radians(v) for v in RANGE_DEG)
    theta1 = lo + START_SHARE * (hi - lo)
    joints = []
    frame = np.eye(4)  # loop 1's joint 1 frame (attached to its link 4, the ground)
    before, after = "l1_4", "l1_1"  # the bodies joint 1 of the current loop joins
    for k in range(n):
        angles, rows = bennett(*LOOPS[k % 2], theta1)
        links = [after, f"l{k + 1}_2", f"l{k + 1}_3", before]  # link 1 .. link 4 of the loop (link 4 before joint 1)
        frames = [frame]
        for (a, alpha), t in zip(rows, angles, strict=True):
            frames.append(frames[-1] @ transform(rot_z(t)) @ transform(None, [a, 0.0, 0.0]) @ transform(rot_x(alpha)))
        closure = float(np.max(np.abs(frames[-1] - frames[0])))
        assert closure < 1e-12, f"loop {k + 1} does not close: {closure}"
        for j in range(4):
            if k > 0 and j == 0:
                continue  # the shared joint: the last loop's joint 3
            joints.append({
                "name": f"j{k + 1}_{j + 1}", "bodies": [links[j - 1], links[j]],  # joint j + 1 turns link j + 1
                "point": [float(v) for v in frames[j][:3, 3]], "direction": [float(v) for v in frames[j][:3, 2]],
                "theta0": float(angles[j]),
            })
        # the next loop's joint 1 is this loop's joint 3 (frame 3, between link 2 and link 3), its angle -theta1
        frame, before, after, theta1 = frames[2], links[1], links[2], angles[2]
    return {
        "sim_origami_linkage": 1, "form": "axes", "name": f"bennett-chain-{n}",
        "units": {"length": "m", "angle": "rad"}, "ground": "l1_4", "joints": joints,
        "input": {"joint": "j1_1", "range": [math.radians(v) for v in RANGE_DEG]},
        "notes": f"a chain of {n} Bennett loops, each sharing a joint (and the two links it joins) with the last",
    }


def trace_cpu(path: Path) -> tuple[float, str]:
    """CPU (s) of reading the file and tracing it as the scene does, and the trace's summary line."""
    t0 = time.process_time()
    spec = read_linkage(path)
    gauge, spinning = idle_spin_gauge(spec.mechanism)
    kinematics = _kinematics(spec, gauge, spinning)
    return time.process_time() - t0, kinematics.summary()


def validate(path: Path, out: Path, profile: Path | None = None) -> dict:
    """`sim-origami validate --linkage path` in a child: CPU, wall time, exit code, failing verdicts."""
    command = [sys.executable, "-m", "sim_origami", "validate", "--linkage", str(path), "--out", str(out), "--force"]
    if profile is not None:
        command[1:1] = ["-m", "cProfile", "-o", str(profile)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    wall = time.perf_counter()
    done = subprocess.run(command, capture_output=True, text=True, env={**os.environ, "MPLBACKEND": "Agg"})
    wall = time.perf_counter() - wall
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    result = {"exit": done.returncode, "cpu": cpu, "wall": wall, "failing": [], "report_cpu": None, "error": None,
              "verdicts": 0, "tail": (done.stderr or done.stdout).strip().splitlines()[-3:]}
    report = out / "report.json"
    if report.exists() and report.stat().st_mtime > time.time() - wall - 1:
        data = json.loads(report.read_text())
        verdicts = data["verdicts"] + [v for b in data.get("branches", []) for v in b.get("verdicts", [])]
        result["report_cpu"] = data.get("timings_s", {}).get("total_cpu_s")
        result["error"] = data.get("angle_error_max_rad")
        result["verdicts"] = len(verdicts)
        result["failing"] = [f"{v['id']} ({v.get('branch', '')}): {v.get('measured')} > {v.get('tolerance')}"
                             for v in verdicts if not v.get("passed")]
    return result


def exponent(joints: list[int], cpu: list[float]) -> float:
    """Slope of log(cpu) against log(joints), least squares."""
    return float(np.polyfit(np.log(joints), np.log(cpu), 1)[0])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="1,2,4,8,16,32,64")
    parser.add_argument("--fit", type=int, default=3, help="fit the exponent over this many largest sizes")
    parser.add_argument("--profile", type=int, default=0, help="profile the validation of this size")
    parser.add_argument("--no-validate", action="store_true", help="the trace only")
    parser.add_argument("--keep", type=Path, default=None, help="write the files and runs here")
    args = parser.parse_args()
    folder = args.keep or Path(tempfile.mkdtemp(prefix="linkage-chain-"))
    folder.mkdir(parents=True, exist_ok=True)
    rows = []
    print("| N | joints | bodies | trace CPU (s) | validate CPU (s) | validate wall (s) | report total_cpu_s | "
          "MuJoCo path error (rad) | exit | verdict |", flush=True)
    print("|---|---|---|---|---|---|---|---|---|---|", flush=True)
    for n in (int(s) for s in args.sizes.split(",")):
        doc = chain(n)
        path = folder / f"bennett-chain-{n}.json"
        path.write_text(json.dumps(doc, indent=1))
        joints = len(doc["joints"])
        bodies = len({b for j in doc["joints"] for b in j["bodies"]})
        trace, summary = trace_cpu(path)
        run = None if args.no_validate else validate(path, folder / f"run-{n}")
        verdict = "-" if run is None else (f"PASS ({run['verdicts']} checks)" if run["exit"] == 0 else
                                           "; ".join(run["failing"] or run["tail"]))
        rows.append((n, joints, trace, run))
        cells = ["-"] * 5 if run is None else [f"{run['cpu']:.1f}", f"{run['wall']:.1f}",
                                                 "-" if run["report_cpu"] is None else f"{run['report_cpu']:.2f}",
                                                 "-" if run["error"] is None else f"{run['error']:.1e}", run["exit"]]
        print(f"| {n} | {joints} | {bodies} | {trace:.2f} | {' | '.join(map(str, cells))} | {verdict} |", flush=True)
        print(f"    trace: {summary[:300]}", file=sys.stderr, flush=True)
    big = rows[-args.fit:]
    if len(big) >= 2:
        print(f"exponent over N = {', '.join(str(r[0]) for r in big)}: trace "
              f"{exponent([r[1] for r in big], [r[2] for r in big]):.2f}", end="")
        if all(r[3] is not None for r in big):
            print(f", validate {exponent([r[1] for r in big], [r[3]['cpu'] for r in big]):.2f}", end="")
        print()
    if args.profile:
        import pstats

        doc = chain(args.profile)
        path = folder / f"bennett-chain-{args.profile}.json"
        path.write_text(json.dumps(doc, indent=1))
        stats_file = folder / f"profile-{args.profile}.prof"
        run = validate(path, folder / f"run-profile-{args.profile}", stats_file)
        # the exit status under cProfile is not the validation's: the report's failing verdicts say
        print(f"profiled N = {args.profile}: CPU {run['cpu']:.1f} s (under cProfile); failing verdicts: "
              f"{'; '.join(run['failing']) or 'none'}")
        stats = pstats.Stats(str(stats_file))
        stats.sort_stats("cumulative").print_stats(35)
        stats.sort_stats("tottime").print_stats(20)


if __name__ == "__main__":
    main()
