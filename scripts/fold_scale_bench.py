"""How the CPU of `validate --fold` grows with the sheet (issue 28): per phase, against the face count, as a table.

Miura-ori sheets of n x n panels (`MiuraSheet`, 60 deg, 0.5 m sides, written by `fold_dict`) given as M/V letters
only: coordinates, edges and letters, no faces_vertices and no fold angles, so that the reader builds the faces
from the planar edge graph and the trace runs from flat. Each size runs `sim-origami validate --fold FILE --preset
fast` (no --render) in a child process, one size after another, twice:

- plain: the whole child's CPU (user + system, every thread) and peak memory (ru_maxrss) from `os.wait4`, and the
  CPU of each phase from timers put around the functions that make it up (a few hundred calls a run, each timed
  exclusively: a phase's time leaves out the phases nested inside it, so the phases add up to the total);
- under cProfile (the same timers), whose per-phase CPU carries the profiler's overhead, which differs per phase
  (many small Python calls cost more under it than one large LAPACK call), and whose function lines name what
  dominates at the largest size.

Phases (the entry points each times; `PHASES`): start-up (interpreter and imports), read (`read_fold`), faces
(`fold_mesh.planar_faces`, `side_faces`, `orient`), trace (`PatternPath.__init__`), self-contact (`SelfContact`),
freedoms and rank (`path.mobility` in the trace, `LoopSystem.mobility`, `validation.mobility_report` with its truss
and MuJoCo counts), input choice (`fold_file._choose_inputs`, `_by_rank` with `independent_joints`), model
(`pattern_mechanism`, `scene_xml`, `compile_model`), MuJoCo run (`validation.simulate` less its model and
reference parts), projection (`validation.project`, `projection_conditions`), condition numbers
(`closure_conditions`: the loop closure's, at each sample whose error is above the base tolerance, for the
projection's rounding floor), reference (`evaluate_held`: the polish; `closed_form_verdicts`: the continuation
check; `compare`, `classify`), report and plots (report.json, curves, model.xml, the page, curves.png); other = the
rest. The growth exponent is the slope of log(CPU) against log(faces), least squares over the `--fit` largest
sizes. The profile's function lines are in cProfile's own clock (wall time). Timings live here and in
docs/performance.md, never in tests; CPU on the shared 2-core machine varies by about 10 % from run to run.

    python scripts/fold_scale_bench.py [--sizes 6,8,10,12,16,20,24] [--fit 4] [--out table.md] [--no-profile]
"""

import argparse
import json
import os
import pstats
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import sim_origami  # noqa: F401  (before numpy: one OpenBLAS thread unless set, see sim_origami/__init__.py)

# isort: split
import numpy as np

# (phase, module, attribute): the attribute is patched where it is looked up (a name imported into a module is
# patched in that module); "Class.method" patches the class.
PHASES = (
    ("read", "sim_origami.scenes.fold_file", "read_fold"),
    ("faces", "sim_origami.fold_mesh", "planar_faces"),
    ("faces", "sim_origami.fold_mesh", "side_faces"),
    ("faces", "sim_origami.fold_mesh", "orient"),
    ("trace", "sim_origami.kinematics.numeric_pattern", "PatternPath.__init__"),
    ("self-contact", "sim_origami.kinematics.self_contact", "SelfContact.__init__"),
    ("self-contact", "sim_origami.kinematics.self_contact", "SelfContact.__call__"),
    ("freedoms and rank", "sim_origami.path", "mobility"),
    ("freedoms and rank", "sim_origami.closure", "LoopSystem.mobility"),
    ("freedoms and rank", "sim_origami.validation", "mobility_report"),
    ("input choice", "sim_origami.scenes.fold_file", "_choose_inputs"),
    ("input choice", "sim_origami.scenes.fold_file", "_by_rank"),
    ("model", "sim_origami.scenes.fold_file", "pattern_mechanism"),
    ("model", "sim_origami.validation", "compile_model"),
    ("MuJoCo run", "sim_origami.validation", "simulate"),
    ("projection", "sim_origami.validation", "project"),
    ("projection", "sim_origami.validation", "projection_conditions"),
    ("condition numbers", "sim_origami.checks.paths", "closure_conditions"),
    ("condition numbers", "sim_origami.validation", "closure_conditions"),
    ("reference", "sim_origami.kinematics.numeric_pattern", "PatternPath.evaluate_held"),
    ("reference", "sim_origami.validation", "closed_form_verdicts"),
    ("reference", "sim_origami.validation", "compare"),
    ("reference", "sim_origami.validation", "classify"),
    ("report and plots", "sim_origami.cli.validate", "as_dict"),
    ("report and plots", "sim_origami.cli.validate", "write"),
    ("report and plots", "sim_origami.cli.validate", "motion_view"),
    ("report and plots", "sim_origami.cli.validate", "write_page"),
    ("report and plots", "sim_origami.plots", "plot_report"),
)
ORDER = ("start-up", "read", "faces", "input choice", "trace", "self-contact", "freedoms and rank", "model",
         "MuJoCo run", "projection", "condition numbers", "reference", "report and plots", "other")
# Function lines printed for the largest size's profile.
TOP = 12


# -- the child: one validate, phases timed ------------------------------------------------------------------------
class PhaseClock:
    """Exclusive CPU (process_time: every thread) per phase: a phase entered inside another is taken off the outer
    one; a phase entered inside itself is not timed again."""

    def __init__(self) -> None:
        self.seconds: dict[str, float] = {}
        self.calls: dict[str, int] = {}
        self.stack: list[list] = []  # [phase, CPU of the phases nested in it]

    def wrap(self, phase: str, fn):
        def timed(*args, **kwargs):
            if self.stack and self.stack[-1][0] == phase:
                return fn(*args, **kwargs)
            t0 = time.process_time()
            self.stack.append([phase, 0.0])
            try:
                return fn(*args, **kwargs)
            finally:
                _, inner = self.stack.pop()
                spent = time.process_time() - t0
                self.seconds[phase] = self.seconds.get(phase, 0.0) + spent - inner
                self.calls[phase] = self.calls.get(phase, 0) + 1
                if self.stack:
                    self.stack[-1][1] += spent

        timed.__wrapped__ = fn
        return timed

    def install(self) -> None:
        import importlib

        for phase, module, attribute in PHASES:
            owner = importlib.import_module(module)
            *classes, name = attribute.split(".")
            for c in classes:
                owner = getattr(owner, c)
            setattr(owner, name, self.wrap(phase, getattr(owner, name)))


def child(fold: str, out: str, result: str, profile: str | None) -> int:
    """Validate `fold` into `out` as the CLI does, phases timed (under cProfile when `profile` names a file); the
    phases' CPU and the exit code as JSON into `result`."""
    from sim_origami.cli import main
    from sim_origami.cli import validate as _  # noqa: F401  (imported by main anyway; patched before it runs)

    clock = PhaseClock()
    clock.install()
    startup = time.process_time()
    argv = ["validate", "--fold", fold, "--preset", "fast", "--out", out]
    if profile:
        import cProfile

        profiler = cProfile.Profile()
        code = profiler.runcall(main, argv)
        profiler.dump_stats(profile)
    else:
        code = main(argv)
    seconds = {"start-up": startup, **clock.seconds, "total in process": time.process_time()}
    Path(result).write_text(json.dumps({"code": code, "seconds": seconds, "calls": clock.calls}))
    return code


# -- the parent ---------------------------------------------------------------------------------------------------
def miura_letters(rows: int, cols: int, path: Path) -> tuple[Path, int, int]:
    """An n x m Miura sheet as M/V letters only (no faces, no fold angles) written to path; (path, faces,
    creases)."""
    from sim_origami.fold import fold_dict
    from sim_origami.kinematics.miura_sheet import MiuraSheet

    pattern = MiuraSheet(rows, cols, 0.5, 0.5, np.deg2rad(60.0)).pattern
    doc = fold_dict(pattern, title=f"{rows} x {cols} Miura-ori, M/V letters only")
    for field in ("faces_vertices", "edges_foldAngle"):
        del doc[field]
    path.write_text(json.dumps(doc))
    return path, len(pattern.faces), len(pattern.creases)


def run_child(fold: Path, out: Path, profile: Path | None) -> dict:
    """One child: its own rusage (os.wait4: CPU of every thread, peak memory), its phases, report.json's timings."""
    result = out.with_suffix(".json")
    command = [sys.executable, __file__, "--child", str(fold), str(out), str(result)]
    if profile is not None:
        command += ["--profile-file", str(profile)]
    with open(out.with_suffix(".log"), "w") as log:
        process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        _, status, usage = os.wait4(process.pid, 0)
        process.returncode = os.waitstatus_to_exitcode(status)
    doc = json.loads(result.read_text()) if result.exists() else {"code": process.returncode, "seconds": {}}
    report = out / "report.json"
    timings = json.loads(report.read_text()).get("timings_s", {}) if report.exists() else {}
    seconds = dict(doc["seconds"])
    total = usage.ru_utime + usage.ru_stime
    seconds["other"] = total - sum(v for k, v in seconds.items() if k != "total in process")
    return {"code": doc["code"], "cpu_s": total, "maxrss_mb": usage.ru_maxrss / 1024, "seconds": seconds,
            "calls": doc.get("calls", {}), "timings_s": timings}


def slope(faces: list[int], seconds: list[float]) -> float:
    """Least-squares slope of log(seconds) against log(faces); NaN where a time is not positive."""
    if len(faces) < 2 or min(seconds) <= 0:
        return float("nan")
    return float(np.polyfit(np.log(faces), np.log(seconds), 1)[0])


def table(rows: list[dict], fit: int, key: str) -> str:
    """Markdown: one row per phase (CPU s per size, growth exponent over the `fit` largest), then totals."""
    fitted = rows[-fit:]
    head = "| phase (CPU s) | " + " | ".join(f"{r['n']} x {r['n']}: {r['faces']} faces" for r in rows)
    head += f" | exponent ({fitted[0]['faces']}-{fitted[-1]['faces']} faces) |"
    lines = [head, "|---" * (len(rows) + 2) + "|"]

    def line(name: str, values: list[float], fmt: str = ".2f") -> str:
        exponent = slope([r["faces"] for r in fitted], values[-fit:])
        return f"| {name} | " + " | ".join(format(v, fmt) for v in values) + f" | {exponent:.2f} |"

    for phase in ORDER:
        lines.append(line(phase, [r[key]["seconds"].get(phase, 0.0) for r in rows]))
    lines.append(line("**whole child** (os.wait4: user + system)", [r[key]["cpu_s"] for r in rows]))
    lines.append(line("peak memory (ru_maxrss, MB)", [r[key]["maxrss_mb"] for r in rows], ".0f"))
    if key == "plain" and all("profiled" in r for r in rows):
        lines.append(line("whole child under cProfile", [r["profiled"]["cpu_s"] for r in rows]))
    return "\n".join(lines)


def counts(rows: list[dict]) -> str:
    """Markdown: what each size did (creases, traces, MuJoCo steps, report.json's stages, exit code)."""
    lines = ["| sheet | faces | creases | traces | MuJoCo steps | report.json stages (CPU s) | exit |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        p = r["plain"]
        stages = ", ".join(f"{k.removesuffix('_cpu_s')} {v:.2f}" for k, v in p["timings_s"].items()
                           if k.endswith("cpu_s"))
        lines.append(f"| {r['n']} x {r['n']} | {r['faces']} | {r['creases']} | {p['calls'].get('trace', 0)} | "
                     f"{p['timings_s'].get('mujoco_steps', '')} | {stages} | {p['code']} |")
    return "\n".join(lines)


def top_lines(profile: Path, n: int = TOP) -> str:
    """The profile's functions by own time (tottime) and by cumulative time, n each, as text."""
    out = []
    for order in ("tottime", "cumulative"):
        stats = pstats.Stats(str(profile))
        rows = sorted(stats.stats.items(), key=lambda kv: kv[1][2 if order == "tottime" else 3], reverse=True)
        out.append(f"by {order}: ncalls, tottime s, cumtime s, function")
        for (file, line, name), (_, calls, tt, ct, _) in rows[:n]:
            where = f"{Path(file).name}:{line}" if line else file
            out.append(f"  {calls:>9} {tt:9.2f} {ct:9.2f}  {where}({name})")
    return "\n".join(out)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", default="6,8,10,12,16,20,24", help="panels a side, comma separated")
    parser.add_argument("--fit", type=int, default=4, help="fit the growth exponents over this many largest sizes")
    parser.add_argument("--out", type=Path, help="write the tables as markdown here")
    parser.add_argument("--keep", type=Path, help="keep each run's folder and profile here")
    parser.add_argument("--no-profile", action="store_true", help="skip the runs under cProfile")
    parser.add_argument("--child", nargs=3, metavar=("FOLD", "OUT", "RESULT"), help=argparse.SUPPRESS)
    parser.add_argument("--profile-file", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        sys.exit(child(*args.child, args.profile_file))
    sizes = [int(s) for s in args.sizes.split(",")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        work = args.keep or Path(tmp)
        work.mkdir(parents=True, exist_ok=True)
        for n in sizes:
            fold, faces, creases = miura_letters(n, n, work / f"miura{n}.fold")
            row = {"n": n, "faces": faces, "creases": creases, "plain": run_child(fold, work / f"plain{n}", None)}
            if not args.no_profile:
                row["profiled"] = run_child(fold, work / f"profiled{n}", work / f"miura{n}.prof")
            rows.append(row)
            p = row["plain"]
            print(f"{n} x {n}: {faces} faces, {creases} creases: {p['cpu_s']:.1f} s CPU, {p['maxrss_mb']:.0f} MB, "
                  f"exit {p['code']}" + (f"; under cProfile {row['profiled']['cpu_s']:.1f} s" if "profiled" in row
                                         else ""), flush=True)
        fit = min(args.fit, len(rows))
        text = ["Letters-only Miura sheets, `validate --fold --preset fast`, one child process each, CPU s.",
                "", "Phases of the plain run (timers only):", "", table(rows, fit, "plain")]
        if not args.no_profile:
            text += ["", "Phases under cProfile:", "", table(rows, fit, "profiled"), "",
                     f"The {sizes[-1]} x {sizes[-1]} profile:", "", "```",
                     top_lines(work / f"miura{sizes[-1]}.prof"), "```"]
        text += ["", counts(rows)]
    markdown = "\n".join(text) + "\n"
    print(markdown)
    if args.out:
        args.out.write_text(markdown)


if __name__ == "__main__":
    main()
