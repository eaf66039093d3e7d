"""Parameter sweeps: one light cross-check per grid point, in parallel, as a table.

Each point builds the scene from command-line units (degrees, metres) and, on every branch, checks the closed
form's loop residual and runs MuJoCo with the scene's preset over its default sweep (path error against the
closed form, closure gap, branch followed); the numeric continuation, projection and bifurcation study of a
full `validate` are left out so that thousands of points stay cheap. A point that fails (bad geometry, a
linkage that cannot be assembled, a MuJoCo warning) is recorded with its error message, never fatal.

Execution: local processes by default (`concurrent.futures`), or a Dask distributed cluster given its
scheduler address; both run the same picklable `run_point`. Dask and pyarrow come with the `cluster` extra
(`pip install -e '.[cluster]'`): without dask `--scheduler` is refused, without pyarrow only sweep.csv is written.
"""

import csv
import importlib.util
import io
import itertools
import os
import re
import socket
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import scenes
from .checks.branches import classify
from .checks.paths import compare
from .errors import ParameterError
from .files import atomic_path, write_text
from .mjcf import ModelOptions
from .presets import Preset, as_preset
from .simulate import compile_model, simulate
from .tolerances import TOLERANCES

# Largest grid a sweep takes: at 1 to 20 s of CPU per point, 10 000 points keep 8 cores busy for up to 7 hours.
GRID_POINTS_MAX = 10_000
# Most local processes (each holds a MuJoCo model; far beyond the cores only costs memory).
WORKERS_MAX = 1024
# How long a scheduler may take to accept a connection before the sweep is refused (s).
SCHEDULER_TIMEOUT_S = 5.0

METRICS = ("passed", "angle_error_max_rad", "closure_residual_max_m", "closed_form_residual_max",
           "branches_followed", "cpu_s", "error")


@dataclass(frozen=True)
class Axis:
    """One swept parameter and its values, in command-line units (degrees, metres)."""

    name: str
    values: tuple[float, ...]


def parse_axis(text: str) -> Axis:
    """'NAME=START:STOP:STEP' (STOP included when the steps land on it) -> Axis; ParameterError otherwise."""
    name, sep, spec = text.partition("=")
    parts = spec.split(":")
    if not sep or not name or len(parts) != 3:
        raise ParameterError(f"grid axis {text!r} is not NAME=START:STOP:STEP")
    try:
        start, stop, step = (float(p) for p in parts)
    except ValueError:
        raise ParameterError(f"grid axis {text!r}: START, STOP and STEP must be numbers") from None
    if not all(np.isfinite((start, stop, step))):
        raise ParameterError(f"grid axis {text!r}: START, STOP and STEP must be finite numbers")
    if not step > 0 or stop < start:
        raise ParameterError(f"grid axis {text!r}: needs STEP > 0 and STOP >= START")
    count = np.floor((stop - start) / step + 1e-9) + 1  # a float first: a tiny step must not allocate the grid
    if not count <= GRID_POINTS_MAX:
        raise ParameterError(f"grid axis {text!r} has {count:.3g} points; a sweep takes at most {GRID_POINTS_MAX}")
    return Axis(name.strip(), tuple(float(v) for v in start + step * np.arange(int(count))))


def check_grid(scene_name: str, axes: list[Axis]) -> None:
    """
    ParameterError before any work when an axis names no parameter of the scene or is given twice, a value breaks
    its parameter's rule (`Param.check`), or the grid has more than GRID_POINTS_MAX points.
    """
    kind = scenes.get(scene_name)
    known = {p.name: p for p in kind.params}
    seen = set()
    for axis in axes:
        if axis.name not in known:
            raise ParameterError(f"unknown parameter {axis.name!r} for scene {scene_name!r}; parameters are "
                                 f"{', '.join(sorted(known))}")
        if axis.name in seen:
            raise ParameterError(f"grid axis {axis.name!r} is given twice; give each parameter one --grid")
        seen.add(axis.name)
        for value in axis.values:
            known[axis.name].check(known[axis.name].to_api(value))
    total = float(np.prod([len(a.values) for a in axes]))
    if total > GRID_POINTS_MAX:
        raise ParameterError(f"the grid has {total:.3g} points; a sweep takes at most {GRID_POINTS_MAX}")


def check_workers(workers: int | None) -> None:
    """ParameterError unless `workers` is None (every core) or a whole number from 1 to WORKERS_MAX."""
    if workers is not None and not 1 <= workers <= WORKERS_MAX:
        raise ParameterError(f"--workers {workers}; it must be a whole number from 1 to {WORKERS_MAX}")


def check_scheduler(address: str, timeout: float = SCHEDULER_TIMEOUT_S) -> None:
    """
    ParameterError unless `address` is PROTOCOL://HOST:PORT (tcp, tls, ws, wss) and a scheduler answers there
    within `timeout` seconds (a TCP connection): an unreachable cluster is refused before any work.
    """
    if address.startswith("inproc://"):
        return  # a scheduler in this process (dask's LocalCluster(processes=False)): nothing to connect to
    match = re.fullmatch(r"(tcp|tls|ws|wss)://(\[[0-9a-fA-F:]+\]|[A-Za-z0-9_.-]+):(\d{1,5})", address)
    if not match:
        raise ParameterError(f"--scheduler {address!r} is not an address like tcp://HOST:PORT (tcp, tls, ws, wss)")
    host, port = match.group(2).strip("[]"), int(match.group(3))
    try:
        with socket.create_connection((host, port), timeout=timeout):
            pass
    except OSError as exc:
        raise ParameterError(
            f"--scheduler {address}: no scheduler answers there within {timeout:g} s ({exc.strerror or exc})"
        ) from None


def grid_points(axes: list[Axis]) -> list[dict[str, float]]:
    """Every combination of the axes' values (the last axis varies fastest)."""
    names = [a.name for a in axes]
    return [dict(zip(names, combo, strict=True)) for combo in itertools.product(*(a.values for a in axes))]


def run_point(scene_name: str, params: dict[str, float], preset: Preset | None = None) -> dict:
    """The light cross-check of one grid point (module docstring), with `preset` or the scene's; never raises."""
    row: dict = dict(params)
    t0 = time.process_time()
    try:
        scene = scenes.get(scene_name).build_from_user(params)
        kin, loops = scene.kinematics, scene.kinematics.loop_system()
        model = compile_model(scene, ModelOptions(preset=preset or scene.tuning.preset))  # every branch's run
        errors, gaps, residuals, followed = [], [], [], []
        for branch in kin.branches():
            start, stop = scene.branch_path(branch.name)
            x = np.linspace(start, stop, 50)
            residuals.append(float(np.max(loops.residual_norm(kin.loop_angles(kin.joint_angles(branch.name, x))))))
            run = simulate(scene, branch.name, model=model)
            path = compare(scene, branch.name, run.q)
            errors.append(path.max_error())
            gaps.append(float(np.max(run.closure_residual)))
            followed.append(classify(kin, path.input, path.simulated).followed)
        used = preset or scene.tuning.preset
        passed = (max(errors) <= used.angle_rad and max(gaps) <= used.residual(scene.length_scale)
                  and max(residuals) <= TOLERANCES.loop_residual(scene.length_scale)
                  and followed == [b.name for b in kin.branches()])
        row |= {"passed": bool(passed), "angle_error_max_rad": max(errors), "closure_residual_max_m": max(gaps),
                "closed_form_residual_max": max(residuals), "branches_followed": ";".join(followed),
                "error": ""}
    except Exception as exc:  # a failed point is data: record it and go on
        row |= {"passed": False, "angle_error_max_rad": float("nan"), "closure_residual_max_m": float("nan"),
                "closed_form_residual_max": float("nan"), "branches_followed": "",
                "error": f"{type(exc).__name__}: {exc}"}
    row["cpu_s"] = time.process_time() - t0
    return row


def _local(tasks: list[tuple], workers: int) -> Iterator[dict]:
    with ProcessPoolExecutor(max_workers=workers) as pool:
        futures = [pool.submit(run_point, *task) for task in tasks]
        for future in as_completed(futures):
            yield future.result()


def _dask(tasks: list[tuple], scheduler: str) -> Iterator[dict]:
    from dask.distributed import Client
    from dask.distributed import as_completed as dask_completed

    with Client(scheduler) as client:
        futures = client.map(run_point, *zip(*tasks, strict=True), pure=False)
        for future in dask_completed(futures):
            yield future.result()


def sweep(
    scene_name: str,
    axes: list[Axis],
    *,
    preset: Preset | str | None = None,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: Callable[[Iterator[dict], int], Iterator[dict]] | None = None,
) -> list[dict]:
    """
    Run `run_point` over the grid; rows in grid order.

    Parameters
    ----------
    preset : a `Preset` or its name; default each point's scene's.
    workers : local processes (default: the machine's cores); ignored with `scheduler`.
    scheduler : a Dask distributed scheduler address (e.g. tcp://10.0.0.5:8786), or None for local processes.
    progress : wraps the stream of finished rows (e.g. a tqdm bar), given the number of points.
    """
    chosen = as_preset(preset) if preset else None
    check_grid(scene_name, axes)
    check_workers(workers)
    if scheduler and importlib.util.find_spec("distributed") is None:
        raise ParameterError(f"--scheduler {scheduler} needs Dask distributed: pip install -e '.[cluster]'")
    if scheduler:
        check_scheduler(scheduler)
    points = grid_points(axes)
    tasks = [(scene_name, p, chosen) for p in points]
    stream = _dask(tasks, scheduler) if scheduler else _local(tasks, workers or os.cpu_count() or 1)
    rows = list(progress(stream, len(tasks)) if progress else stream)
    order = {tuple(p.values()): k for k, p in enumerate(points)}
    return sorted(rows, key=lambda r: order[tuple(r[a.name] for a in axes)])


def write_tables(rows: list[dict], out: Path) -> dict[str, Path]:
    """sweep.csv and, when pyarrow is installed (the `cluster` extra), sweep.parquet in `out`, each atomically."""
    columns = list(rows[0])
    buf = io.StringIO()
    writer = csv.DictWriter(buf, fieldnames=columns)
    writer.writeheader()
    writer.writerows(rows)
    paths = {"csv": write_text(out / "sweep.csv", buf.getvalue())}
    if importlib.util.find_spec("pyarrow") is None:
        return paths
    import pyarrow as pa
    import pyarrow.parquet as pq

    with atomic_path(out / "sweep.parquet") as tmp:
        pq.write_table(pa.Table.from_pylist(rows), tmp)
    paths["parquet"] = out / "sweep.parquet"
    return paths
