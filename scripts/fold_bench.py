"""FOLD-file benchmarks (issue 15): CPU seconds of the verdicts, printed as a table (timings live here, not in tests).

- a 16 x 16 Miura-ori given only as M/V letters: the numeric trace from flat, 200 polished reference inputs, and
  with --validate the whole `validate` with the fast preset (slow: see docs/performance.md);
- the same sheet's trace with and without the self-contact test at every node (its cost);
- a 480-crease non-rigid pattern (the same sheet with jittered vertices): time to its stall verdict.
"""

import argparse
import tempfile
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from sim_origami.fold import write_fold
from sim_origami.kinematics.miura_sheet import MiuraSheet
from sim_origami.kinematics.numeric_pattern import BRANCH, PatternPath, assignment_signs
from sim_origami.kinematics.self_contact import SelfContact
from sim_origami.scenes.fold_file import fold_scene
from sim_origami.validation import validate


def cpu(fn):
    t0 = time.process_time()
    out = fn()
    return out, time.process_time() - t0


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
            report, t_val = cpu(lambda: validate(scene, preset="fast"))
            rows.append(("16 x 16 Miura, M/V letters only: validate fast", len(sheet.creases), t_val,
                         f"passed={report.passed}, error {report.runs[0].dynamic_path.max_error():.2e} rad"))
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
