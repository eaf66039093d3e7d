"""`sim-origami validate`: the three-way cross-check with report, plots and (optionally) frames."""

import argparse
import json
import sys
from pathlib import Path

import numpy as np
from tqdm import tqdm

from .. import scenes
from ..errors import ParameterError
from ..files import claimed_folder, write_text
from ..report import as_dict, plain, write
from ..scenes.fold_file import fold_scene
from ..validation import validate
from .options import add_params, parse_params

NAME = "validate"
HELP = "cross-check closed form, numeric closure and MuJoCo; write report.json, curves.csv/png, frames"
# Frames rendered per run with --render.
FRAMES = 60


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", nargs="?", help="scene name (see list); omit with --all or --fold")
    parser.add_argument("--all", action="store_true", help="every scene with its defaults, plus a summary")
    parser.add_argument("--fold", type=Path, help="a FOLD 1.2 file with a folded state: numeric reference")
    parser.add_argument("--input", help="with --fold: the driven crease, e<edge index> (default: the most folded)")
    add_params(parser)
    parser.add_argument("--branch", help="one branch (default: every branch)")
    parser.add_argument(
        "--preset", choices=("fast", "stiff", "accurate"), help="default: the scene's own (describe shows it)"
    )
    parser.add_argument(
        "--seed",
        default="closed",
        choices=("closed", "flat"),
        help="start at a closed pose on the branch, or 1e-4 rad from flat on it (with --preset accurate)",
    )
    parser.add_argument("--out", type=Path, help="output folder (default runs/<scene>)")
    parser.add_argument("--force", action="store_true", help="write into a folder holding files this tool did not")
    parser.add_argument("--render", action="store_true", help="also write frames/, fold.gif and fold.mp4")
    parser.add_argument("--json", action="store_true", help="print report.json to stdout")


def run_one(scene, args, out: Path) -> dict:
    """Validate, write every output file into `out`, return the report as a dict."""
    from ..plots import plot_report

    report = validate(scene, preset=args.preset, branch=args.branch, seed=args.seed)
    write(report, out)
    plot_report(report, out / "curves.png")
    doc = as_dict(report)
    if args.render:
        from ..render import render_frames

        q = report.runs[0].dynamic.q
        frames = render_frames(scene, q[np.linspace(0, len(q) - 1, FRAMES).astype(int)], out)
        doc["render"] = {"gl_renderer": frames.gl_renderer, "seconds_per_frame": frames.seconds_per_frame,
                         "frames": len(frames.pngs)}  # fmt: skip
        write_text(out / "report.json", json.dumps(doc, indent=2, default=plain) + "\n")
    return doc


def summary_line(doc: dict) -> str:
    status = "PASS" if doc["passed"] else "FAIL"
    return (f"| {doc['scene']} | {status} | {doc['preset']} | "
            f"{', '.join(b['branch_followed'] or '-' for b in doc['branches'])} | "
            f"{doc['angle_error_max_rad']:.2e} | {doc['closure_residual_max_m']:.2e} | "
            f"{doc['timings_s']['mujoco_step_cpu_s'] * 1e3:.1f} |")  # fmt: skip


HEADER = ("| scene | result | preset | branches followed | max angle error (rad) | max closure residual (m) "
          "| MuJoCo step CPU (ms) |\n|---|---|---|---|---|---|---|")  # fmt: skip


def run(args: argparse.Namespace) -> int:
    if sum((args.all, bool(args.scene), args.fold is not None)) != 1:
        raise ParameterError("give one of a SCENE, --all or --fold FILE")
    if args.input and args.fold is None:
        raise ParameterError("--input names the driven crease of a --fold pattern")
    if args.all:
        if args.param or args.branch:
            raise ParameterError("--all runs every scene with its defaults; -p and --branch need a SCENE")
        out = args.out or Path("runs")
        docs = []
        with claimed_folder(out, force=args.force):
            for name in tqdm(scenes.names(), desc="validate", unit="scene", file=sys.stderr):
                with claimed_folder(out / name, force=args.force):
                    docs.append(run_one(scenes.get(name).build(), args, out / name))
            table = "\n".join([HEADER, *map(summary_line, docs)])
            write_text(out / "summary.md", f"# sim_origami validation\n\n{table}\n")
            write_text(out / "summary.json", json.dumps(docs, indent=2, default=plain) + "\n")
        print(table)
        return 0 if all(d["passed"] for d in docs) else 1
    if args.fold is not None:
        if args.param:
            raise ParameterError("-p sets a registered scene's parameters; a --fold pattern has none")
        scene = fold_scene(args.fold, args.input)
    else:
        scene = scenes.get(args.scene).build_from_user(parse_params(args.param))
    out = args.out or Path("runs") / scene.name
    with claimed_folder(out, force=args.force):
        doc = run_one(scene, args, out)
    if args.json:
        print(json.dumps(doc, indent=2, default=plain))
    else:
        print("\n".join([HEADER, summary_line(doc)]))
        for v in doc["verdicts"] + [v for b in doc["branches"] for v in b["verdicts"]]:
            mark = "ok  " if v["passed"] else "FAIL"
            print(f"  {mark} {v['name']}: {v['measured']:.3g} (tolerance {v['tolerance']:g})")
        print(f"outputs in {out}/")
    return 0 if doc["passed"] else 1
