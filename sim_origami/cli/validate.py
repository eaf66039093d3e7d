"""`sim-origami validate`: the three-way cross-check with report, plots and (optionally) frames."""

import argparse
import contextlib
import sys
from pathlib import Path

import numpy as np
from tqdm import tqdm

from .. import scenes
from ..checks.reference import read_reference, summary_lines
from ..checks.verdict import Verdict
from ..conventions import deg_to_rad
from ..errors import DomainError, ParameterError, SimulationError
from ..files import check_folder, claimed_folder, write_text
from ..presets import PRESET_NAMES, Preset, as_preset
from ..report import as_dict, json_text, motion_view, provenance, verdict_json, write
from ..report_page import write_index, write_page, write_thumbnail
from ..scenes.fold_file import fold_scene
from ..scenes.linkage_file import linkage_scene
from ..simulate import start_input
from ..validation import ZeroSweepError, validate
from .options import add_params, number_at_least, out_folder, parse_params

NAME = "validate"
HELP = "cross-check closed form, numeric closure and MuJoCo; write report.json, curves.csv/png, frames"
# Frames rendered per run with --render, and their size (pixels) unless --size says.
FRAMES = 60
DEFAULT_SIZE = (640, 480)
# The stable id (`Verdict.id`) of the check a run MuJoCo could not finish fails.
MUJOCO_RUN_FINISHED = "mujoco-run-finished"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", nargs="?", help="scene name (see list); omit with --all, --fold or --linkage")
    parser.add_argument("--all", action="store_true", help="every scene with its defaults, plus a summary")
    parser.add_argument("--fold", type=Path, help="a FOLD 1.2 file with a folded state: numeric reference")
    parser.add_argument("--input", help="with --fold: the driven crease(s), e<edge index>[,e<edge index>...] "
                        "(default: as many as the pattern has freedoms, picked by rank, the steadiest first)")
    parser.add_argument("--frames-tolerance", type=number_at_least("--frames-tolerance", 0.0), metavar="DEG",
                        help="with --fold: fail frames farther than this from the rigid motion (default 0.573 deg "
                        "for exact angles; frames measured from 3-D coordinates are reported only)")
    parser.add_argument("--linkage", type=Path, metavar="FILE",
                        help="a linkage file (JSON or TOML, docs/linkage_files.md): numeric reference")
    add_params(parser)
    parser.add_argument("--branch", help="one branch (default: every branch)")
    parser.add_argument(
        "--preset", choices=PRESET_NAMES, help="default: the scene's own (describe shows it)"
    )
    parser.add_argument(
        "--seed",
        default="closed",
        choices=("closed", "flat"),
        help="start at a closed pose on the branch, or 1e-4 rad from flat on it (with --preset accurate)",
    )
    parser.add_argument("--reference", type=Path, metavar="CSV", help="your own curves (input and joint columns)")
    parser.add_argument("--reference-units", choices=("deg", "rad"), help="units of reference columns stating none")
    parser.add_argument("--reference-tol", type=number_at_least("--reference-tol", 0.0, open_low=True), metavar="DEG",
                        help="one tolerance (deg) for every reference value (default: its printed precision)")
    parser.add_argument("--out", type=out_folder, help="output folder (default runs/<scene>)")
    parser.add_argument("--force", action="store_true", help="write into a folder holding files this tool did not")
    parser.add_argument("--render", action="store_true", help="also write frames/, fold.gif and fold.mp4")
    parser.add_argument("--size", type=frame_size, metavar="WxH",
                        help="frame size in pixels with --render (default 640x480)")
    parser.add_argument("--json", action="store_true", help="print report.json to stdout")
    parser.add_argument("--full-curves", action="store_true",
                        help="curves.csv with every MuJoCo step (default: 400 samples a run and each joint's worst)")


def frame_size(text: str) -> tuple[int, int]:
    """'WxH' -> (W, H) pixels, each 16 .. 4096."""
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"--size {text!r}: give WIDTHxHEIGHT in pixels, e.g. 640x480") from None
    if not (16 <= width <= 4096 and 16 <= height <= 4096):
        raise argparse.ArgumentTypeError(f"--size {text!r}: width and height must be 16 .. 4096 pixels")
    return width, height


def check_run(scene, args: argparse.Namespace) -> None:
    """
    Refuse, before the output folder is claimed, what `validate` would refuse only once running: an unknown
    --branch, or a --seed start outside a branch's domain (`--seed flat` on a FOLD pattern traced from 0.024 rad).
    """
    for name in [args.branch] if args.branch else [b.name for b in scene.kinematics.branches()]:
        try:
            scene.pose(name, start_input(scene, name, args.seed))
        except DomainError as exc:
            raise DomainError(f"--seed {args.seed}: {exc}") from None


def chosen_preset(scene, args: argparse.Namespace) -> Preset:
    """The preset --preset names, or the scene's own."""
    return as_preset(args.preset) if args.preset else scene.tuning.preset


def registered(scene, args: argparse.Namespace) -> dict:
    """
    For a registered scene (not a --fold or --linkage file's): its one-line summary and its parameters in the units
    people type (`params_user`: name -> value and unit, `Param.to_user`).
    """
    if args.fold is not None or args.linkage is not None or scene.name not in scenes.names():
        return {}
    kind = scenes.get(scene.name)
    declared = {p.name: p for p in kind.params}
    return {"summary": kind.summary,
            # 12 digits: 30 deg comes back from radians as 29.999999999999996
            "params_user": {name: ({"value": float(f"{declared[name].to_user(v):.12g}"), "unit": declared[name].unit}
                                   if name in declared else {"value": v, "unit": ""})
                            for name, v in scene.params.items()}}


def run_one(scene, args, out: Path, reference=None) -> dict:
    """Validate, write every output file into `out`, return the report as a dict."""
    from ..plots import plot_report

    # At a terminal a bar names each phase (a scene takes up to minutes); piped or logged output stays clean.
    with tqdm(desc=scene.name, unit="phase", file=sys.stderr, disable=None, leave=False) as bar:

        def progress(phase: str, done: int, total: int) -> None:
            bar.total = total
            bar.n = done
            bar.set_postfix_str(phase)

        report = validate(scene, preset=chosen_preset(scene, args), branch=args.branch, seed=args.seed,
                          reference=reference, progress=progress)
    doc = as_dict(report, command=getattr(args, "command_line", None)) | registered(scene, args)
    write(report, out, full_curves=args.full_curves, doc=doc)
    plot_report(report, out / "curves.png")
    if args.render:
        from ..render import render_frames

        q = report.runs[0].dynamic.q
        width, height = args.size or DEFAULT_SIZE
        frames = render_frames(scene, q[np.linspace(0, len(q) - 1, FRAMES).astype(int)], out, width=width,
                               height=height)
        doc["render"] = {"gl_renderer": frames.gl_renderer, "seconds_per_frame": frames.seconds_per_frame,
                         "frames": frames.count, "stills": len(frames.pngs)}
    if args.all and (thumb := write_thumbnail(out)) is not None:  # index.html shows it
        doc["thumbnail"] = thumb.name
    if args.render or "thumbnail" in doc:
        write_text(out / "report.json", json_text(doc))
    write_page(doc, out, motion_view(report), in_index=args.all)
    return doc


def validate_in_all(scene, args, out: Path) -> dict:
    """One scene of `--all`: its report (`run_one`), or a run MuJoCo could not finish (`failed_run`), which fails
    that scene with its report.json and lets the others run."""
    try:
        return run_one(scene, args, out)
    except SimulationError as err:
        return failed_run(scene, args, out, err)


def failed_run(scene, args, out: Path, err: SimulationError) -> dict:
    """report.json for a run MuJoCo could not finish: the failing check and the configuration where it happened."""
    preset = chosen_preset(scene, args)
    stopped = verdict_json(Verdict("MuJoCo run finished without a warning", 1.0, 0.0, str(err),
                                   id=MUJOCO_RUN_FINISHED))
    # no run made (a --fold trace stuck at its start): the trace's stop is the failing check, and its events say more
    ran = not isinstance(err, ZeroSweepError)
    doc = {"scene": scene.name, "params": scene.params, "preset": preset.name, "passed": False,
           "notes": scene.notes, "verdicts": [*map(verdict_json, err.verdicts), *([stopped] if ran else [])],
           "provenance": provenance(preset, getattr(args, "command_line", None))}
    if not ran:
        doc["events"] = list(err.events)
    write_text(out / "report.json", json_text(doc))
    return doc


def number(value: float | None, spec: str) -> str:
    """A report.json number as printed: JSON's null (an inf or NaN value) says so."""
    return "null (inf or nan)" if value is None else format(value, spec)


def summary_line(doc: dict) -> str:
    """A report's row of the summary table; a run MuJoCo could not finish (`failed_run`) shows dashes."""
    status = "PASS" if doc["passed"] else "FAIL"
    if "branches" not in doc:
        return f"| {doc['scene']} | {status} | {doc['preset']} | - | - | - | - |"
    return (f"| {doc['scene']} | {status} | {doc['preset']} | "
            f"{', '.join(b['branch_followed'] or '-' for b in doc['branches'])} | "
            f"{number(doc['angle_error_max_rad'], '.2e')} | {number(doc['closure_residual_max_m'], '.2e')} | "
            f"{doc['timings_s']['mujoco_step_cpu_s'] * 1e3:.1f} |")


HEADER = ("| scene | result | preset | branches followed | max angle error (rad) | max closure residual (m) "
          "| MuJoCo step CPU (ms) |\n|---|---|---|---|---|---|---|")


def run(args: argparse.Namespace) -> int:
    if sum((args.all, bool(args.scene), args.fold is not None, args.linkage is not None)) != 1:
        raise ParameterError("give one of a SCENE, --all, --fold FILE or --linkage FILE")
    if args.input and args.fold is None:
        raise ParameterError("--input names the driven crease of a --fold pattern")
    if args.frames_tolerance is not None and args.fold is None:
        raise ParameterError("--frames-tolerance holds a --fold file's frames; give it with --fold FILE")
    if args.size is not None and not args.render:
        raise ParameterError("--size sets the frames' size; give it with --render")
    if args.render:
        from ..render import require_rendering

        require_rendering()  # before any work: a machine without a GL library is told what to install
    if args.reference is None and (args.reference_units or args.reference_tol is not None):
        raise ParameterError("--reference-units and --reference-tol qualify a --reference FILE")
    if args.all and args.reference is not None:
        raise ParameterError("--reference checks one scene's curves; give a SCENE (or --fold / --linkage FILE), "
                             "not --all")
    if args.all:
        if args.param or args.branch:
            raise ParameterError("--all runs every scene with its defaults; -p and --branch need a SCENE")
        out = args.out or Path("runs")
        docs = []
        # Every scene's folder is claimed before the first scene runs, and all of them are swapped in at the end.
        with contextlib.ExitStack() as claims:
            stage = claims.enter_context(claimed_folder(out, force=args.force))
            stages = {name: claims.enter_context(claimed_folder(out / name, force=args.force))
                      for name in scenes.names()}
            scenes_bar = tqdm(stages, desc="validate --all", unit="scene", file=sys.stderr)
            for name in scenes_bar:
                scenes_bar.set_postfix_str(name)
                docs.append(validate_in_all(scenes.get(name).build(), args, stages[name]))
            table = "\n".join([HEADER, *map(summary_line, docs)])
            write_text(stage / "summary.md", f"# sim_origami validation\n\n{table}\n")
            write_text(stage / "summary.json", json_text(docs))
            write_index(docs, stage)
        print(table)
        print(f"index: {out / 'index.html'}")
        return 0 if all(d["passed"] for d in docs) else 1
    if args.out is not None:  # before the scene is built (a large pattern's trace takes seconds); made when claimed
        check_folder(args.out, make=False)
    if args.fold is not None:
        if args.param:
            raise ParameterError("-p sets a registered scene's parameters; a --fold pattern has none")
        tolerance = None if args.frames_tolerance is None else np.deg2rad(args.frames_tolerance)
        scene = fold_scene(args.fold, args.input, tolerance)
    elif args.linkage is not None:
        if args.param:
            raise ParameterError("-p sets a registered scene's parameters; a --linkage file holds its own")
        scene = linkage_scene(args.linkage)
    else:
        scene = scenes.get(args.scene).build_from_user(parse_params(args.param))
    check_run(scene, args)
    return validate_scene(scene, args)


def validate_scene(scene, args: argparse.Namespace) -> int:
    """Validate one built scene, print the verdicts, return the exit status (a MuJoCo divergence is a failure)."""
    reference = None
    if args.reference is not None:  # read and checked before anything is simulated
        tol = None if args.reference_tol is None else float(deg_to_rad(args.reference_tol))
        reference = read_reference(args.reference, scene.kinematics, units=args.reference_units, tol=tol)
    if not args.json:
        for note in scene.source_notes:  # what reading the file did, before the long work
            print(f"  read: {note}")
    out = args.out or Path("runs") / scene.name
    with claimed_folder(out, force=args.force) as stage:  # the previous run's files stay until this one finishes
        try:
            doc = run_one(scene, args, stage, reference)
        except SimulationError as err:  # MuJoCo diverged: a failed check on this pattern, not bad input
            doc = failed_run(scene, args, stage, err)
            # the checks made without MuJoCo first: an under-driven pattern's divergence is the symptom, not the cause
            for v in (v for v in doc["verdicts"] if not v["passed"] and v["id"] != MUJOCO_RUN_FINISHED):
                print(f"  FAIL {v['name']}: {number(v['measured'], '.3g')} (tolerance {v['tolerance']:g})")
                if isinstance(err, ZeroSweepError):  # why the trace stopped is the reason the run failed
                    print(f"       {v['detail']}")
            print(f"FAIL {scene.name}: {err}\noutputs in {out}/")
            return 1
    if args.json:
        print(json_text(doc), end="")
    else:
        print("\n".join([HEADER, summary_line(doc)]))
        for a in scene.adjustments:  # the model validated is the nearest exact one to the values as typed
            print(f"  adjusted {a.text()}")
        for v in doc["verdicts"] + [v for b in doc["branches"] for v in b["verdicts"]]:
            mark = "ok  " if v["passed"] else "FAIL"
            over = "" if v.get("compared") is None else f", {v['compared']} compared"
            print(f"  {mark} {v['name']}: {number(v['measured'], '.3g')} (tolerance {v['tolerance']:g}{over})")
            if not v["passed"]:  # why it failed: the samples over tolerance, a singular pose crossed, ...
                print(f"       {v['detail']}")
        if "reference" in doc:
            print("\n".join(summary_lines(doc["reference"])))
        for e in doc.get("events", []):  # where a traced reference stopped (short of its target), and why
            if e["kind"] in ("contact", "stall", "lock"):
                print(f"  {e['kind']} at {e['input_rad']:.6g} rad: {e['detail']}")
        print(f"outputs in {out}/")
    return 0 if doc["passed"] else 1
