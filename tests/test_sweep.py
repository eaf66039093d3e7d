"""Parameter sweeps (`sim_origami.sweep`, `sim-origami sweep`): grid parsing, points that fail, local processes and a
real Dask cluster, CSV/Parquet/PNG outputs."""

import csv

import numpy as np
import pyarrow.parquet as pq
import pytest
from dask.distributed import LocalCluster

from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.sweep import Axis, grid_points, parse_axis, run_point, sweep, write_tables


def test_parse_axis_includes_the_stop_and_refuses_malformed_specs():
    assert parse_axis("alpha1=30:60:10") == Axis("alpha1", (30.0, 40.0, 50.0, 60.0))
    assert parse_axis("t=0.1:0.35:0.1").values == pytest.approx((0.1, 0.2, 0.3))
    for bad, match in (("alpha1=30:60", "NAME=START:STOP:STEP"), ("alpha1=a:60:10", "must be numbers"),
                       ("alpha1=60:30:10", "STOP >= START"), ("alpha1=30:60:0", "STEP > 0")):
        with pytest.raises(ParameterError, match=match):
            parse_axis(bad)
    assert grid_points([Axis("a", (1.0, 2.0)), Axis("b", (3.0,))]) == [{"a": 1.0, "b": 3.0}, {"a": 2.0, "b": 3.0}]


def test_a_point_passes_and_a_bad_point_is_recorded_not_raised():
    good = run_point("miura", {"alpha1": 30.0, "alpha2": 60.0})
    assert good["passed"] and good["error"] == "" and good["branches_followed"] == "miura;straight"
    assert good["angle_error_max_rad"] <= 1e-6  # measured 6.9e-8 (fast)
    bad = run_point("vertex4", {"alpha1": 50.0})  # sectors no longer sum to 360 deg
    assert not bad["passed"] and bad["error"].startswith("ParameterError: sector angles sum to 350 deg")
    assert np.isnan(bad["angle_error_max_rad"])


def test_local_processes_and_a_dask_cluster_give_the_same_table(tmp_path):
    axes = [Axis("alpha1", (30.0, 35.0)), Axis("alpha2", (55.0, 60.0))]
    local = sweep("miura", axes, workers=2)
    with LocalCluster(n_workers=1, threads_per_worker=2, processes=False, dashboard_address=None) as cluster:
        dask = sweep("miura", axes, scheduler=cluster.scheduler_address)
    assert [(r["alpha1"], r["alpha2"]) for r in local] == [(30.0, 55.0), (30.0, 60.0), (35.0, 55.0), (35.0, 60.0)]
    for a, b in zip(local, dask, strict=True):  # the same runs: bitwise-deterministic MuJoCo
        assert a["angle_error_max_rad"] == b["angle_error_max_rad"] and a["passed"] and b["passed"]
    paths = write_tables(local, tmp_path)
    table = pq.read_table(paths["parquet"]).to_pylist()
    with open(paths["csv"]) as f:
        rows = list(csv.DictReader(f))
    assert len(table) == len(rows) == 4
    assert table[3]["angle_error_max_rad"] == local[3]["angle_error_max_rad"]
    assert float(rows[3]["angle_error_max_rad"]) == pytest.approx(local[3]["angle_error_max_rad"], rel=1e-12)


def test_unknown_parameter_is_refused_before_any_point_runs():
    with pytest.raises(ParameterError, match="unknown parameter 'beta9'"):
        sweep("miura", [Axis("beta9", (1.0,))])


@pytest.mark.slow
def test_cli_sweep_writes_tables_and_plot_and_exits_1_when_a_point_fails(tmp_path, capsys):
    out = tmp_path / "s"
    code = main(["sweep", "vertex4", "--grid", "alpha1=55:60:5", "--workers", "2", "--out", str(out)])
    text = capsys.readouterr().out
    assert code == 1 and "2 points, 1 passed, 1 failed" in text and "alpha1=55" in text
    assert {p.name for p in out.iterdir()} == {"sweep.csv", "sweep.parquet", "sweep.png", ".sim_origami-run.json"}
    code = main(["sweep", "vertex4", "--grid", "alpha1=60:60:5", "--workers", "1", "--out", str(out)])
    assert code == 0
    assert main(["sweep", "vertex4", "--grid", "nope=1:2:1"]) == 2
