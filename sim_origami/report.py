"""Report -> report.json, curves.csv (radians; field names carry their units) and model.xml."""

import base64
import csv
import functools
import gzip
import io
import json
import math
import os
import platform
import subprocess
from datetime import datetime, timezone
from pathlib import Path

import mujoco
import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import sparse as sp
from scipy.spatial.transform import Rotation

from . import __version__
from .files import atomic_path, write_text
from .fold import write_fold
from .mjcf import CompiledModel, Replay, replay_xml
from .path import null_space
from .presets import Preset
from .simulate import Bindings, Scene, closure_model, constraint_jacobian, start_input
from .validation import Report

# Frames of each branch's motion in report.html's 3-D view, and the significant digits of its solids' vertices and
# inputs. The poses are 16-bit integers (`_packed`): a position to 1/32767 of the largest offset of a body's origin
# from the view's centre, a quaternion component to 1/32767 (a turn under 1e-4 rad), both far below a pixel of the
# 800-pixel view; as 5-digit text waterbomb-twist's three branches' poses took 1.8 MB of page, as integers 0.6 MB.
VIEW_FRAMES = 100
VIEW_DIGITS = 5
VIEW_INT = 32767
# The view's paper: front (+z of the flat sheet) and back colours; crease lines mountain red, valley blue (the
# colours of Origami Simulator and most crease-pattern drawings).
PAPER_FRONT = (0.96, 0.86, 0.64)
PAPER_BACK = (0.62, 0.74, 0.88)
# Frames of the simulated motion written to motion.fold (evenly spaced over the first run).
FOLD_FRAMES = 60
# model.xml's position servo on each driven joint: critically damped with this time constant (s) on the mechanism's
# inertia at that joint in the lightest start pose. It is explicit in MuJoCo (RK4 steps kv / I h with I the inertia of
# the pose reached): along every built-in path that inertia falls to at most 1/6.7 of the start's (vertex4, measured),
# where 2 h / SERVO_TIMECONST x 6.7 = 1.1 at h = 8 ms (1.3 at 10 ms) stays inside RK4's stability limit of 2.8.
SERVO_TIMECONST = 0.1
# Singular values of the closures' Jacobian below this times the largest span its null space (free motions).
NULL_RTOL = 1e-9
# Samples of each run that curves.csv keeps (plus each joint's worst): every MuJoCo step of every joint made the main
# job's curves 197 MB (81 MB for corrugated-sheet alone); `validate --full-curves` writes them all.
CURVE_ROWS = 400
# curves.csv's significant digits: the input and every angle (rad) CURVE_DIGITS (rounded by at most 5e-13 rad at
# |angle| < 10, 20x under the tightest MuJoCo check's tolerance, fast-projected 1e-11), each error ERROR_DIGITS,
# computed from the unrounded angles (an error of 1e-14, a projection's, is written as such; the written angles
# resolve differences of about 1e-12 only). `--full-curves` writes every angle to 17 digits (each float exactly).
CURVE_DIGITS = 13
FULL_DIGITS = 17
ERROR_DIGITS = 4
# curves.csv text longer than this (bytes) is written gzip-compressed, as curves.csv.gz (a 5.5th of the text): the
# wide files of the big patterns (waterbomb-twist's 453 columns: 13.0 MB at 17 digits, 10.8 MB at 13, 1.9 MB as .gz).
# Python's csv with gzip.open(..., "rt"), pandas.read_csv and `zcat` read it as it is.
CURVES_GZIP_BYTES = 1_000_000


def _num(value: float) -> float | None:
    """JSON has no NaN or inf: those become null."""
    value = float(value)
    return value if math.isfinite(value) else None


def verdict_json(v) -> dict:
    """A check as JSON: its stable `id` (the check's kind), the branch it is about ("" for the whole scene), its
    display name; `compared`: how many values it compared (null where it counts no samples)."""
    return {"id": v.id, "branch": v.branch, "name": v.name, "measured": _num(v.measured), "tolerance": v.tolerance,
            "passed": v.passed, "detail": v.detail, "compared": v.compared}


@functools.cache
def git_commit() -> str | None:
    """
    The short commit of the checkout the package runs from, "+dirty" when tracked files are modified; None when
    it is not run from a git checkout (an installed wheel) or git is missing or slow (a venv inside a checkout
    would otherwise report the enclosing repository, hence the .git beside the package).
    """
    root = Path(__file__).resolve().parent.parent
    if not (root / ".git").exists():
        return None
    try:
        head = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"], capture_output=True,
                              text=True, timeout=5, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(root), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=5, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return None
    return f"{head}+dirty" if dirty else head or None


def provenance(preset: Preset, command: str | None = None) -> dict:
    """What made this run: versions, commit, the command as typed (None from the API), UTC date and the machine."""
    import mujoco

    return {
        "sim_origami": __version__,
        "git_commit": git_commit(),
        "mujoco": mujoco.__version__,
        "python": platform.python_version(),
        "numpy": np.__version__,
        "command": command,
        "date_utc": datetime.now(timezone.utc).isoformat(timespec="seconds"),
        "preset": preset.name,
        "machine": {"os": platform.platform(), "arch": platform.machine(), "cores": os.cpu_count()},
    }


def as_dict(report: Report, command: str | None = None) -> dict:
    """
    The report as JSON-ready data; angles in radians, lengths in metres, times in seconds. `command` is the
    command line that ran it, for `provenance`.
    """
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
                "sweep_time_s": run.dynamic.sweep_time_s,  # from the path's joint rates (`sweep_rate`)
                "steps": run.dynamic.steps,
                "step_cpu_time_s": run.dynamic.cpu_time_s,
                "events": run.events,
                "mobility": run.mobility,
                "verdicts": [verdict_json(v) for v in run.verdicts],
            }
        )
    out = {
        "sim_origami": __version__,
        "scene": scene.name,
        "params": scene.params,
        # values as typed that the nearest exact model moved, each against its precision (in the unit it was given)
        "adjustments": [a.as_dict() for a in scene.adjustments],
        "notes": scene.notes,
        "preset": report.preset.name,
        # "none" for plain MuJoCo; "position" when the preset projects qpos onto the closures after each step
        "stabilize": report.preset.stabilize,
        "seed": report.seed,
        "input": {"name": scene.kinematics.input_name, "drive_joint": scene.drive_joint},
        "joints": list(scene.kinematics.joint_names),
        "angle_error_max_rad": _num(max(r.dynamic_path.max_error() for r in report.runs)),
        "closure_residual_max_m": _num(max(np.max(r.dynamic.closure_residual) for r in report.runs)),
        "branches": branches,
        "events": [e for r in report.runs for e in r.events],
        "bifurcation_study": list(report.bifurcations),
        "free_run": report.free_run,
        "verdicts": [verdict_json(v) for v in report.verdicts],
        "timings_s": report.timings,
        "passed": report.passed,
        "provenance": provenance(report.preset, command),
    }
    if report.reference is not None:
        out["reference"] = report.reference.doc
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
                              "detail": "force-limited drive stopped by contact"})
    return out


def curve_rows(n: int, error: NDArray[np.float64], rows: int | None) -> NDArray[np.intp]:
    """
    Which of n samples curves.csv keeps: all where `rows` is None; else about `rows` evenly spaced, both ends, and
    the sample of each joint's largest error (`error` (n, k)), so the file still holds every maximum the report
    states.
    """
    if rows is None or n <= rows:
        return np.arange(n)
    worst = np.argmax(np.where(np.isfinite(error), error, -np.inf), axis=0) if error.size else np.zeros(0, int)
    return np.unique(np.concatenate([np.linspace(0, n - 1, rows).round().astype(np.intp), worst]))


def curves_csv(report: Report, rows: int | None = CURVE_ROWS, digits: int = CURVE_DIGITS) -> str:
    """
    One row per sample: branch, mode, input and each joint simulated/analytic/error (rad); at most about `rows`
    samples of each run (`curve_rows`), every one where `rows` is None. The input and angles keep `digits`
    significant digits, the errors ERROR_DIGITS.
    """
    names = report.scene.kinematics.joint_names
    buf = io.StringIO()
    writer = csv.writer(buf)
    header = ["branch", "mode", "input_rad"]
    for n in names:
        header += [f"{n}_sim_rad", f"{n}_analytic_rad", f"{n}_error_rad"]
    writer.writerow(header)
    for run in report.runs:
        for mode, path in (("dynamic", run.dynamic_path), ("projection", run.projection_path)):
            keep = curve_rows(len(path.input), path.error, rows)
            values = np.stack([path.simulated, path.analytic, path.error], -1)[keep].reshape(len(keep), -1)
            # one format for the whole row: the branch and mode lead every line (names carry no '%')
            angle, error = f"%.{digits}g", f"%.{ERROR_DIGITS - 1}e"
            fmt = ",".join([run.requested, mode, angle] + [f"{angle},{angle},{error}"] * len(names))
            np.savetxt(buf, np.column_stack([path.input[keep], values]), fmt=fmt)
    return buf.getvalue()


def finite(value):
    """`value` (JSON-ready data, numpy included) with every non-finite number as None (JSON's null), as `_num`
    writes the report's measured values: JSON has no NaN or inf, and a reader that follows the standard refuses them."""
    if isinstance(value, dict):
        return {k: finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [finite(v) for v in value]
    if isinstance(value, np.ndarray):
        return finite(value.tolist())
    if isinstance(value, float | np.floating):
        return float(value) if np.isfinite(value) else None
    if isinstance(value, np.integer | np.bool_):
        return value.item()
    return value


def json_text(doc) -> str:
    """The one writer of report.json and summary.json: indented, every number finite or null (`finite`)."""
    return json.dumps(finite(doc), indent=2, allow_nan=False) + "\n"


def motion_fold(report: Report, out: Path) -> Path:
    """
    The first run's simulated fold angles as a multi-frame FOLD file (at most FOLD_FRAMES frames; `fold_dict`
    for the assignments). The key frame holds the last frame's angles, the motion's end state: viewers that
    read only the key frame (Origami Simulator takes its edges_foldAngle as the target) fold to it. MuJoCo's
    hinge angles are continuous and written unwrapped, so a crease folded flat stays at +180 (or -180) deg;
    one that overshoots +-pi by contact is written at +-pi, and the file's description says by how much when
    that exceeds the preset's angle tolerance. A crease that stays within that tolerance of flat (the
    simulation's accepted error) is F.
    """
    scene, run = report.scene, report.runs[0]
    rows = np.unique(np.linspace(0, len(run.dynamic.q) - 1, FOLD_FRAMES).astype(int))
    columns = [scene.mechanism.joint_index(c.name) for c in scene.pattern.creases]
    rho = run.dynamic.q[np.ix_(rows, columns)]
    tol = report.preset.angle_rad
    over = np.max(np.abs(rho), axis=0) - np.pi
    side = np.where(np.max(rho, axis=0) > -np.min(rho, axis=0), "+", "-")
    notes = tuple(
        f"{c.name} overshoots {side[k]}180 deg by {over[k]:.3g} rad in the simulation and is written at {side[k]}180."
        for k, c in enumerate(scene.pattern.creases)
        if over[k] > tol
    )
    title = f"{scene.name}: MuJoCo {report.preset.name}, branch {run.requested}"
    rho = np.clip(rho, -np.pi, np.pi)
    return write_fold(out, scene.pattern, rho, fold_angles=rho[-1], title=title, flat_tol=tol, notes=notes,
                      numbering=scene.numbering)


def _rounded(values: ArrayLike, digits: int = VIEW_DIGITS) -> list[float]:
    """Flat list of values kept to `digits` significant digits (the view's JSON, compact)."""
    return [float(f"{v:.{digits}g}") for v in np.ravel(values)]


def _quaternions(R: NDArray[np.float64]) -> NDArray[np.float64]:
    """Unit quaternions (..., 4) as x, y, z, w of rotation matrices (..., 3, 3)."""
    return Rotation.from_matrix(R.reshape(-1, 3, 3)).as_quat().reshape(*R.shape[:-2], 4)


def _crease_segment(mech, joint) -> tuple[str, NDArray[np.float64]] | None:
    """
    A crease as a line in its parent panel's frame, (body, (2k, 3) ends): the stretch of the hinge axis along the
    panel's edge, on both faces of a thin panel (the line would be hidden inside it); None without such an edge.
    """
    solid = next(b.solid for b in mech.bodies if b.name == joint.parent)
    v = np.asarray(solid.vertices)
    origin, axis = joint.frame_parent[:3, 3], joint.frame_parent[:3, 2]
    along = (v - origin) @ axis
    off = np.linalg.norm(v - origin - np.outer(along, axis), axis=1)
    # the edge's corners lie on the axis, or half a thin panel's thickness off it (2 % of the panel's size)
    near = off < 0.02 * np.ptp(v, axis=0).max()
    if near.sum() < 2:
        return None
    ends = origin + np.outer([along[near].min(), along[near].max()], axis)
    z = v[:, 2]
    if z.min() < ends[:, 2].min() and ends[:, 2].max() < z.max():
        up = np.array([0.0, 0.0, 1.0])
        ends = np.vstack([ends + (z.max() - ends[:, 2:]) * up, ends + (z.min() - ends[:, 2:]) * up])
    return joint.parent, ends


def _packed(values: NDArray[np.float64]) -> str:
    """`values` rounded to whole numbers within +-VIEW_INT, as little-endian int16 in base64 (the view's poses)."""
    ints = np.clip(np.round(values), -VIEW_INT, VIEW_INT).astype("<i2")
    return base64.b64encode(ints.tobytes()).decode("ascii")


def motion_view(report: Report) -> dict:
    """
    The data of report.html's 3-D view: each body's solid (vertices and triangles in its frame, front and back
    colours), the creases as lines in a panel's frame (on both faces of a thin panel), and per branch about
    VIEW_FRAMES frames of every body's pose from the MuJoCo run's joint angles, with the input (rad) and each
    crease's side (M, V or F by the sign of its last angle). Vertices and inputs keep VIEW_DIGITS significant
    digits. A branch's `poses` are frames x bodies x 7 int16 (`_packed`): the position's offset from `centre` in
    units of the branch's `scale` (m), then the quaternion x y z w in units of 1 / VIEW_INT.
    """
    scene = report.scene
    mech = scene.mechanism
    bodies = [b for b in mech.bodies if not b.spacer]
    paper = {name for j in mech.joints if j.name in scene.crease_hinges for name in (j.parent, j.child)}
    solids = [
        {"name": b.name, "v": _rounded(b.solid.vertices), "f": np.ravel(b.solid.faces).astype(int).tolist(),
         "front": list(PAPER_FRONT if b.name in paper else b.rgba[:3]),
         "back": list(PAPER_BACK if b.name in paper else b.rgba[:3])}
        for b in bodies
    ]
    creases, crease_joints = [], []
    if scene.pattern is not None:
        for c in scene.pattern.creases:
            segment = _crease_segment(mech, mech.joints[mech.joint_index(c.name)])
            if segment is not None:
                creases.append({"name": c.name, "body": [b.name for b in bodies].index(segment[0]),
                                "p": _rounded(segment[1])})
                crease_joints.append(mech.joint_index(c.name))
    branches, corners, frames = [], [], []
    tol = report.preset.angle_rad
    for run in report.runs:
        q = run.dynamic.q
        rows = np.unique(np.linspace(0, len(q) - 1, min(VIEW_FRAMES, len(q))).round().astype(int))
        poses = mech.body_poses(q[rows])
        T = np.stack([poses[b.name] for b in bodies], 1)  # (frames, bodies, 4, 4)
        frames.append(T)
        for k, b in enumerate(bodies):  # every body's extent over the motion
            world = T[:, k, :3, :3] @ np.asarray(b.solid.vertices).T + T[:, k, :3, 3, None]  # (frames, 3, n)
            corners += [world.min(axis=(0, 2)), world.max(axis=(0, 2))]
        last = q[-1, crease_joints] if crease_joints else np.zeros(0)
        branches.append({"name": run.requested, "followed": run.followed,
                         "input": _rounded(run.dynamic.target[rows]),
                         "sides": "".join("V" if r > tol else "M" if r < -tol else "F" for r in last)})
    corners = np.array(corners)
    lo, hi = corners.min(0), corners.max(0)
    centre = np.array(_rounded((lo + hi) / 2))
    for branch, T in zip(branches, frames, strict=True):
        offset = T[..., :3, 3] - centre
        scale = float(f"{max(np.abs(offset).max(initial=0.0), 1e-9) / VIEW_INT * (1 + 1e-6):.6g}")
        branch["scale"] = scale  # so that the largest offset, rounded up, still fits in VIEW_INT units
        branch["poses"] = _packed(np.concatenate([offset / scale, _quaternions(T[..., :3, :3]) * VIEW_INT], -1))
    view = {"scene": scene.name, "input": scene.kinematics.input_name, "bodies": solids, "creases": creases,
            "branches": branches, "centre": centre.tolist(),
            "radius": _rounded(np.linalg.norm(hi - lo) / 2)[0]}
    if scene.pattern is not None:
        view["pattern"] = pattern_drawing(report)
    return view


def pattern_drawing(report: Report) -> dict:
    """
    A crease pattern as drawn on report.html: flat vertices (m), the border (face edges that are no crease),
    each crease's ends, assignment letter and side in the first run (M, V or F by the sign of its last simulated
    angle), and the driven creases.
    """
    scene, run = report.scene, report.runs[0]
    pattern = scene.pattern
    crease_edges = {frozenset((c.start, c.end)) for c in pattern.creases}
    border = sorted({tuple(sorted((a, b))) for face in pattern.faces for a, b in zip(face, face[1:] + face[:1],
                     strict=True) if frozenset((a, b)) not in crease_edges})
    tol = report.preset.angle_rad
    last = run.dynamic.q[-1]
    return {
        "vertices": _rounded(pattern.vertices),
        "border": [list(e) for e in border],
        "creases": [{"name": c.name, "ends": [c.start, c.end], "assignment": c.assignment,
                     "side": "V" if r > tol else "M" if r < -tol else "F"}
                    for c in pattern.creases for r in [last[scene.mechanism.joint_index(c.name)]]],
        "driven": list(scene.drives),
    }


def model_xml(report: Report) -> str:
    """model.xml of a validation (`replay_model_xml` of the model its runs stepped, for their branches and start
    inputs)."""
    scene = report.scene
    return replay_model_xml(scene, report.model, {r.requested: start_input(scene, r.requested, report.seed)
                                                  for r in report.runs})


def replay_model_xml(scene: Scene, model: CompiledModel, starts: dict[str, float]) -> str:
    """
    model.xml for runs from these start inputs (rad) by branch: the MJCF text of `model`, the one the dynamic runs
    stepped (`simulate.compile_model`: preset, joint-equality drive, no contact), with what plain MuJoCo needs to play
    it alone (`mjcf.replay_xml`): keyframes
    `start_<branch>` at the closed form's start poses with ctrl there, and a position servo per driven joint. Loaded
    with `mujoco.MjModel.from_xml_path`, reset to a keyframe and stepped, it holds the start pose. To repeat a run
    bitwise: multiply `body_invweight0` and `dof_invweight0` by its numeric `regularization_scale`, disable actuation,
    reset to the keyframe, turn the equality `drive_<joint>` on and write the drive's targets
    (`simulate.drive_targets`) into its eq_data each step.
    """
    poses = {branch: scene.pose(branch, x) for branch, x in starts.items()}
    kp, kv = servo_gains(model, poses)
    replay = Replay(poses, kp, kv, _ctrl_ranges(scene, starts), SERVO_TIMECONST)
    return replay_xml(model.xml, scene.mechanism, scene.drives, replay) + "\n"


def servo_gains(
    compiled: CompiledModel, poses: dict[str, NDArray[np.float64]]
) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """model.xml's servo gains (kp, kv) per driven joint: critically damped with SERVO_TIMECONST on the mechanism's
    inertia at that joint (`drive_inertia`) in the lightest of the start poses, on the compiled model."""
    model, data, _ = closure_model(compiled)
    binds = Bindings(compiled)
    dofs = np.array(compiled.ids.drive_dofs)
    inertia = []
    for q in poses.values():
        binds.set_pose(data, q)
        inertia.append(drive_inertia(model, data, dofs))
    rate = 1.0 / SERVO_TIMECONST
    lightest = np.min(inertia, axis=0)
    return tuple((lightest * rate**2).tolist()), tuple((2.0 * lightest * rate).tolist())


def drive_inertia(model: mujoco.MjModel, data: mujoco.MjData, dofs: NDArray[np.int64]) -> NDArray[np.float64]:
    """
    The inertia (kg m^2) a torque at each dof in `dofs` meets at data's qpos: the others moving as the active
    equalities (the closures) allow with the least kinetic energy, 1 / (e' N (N' M N)^-1 N' e) over a basis N of
    their Jacobian's null space; the dof's own mass-matrix entry where the closures hold it (N' e = 0).
    """
    mujoco.mj_forward(model, data)
    M = np.zeros((model.nv, model.nv))
    mujoco.mj_fullM(model, data, M)
    J = constraint_jacobian(model, data)[data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY]
    N = null_space(sp.csr_matrix(J), NULL_RTOL) if len(J) else np.eye(model.nv)
    out = np.diag(M)[dofs].copy()
    for k, dof in enumerate(dofs):
        e = N[dof]
        if e @ e > NULL_RTOL:
            out[k] = 1.0 / (e @ np.linalg.solve(N.T @ M @ N, e))
    return out


def _ctrl_ranges(scene: Scene, starts: dict[str, float]) -> tuple[tuple[float, float], ...]:
    """Each driven joint's angles (rad) over the branches' paths from their starts: the range of its ctrl slider."""
    x = np.concatenate([np.linspace(x0, scene.branch_path(b)[1], 65) for b, x0 in starts.items()])
    angles = scene.drive_values(x)
    return tuple((float(lo), float(hi)) for lo, hi in zip(angles.min(axis=0), angles.max(axis=0), strict=True))


def write_curves(out: Path, text: str, limit: int = CURVES_GZIP_BYTES) -> Path:
    """
    out/curves.csv, or out/curves.csv.gz (gzip, no timestamp: the same curves give the same bytes) when the text is
    longer than `limit` bytes; the other of the two, from an earlier write into `out`, is removed.
    """
    if len(text) <= limit:
        path = write_text(out / "curves.csv", text)
    else:
        path = out / "curves.csv.gz"
        with atomic_path(path) as tmp:
            tmp.write_bytes(gzip.compress(text.encode(), compresslevel=6, mtime=0))
    (out / ("curves.csv.gz" if path.name == "curves.csv" else "curves.csv")).unlink(missing_ok=True)
    return path


def write(report: Report, out: str | Path, *, full_curves: bool = False, doc: dict | None = None) -> dict[str, Path]:
    """
    Write report.json (`doc`, default `as_dict(report)`), curves.csv (`write_curves`: every sample to 17 digits with
    `full_curves`, else CURVE_ROWS of each run to CURVE_DIGITS; curves.csv.gz when long), model.xml and, for
    crease-pattern scenes, motion.fold, with reference curves reference.csv, into `out` (atomically).
    """
    out = Path(out)
    doc = as_dict(report) if doc is None else doc
    text = curves_csv(report, None, FULL_DIGITS) if full_curves else curves_csv(report)
    paths = {
        "report": write_text(out / "report.json", json_text(doc)),
        "curves": write_curves(out, text),
        "model": write_text(out / "model.xml", model_xml(report)),
    }
    if report.scene.pattern is not None:
        paths["fold"] = motion_fold(report, out / "motion.fold")
    if report.reference is not None:
        paths["reference"] = write_text(out / "reference.csv", report.reference.table)
    return paths
