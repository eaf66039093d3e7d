"""FOLD-file benchmarks (issue 15): CPU seconds of the verdicts, printed as a table (timings live here, not in tests).

- a 16 x 16 Miura-ori given only as M/V letters: the numeric trace from flat, 200 polished reference inputs, and
  with --validate the whole `sim-origami validate --fold FILE --preset fast` (no --render) in a child process, its
  CPU (user + system, every thread) and the stages of its report.json;
- the same sheet's trace with and without the self-contact test at every node (its cost);
- a 480-crease non-rigid pattern (the same sheet with jittered vertices): time to its stall verdict.
"""

import argparse
import json
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import sim_origami  # noqa: F401  (before numpy: one OpenBLAS thread unless set, see sim_origami/__init__.py)

# isort: split
import numpy as np

from sim_origami.fold import write_fold
from sim_origami.kinematics.miura_sheet import MiuraSheet
from sim_origami.kinematics.numeric_pattern import BRANCH, PatternPath, assignment_signs
from sim_origami.kinematics.self_contact import SelfContact
from sim_origami.scenes.fold_file import fold_scene


def cpu(fn):
    t0 = time.process_time()
    out = fn()
    return out, time.process_time() - t0


def validate_cli(path: Path, out: Path, creases: int) -> list[tuple]:
    """`sim-origami validate --fold path --preset fast` as a user runs it: whole CPU, then report.json's stages."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    command = "import sys; from sim_origami.cli import main; sys.exit(main(sys.argv[1:]))"
    code = subprocess.run([sys.executable, "-c", command, "validate", "--fold", str(path), "--preset", "fast",
                           "--out", str(out)], capture_output=True, text=True).returncode
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    total = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    doc = json.loads((out / "report.json").read_text())
    failed = [v["name"] for v in doc["verdicts"] + [v for b in doc["branches"] for v in b["verdicts"]]
              if not v["passed"]]
    rows = [("16 x 16 Miura, M/V letters only: `validate --fold --preset fast`, whole process", creases, total,
             f"exit {code}; failed: {', '.join(failed) or 'none'}")]
    rows += [(f"  stage {name}", creases, seconds, "report.json timings_s") for name, seconds in
             doc["timings_s"].items() if name.endswith("cpu_s")]
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--validate", action="store_true", help="also time the whole validate of the 16 x 16 sheet")
    args = parser.parse_args()
    sheet = MiuraSheet(16, 16, 0.5, 0.5, np.deg2rad(60.0)).pattern
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        path = write_fold(Path(tmp) / "miura16.fold", sheet)
        scene, t_build = cpu(lambda: fold_scene(path))
        kin = scene.kinematics
        rows.append(("16 x 16 Miura, M/V letters only: read + trace from flat", len(sheet.creases), t_build,
                     f"{len(kin.s_nodes)} nodes, {kin.stops[0].kind} at {kin.stops[0].s:.4g} rad"))
        x = np.linspace(*kin.branch(BRANCH).domain, 200)
        values, t_eval = cpu(lambda: kin.joint_angles(BRANCH, x))
        rows.append(("16 x 16 Miura: 200 reference inputs polished", len(sheet.creases), t_eval,
                     f"residual <= {np.max(kin.loop_system().residual_norm(values)):.2g}"))
        pattern, signs = kin.pattern, assignment_signs(kin.pattern)
        first = pattern.creases[0].name
        for contact in (False, True):
            traced, t_trace = cpu(lambda c=contact: PatternPath(pattern, first, signs=signs, contact=c))
            rows.append((f"16 x 16 Miura: trace {'with' if contact else 'without'} the self-contact test",
                         len(sheet.creases), t_trace, f"{len(traced.s_nodes)} nodes, {traced.stops[0].kind}"))
        test = SelfContact(pattern)
        hits, t_test = cpu(lambda: [test(q) for q in traced.nodes])
        rows.append((f"16 x 16 Miura: the self-contact test alone at those {len(hits)} nodes", len(sheet.creases),
                     t_test, f"{sum(h is not None for h in hits)} contacts"))
        if args.validate:
            rows += validate_cli(path, Path(tmp) / "out", len(sheet.creases))
    rng = np.random.default_rng(1)
    jittered = replace(sheet, vertices=sheet.vertices + rng.uniform(-0.02, 0.02, sheet.vertices.shape))
    path, t_stall = cpu(lambda: PatternPath(jittered, jittered.creases[0].name, signs=assignment_signs(jittered)))
    rows.append(("jittered 16 x 16 sheet (non-rigid): stall verdict", len(jittered.creases), t_stall,
                 ", ".join(e.kind for e in path.events())))
    print("| case | creases | CPU s | outcome |\n|---|---|---|---|")
    for name, n, t, what in rows:
        print(f"| {name} | {n} | {t:.2f} | {what} |")


if __name__ == "__main__":
    main()
