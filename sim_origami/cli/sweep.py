"""`sim-origami sweep SCENE --grid NAME=START:STOP:STEP ...`: many light cross-checks in parallel, as a table.

Grid values are in command-line units (degrees, metres). Local processes by default; `--scheduler ADDRESS`
runs the same points on a Dask distributed cluster. Writes sweep.csv, sweep.parquet and sweep.png (the angle
error over the first axis, or a map over the first two); exit 0 when every point passes, 1 otherwise.
"""

import argparse
import importlib.util
import sys
from pathlib import Path

from tqdm import tqdm

from ..errors import ParameterError
from ..files import check_folder, claimed_folder
from ..presets import PRESET_NAMES, as_preset
from ..sweep import check_grid, check_scheduler, check_workers, parse_axis, sweep, write_tables
from .options import out_folder

NAME = "sweep"
HELP = "cross-check a scene over a parameter grid in parallel (local processes or a Dask cluster)"


def add_args(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("scene", help="scene name (see list)")
    parser.add_argument("--grid", action="append", required=True, metavar="NAME=START:STOP:STEP",
                        help="a swept parameter in degrees or metres (repeat for a product grid)")
    parser.add_argument("--preset", choices=PRESET_NAMES, help="default: the scene's own")
    parser.add_argument("--workers", type=int, help="local processes (default: every core)")
    parser.add_argument("--scheduler", help="Dask distributed scheduler address, e.g. tcp://10.0.0.5:8786")
    parser.add_argument("--out", type=out_folder, help="output folder (default runs/sweep-<scene>)")
    parser.add_argument("--force", action="store_true", help="write into a folder holding files this tool did not")


def _bar(stream, total: int):
    return tqdm(stream, total=total, desc="sweep", unit="point", file=sys.stderr)


def run(args: argparse.Namespace) -> int:
    from ..plots import plot_sweep

    axes = [parse_axis(text) for text in args.grid]
    check_grid(args.scene, axes)
    check_workers(args.workers)
    out = args.out or Path("runs") / f"sweep-{args.scene}"
    check_folder(out, make=False)
    if args.scheduler:  # as `sweep` checks it, but before the output folder is claimed
        if importlib.util.find_spec("distributed") is None:
            raise ParameterError(f"--scheduler {args.scheduler} needs Dask distributed: pip install -e '.[cluster]'")
        check_scheduler(args.scheduler)
    with claimed_folder(out, force=args.force) as stage:  # the previous sweep's files stay until this one finishes
        preset = as_preset(args.preset) if args.preset else None
        rows = sweep(args.scene, axes, preset=preset, workers=args.workers, scheduler=args.scheduler, progress=_bar)
        paths = {kind: out / path.name for kind, path in write_tables(rows, stage).items()}
        plot_sweep(rows, [a.name for a in axes], stage / "sweep.png")
    failed = [r for r in rows if not r["passed"]]
    parquet = paths.get("parquet", "no sweep.parquet (pip install -e '.[cluster]' for pyarrow)")
    print(f"{len(rows)} points, {len(rows) - len(failed)} passed, {len(failed)} failed; "
          f"{paths['csv']}, {parquet}, {out / 'sweep.png'}")
    for r in failed[:5]:
        where = ", ".join(f"{a.name}={r[a.name]:g}" for a in axes)
        print(f"  failed at {where}: {r['error'] or format(r['angle_error_max_rad'], '.3g') + ' rad off'}")
    return 0 if not failed else 1
