"""Linkage files with numbers as people type them: each number's precision, the nearest mobile linkage within it
(validated, its moves reported), the refusal beyond it with the distance, spherical D-H rows, and placement."""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.dh import DHRow
from sim_origami.linkage_file import read_linkage
from sim_origami.linkage_forms import chain_poses
from sim_origami.scenes.linkage_file import linkage_scene

EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples" / "linkages"


SPHERICAL = {"sim_origami_linkage": 1, "form": "dh", "name": "spherical-4r",
             "joints": [{"a": 0.0, "alpha": alpha} for alpha in (70.0, 90.0, 80.0, 100.0)],
             "input": {"joint": "theta1", "range": [10.0, 60.0]}}


def bennett_text(beta: str = "48.5904", a: str = "1.0000", b: str = "1.5000", alpha: str = "30.0000") -> str:
    """The Bennett example as TOML with its numbers printed as given."""
    rows = "".join(f'[[joints]]\nname = "theta{k + 1}"\na = {length}\nalpha = {twist}\n\n'
                   for k, (length, twist) in enumerate([(a, alpha), (b, beta)] * 2))
    return (f'sim_origami_linkage = 1\nform = "dh"\nname = "bennett4"\n\n{rows}'
            '[input]\njoint = "theta1"\nrange = [-150.0, 150.0]\n')


def write(tmp_path: Path, text: str, name: str = "linkage.toml") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


def validate(tmp_path: Path, path: Path, capsys) -> tuple[int, str]:
    code = main(["validate", "--linkage", str(path), "--out", str(tmp_path / "out")])
    captured = capsys.readouterr()
    return code, captured.out + captured.err


def test_numbers_carry_their_printed_precision(tmp_path):
    """Half a unit in the last printed digit, in the file's units: TOML and JSON floats, integers +-0.5, and a
    stated precision table overriding the printing; the D-H defaults (an absent offset) are exact."""
    spec = read_linkage(write(tmp_path, bennett_text(beta="48.59", a="1", b="1.50")))
    given = {v.field: v for v in spec.values}
    assert given["joints[1].alpha"].precision == pytest.approx(0.005) and given["joints[1].alpha"].unit == "deg"
    assert given["joints[0].a"].precision == 0.5 and given["joints[1].a"].precision == pytest.approx(0.005)
    assert given["joints[0].offset"].precision == 0.0
    doc = {"sim_origami_linkage": 1, "form": "dh", "units": {"length": "mm"},
           "joints": [{"a": 10.25, "alpha": 30.0}, {"a": 15, "alpha": 4.859e1}] * 2,
           "input": {"joint": "theta1", "range": [20, 140]}}
    path = tmp_path / "b.json"
    path.write_text(json.dumps(doc))
    given = {v.field: v for v in read_linkage(path).values}
    assert given["joints[0].a"].precision == pytest.approx(0.005) and given["joints[0].a"].unit == "mm"
    assert given["joints[1].a"].precision == 0.5 and given["joints[1].alpha"].precision == pytest.approx(0.005)
    doc["precision"] = {"length": 0.001, "angle": 1e-6}
    path.write_text(json.dumps(doc))
    given = {v.field: v for v in read_linkage(path).values}
    assert given["joints[1].a"].precision == 0.001 and given["joints[1].alpha"].precision == 1e-6
    doc["precision"] = {"angle": 0}
    path.write_text(json.dumps(doc))
    with pytest.raises(ParameterError, match=r"precision\.angle = 0: it must be > 0"):
        read_linkage(path)


@pytest.mark.parametrize("junk", [None, "1e-4", [], {"length": None}, {"angle": True}, {"angle": -1.0},
                                  {"length": float("nan")}, {"lenght": 1e-4}])
def test_a_precision_table_that_is_no_table_of_positive_numbers_is_refused_in_one_line(tmp_path, junk):
    doc = {**SPHERICAL, "precision": junk}
    path = tmp_path / "p.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(ParameterError, match=r"^precision") as refused:
        read_linkage(path)
    assert "\n" not in str(refused.value)


@pytest.mark.slow
def test_bennett_with_every_number_to_4_decimals_validates_the_nearest_bennett(tmp_path, capsys):
    """docs/examples/linkages/bennett-typed.toml: as typed, the loops do not close (residual 1.1e-7); the nearest
    Bennett linkage within the numbers' precision is validated (exit 0) and every value it moved is on the scene, each
    within its precision, and meets the Bennett conditions exactly."""
    path = EXAMPLES / "bennett-typed.toml"
    assert all(v.precision == pytest.approx(5e-5) for v in read_linkage(path).values if v.precision)  # 4 decimals
    scene = linkage_scene(path)
    assert scene.adjustments and all(a.ratio <= 1.0 for a in scene.adjustments)
    value = {v.field: v.given for v in read_linkage(path).values} | {a.name: a.value for a in scene.adjustments}
    a1, a2, a3, a4 = (value[f"joints[{k}].a"] for k in range(4))
    t1, t2, t3, t4 = (math.radians(value[f"joints[{k}].alpha"]) for k in range(4))
    assert abs(a1 - a3) < 1e-12 and abs(a2 - a4) < 1e-12 and abs(t1 - t3) < 1e-12 and abs(t2 - t4) < 1e-12
    assert abs(math.sin(t1) / a1 - math.sin(t2) / a2) < 1e-12
    assert "nearest mobile linkage" in scene.notes
    assert [b.domain for b in scene.kinematics.branches()] == [pytest.approx((-150 * math.pi / 180,
                                                                              150 * math.pi / 180))]
    code, out = validate(tmp_path, path, capsys)
    assert code == 0, out


@pytest.mark.slow
@pytest.mark.parametrize("beta", ["48.59037789", "48.5903778907"])
def test_a_bennett_linkage_that_closes_only_to_its_rounding_is_moved_too(tmp_path, beta):
    """beta to 8 and 10 decimals: the loops assemble and the trace covers the range, closed only to 1.7e-11 and
    2.4e-13 (validation failed on both); the nearest Bennett linkage closes its traced nodes to 1e-15."""
    scene = linkage_scene(write(tmp_path, bennett_text(beta=beta, a="1.0", b="1.5", alpha="30.0")))
    assert scene.adjustments and max(a.ratio for a in scene.adjustments) <= 1.0
    loops = scene.kinematics.loop_system()
    nodes = np.vstack([q for _, q, _ in scene.kinematics.nodes.values()])
    assert float(np.median(loops.residual_size(loops.residual(nodes)))) < 1e-15


@pytest.mark.slow
def test_myard_with_a_to_4_decimals_validates(tmp_path, capsys):
    path = write(tmp_path, (EXAMPLES / "myard.toml").read_text().replace("0.766044443118978", "0.7660"))
    scene = linkage_scene(path)
    assert scene.adjustments and max(a.ratio for a in scene.adjustments) <= 1.0
    code, out = validate(tmp_path, path, capsys)
    assert code == 0, out


@pytest.mark.slow
def test_a_file_beyond_its_precision_is_refused_naming_the_distance(tmp_path, capsys):
    """beta typed 48.6000 where the Bennett condition needs 48.590378 (every other number to 5 decimals too): the
    nearest Bennett linkage lies 19 precision units away (measured), refused in one line before any work."""
    path = write(tmp_path, bennett_text(beta="48.60000", a="1.00000", b="1.50000", alpha="30.00000"))
    code, out = validate(tmp_path, path, capsys)
    assert code == 2
    assert len(out.strip().splitlines()) == 1
    assert "joints: the loops cannot be assembled at theta1" in out
    distance = float(out.split("the nearest mobile linkage lies ")[1].split(" precision units away")[0])
    assert 5 < distance < 100
    assert not (tmp_path / "out").exists()


@pytest.mark.slow
def test_a_stated_precision_replaces_the_printed_one(tmp_path):
    """beta printed 48.5904 with a stated angle precision of 1e-9 deg and length precision 1e-9: no longer within
    reach of a Bennett linkage, refused with the distance; with 1e-4 deg it validates."""
    stated = 'name = "bennett4"\nprecision = {{ length = 1e-9, angle = {} }}\n'
    text = bennett_text().replace('name = "bennett4"\n', stated.format("1e-9"))
    with pytest.raises(ParameterError, match="precision units away"):
        linkage_scene(write(tmp_path, text))
    scene = linkage_scene(write(tmp_path, bennett_text().replace('name = "bennett4"\n', stated.format("1e-4"))))
    assert scene.adjustments and max(a.ratio for a in scene.adjustments) <= 1.0
    moved = {a.name: abs(a.moved) for a in scene.adjustments}
    assert moved["joints[1].alpha"] > 1e-6 > max(moved.get(f"joints[{k}].a", 0.0) for k in range(4))




@pytest.mark.slow
@pytest.mark.parametrize("example", [None, "vertex4.toml"])
def test_a_spherical_4r_as_dh_rows_validates(tmp_path, capsys, example):
    """Every a = 0 (a spherical 4R; vertex4.toml: an origami vertex, the twists its sector angles): the loop takes
    its size from one length unit (it was refused, 'the loop has no size'); two assemblies, both validated."""
    path = tmp_path / "sph.json" if example is None else EXAMPLES / example
    if example is None:
        path.write_text(json.dumps(SPHERICAL))
    scene = linkage_scene(path)
    assert len(scene.kinematics.branches()) == 2
    assert scene.mechanism.length_scale == pytest.approx(0.05)  # the bars: 5% of one length unit
    code, out = validate(tmp_path, path, capsys)
    assert code == 0, out


def placed(tmp_path: Path, rows, q0, rotation: np.ndarray, offset: np.ndarray, name: str, span=(10.0, 60.0),
           decimals: int | None = None) -> Path:
    """A 4R drawn as axis lines at pose q0, turned and moved (each point one unit out along its axis), its numbers
    rounded to `decimals` if given."""
    poses = chain_poses(rows, q0)
    joints = []

    def printed(v: np.ndarray) -> list[float]:
        return [round(float(x), decimals) if decimals is not None else float(x) for x in np.atleast_1d(v)]

    for k in range(4):
        T = poses[f"link_{k + 1}"][0]
        joints.append({"name": f"theta{k + 1}", "bodies": [f"link_{(k - 1) % 4 + 1}", f"link_{k + 1}"],
                       "point": printed(rotation @ (T[:3, 3] + T[:3, 2]) + offset),
                       "direction": printed(rotation @ T[:3, 2]), "theta0": printed(np.rad2deg(q0[k]))[0]})
    doc = {"sim_origami_linkage": 1, "form": "axes", "ground": "link_4", "name": name, "joints": joints,
           "input": {"joint": "theta1", "range": list(span)}}
    path = tmp_path / f"{name}.json"
    path.write_text(json.dumps(doc))
    return path


@pytest.mark.slow
def test_a_bennett_linkage_drawn_as_axes_to_4_decimals_moves_to_the_nearest_bennett(tmp_path):
    """Rounded, the drawn pose still closes but the linkage is rigid ('does not move from its start'); the nearest
    mobile one moves its points and directions within their precision (0.92 of it at most, measured) and moves over
    the whole range."""
    dh = tmp_path / "bennett.toml"
    dh.write_text(bennett_text(beta="48.590377890729144"))
    q0 = linkage_scene(dh).kinematics.evaluate("path-1", [math.radians(30.0)])[0][0]
    rows = tuple(DHRow(0.0, a, math.radians(t)) for a, t in [(1.0, 30.0), (1.5, 48.590377890729144)] * 2)
    rotation = Rotation.from_rotvec([0.3, -1.1, 0.7]).as_matrix()
    path = placed(tmp_path, rows, q0, rotation, np.array([3.7, -1.2, 5.5]), "bennett-axes", (20.0, 140.0), 4)
    scene = linkage_scene(path)
    assert scene.adjustments and max(a.ratio for a in scene.adjustments) <= 1.0
    assert any(".direction[" in a.name for a in scene.adjustments)
    (branch,) = scene.kinematics.branches()
    assert branch.domain == pytest.approx((math.radians(20.0), math.radians(140.0)))


@pytest.mark.slow
def test_where_a_linkage_sits_does_not_change_its_verdict(tmp_path, capsys):
    """The spherical 4R drawn at the origin, 70 units off, and rotated too: the same branches, the same paths to
    1e-12 rad, the polished poses closed to 1e-14, and the same exit status (CPU: scripts/placement_bench.py)."""
    path = tmp_path / "sph.json"
    path.write_text(json.dumps(SPHERICAL))
    q0 = linkage_scene(path).kinematics.evaluate("path-1", [math.radians(30.0)])[0][0]
    rows = tuple(DHRow(0.0, 0.0, math.radians(j["alpha"])) for j in SPHERICAL["joints"])
    offset = np.array([37.3, -12.9, 55.1])
    files = [placed(tmp_path, rows, q0, np.eye(3), np.zeros(3), "origin"),
             placed(tmp_path, rows, q0, np.eye(3), offset, "translated"),
             placed(tmp_path, rows, q0, Rotation.from_rotvec([0.3, -1.1, 0.7]).as_matrix(), offset, "rotated")]
    x = np.linspace(math.radians(10.0), math.radians(60.0), 50)
    reference = None
    for file in files:
        kin = linkage_scene(file).kinematics
        paths = [kin.evaluate(b.name, x)[0] for b in kin.branches()]
        loops = kin.loop_system()
        assert max(float(np.max(loops.residual_size(loops.residual(kin.loop_angles(p))))) for p in paths) < 1e-14
        if reference is None:
            reference = paths
        assert len(paths) == len(reference) == 2
        assert max(float(np.max(np.abs(wrap(p - r)))) for p, r in zip(paths, reference, strict=True)) < 1e-12
    for file in files[1:]:
        code = main(["validate", "--linkage", str(file), "--out", str(tmp_path / file.stem)])
        assert code == 0, capsys.readouterr().out
