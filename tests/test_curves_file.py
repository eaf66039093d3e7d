"""curves.csv keeps what the report states at a bounded size: evenly spaced samples of each run plus each joint's
worst, angles to 13 digits and errors to 4, gzipped when long (curves.csv.gz); every step to 17 digits with
--full-curves (the main job's curves were 197 MB, then 44.7 MB)."""

import csv
import gzip
import io
import json

import numpy as np
import pytest

from sim_origami.cli import main
from sim_origami.report import (
    CURVE_DIGITS,
    CURVE_ROWS,
    CURVES_GZIP_BYTES,
    ERROR_DIGITS,
    FULL_DIGITS,
    curve_rows,
    write_curves,
)


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


def test_long_curves_are_written_gzipped_and_read_back_whole(tmp_path):
    text = "branch,mode,input_rad\n" + "".join(f"b,dynamic,{k / 7:.13g}\n" for k in range(2000))
    assert write_curves(tmp_path, text, limit=len(text)).name == "curves.csv"
    assert (tmp_path / "curves.csv").read_text() == text
    path = write_curves(tmp_path, text, limit=len(text) - 1)
    assert path.name == "curves.csv.gz" and not (tmp_path / "curves.csv").exists()  # one of the two at a time
    with gzip.open(path, "rt", newline="") as f:
        assert f.read() == text
    first = path.read_bytes()
    assert write_curves(tmp_path, text, limit=0).read_bytes() == first  # no timestamp: the same bytes each time
    assert len(first) < len(text) / 3
    write_curves(tmp_path, text)
    assert (tmp_path / "curves.csv").exists() and not path.exists()
    assert CURVES_GZIP_BYTES == 1_000_000


def significant(field: str) -> int:
    """Significant digits written in a number like 1.2345678901234, -0.00012 or 1.234e-05."""
    mantissa = field.lower().split("e")[0].lstrip("-").replace(".", "").lstrip("0")
    return len(mantissa)


@pytest.mark.slow
def test_angles_keep_13_digits_errors_4_and_full_curves_every_digit(tmp_path):
    out, full = tmp_path / "bennett", tmp_path / "full"
    assert main(["validate", "bennett", "--out", str(out)]) == 0
    assert main(["validate", "bennett", "--full-curves", "--out", str(full)]) == 0
    doc = json.loads((out / "report.json").read_text())
    rows = list(csv.DictReader((out / "curves.csv").open()))
    angles = [r[k] for r in rows for k in r if k == "input_rad" or k.endswith(("_sim_rad", "_analytic_rad"))]
    errors = [r[f"{j}_error_rad"] for r in rows for j in doc["joints"]]
    assert max(map(significant, angles)) == CURVE_DIGITS == 13
    assert {significant(e) for e in errors if float(e) != 0} == {ERROR_DIGITS}
    every = list(csv.DictReader((full / "curves.csv").open()))
    assert max(significant(r["theta2_sim_rad"]) for r in every) == FULL_DIGITS  # each float as it is
    # the thinned file's angles are the full file's rounded to 13 digits (the same run: deterministic)
    by_input = {(r["branch"], r["mode"], r["input_rad"]): r for r in every}
    for r in rows[:50]:
        match = next(f for key, f in by_input.items() if key[:2] == (r["branch"], r["mode"])
                     and float(key[2]) == pytest.approx(float(r["input_rad"]), abs=1e-12))
        assert r["theta2_sim_rad"] == f"{float(match['theta2_sim_rad']):.13g}"
        assert r["theta2_error_rad"] == match["theta2_error_rad"]
    assert (out / "curves.csv").stat().st_size < 125_000  # measured: 118 kB at 13 digits, 140 kB at 17
    assert '<a href="curves.csv">' in (out / "report.html").read_text()


@pytest.mark.slow
def test_a_wide_run_writes_curves_csv_gz_that_holds_the_reported_maximum(tmp_path):
    # a 6 x 6 Miura sheet: 60 creases, 1.5 MB of curves as text (measured; 250 kB as .gz)
    out = tmp_path / "miura-sheet"
    main(["validate", "miura-sheet", "-p", "rows=6", "-p", "cols=6", "--out", str(out)])
    doc = json.loads((out / "report.json").read_text())
    assert not (out / "curves.csv").exists()
    with gzip.open(out / "curves.csv.gz", "rt", newline="") as f:
        text = f.read()
    assert len(text) > CURVES_GZIP_BYTES
    rows = [r for r in csv.DictReader(io.StringIO(text)) if r["mode"] == "dynamic"]
    worst = max(float(r[f"{j}_error_rad"]) for r in rows for j in doc["joints"])
    assert worst == pytest.approx(doc["angle_error_max_rad"], rel=1e-3)
    assert (out / "curves.csv.gz").stat().st_size < len(text) / 4
    page = (out / "report.html").read_text()
    assert '<a href="curves.csv.gz">curves.csv.gz</a>' in page and 'href="curves.csv"' not in page
