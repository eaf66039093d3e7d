"""Crease patterns without a closed form (`kinematics.numeric_pattern`, `validate --fold`) and the Miura-ori sheet
(`kinematics.miura_sheet`, scene `miura-sheet`): numeric reference, closed form and MuJoCo."""

from dataclasses import replace

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.cli import main
from sim_origami.creases import Crease, CreasePattern
from sim_origami.errors import ParameterError
from sim_origami.fold import read_fold, write_fold
from sim_origami.kinematics.miura_sheet import MiuraSheet
from sim_origami.kinematics.numeric_pattern import BRANCH, PatternPath
from sim_origami.kinematics.vertex4 import Vertex4
from sim_origami.presets import FAST
from sim_origami.scenes.fold_file import fold_scene
from sim_origami.simulate import project, simulate
from sim_origami.tolerances import TOLERANCES

ALPHA = np.deg2rad([60.0, 100.0, 90.0, 110.0])


def vertex_pattern(alpha: np.ndarray) -> CreasePattern:
    """A degree-4 vertex as four triangles round the origin; creases c1..c4 along the vertex convention's d_i."""
    angles = np.concatenate([[0.0], np.cumsum(alpha)[:-1]])
    vertices = np.vstack([[0.0, 0.0], np.c_[np.cos(angles), np.sin(angles)]])
    faces = tuple((0, i + 1, (i + 1) % 4 + 1) for i in range(4))
    creases = tuple(Crease(f"c{i + 1}", 0, i + 1, "MVMV"[i]) for i in range(4))
    return CreasePattern(vertices, faces, creases, tuple(f"p{i}" for i in range(4)))


@pytest.mark.parametrize(("branch", "end"), [("odd1", 1.12213), ("odd2", np.pi)])
def test_numeric_trace_of_a_vertex_matches_its_closed_form(branch, end):
    vertex = Vertex4(ALPHA)
    path = PatternPath(vertex_pattern(ALPHA), "c1", vertex.joint_angles(branch, 1.0)[0] + 0.003)
    lo, hi = path.branch(BRANCH).domain
    # traced from near flat to where a crease folds flat: odd1 ends where crease 2 does (rho1 = 1.12213)
    assert lo < 0.05 and end - 0.02 < hi <= end
    x = np.linspace(lo, hi, 40)
    # measured 3.4e-13 (odd2): both are solutions of the same loop, to the solver's 1e-15 polish
    assert np.max(np.abs(path.joint_angles(BRANCH, x) - vertex.joint_angles(branch, x))) <= TOLERANCES.closed_form_rad
    assert path.gruebler() == 1 and path.stalled_at == ()


def test_a_state_the_pattern_cannot_reach_is_a_direction_and_its_distance_is_reported():
    target = np.array([1.0, 1.0, 1.0, 1.0])  # all valleys: no degree-4 vertex folds so (Maekawa)
    path = PatternPath(vertex_pattern(ALPHA), "c1", target)
    off = [e for e in path.events() if e.kind == "off-target"]
    # traced from flat to c1 = 1 on a rigid branch; that branch's state is 1.19 rad from the target (measured)
    assert path.branch(BRANCH).domain[1] == 1.0 and len(off) == 1 and path.target_gap > 0.5
    assert np.max(path.loop_system().residual_norm(path.joint_angles(BRANCH, [0.5, 1.0]))) <= 1e-14


def test_bad_input_crease():
    with pytest.raises(ParameterError, match="input crease 'c9' is not a crease"):
        PatternPath(vertex_pattern(ALPHA), "c9", np.ones(4))
    with pytest.raises(ParameterError, match="is flat in the target state"):
        PatternPath(vertex_pattern(ALPHA), "c1", np.array([0.0, 0.3, 0.0, 0.3]))


def test_fold_file_scene_validates_against_the_numeric_reference(tmp_path):
    vertex = Vertex4(ALPHA)
    path = write_fold(tmp_path / "v4.fold", vertex_pattern(ALPHA), vertex.joint_angles("odd2", [0.5, 1.2]))
    scene = fold_scene(path)
    assert scene.drive_joint == "e0"  # the crease folded most in the last frame: crease 1 (1.2 rad) on odd2
    run = simulate(scene, BRANCH)
    measured = compare(scene, BRANCH, run.q)
    assert measured.max_error() <= FAST.angle_rad  # measured 9.9e-9
    # the same run against the closed form of the vertex, through the file's crease order
    x = run.q[:, scene.mechanism.joint_index("e0")]
    closed = vertex.joint_angles("odd2", x)
    got = run.q[:, [scene.mechanism.joint_index(f"e{k}") for k in range(4)]]
    assert np.max(np.abs(got - closed)) <= FAST.angle_rad


def test_fold_scene_without_a_folded_state_or_letters_is_refused(tmp_path):
    pattern = vertex_pattern(ALPHA)
    unassigned = replace(pattern, creases=tuple(replace(c, assignment="U") for c in pattern.creases))
    path = write_fold(tmp_path / "flat.fold", unassigned)
    with pytest.raises(ParameterError, match="no folded state"):
        fold_scene(path)


def cli(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.slow
def test_cli_validate_fold(tmp_path, capsys):
    vertex = Vertex4(ALPHA)
    path = write_fold(tmp_path / "v4.fold", vertex_pattern(ALPHA), vertex.joint_angles("odd1", [1.0]))
    code, out, err = cli(capsys, "validate", "--fold", str(path), "--out", str(tmp_path / "out"))
    assert code == 0, out + err
    assert "fold-v4 | PASS" in out and (tmp_path / "out" / "motion.fold").exists()
    code, _, err = cli(capsys, "validate", "--fold", str(tmp_path / "nope.fold"))
    assert code == 2 and "cannot read FOLD file" in err
    code, _, err = cli(capsys, "validate", "--fold", str(path), "--input", "zz")
    assert code == 2 and "input crease 'zz'" in err
    code, _, err = cli(capsys, "validate", "vertex4", "--fold", str(path))
    assert code == 2 and "one of a SCENE, --all, --fold FILE or --linkage FILE" in err


@pytest.mark.parametrize(("rows", "cols"), [(2, 2), (3, 2), (2, 5), (4, 4), (16, 16)])
def test_miura_sheet_closed_form_closes_every_vertex(rows, cols):
    sheet = MiuraSheet(rows, cols, 0.5, 0.7, np.deg2rad(55.0))
    q = sheet.joint_angles("miura", np.linspace(-3.1, 3.1, 41))
    assert np.max(sheet.loop_system().residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured 3.6e-15
    assert len(sheet.loop_system().loops) == (rows - 1) * (cols - 1)


def test_miura_sheet_numeric_and_mujoco():
    scene = scenes.get("miura-sheet").build()
    kin = scene.kinematics
    x = np.linspace(*scene.branch_path("miura"), 60)
    q = kin.joint_angles("miura", x)
    numeric = kin.loop_system().follow(q[0], kin.loop_input()[0], x)
    assert np.max(np.abs(numeric - q)) <= TOLERANCES.closed_form_rad  # measured 2.1e-14
    assert kin.loop_system().mobility(q[30]) == 1
    assert compare(scene, "miura", project(scene, "miura", x).q).max_error() <= TOLERANCES.projection_rad
    assert compare(scene, "miura", simulate(scene, "miura").q).max_error() <= FAST.angle_rad  # 6.8e-8


@pytest.mark.slow
def test_16_by_16_miura_sheet_folds_within_1e6_rad_with_contact_on():
    """Issue 4: a 16 x 16 sheet (256 panels, 225 connect pairs) from 5% to 90% of its range, contact on. Fast, 4 s
    sweep: measured 7.3e-7 rad in 500 steps (3.4-3.7 s of CPU on the shared 2-core machine, 2.0 s contact off);
    the breadth-first tree from the mid-sheet drive is 16 deep (Kruskal's: 27)."""
    scene = scenes.get("miura-sheet").build(rows=16, cols=16)
    depth = {scene.mechanism.root: 0}
    for edge in scene.mechanism.tree:
        depth[edge.child] = depth[edge.parent] + 1
    assert max(depth.values()) == 16
    run = simulate(scene, "miura", contact=True, duration=4.0)
    assert compare(scene, "miura", run.q).max_error() <= FAST.angle_rad
    assert run.steps == 500 and np.max(run.closure_residual) <= FAST.residual_per_m


def test_miura_sheet_round_trips_through_fold_and_the_numeric_reference_agrees(tmp_path):
    sheet = MiuraSheet(3, 3, 0.5, 0.5, np.deg2rad(60.0))
    path = write_fold(tmp_path / "sheet.fold", sheet.pattern, sheet.joint_angles("miura", [1.0, 2.0]))
    assert [c.assignment for c in read_fold(path).pattern.creases] == [c.assignment for c in sheet.pattern.creases]
    scene = fold_scene(path, input_crease=f"e{[c.name for c in sheet.pattern.creases].index(sheet.input_crease)}")
    x = np.linspace(*scene.branch_path(BRANCH), 30)
    assert np.max(np.abs(scene.kinematics.joint_angles(BRANCH, x) - sheet.joint_angles("miura", x))) <= 1e-12


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [({"rows": 1}, "rows = 1"), ({"cols": 2.5}, "cols = 2.5"), ({"gamma": np.pi / 2}, "gamma = 90"),
     ({"a": 0.0}, "a = 0 m")],
)
def test_miura_sheet_bad_input(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("miura-sheet").build(**kwargs)
