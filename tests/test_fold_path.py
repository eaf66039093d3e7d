"""FOLD patterns as people write them (issue 15): the path follower (`sim_origami.path`), directed traces towards
+-180 deg, open chains, several inputs, letters only, stalls, scale, and MuJoCo divergence. Real MuJoCo."""

import json
from dataclasses import replace

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.cli import main
from sim_origami.closure import LoopSystem
from sim_origami.creases import Crease, CreasePattern
from sim_origami.fold import write_fold
from sim_origami.kinematics.miura_sheet import MiuraSheet
from sim_origami.kinematics.numeric_pattern import BRANCH, PatternPath
from sim_origami.kinematics.vertex4 import Vertex4
from sim_origami.path import Polyline, independent_joints, trace
from sim_origami.presets import FAST
from sim_origami.scenes.fold_file import fold_scene, steadiest
from sim_origami.simulate import simulate
from sim_origami.validation import MIN_SWEEP_RAD, SWEPT_RANGE, validate


def strip(n: int, letters: str = "MVMVMV") -> CreasePattern:
    """n parallel creases x = 1..n across a 1 x (n + 1) strip: an open chain (no interior vertex)."""
    vertices = np.array([[x, y] for x in range(n + 2) for y in (0.0, 1.0)], dtype=float)
    faces = tuple((2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1) for i in range(n + 1))
    creases = tuple(Crease(f"c{i}", 2 * i, 2 * i + 1, letters[i - 1]) for i in range(1, n + 1))
    return CreasePattern(vertices, faces, creases, tuple(f"p{i}" for i in range(n + 1)))


def fan(angles_deg: list[float], letters: str) -> CreasePattern:
    """Creases from a border vertex at the origin to a half-disc's rim: an open fan (the vertex is not surrounded)."""
    a = np.deg2rad(np.concatenate([[0.0], np.cumsum(angles_deg)]))
    vertices = np.vstack([[0.0, 0.0], np.c_[np.cos(a), np.sin(a)]])
    faces = tuple((0, i + 1, i + 2) for i in range(len(a) - 1))
    creases = tuple(Crease(f"c{i}", 0, i + 1, letters[i - 1]) for i in range(1, len(a) - 1))
    return CreasePattern(vertices, faces, creases, tuple(f"p{i}" for i in range(len(a) - 1)))


def vertex(alpha_deg: list[float], letters: str) -> CreasePattern:
    """A degree-n vertex at the origin, sectors alpha (sum 360 deg)."""
    a = np.deg2rad(np.concatenate([[0.0], np.cumsum(alpha_deg)[:-1]]))
    vertices = np.vstack([[0.0, 0.0], np.c_[np.cos(a), np.sin(a)]])
    n = len(alpha_deg)
    faces = tuple((0, i + 1, (i + 1) % n + 1) for i in range(n))
    creases = tuple(Crease(f"c{i + 1}", 0, i + 1, letters[i]) for i in range(n))
    return CreasePattern(vertices, faces, creases, tuple(f"p{i}" for i in range(n)))


def cube_net() -> CreasePattern:
    """The cross-shaped net of a cube: six unit squares, five creases, no interior vertex."""
    cells = [(1, 0), (0, 1), (1, 1), (2, 1), (1, 2), (1, 3)]
    index: dict[tuple[int, int], int] = {}
    faces = []
    for x, y in cells:
        loop = []
        for corner in ((x, y), (x + 1, y), (x + 1, y + 1), (x, y + 1)):
            loop.append(index.setdefault(corner, len(index)))
        faces.append(tuple(loop))
    vertices = np.array(sorted(index, key=index.get), dtype=float)
    pairs = [((1, 1), (2, 1)), ((1, 1), (1, 2)), ((2, 1), (2, 2)), ((1, 2), (2, 2)), ((1, 3), (2, 3))]
    creases = tuple(Crease(f"c{k}", index[a], index[b], "V") for k, (a, b) in enumerate(pairs))
    return CreasePattern(vertices, tuple(faces), creases, tuple(f"f{k}" for k in range(6)))


def run_validate(capsys, *argv: str) -> tuple[int, str]:
    code = main(["validate", *argv])
    out, err = capsys.readouterr()
    return code, out + err


def test_polyline_parameter_is_the_value_for_one_input_and_arc_length_for_several():
    one = Polyline.through([[0.0], [-1.0], [-2.5]])
    assert np.array_equal(one.s, [0.0, -1.0, -2.5]) and one.at(-1.7)[0] == pytest.approx(-1.7)
    two = Polyline.through([[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]])
    np.testing.assert_allclose(two.s, [0.0, 5.0, 6.0])
    np.testing.assert_allclose(two.parameter_of(two.at([1.0, 5.5])), [1.0, 5.5], atol=1e-12)


def test_an_open_chain_traces_with_every_joint_free_and_an_empty_closure():
    loops = LoopSystem(3, ())
    assert loops.residual(np.zeros(3)).shape == (0,) and loops.residual_norm(np.zeros((5, 3))).shape == (5,)
    traced = trace(loops, np.zeros(3), [0, 2], Polyline.through([[0.0, 0.0], [1.0, -1.0]]))
    assert traced.stop.kind == "end" and np.all(traced.mobility == 3)
    np.testing.assert_allclose(traced.q[-1], [1.0, 0.0, -1.0])


@pytest.mark.slow
def test_a_180_deg_target_is_a_direction_not_a_vacuous_pass(tmp_path, capsys):
    """Before: input range [pi, pi], error 0, passed. Now the sweep reaches 0.95 of the lock at |rho| = pi."""
    pattern = vertex([60.0, 100.0, 90.0, 110.0], "MVMV")
    path = PatternPath(pattern, "c2", np.array([np.nan, np.pi, np.nan, np.nan]))
    lock = [e for e in path.events() if e.kind == "lock"]
    assert len(lock) == 1 and "folds flat" in lock[0].detail and lock[0].input > 3.1
    fold = write_fold(tmp_path / "v.fold", strip(1, "V"), fold_angles=[np.pi])
    code, text = run_validate(capsys, "--fold", str(fold), "--out", str(tmp_path / "out"))
    doc = json.loads((tmp_path / "out" / "report.json").read_text())
    lo, hi = doc["branches"][0]["input_range_rad"]
    assert code == 0, text
    assert hi - lo > 1.0 and hi < np.pi  # swept 0.94 .. 2.98 rad (measured)
    assert {e["kind"] for e in doc["events"]} >= {"lock", "open-chain"}


def test_a_frozen_sweep_fails_the_swept_range_verdict(tmp_path):
    scene = fold_scene(write_fold(tmp_path / "s.fold", strip(1, "V"), fold_angles=[1.0]))
    report = validate(replace(scene, path=(0.5, 0.5)))
    swept = [v for r in report.runs for v in r.verdicts if v.id == SWEPT_RANGE]
    assert not report.passed and len(swept) == 1 and not swept[0].passed and MIN_SWEEP_RAD == 1e-3


@pytest.mark.parametrize(
    ("pattern", "angles_deg", "inputs"),
    [(strip(1, "V"), [100.0], 1), (strip(3), [-60.0, 90.0, -120.0], 3), (fan([40.0, 50.0, 60.0, 30.0], "MVM"),
      [-50.0, 80.0, -40.0], 3), (cube_net(), [90.0] * 5, 5)],
    ids=["single-crease", "strip-3", "fan-to-border", "cube-net"],
)
def test_open_chains_validate_three_ways_with_every_freedom_driven(tmp_path, pattern, angles_deg, inputs):
    scene = fold_scene(write_fold(tmp_path / "p.fold", pattern, fold_angles=np.deg2rad(angles_deg)))
    assert len(scene.drives) == inputs and scene.kinematics.open_chain
    report = validate(scene)
    assert report.passed, [v for r in report.runs for v in r.verdicts if not v.passed]
    run = report.runs[0]
    assert run.mobility["along_path"]["typical"] == inputs and run.dynamic_path.max_error() <= FAST.angle_rad
    assert any(e["kind"] == "open-chain" for e in run.events)


@pytest.mark.slow
def test_a_two_dof_vertex_driven_by_named_inputs(tmp_path, capsys):
    """A degree-5 vertex has mobility 2: one input leaves a freedom undriven (a failed verdict), two agree."""
    pattern = vertex([70.0, 80.0, 60.0, 75.0, 75.0], "MVMVV")
    guess = np.array([0.6, -0.2, 0.5, 0.2, 0.0])
    q = pattern.loop_system().solve(guess, [True, False, True, False, False])  # a state on its motion
    fold = write_fold(tmp_path / "v5.fold", pattern, fold_angles=q)
    assert len(fold_scene(fold).drives) == 2
    code, text = run_validate(capsys, "--fold", str(fold), "--input", "e0,e2", "--out", str(tmp_path / "two"))
    assert code == 0, text
    code, text = run_validate(capsys, "--fold", str(fold), "--input", "e0", "--out", str(tmp_path / "one"))
    assert code == 1 and "FAIL through-target: freedoms not driven" in text


def test_a_non_rigid_pattern_stalls(tmp_path):
    """A generic quadrilateral mesh (Kokotsakis, jittered): no rigid motion off flat, so the trace stalls at once."""
    rng = np.random.default_rng(3)
    sheet = MiuraSheet(3, 3, 0.5, 0.5, np.deg2rad(60.0)).pattern
    jittered = replace(sheet, vertices=sheet.vertices + rng.uniform(-0.03, 0.03, sheet.vertices.shape))
    path = PatternPath(jittered, jittered.creases[0].name,
                       np.where([c.assignment == "V" for c in jittered.creases], 1.0, -1.0))
    stall = [e for e in path.events() if e.kind == "stall"]
    assert len(stall) == 1 and "no rigid configuration beyond" in stall[0].detail
    assert path.branch(BRANCH).domain[1] - path.branch(BRANCH).domain[0] < MIN_SWEEP_RAD


@pytest.mark.slow
def test_letters_only_miura_finds_the_rigid_motion(tmp_path):
    sheet = MiuraSheet(3, 3, 0.5, 0.5, np.deg2rad(60.0))
    scene = fold_scene(write_fold(tmp_path / "letters.fold", sheet.pattern))
    kin = scene.kinematics
    x = np.linspace(*scene.branch_path(BRANCH), 7)
    k = kin.input_index
    assert len(scene.drives) == 1 and kin.stops[0].kind == "bound"  # traced until a crease folds flat
    closed = sheet.joint_angles("miura", np.abs(x) if sheet.pattern.creases[k].assignment == "V" else x)
    got = kin.joint_angles(BRANCH, x)
    # the same motion as the closed form, up to the driven crease's own parametrisation: compare the crease angles
    order = np.argsort(np.abs(got[:, k]))
    assert np.all(np.sign(got[-1]) == [1 if c.assignment == "V" else -1 for c in sheet.pattern.creases])
    assert np.max(kin.loop_system().residual_norm(got)) <= 1e-13 and order.size == closed.shape[0]
    run = simulate(scene, BRANCH)
    assert compare(scene, BRANCH, run.q).max_error() <= FAST.angle_rad


@pytest.mark.slow
def test_same_pattern_at_1_mm_1_m_and_1000_units_gives_the_same_verdict(tmp_path):
    pattern = vertex([60.0, 100.0, 90.0, 110.0], "MVMV")
    q = Vertex4(np.deg2rad([60.0, 100.0, 90.0, 110.0])).joint_angles("odd2", 1.2)[0]
    errors = []
    for unit, scale in (("mm", 1.0), ("m", 1.0), ("unit", 1000.0)):
        doc = json.loads((write_fold(tmp_path / "x.fold", pattern, fold_angles=q)).read_text())
        doc["frame_unit"] = unit
        doc["vertices_coords"] = (np.array(doc["vertices_coords"]) * scale).tolist()
        (tmp_path / f"{unit}.fold").write_text(json.dumps(doc))
        report = validate(fold_scene(tmp_path / f"{unit}.fold"))
        assert report.passed
        errors.append(report.runs[0].dynamic_path.max_error())
    assert errors[0] == errors[1] == errors[2]


def test_independent_joints_respects_the_first_pick():
    loops = vertex([70.0, 80.0, 60.0, 75.0, 75.0], "MVMVV").loop_system()
    q = loops.solve(np.array([0.6, -0.2, 0.5, 0.2, 0.0]), [True, False, True, False, False])
    assert independent_joints(loops, q, first=(3,))[0] == 3 and len(independent_joints(loops, q)) == 2


@pytest.mark.slow
def test_frames_are_compared_with_the_rigid_motion_through_them(tmp_path):
    pattern = vertex([60.0, 100.0, 90.0, 110.0], "MVMV")
    frames = Vertex4(np.deg2rad([60.0, 100.0, 90.0, 110.0])).joint_angles("odd2", [0.4, 0.8, 1.2])
    kin = fold_scene(write_fold(tmp_path / "f.fold", pattern, frames)).kinematics
    assert kin.frames_tolerance == pytest.approx(1e-2) and len(kin.frame_distances) == 3
    assert max(d["distance_rad"] for d in kin.frame_distances) <= 1e-12  # exact frames: on the motion
    bent = frames.copy()
    bent[1, 2] += 0.1  # a frame off the rigid motion (as a simulator with bending panels writes)
    scene = fold_scene(write_fold(tmp_path / "b.fold", pattern, bent))
    assert scene.kinematics.frame_distances[1]["distance_rad"] > 0.05
    report = validate(scene)
    failed = [v.name for r in report.runs for v in r.verdicts if not v.passed]
    assert failed == ["through-target: frames' distance from the rigid motion (rad)"]


def test_frames_are_traced_from_the_first_frame_on_the_files_branch(tmp_path):
    """Flat is a branch point of the waterbomb: traced from flat with e1 driven, the thick cell took another branch,
    0.79 rad from its exact frames; traced from the first frame it stays on theirs."""
    scene = scenes.get("waterbomb-thick").build()
    q = np.stack([scene.pose("line-symmetric", x) for x in np.linspace(*scene.path, 5)])
    rho = q[:, [scene.mechanism.joint_index(c.name) for c in scene.pattern.creases]]
    path = write_fold(tmp_path / "thick.fold", scene.pattern, rho)
    for inputs in ("e1", None):
        kin = fold_scene(path, inputs).kinematics
        assert max(d["distance_rad"] for d in kin.frame_distances) <= 1e-12, kin.inputs
    assert kin.inputs not in (("e7",), ("e10",))  # the default: not the most folded creases, the slowest


def test_the_steadiest_crease_is_the_one_that_never_slows_down():
    t = np.linspace(0.0, 1.0, 11)[:, None]
    states = np.hstack([np.sin(2.5 * t), 0.8 * t, 2.0 * t, np.full_like(t, np.nan)])  # crease 0 turns near t = 0.63
    usable = np.array([True, True, False, True])  # crease 2 (the fastest) is an F crease
    assert steadiest(states, usable, default=0) == (1,)
    assert steadiest(states[:6], usable, default=0) == (0,)  # before its turn, crease 0 is the steadier
    assert steadiest(np.zeros((3, 4)), usable, default=3) == (3,)  # nothing moves: the default


def test_creases_tied_as_steadiest_are_all_candidates_the_default_first():
    """Scores within TIE are a set, whatever rounding makes of them: the default leads when it is one of them."""
    t = np.linspace(0.0, 1.0, 11)[:, None]
    states = np.hstack([t, t * (1 + 1e-15), 0.5 * t, t])  # creases 0, 1 and 3 tie; 2 scores 0.5
    usable = np.ones(4, dtype=bool)
    assert steadiest(states, usable, default=2) == (0, 1, 3)
    assert steadiest(states, usable, default=3) == (3, 0, 1)


def test_f_creases_stay_flat_and_a_vertex_needing_them_stalls():
    strip_f = strip(3, "MFV")
    path = PatternPath(strip_f, ("c1", "c3"), np.array([-1.0, np.nan, 1.0]))
    assert path.stops[0].kind == "end" and np.all(path.nodes[:, 1] == 0.0)
    # a degree-4 vertex cannot fold with one crease held flat (its other three would have to fold alone)
    locked = vertex([60.0, 100.0, 90.0, 110.0], "MVMF")
    stuck = PatternPath(locked, "c1", np.array([-1.0, 1.5, -1.0, np.nan]))
    assert [e.kind for e in stuck.events() if e.kind in ("stall", "lock")] == ["stall"]


@pytest.mark.slow
def test_the_square_base_has_five_freedoms_and_validates_with_five_inputs(tmp_path, capsys):
    """The square (preliminary) base: one degree-8 vertex, mobility 8 - 3 = 5 along its motion."""
    pattern = vertex([45.0] * 8, "VMVMVMVM")
    guess = np.array([0.6, -0.4, 0.6, -0.4, 0.6, -0.4, 0.6, -0.4])
    q = pattern.loop_system().solve(guess, [True, False, True, False, True, False, False, False])
    fold = write_fold(tmp_path / "base.fold", pattern, fold_angles=q)
    scene = fold_scene(fold)
    assert len(scene.drives) == 5 and scene.drive_path is not None
    report = validate(scene)
    assert report.passed, [(v.name, v.measured) for r in report.runs for v in r.verdicts if not v.passed]
    assert report.runs[0].mobility["along_path"]["typical"] == 5
    code, text = run_validate(capsys, "--fold", str(fold), "--input", "e0", "--out", str(tmp_path / "one"))
    assert code == 1 and "FAIL through-target: freedoms not driven" in text
