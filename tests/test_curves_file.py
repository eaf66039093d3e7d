"""curves.csv keeps what the report states at a bounded size: evenly spaced samples of each run plus each joint's
worst, every step with --full-curves (the main job's curves were 197 MB)."""

import csv
import json

import numpy as np
import pytest

from sim_origami.cli import main
from sim_origami.report import CURVE_ROWS, curve_rows


def test_curve_rows_keep_both_ends_and_every_joints_worst_sample():
    error = np.zeros((5000, 3))
    error[1234, 0], error[4321, 2] = 1.0, 2.0
    keep = curve_rows(5000, error, 400)
    assert keep[0] == 0 and keep[-1] == 4999 and {1234, 4321} <= set(keep)
    assert len(keep) <= 400 + 3 and np.all(np.diff(keep) > 0)
    assert np.array_equal(curve_rows(300, error[:300], 400), np.arange(300))
    assert np.array_equal(curve_rows(5000, error, None), np.arange(5000))


@pytest.mark.slow
def test_curves_csv_is_thinned_but_holds_the_reported_maximum(tmp_path):
    out = tmp_path / "bennett"
    assert main(["validate", "bennett", "--out", str(out)]) == 0
    doc = json.loads((out / "report.json").read_text())
    rows = list(csv.DictReader((out / "curves.csv").open()))
    dynamic = [r for r in rows if r["mode"] == "dynamic"]
    assert len(dynamic) <= CURVE_ROWS + 4 < doc["timings_s"]["mujoco_steps"]
    worst = max(float(r[f"{j}_error_rad"]) for r in dynamic for j in doc["joints"])
    assert worst == pytest.approx(doc["angle_error_max_rad"], rel=1e-3)  # written to 4 digits
    full = tmp_path / "full"
    assert main(["validate", "bennett", "--full-curves", "--out", str(full)]) == 0
    every = [r for r in csv.DictReader((full / "curves.csv").open()) if r["mode"] == "dynamic"]
    assert len(every) == doc["timings_s"]["mujoco_steps"]
