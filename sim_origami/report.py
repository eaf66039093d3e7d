"""Report -> report.json and curves.csv (radians; field names carry their units)."""

import csv
import io
import json
import math
from pathlib import Path

import numpy as np

from . import __version__
from .files import write_text
from .fold import write_fold
from .geometry import wrap
from .stabilize import preset_mode
from .validation import Report

# Frames of the simulated motion written to motion.fold (evenly spaced over the first run).
FOLD_FRAMES = 60


def _num(value: float) -> float | None:
    """JSON has no NaN or inf: those become null."""
    value = float(value)
    return value if math.isfinite(value) else None


def _verdict(v) -> dict:
    return {"name": v.name, "measured": _num(v.measured), "tolerance": v.tolerance, "passed": v.passed,
            "detail": v.detail}  # fmt: skip


def as_dict(report: Report) -> dict:
    """The report as JSON-ready data; angles in radians, lengths in metres, times in seconds."""
    scene = report.scene
    branches = []
    for run in report.runs:
        dyn, proj = run.dynamic_path, run.projection_path
        branches.append(
            {
                "branch_requested": run.requested,
                "branch_followed": run.followed,
                "branch_flips": run.flips,
                "input_range_rad": [_num(np.min(dyn.input)), _num(np.max(dyn.input))],
                "angle_error_max_rad": _num(dyn.max_error()),
                "angle_error_max_by_joint_rad": {
                    name: _num(np.max(dyn.error[:, k])) for k, name in enumerate(scene.kinematics.joint_names)
                },
                "closure_residual_max_m": _num(np.max(run.dynamic.closure_residual)),
                "projection_angle_error_max_rad": _num(proj.max_error()),
                "projection_closure_residual_max_m": _num(run.projection_residual_m),
                "steps": run.dynamic.steps,
                "step_cpu_time_s": run.dynamic.cpu_time_s,
                "events": run.events,
                "mobility": run.mobility,
                "verdicts": [_verdict(v) for v in run.verdicts],
            }
        )
    out = {
        "sim_origami": __version__,
        "scene": scene.name,
        "params": scene.params,
        "preset": report.preset,
        # "none" for plain MuJoCo; "position" when the preset projects qpos onto the closures after each step
        "stabilize": preset_mode(report.preset),
        "seed": report.seed,
        "input": {"name": scene.kinematics.input_name, "drive_joint": scene.drive_joint},
        "joints": list(scene.kinematics.joint_names),
        "angle_error_max_rad": _num(max(r.dynamic_path.max_error() for r in report.runs)),
        "closure_residual_max_m": _num(max(np.max(r.dynamic.closure_residual) for r in report.runs)),
        "branches": branches,
        "events": [e for r in report.runs for e in r.events],
        "bifurcation_study": list(report.bifurcations),
        "free_run": report.free_run,
        "verdicts": [_verdict(v) for v in report.verdicts],
        "timings_s": report.timings,
        "passed": report.passed,
    }
    if report.blockage is not None:
        b = report.blockage
        out["blockage"] = {
            "stop_input_rad": b.stop_input,
            "kinematic_contact_input_rad": _num(b.contact_input),
            "zero_thickness_lock_input_rad": b.analytic_limit,
            "stopped": b.stopped,
            "drive_saturated": b.drive_saturated,
        }
        out["events"].append({"kind": "blockage", "input_rad": b.stop_input, "branches": [report.runs[0].requested],
                              "detail": "force-limited drive stopped by contact"})  # fmt: skip
    return out


def curves_csv(report: Report) -> str:
    """One row per sample: branch, mode, input and each joint simulated/analytic/error (rad)."""
    names = report.scene.kinematics.joint_names
    buf = io.StringIO()
    writer = csv.writer(buf)
    header = ["branch", "mode", "input_rad"]
    for n in names:
        header += [f"{n}_sim_rad", f"{n}_analytic_rad", f"{n}_error_rad"]
    writer.writerow(header)
    for run in report.runs:
        for mode, path in (("dynamic", run.dynamic_path), ("projection", run.projection_path)):
            values = np.stack([path.simulated, path.analytic, path.error], -1).reshape(len(path.input), -1)
            # one format for the whole row: the branch and mode lead every line (names carry no '%')
            fmt = ",".join([run.requested, mode, "%.17g"] + ["%.17g,%.17g,%.3e"] * len(names))
            np.savetxt(buf, np.column_stack([path.input, values]), fmt=fmt)
    return buf.getvalue()


def plain(value):
    """JSON fallback for numpy scalars and arrays."""
    if isinstance(value, np.generic | np.ndarray):
        return value.tolist()
    raise TypeError(f"cannot write {type(value).__name__} to JSON")


def motion_fold(report: Report, out: Path) -> Path:
    """The first run's simulated fold angles as a multi-frame FOLD file (at most FOLD_FRAMES frames)."""
    scene, run = report.scene, report.runs[0]
    rows = np.unique(np.linspace(0, len(run.dynamic.q) - 1, FOLD_FRAMES).astype(int))
    columns = [scene.mechanism.joint_index(c.name) for c in scene.pattern.creases]
    title = f"{scene.name}: MuJoCo {report.preset}, branch {run.requested}"
    return write_fold(out, scene.pattern, wrap(run.dynamic.q[np.ix_(rows, columns)]), title=title)


def write(report: Report, out: str | Path) -> dict[str, Path]:
    """Write report.json, curves.csv and, for crease-pattern scenes, motion.fold into `out` (atomically)."""
    out = Path(out)
    paths = {
        "report": write_text(out / "report.json", json.dumps(as_dict(report), indent=2, default=plain) + "\n"),
        "curves": write_text(out / "curves.csv", curves_csv(report)),
    }
    if report.scene.pattern is not None:
        paths["fold"] = motion_fold(report, out / "motion.fold")
    return paths
