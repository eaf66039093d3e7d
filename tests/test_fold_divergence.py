"""A FOLD file whose run cannot finish normally is a failed check (issue 15 item 4): exit 1 with report.json, not exit
2 (bad input) or an internal error; and a large pattern's reference is exact to its rounding floor. Real MuJoCo, no
mocks. No realistic file was found that makes MuJoCo itself warn under a preset (sliver panels, near-degenerate
vertices, near-flat and near-square Miura sheets all step cleanly); the one below made the projection's own
predictor divide by zero."""

import json

import numpy as np

from sim_origami.cli import main
from sim_origami.creases import Crease, CreasePattern
from sim_origami.fold import write_fold
from sim_origami.kinematics.miura_sheet import MiuraSheet
from sim_origami.kinematics.numeric_pattern import BRANCH, SPARSE_FROM
from sim_origami.presets import FAST
from sim_origami.scenes.fold_file import fold_scene
from sim_origami.simulate import project


def near_square_vertex() -> CreasePattern:
    """A degree-4 vertex drawn as a square grid's with one sector 1e-4 deg off (89.9999 and 90.0001 deg), letters
    MVVV: its rigid motion locks at the trace's first step (a crease would fold against its letter), so the branch's
    domain is one input, -0.0628 rad, and every sweep sample repeats it."""
    alpha = np.deg2rad(np.cumsum([0.0, 90.0, 90.0, 90.0 - 1e-4]))
    vertices = np.vstack([[0.0, 0.0], np.c_[np.cos(alpha), np.sin(alpha)]])
    faces = tuple((0, i + 1, (i + 1) % 4 + 1) for i in range(4))
    creases = tuple(Crease(f"c{i + 1}", 0, i + 1, letter) for i, letter in enumerate("MVVV"))
    return CreasePattern(vertices, faces, creases, tuple(f"p{i}" for i in range(4)))


def test_a_projection_over_repeated_inputs_stays_finite(tmp_path):
    """The secant predictor divided by the inputs' difference: repeated inputs made qpos NaN at the third sample."""
    scene = fold_scene(write_fold(tmp_path / "vertex.fold", near_square_vertex()))
    lo, hi = scene.kinematics.branches()[0].domain
    assert lo == hi
    run = project(scene, scene.kinematics.branches()[0].name, np.full(5, lo), preset=FAST)
    assert np.all(np.isfinite(run.q)) and np.max(run.closure_residual) <= 1e-13


def test_a_one_point_motion_exits_1_with_a_report(tmp_path, capsys):
    """Was an internal error (exit 3): first the NaN projection, then printing the swept-range verdict's inf (null in
    JSON); then a failing swept range. Its trace stops at its first step, so that stop is the failing check and no
    MuJoCo run is made on the zero-length drive (issue 27)."""
    path = write_fold(tmp_path / "vertex.fold", near_square_vertex())
    out = tmp_path / "out"
    assert main(["validate", "--fold", str(path), "--preset", "fast", "--out", str(out)]) == 1
    printed = capsys.readouterr().out
    assert "FAIL through-target: traced motion stops at its start: 1" in printed and "lock at -0.0628319" in printed
    assert "no MuJoCo run: the drive of through-target sweeps 0 rad" in printed
    report = json.loads((out / "report.json").read_text())
    assert report["passed"] is False


def test_a_sparse_pattern_is_polished_to_the_rounding_floor(tmp_path):
    """Patterns above SPARSE_FROM creases polish by chord steps (`path.ChordPolish`): to the residual's floor,
    not to 1e-13, which near the 16 x 16 Miura sheet's folded end left the reference 3.7e-12 rad off."""
    sheet = MiuraSheet(8, 8, 0.5, 0.5, np.deg2rad(60.0)).pattern
    assert len(sheet.creases) > SPARSE_FROM
    scene = fold_scene(write_fold(tmp_path / "miura8.fold", sheet))
    kin = scene.kinematics
    x = np.linspace(*scene.path, 60)
    values = kin.joint_angles(BRANCH, x)
    assert np.max(kin.loop_system().residual_norm(values)) <= 1e-14  # measured 1.8e-15 (9.7e-14 before)
    assert np.array_equal(kin.joint_angles(BRANCH, x), values)  # kept values, not a second polish
