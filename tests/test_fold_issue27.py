"""FOLD files the validation judged wrongly or let through (issue 27): a folded state off the rigid motion passed, a
stall at the start failed as 'MuJoCo unstable', and malformed numbers, angles and inputs crashed, hung or were read
as something else. Files are built as other tools write them (small generated FOLD dicts)."""

import numpy as np
import pytest
from fold_fixtures import degree4_letters, miura_letters_only, validated, write

from sim_origami.fold import read_fold
from sim_origami.kinematics.numeric_pattern import BRANCH, TARGET_TOL, PatternPath, assignment_signs
from sim_origami.scenes.fold_file import fold_scene


def four_mountains(angle: float) -> dict:
    """The degree-4 vertex of tests/fold_fixtures.py with four M creases, each asked to fold to `angle` deg."""
    return degree4_letters() | {"edges_assignment": ["M"] * 4 + ["B"] * 4, "edges_foldAngle": [angle] * 4 + [0] * 4}


@pytest.mark.slow
def test_a_folded_state_off_the_rigid_motion_fails_with_its_distance(tmp_path, capsys):
    # four mountains at -160 deg: a degree-4 vertex folds one diagonal pair only (Maekawa), so the state is far off
    # its rigid motion (measured 3.28 rad at the inputs' end); it passed with exit 0 and an event in report.json only
    code, report = validated(tmp_path, "four mountains", four_mountains(-160.0))
    verdict = next(v for b in report["branches"] for v in b["verdicts"] if "folded state's distance" in v["name"])
    assert code == 1 and not report["passed"] and not verdict["passed"] and verdict["measured"] > 3.0
    assert verdict["tolerance"] == TARGET_TOL and "does not fold rigidly to it" in verdict["detail"]
    shown = capsys.readouterr().out
    assert "FAIL through-target: folded state's distance from the rigid motion (rad): 3.28" in shown
    assert "does not fold rigidly to it" in shown


def test_a_folded_state_on_the_rigid_motion_passes_the_check(tmp_path):
    doc = degree4_letters()
    pattern = read_fold(doc).pattern
    exact = np.rad2deg(PatternPath(pattern, "e1", signs=assignment_signs(pattern)).evaluate(BRANCH, [1.2])[0][0])
    scene = fold_scene(write(tmp_path, "exact", doc | {"edges_foldAngle": [*exact.tolist(), 0, 0, 0, 0]}))
    gap, tol, detail, compared = scene.kinematics.target_check()
    assert gap <= 1e-12 and tol == TARGET_TOL and compared == 4 and "does not fold" not in detail
    off = fold_scene(write(tmp_path, "off", four_mountains(-160.0))).kinematics.target_check()
    assert off[0] > 3.0 and "largest at crease" in off[2]


@pytest.mark.slow
def test_a_trace_stuck_at_its_start_fails_on_its_stall_without_a_mujoco_run(tmp_path, capsys):
    # a 4 x 4 Miura sheet as Rabbit Ear writes it, one interior vertex moved off the flat-foldable geometry: 9 vertices
    # hold 24 creases rigid, the trace stalls at its first step; it failed on a zero-length sweep (or as 'MuJoCo
    # unstable' holding a pose that does not close), the stall shown only as an event
    doc = miura_letters_only(4, 4)
    doc["vertices_coords"][6] = [doc["vertices_coords"][6][0] + 0.05, doc["vertices_coords"][6][1] + 0.03]
    code, report = validated(tmp_path, "moved vertex", doc)
    failing = [v for v in report["verdicts"] if not v["passed"]]
    assert code == 1 and [v["name"] for v in failing] == ["through-target: traced motion stops at its start"]
    assert failing[0]["detail"].startswith("stall at 0.153906 rad: no rigid configuration beyond")
    assert not any("MuJoCo" in v["name"] for v in report["verdicts"]) and report["events"][0]["kind"] == "stall"
    shown = capsys.readouterr().out
    assert "FAIL through-target: traced motion stops at its start" in shown and "stall at 0.153906 rad" in shown
    assert "no MuJoCo run: the drive of through-target sweeps 0 rad" in shown
