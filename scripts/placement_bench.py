"""Where a linkage sits does not matter: one linkage drawn as axis lines at several placements, validated side by side.

The spherical 4R (twists 70, 90, 80, 100 deg) and the Bennett linkage of docs/examples/linkages/bennett.toml, each
written as D-H rows, traced, then drawn as axis lines at its pose theta1 = 30 deg (each joint's point one length unit
out along its axis) at the origin, translated only, and rotated and translated (three rotations); every number
written as Python prints a float (17 significant digits). Prints each run's verdict and its report's
CPU (s), and each rotated placement's CPU over the translated one's (docs/performance.md, "Placement").

    .venv/bin/python scripts/placement_bench.py
"""

import json
import sys
import tempfile
from contextlib import redirect_stdout
from io import StringIO
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

from sim_origami.cli import main
from sim_origami.kinematics.dh import DHRow
from sim_origami.linkage_forms import chain_poses
from sim_origami.scenes.linkage_file import linkage_scene
from sim_origami.validation import CLOSED_FORM_VS_NUMERIC

OFFSET = np.array([37.3, -12.9, 55.1])  # length units: 40 times the spherical 4R's size
ROTATIONS = ([0.3, -1.1, 0.7], [2.0, 0.4, -0.9], [-0.6, 1.7, 2.2])  # rotation vectors (rad)
# D-H rows (a in length units, alpha in deg) and the input range (deg)
ROWS = {"spherical-4r": [(0.0, 70.0), (0.0, 90.0), (0.0, 80.0), (0.0, 100.0)],
        "bennett": [(1.0, 30.0), (1.5, 48.590377890729144)] * 2}
RANGE = {"spherical-4r": [10.0, 60.0], "bennett": [20.0, 140.0]}
DRAWN_AT = 30.0  # theta1 (deg) of the drawn pose


def drawn_pose(folder: Path, name: str) -> tuple[tuple[DHRow, ...], np.ndarray]:
    """A linkage's D-H rows (length units, rad) and its joint angles (rad) at theta1 = DRAWN_AT, traced from its
    D-H file."""
    doc = {"sim_origami_linkage": 1, "form": "dh", "input": {"joint": "theta1", "range": RANGE[name]},
           "joints": [{"a": a, "alpha": alpha} for a, alpha in ROWS[name]]}
    source = folder / f"{name}-dh.json"
    source.write_text(json.dumps(doc))
    q0 = linkage_scene(source).kinematics.evaluate("path-1", [np.radians(DRAWN_AT)])[0][0]
    return tuple(DHRow(0.0, a, np.radians(alpha)) for a, alpha in ROWS[name]), q0


def axes_file(folder: Path, name: str, rows, q0, rotation: np.ndarray, offset: np.ndarray, tag: str) -> Path:
    """The linkage drawn as axis lines at pose q0, turned by `rotation` and moved by `offset`."""
    poses = chain_poses(rows, q0)
    joints = []
    for k in range(len(rows)):
        T = poses[f"link_{k + 1}"][0]
        point = rotation @ (T[:3, 3] + T[:3, 2]) + offset  # one unit out along the axis: a sphere's joints apart
        joints.append({"name": f"theta{k + 1}", "bodies": [f"link_{(k - 1) % len(rows) + 1}", f"link_{k + 1}"],
                       "point": point.tolist(), "direction": (rotation @ T[:3, 2]).tolist(),
                       "theta0": float(np.rad2deg(q0[k]))})
    doc = {"sim_origami_linkage": 1, "form": "axes", "name": f"{name}-{tag}", "ground": f"link_{len(rows)}",
           "joints": joints, "input": {"joint": "theta1", "range": RANGE[name]}}
    path = folder / f"{name}-{tag}.json"
    path.write_text(json.dumps(doc))
    return path


def validate(path: Path, out: Path) -> tuple[int, float, float]:
    """Exit status, the report's total CPU (s) and its largest closed-form vs numeric closure distance (rad)."""
    with redirect_stdout(StringIO()):
        code = main(["validate", "--linkage", str(path), "--out", str(out)])
    report = json.loads((out / "report.json").read_text())
    worst = max((v["measured"] for v in report["verdicts"] if v["id"] == CLOSED_FORM_VS_NUMERIC), default=0.0)
    return code, report["timings_s"]["total_cpu_s"], worst


def run() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        print("| linkage | placement | exit | total CPU (s) | closed form vs numeric (rad) | CPU / translated |")
        print("|---|---|---|---|---|---|")
        for name in RANGE:
            rows, q0 = drawn_pose(folder, name)
            placements = [("origin", np.eye(3), np.zeros(3)), ("translated", np.eye(3), OFFSET)]
            placements += [(f"rotated {k + 1} + translated", Rotation.from_rotvec(r).as_matrix(), OFFSET)
                           for k, r in enumerate(ROTATIONS)]
            base = None
            for tag, rotation, offset in placements:
                path = axes_file(folder, name, rows, q0, rotation, offset, tag.split()[0] + tag[-1])
                code, cpu, worst = validate(path, folder / path.stem)
                base = cpu if tag == "translated" else base
                ratio = f"{cpu / base:.2f}" if base and tag.startswith("rotated") else "-"
                print(f"| {name} | {tag} | {code} | {cpu:.2f} | {worst:.2g} | {ratio} |")
                sys.stdout.flush()


if __name__ == "__main__":
    run()
