"""A user's own curves (CSV) against the numeric path and MuJoCo: the "check my equations" route.

The CSV holds one row per sample: the scene's input and any of its output joints, named as `describe` prints
them, with the unit in the header (`theta[deg],rho_a[deg]`) or given for every column at once. Lines starting
with '#' are comments. Only the scene's `Kinematics` is read (input_name, joint_names, branches, evaluate,
loop_system, loop_input, loop_angles, observe) and MuJoCo's trajectories, so built-in, FOLD and plugin scenes
are checked alike.

Each sample is put on the branch nearest to it (max-norm over its joint columns) and kept on the previous one
while that is as near within the sample's tolerance, so a curve through a bifurcation stays on its branch. The
truth is the independent numeric loop solve, followed by continuation from the sample of each stretch on one branch
that lies farthest from the branch's events (steps of at most MAX_STEP rad); the scene's kinematics and MuJoCo
are reported beside it.

The default tolerance of a value is what its printing allows: half a unit in its last printed digit, plus the
joint's slope times half a unit in the last digit of the printed input, plus TOLERANCES.closed_form_rad (the
numeric truth's own accuracy), plus SINGULAR_RAD at a sample where the closure Jacobian loses rank (a bifurcation
point: there the solve pins the joints only to about the square root of its residual). `tol` replaces that by one
number for every value.
"""

import csv
import io
import itertools
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from ..errors import ConvergenceError, ParameterError
from ..geometry import wrap
from ..kinematics.base import Kinematics
from ..precision import half_unit
from ..scenes.base import Scene
from ..tolerances import TOLERANCES
from .verdict import Verdict

# Unit names accepted in a header bracket or as `units`, to radians per unit.
UNITS = {"deg": np.pi / 180.0, "degree": np.pi / 180.0, "degrees": np.pi / 180.0, "rad": 1.0, "radian": 1.0,
         "radians": 1.0}
# Largest input step (rad) of the numeric continuation between two samples: finer steps are inserted, so a coarse
# reference cannot make the solver jump to another branch.
MAX_STEP = 0.02
# Disagreeing samples listed in report.json (the worst first); the count covers every one.
LISTED = 20
# Input step (rad) of the central difference that gives a joint's slope for the printed-input term.
SLOPE_STEP = 1e-6
# The numeric solve's accuracy where the closure Jacobian loses rank: Newton converges only linearly there and stops
# with joints off by about sqrt(residual). Measured 4.5e-7 rad at the Miura vertex's flat bifurcation (30/60 deg;
# 1e-13 residual), against 1e-14 on either side of it.
SINGULAR_RAD = 2e-6
# Most samples a reference may have: each costs the numeric loop solve about SAMPLE_CPU_MS of CPU (the Goldberg 5R
# example at 2,000 samples: 6.8 s), so 10,000 take about half a minute.
MAX_SAMPLES = 10_000
SAMPLE_CPU_MS = 3.4
# Largest tolerance a value's printing gives it (rad): one decimal in radians (0.05) or whole degrees (0.0087) are
# honoured, while '1e+308' would hold its value to 5e307 rad and pass whatever it is compared with. A value printed
# coarser than this is held to it.
PRINTED_MAX_RAD = 0.1
COLUMN = re.compile(r"^\s*([^\[\]]*?)\s*(?:\[\s*([^\[\]]*?)\s*\])?\s*$")


@dataclass(frozen=True)
class ReferenceCurves:
    """
    A user's curves, read and checked (`read_reference`).

    Attributes
    ----------
    x : (n,) inputs (rad), strictly monotone.
    values : (n, m) joint values (rad) of the `joints` columns.
    printed : (n, m) half a unit in the last printed digit of each value (rad).
    x_printed : (n,) the same for each input (rad).
    lines : (n,) line number of each sample in the file (1-based).
    tol : one tolerance (rad) for every value, or None for the printed-precision rule.
    """

    source: str
    input_name: str
    joints: tuple[str, ...]
    units: dict[str, str]
    x: NDArray[np.float64]
    values: NDArray[np.float64]
    printed: NDArray[np.float64]
    x_printed: NDArray[np.float64]
    lines: NDArray[np.int64]
    tol: float | None = None

    @property
    def tolerance_rule(self) -> str:
        if self.tol is not None:
            return f"{self.tol:.3g} rad for every value (given)"
        return ("half a unit in the last printed digit of each value, plus its slope times half a unit in the "
                f"input's last printed digit, plus {TOLERANCES.closed_form_rad:g} rad (the numeric solve; "
                f"{SINGULAR_RAD:g} rad at singular samples)")


def _shown(cell: str) -> str:
    """A cell as a message quotes it: its first 20 characters and its length when over 40."""
    cell = cell.strip()
    return cell if len(cell) <= 40 else f"{cell[:20]}...({len(cell)} characters)"


def _unit(source: str, column: str, stated: str | None, units: str | None) -> str:
    """The column's unit: the header's, or `units`; one given, known, and never contradicted."""
    if units is not None and units not in UNITS:
        raise ParameterError(f"reference units {units!r} are unknown; use deg or rad")
    if stated is None:
        if units is None:
            raise ParameterError(
                f"reference {source}: column {column!r} states no unit; write {column}[deg] or {column}[rad] in the "
                "header, or give the units (--reference-units deg|rad)"
            )
        return units
    if stated.lower() not in UNITS:
        raise ParameterError(f"reference {source}: column {column!r} has unit [{stated}]; units are deg or rad")
    if units is not None and UNITS[stated.lower()] != UNITS[units]:
        raise ParameterError(f"reference {source}: column {column!r} states [{stated}] but the units given are "
                             f"{units}; drop one of them")
    return stated.lower()


def _rows(source: str, text: str) -> list[tuple[int, list[str]]]:
    """(line number, fields) of every line that is neither blank nor a '#' comment; at most MAX_SAMPLES samples."""
    out = []
    for number, line in enumerate(text.splitlines(), start=1):
        if line.strip() and not line.lstrip().startswith("#"):
            if len(out) > MAX_SAMPLES:
                raise ParameterError(f"reference {source}: more than {MAX_SAMPLES} samples (line {number}); the "
                                     f"numeric solve costs about {SAMPLE_CPU_MS:g} ms of CPU a sample: thin the "
                                     "curve")
            try:
                out.append((number, next(csv.reader([line]))))
            except csv.Error as exc:
                raise ParameterError(f"reference {source}: line {number} is not a CSV row ({exc})") from None
    if not out:
        raise ParameterError(f"reference {source}: no header and no samples (only comments or blank lines)")
    return out


def read_reference(
    path: str | Path, kinematics: Kinematics, *, units: str | None = None, tol: float | None = None
) -> ReferenceCurves:
    """
    Read and check a reference CSV against a scene's kinematics (names and units only; nothing is solved).

    Parameters
    ----------
    units : 'deg' or 'rad' for every column whose header states no unit (a stated one must agree).
    tol : one tolerance (rad) for every value, > 0; None: the printed-precision rule.

    Raises
    ------
    ParameterError
      Naming the file, line and column: missing or unreadable file, no comma-separated header, an unknown,
      repeated or missing column, no unit, a unit other than deg/rad, a value that is not a finite number, a row
      of the wrong length, inputs not strictly monotone, fewer than 2 samples, a tolerance not > 0.
    """
    path = Path(path)
    source = str(path)
    if tol is not None and not (math.isfinite(tol) and tol > 0):
        raise ParameterError(f"reference tolerance {tol!r} rad; it must be a finite number > 0")
    try:
        text = path.read_text(encoding="utf-8-sig")  # a spreadsheet may lead with a byte-order mark
    except FileNotFoundError:
        raise ParameterError(f"reference {source}: no such file") from None
    except IsADirectoryError:
        raise ParameterError(f"reference {source}: is a folder, not a CSV file") from None
    except UnicodeDecodeError:
        raise ParameterError(f"reference {source}: not a text CSV file (not UTF-8)") from None
    except OSError as exc:
        raise ParameterError(f"reference {source}: cannot be read ({exc.strerror})") from None
    rows = _rows(source, text)
    head_line, header = rows[0]
    if len(header) < 2:
        raise ParameterError(
            f"reference {source}: line {head_line} is not a CSV header with an input and at least one joint column, "
            f"e.g. {kinematics.input_name}[deg],{kinematics.joint_names[0]}[deg]"
        )
    names, unit_of = [], {}
    for cell in header:
        match = COLUMN.match(cell)
        name = match.group(1) if match else cell.strip()
        if not match or not name:
            raise ParameterError(f"reference {source}: header column {cell!r} is not NAME or NAME[unit]")
        if name in unit_of:
            raise ParameterError(f"reference {source}: column {name!r} appears twice in the header")
        if name != kinematics.input_name and name not in kinematics.joint_names:
            raise ParameterError(
                f"reference {source}: unknown column {name!r}; this scene's input is {kinematics.input_name} and its "
                f"joints are {', '.join(kinematics.joint_names)}"
            )
        unit_of[name] = _unit(source, name, match.group(2), units)
        names.append(name)
    if kinematics.input_name not in unit_of:
        raise ParameterError(f"reference {source}: no input column {kinematics.input_name!r} in the header "
                             f"({', '.join(names)})")
    joints = tuple(n for n in kinematics.joint_names if n in unit_of and n != kinematics.input_name)
    if not joints:
        raise ParameterError(f"reference {source}: no joint column besides the input; joints are "
                             f"{', '.join(kinematics.joint_names)}")
    data = rows[1:]
    if len(data) < 2:
        raise ParameterError(f"reference {source}: {len(data)} sample(s); a curve needs at least 2")
    numbers = np.empty((len(data), len(names)))
    printed = np.empty_like(numbers)
    for r, (line, fields) in enumerate(data):
        if len(fields) != len(names):
            raise ParameterError(f"reference {source}: line {line} has {len(fields)} values; the header has "
                                 f"{len(names)} columns")
        for c, cell in enumerate(fields):
            try:
                value = float(cell)
            except ValueError:
                raise ParameterError(f"reference {source}: line {line}, column {names[c]}: '{_shown(cell)}' is not "
                                     "a number") from None
            if not math.isfinite(value):
                raise ParameterError(f"reference {source}: line {line}, column {names[c]}: {_shown(cell)} is not a "
                                     "finite number")
            numbers[r, c] = value * UNITS[unit_of[names[c]]]
            printed[r, c] = min(half_unit(cell) * UNITS[unit_of[names[c]]], PRINTED_MAX_RAD)
    lines = np.array([line for line, _ in data])
    k = names.index(kinematics.input_name)
    x = numbers[:, k]
    step = np.sign(x[1] - x[0])
    for r in range(1, len(x)):
        if step == 0 or np.sign(x[r] - x[r - 1]) != step:
            raise ParameterError(f"reference {source}: line {lines[r]}: {kinematics.input_name} does not "
                                 f"{'increase' if step >= 0 else 'decrease'} from the previous sample; inputs must "
                                 "be strictly monotone")
    cols = [names.index(j) for j in joints]
    return ReferenceCurves(source, kinematics.input_name, joints, {n: unit_of[n] for n in names}, x,
                           numbers[:, cols], printed[:, cols], printed[:, k], lines, tol)


@dataclass
class _Branches:
    """Per-sample branch labels ('' outside every domain) and each branch's values at the samples."""

    labels: list[str]
    values: dict[str, NDArray[np.float64]] = field(default_factory=dict)  # (n, k) full joint values, NaN outside
    inputs: dict[str, NDArray[np.float64]] = field(default_factory=dict)  # (n,) inputs held inside the domain


def _assign(
    kin: Kinematics, ref: ReferenceCurves, cols: list[int], row_tol: NDArray[np.float64], names: tuple[str, ...]
) -> _Branches:
    """Nearest of the branches `names` per sample, kept on the previous one while that is as near within the sample's
    tolerance. An input within its printing's half unit of a domain end is taken at that end."""
    out = _Branches([])
    dist = {}
    for b in (kin.branch(name) for name in names):
        lo, hi = b.domain
        xb = np.where((ref.x < lo) & (ref.x >= lo - ref.x_printed), lo, ref.x)
        xb = np.where((xb > hi) & (xb <= hi + ref.x_printed), hi, xb)
        values, valid = kin.evaluate(b.name, xb)
        d = np.full(len(xb), np.inf)
        d[valid] = np.max(np.abs(wrap(ref.values[valid] - values[valid][:, cols])), axis=1)
        out.values[b.name], out.inputs[b.name], dist[b.name] = values, xb, d
    previous = ""
    for i in range(len(ref.x)):
        nearest = min(dist, key=lambda name, i=i: dist[name][i])
        if not np.isfinite(dist[nearest][i]):
            out.labels.append("")
            continue
        if previous and dist[previous][i] <= dist[nearest][i] + row_tol[i]:
            nearest = previous
        out.labels.append(nearest)
        previous = nearest
    # Samples before the first one that tells the branches apart (a curve starting at a bifurcation) take its branch.
    clear = [i for i, lab in enumerate(out.labels)
             if lab and all(dist[b][i] > dist[lab][i] + row_tol[i] for b in dist if b != lab)]
    if clear:
        first = out.labels[clear[0]]
        for i in range(clear[0]):
            if out.labels[i] and dist[first][i] <= dist[out.labels[i]][i] + row_tol[i]:
                out.labels[i] = first
    return out


def _start(kin: Kinematics, branch: str, x: NDArray[np.float64]) -> int:
    """The sample to start the numeric solve at: the farthest from every event of the branch (at a bifurcation the
    first step could take either branch, at a lock the loop is singular); the middle one if there are none."""
    events = np.array([e.input for e in kin.events() if branch in e.branches])
    if not events.size:
        return len(x) // 2
    clearance = np.min(np.abs(x[:, None] - events[None, :]), axis=1)
    return int(np.argmax(clearance))


def _numeric(kin: Kinematics, branch: str, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """
    Outputs (n, k) of the numeric loop solve at inputs x (monotone), followed by continuation both ways from the
    sample farthest from the branch's events (`_start`), started at the kinematics' pose there; steps of at most
    MAX_STEP rad. Also whether each sample is singular: its instantaneous mobility above the start's.
    """
    loops = kin.loop_system()
    joint, scale = kin.loop_input()
    mid = _start(kin, branch, x)
    q0 = kin.loop_angles(kin.evaluate(branch, x[mid : mid + 1])[0])[0]
    out = np.empty((len(x), len(kin.joint_names)))
    singular = np.zeros(len(x), dtype=bool)
    regular = loops.mobility(q0)
    for idx in (np.arange(mid, len(x)), np.arange(mid, -1, -1)):
        grid, at = [x[idx[0]]], [0]
        for a, b in itertools.pairwise(x[idx]):
            steps = max(1, math.ceil(abs(b - a) / MAX_STEP))
            grid.extend(np.linspace(a, b, steps + 1)[1:])
            at.append(len(grid) - 1)
        q = loops.follow(q0, joint, scale * np.array(grid))[at]
        out[idx] = kin.observe(q)
        singular[idx] = [loops.mobility(qi) > regular for qi in q]
    return out, singular


def _slopes(kin: Kinematics, branch: str, x: NDArray[np.float64], cols: list[int]) -> NDArray[np.float64]:
    """|d joint / d input| (n, m) on `branch` by central differences (one-sided at a domain end, 0 if neither)."""
    lo, hi = kin.branch(branch).domain
    up = np.minimum(x + SLOPE_STEP, hi)
    down = np.maximum(x - SLOPE_STEP, lo)
    a, _ = kin.evaluate(branch, up)
    b, _ = kin.evaluate(branch, down)
    width = np.where(up > down, up - down, 1.0)
    return np.nan_to_num(np.abs(wrap(a[:, cols] - b[:, cols])) / width[:, None])


def _mujoco(scene: Scene, runs, branch: str, x: NDArray[np.float64]) -> NDArray[np.float64] | None:
    """
    MuJoCo's outputs (n, k) at inputs x from the run on `branch` (NaN outside its simulated range), or None if no
    run was on it. MuJoCo's deviation from the scene's kinematics, which is small and smooth, is interpolated
    linearly and added to the kinematics at x: interpolating the curves themselves would add the chord error
    (about 1e-6 rad at 250 samples a radian), which is more than MuJoCo's own.
    """
    for run in runs:
        if run.requested != branch:
            continue
        path = run.dynamic_path
        order = np.argsort(path.input, kind="stable")
        xs, keep = np.unique(path.input[order], return_index=True)
        deviation = wrap(path.simulated - path.analytic)[order][keep]
        analytic, _ = scene.kinematics.evaluate(branch, x)
        inside = (x >= xs[0]) & (x <= xs[-1])
        out = np.full_like(analytic, np.nan)
        for j in range(analytic.shape[1]):
            out[inside, j] = analytic[inside, j] + np.interp(x[inside], xs, deviation[:, j])
        return out
    return None


@dataclass(frozen=True)
class ReferenceCheck:
    """The comparison's numbers (report.json's `reference`, radians), its verdicts, and one row per sample
    (reference.csv: line, input, branch, and per joint reference, numeric, MuJoCo, error and tolerance)."""

    doc: dict
    verdicts: tuple[Verdict, ...]
    table: str = ""
    joints: tuple[str, ...] = ()  # the reference's joint columns
    x: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))  # (n,) inputs (rad)
    labels: tuple[str, ...] = ()  # branch of each sample, '' outside every branch
    values: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))  # (n, m) the reference (rad)
    error: NDArray[np.float64] = field(default_factory=lambda: np.zeros((0, 0)))  # (n, m) |reference - numeric|

    def on(self, branch: str) -> NDArray[np.bool_]:
        """Which samples lie on `branch`."""
        return np.array([lab == branch for lab in self.labels], dtype=bool)


def _max(a: NDArray[np.float64]) -> float | None:
    a = a[np.isfinite(a)]
    return float(np.max(a)) if a.size else None


def compare_reference(
    ref: ReferenceCurves, scene: Scene, runs=(), branches: tuple[str, ...] | None = None
) -> ReferenceCheck:
    """
    The user's curves against the numeric loop solve (the verdict), the scene's kinematics and MuJoCo's runs
    (`validation.BranchRun`s), sample by sample on the branch each falls on: one of `branches` (default every
    branch), so that a run restricted to a branch checks the curves on that branch alone. A curve passes only if
    every sample on a branch was compared with the numeric solve, each stretch on a branch was compared with MuJoCo
    where it ran, and it changes branch only where the two branches meet.
    """
    kin = scene.kinematics
    names = tuple(b.name for b in kin.branches()) if branches is None else tuple(branches)
    if ref.input_name != kin.input_name or any(j not in kin.joint_names for j in ref.joints):
        raise ParameterError(f"reference {ref.source} was read for another scene (input {ref.input_name})")
    cols = [kin.joint_names.index(j) for j in ref.joints]
    n, m = ref.values.shape
    slope_tol = np.zeros((n, m))
    row_tol = np.max(ref.printed, axis=1) if ref.tol is None else np.full(n, ref.tol)
    assigned = _assign(kin, ref, cols, row_tol, names)
    labels = np.array(assigned.labels)
    numeric = np.full((n, m), np.nan)
    kinematic = np.full((n, m), np.nan)
    mujoco = np.full((n, m), np.nan)
    simulated = np.zeros(n, dtype=bool)
    singular = np.zeros(n, dtype=bool)
    stalls, segments = [], []
    for name, group in itertools.groupby(range(n), key=lambda i: labels[i]):
        idx = np.array(list(group))
        if not name:
            continue
        xb = assigned.inputs[name][idx]
        segments.append({"branch": str(name), "samples": len(idx), "lines": [int(ref.lines[idx[0]]),
                         int(ref.lines[idx[-1]])], "input_range_rad": [float(xb[0]), float(xb[-1])]})
        kinematic[idx] = assigned.values[name][idx][:, cols]
        try:
            values, singular[idx] = _numeric(kin, name, xb)
            numeric[idx] = values[:, cols]
        except ConvergenceError as exc:
            stalls.append({"branch": str(name), "lines": [int(ref.lines[idx[0]]), int(ref.lines[idx[-1]])],
                           "error": str(exc)})
        if ref.tol is None:
            slope_tol[idx] = _slopes(kin, name, xb, cols) * ref.x_printed[idx, None]
        sim = _mujoco(scene, runs, name, xb)
        if sim is not None:
            mujoco[idx] = sim[:, cols]
            simulated[idx] = np.all(np.isfinite(sim[:, cols]), axis=1)
            segments[-1]["mujoco_samples"] = int(np.sum(simulated[idx]))
    if ref.tol is not None:
        tol = np.full((n, m), ref.tol)
    else:
        tol = ref.printed + slope_tol + TOLERANCES.closed_form_rad + np.where(singular, SINGULAR_RAD, 0.0)[:, None]
    error = np.abs(wrap(ref.values - numeric))
    compared = np.all(np.isfinite(error), axis=1)
    over = np.isfinite(error) & (error > tol)
    outside = [{"line": int(ref.lines[i]), "input_rad": float(ref.x[i])} for i in np.flatnonzero(labels == "")]
    worst = None
    disagree = []
    if compared.any():
        i, j = np.unravel_index(int(np.argmax(np.where(np.isfinite(error), error, -np.inf))), error.shape)
        worst = _sample(ref, labels, error, tol, i, j)
        for i, j in sorted(zip(*np.nonzero(over), strict=True), key=lambda ij: -error[ij])[:LISTED]:
            disagree.append(_sample(ref, labels, error, tol, i, j))
    doc = {
        "file": ref.source,
        "input": ref.input_name,
        "joints": list(ref.joints),
        "units": ref.units,
        "samples": n,
        "tolerance_rule": ref.tolerance_rule,
        "branches": segments,
        "outside_every_branch": outside,
        "numeric_stalls": stalls,
        "singular_samples": [int(line) for line in ref.lines[singular]],
        "compared_samples": int(np.sum(compared)),
        "over_tolerance": {"samples": int(np.sum(np.any(over, axis=1))), "values": int(np.sum(over))},
        "reference_vs_numeric_max_rad": _max(error),
        "reference_vs_kinematics_max_rad": _max(np.abs(wrap(ref.values - kinematic))),
        "kinematics_vs_numeric_max_rad": _max(np.abs(wrap(kinematic - numeric))),
        "mujoco_samples": int(np.sum(simulated)),
        "mujoco_not_simulated": int(np.sum(compared & ~simulated)),
        "reference_vs_mujoco_max_rad": _max(np.abs(wrap(ref.values - mujoco))),
        "numeric_vs_mujoco_max_rad": _max(np.abs(wrap(numeric - mujoco))),
        "worst": worst,
        "disagreeing": disagree,
        "branch_switches": _switches(kin, ref, labels, assigned, cols, row_tol),
    }
    return ReferenceCheck(doc, _verdicts(doc, n), _table(ref, labels, numeric, mujoco, error, tol), ref.joints, ref.x,
                          tuple(str(lab) for lab in labels), ref.values, error)


def _switches(kin: Kinematics, ref: ReferenceCurves, labels, assigned: _Branches, cols: list[int], row_tol) -> list:
    """
    Where the curve passes from one branch to another between consecutive samples, and whether the two branches
    meet there: a bifurcation of both between the samples, or the branches within the samples' tolerance of each
    other at either sample. A curve that jumps between branches that do not meet follows no motion of the mechanism.
    """
    out = []
    for i in np.flatnonzero((labels[:-1] != labels[1:]) & (labels[:-1] != "") & (labels[1:] != "")):
        a, b = str(labels[i]), str(labels[i + 1])
        lo, hi = sorted((ref.x[i], ref.x[i + 1]))
        bifurcation = any(e.kind == "bifurcation" and {a, b} <= set(e.branches) and lo - ref.x_printed[i] <= e.input
                          <= hi + ref.x_printed[i + 1] for e in kin.events())
        gaps = [float(np.max(np.abs(wrap(assigned.values[a][k, cols] - assigned.values[b][k, cols]))))
                for k in (i, i + 1)]
        meet = bifurcation or any(g <= row_tol[k] for g, k in zip(gaps, (i, i + 1), strict=True))
        out.append({"from": a, "to": b, "lines": [int(ref.lines[i]), int(ref.lines[i + 1])],
                    "input_rad": [float(ref.x[i]), float(ref.x[i + 1])], "branch_gap_rad": min(gaps),
                    "branches_meet": bool(meet)})
    return out


def _table(ref: ReferenceCurves, labels, numeric, mujoco, error, tol) -> str:
    """reference.csv: one row per sample ('nan' where a value does not exist: off every branch, not simulated)."""
    buf = io.StringIO()
    header = ["line", "input_rad", "branch"]
    for j in ref.joints:
        header += [f"{j}_reference_rad", f"{j}_numeric_rad", f"{j}_mujoco_rad", f"{j}_error_rad", f"{j}_tolerance_rad"]
    buf.write(",".join(header) + "\n")
    values = np.stack([ref.values, numeric, mujoco, error, tol], -1).reshape(len(ref.x), -1)
    for i in range(len(ref.x)):
        cells = [str(int(ref.lines[i])), f"{ref.x[i]:.17g}", str(labels[i])] + [f"{v:.17g}" for v in values[i]]
        buf.write(",".join(cells) + "\n")
    return buf.getvalue()


def _sample(ref: ReferenceCurves, labels, error, tol, i: int, j: int) -> dict:
    scale = UNITS[ref.units[ref.input_name]]
    return {"line": int(ref.lines[i]), "input_rad": float(ref.x[i]), "input_as_written": float(ref.x[i] / scale),
            "joint": ref.joints[j], "branch": str(labels[i]), "error_rad": float(error[i, j]),
            "tolerance_rad": float(tol[i, j])}


def _where(s: dict, input_name: str, unit: str) -> str:
    return (f"{s['joint']} at {input_name} = {s['input_as_written']:.10g} {unit} (line {s['line']}, branch "
            f"{s['branch']})")


# Each reference check's stable id (`Verdict.id`, report.json's `verdicts[].id`).
REFERENCE_OVER_TOLERANCE = "reference-over-tolerance"  # samples farther from the numeric solve than their tolerance
REFERENCE_OUTSIDE_DOMAINS = "reference-outside-domains"  # samples outside every branch's domain
REFERENCE_NUMERIC_STALLS = "reference-numeric-stalls"  # stretches where the numeric loop solve stalled
REFERENCE_BRANCH_JUMPS = "reference-branch-jumps"  # switches of branch where the two branches do not meet
REFERENCE_UNSIMULATED = "reference-unsimulated"  # stretches on a simulated branch outside MuJoCo's swept range


def _verdicts(doc: dict, n: int) -> tuple[Verdict, ...]:
    unit = doc["units"][doc["input"]]
    w = doc["worst"]
    if w is None:
        detail = "no sample lies on a branch: nothing compared"
    else:
        detail = (f"max {w['error_rad']:.3g} rad, {_where(w, doc['input'], unit)}, tolerance there "
                  f"{w['tolerance_rad']:.3g} rad; {doc['over_tolerance']['samples']} of {doc['compared_samples']} "
                  f"samples over tolerance; tolerance: {doc['tolerance_rule']}")
    over = doc["over_tolerance"]["samples"] if doc["compared_samples"] else n
    outside = doc["outside_every_branch"]
    where = ", ".join(f"line {s['line']}" for s in outside[:5]) + (" ..." if len(outside) > 5 else "")
    jumps = [s for s in doc["branch_switches"] if not s["branches_meet"]]
    jumped = "; ".join(f"{s['from']} -> {s['to']} between lines {s['lines'][0]} and {s['lines'][1]} (the branches "
                       f"{s['branch_gap_rad']:.3g} rad apart)" for s in jumps)
    unsimulated = [s for s in doc["branches"] if s.get("mujoco_samples") == 0]
    return (
        Verdict("reference curves vs numeric loop closure: samples over tolerance", float(over), 0.0, detail,
                doc["compared_samples"], id=REFERENCE_OVER_TOLERANCE),
        Verdict("reference samples outside every branch's domain", float(len(outside)), 0.0, where or "none",
                id=REFERENCE_OUTSIDE_DOMAINS),
        Verdict("reference: numeric loop solve stalled (stretches)", float(len(doc["numeric_stalls"])), 0.0,
                "; ".join(s["error"] for s in doc["numeric_stalls"]) or "none", id=REFERENCE_NUMERIC_STALLS),
        Verdict("reference switches of branch where the two branches do not meet", float(len(jumps)), 0.0,
                jumped or "none", id=REFERENCE_BRANCH_JUMPS),
        Verdict("reference stretches on a simulated branch with no sample in MuJoCo's swept range",
                float(len(unsimulated)), 0.0,
                "; ".join(f"{s['branch']}, lines {s['lines'][0]}-{s['lines'][1]}" for s in unsimulated)
                or f"{doc['mujoco_samples']} of {doc['compared_samples']} compared samples compared with MuJoCo",
                id=REFERENCE_UNSIMULATED),
    )


def summary_lines(doc: dict) -> list[str]:
    """The comparison in a few printed lines (the CLI's verdict block)."""
    fmt = lambda v: "-" if v is None else f"{v:.3g}"  # noqa: E731
    on = ", ".join(f"{s['branch']} ({s['samples']})" for s in doc["branches"]) or "none"
    lines = [f"reference {doc['file']}: {doc['samples']} samples on {on}; "
             f"{len(doc['outside_every_branch'])} outside every branch",
             f"  reference vs numeric {fmt(doc['reference_vs_numeric_max_rad'])} rad, vs kinematics "
             f"{fmt(doc['reference_vs_kinematics_max_rad'])}, vs MuJoCo {fmt(doc['reference_vs_mujoco_max_rad'])} "
             f"({doc['mujoco_samples']} samples in the simulated range); numeric vs MuJoCo "
             f"{fmt(doc['numeric_vs_mujoco_max_rad'])}"]
    unit = doc["units"][doc["input"]]
    for s in doc["disagreeing"][:5]:
        lines.append(f"  over: {_where(s, doc['input'], unit)}: {s['error_rad']:.3g} rad > {s['tolerance_rad']:.3g}")
    return lines
