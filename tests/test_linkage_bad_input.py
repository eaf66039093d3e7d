"""Bad linkage files found by fuzzing (issue 27): each is refused in one line naming the value and the rule (exit 2),
as the file is read, before any trace or simulation; never an internal error (exit 3) or a run of minutes."""

import json
import time
from pathlib import Path

import pytest
from linkage_fixtures import BENNETT, EXAMPLES  # tests/linkage_fixtures.py (tests/ is on sys.path)

from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.kinematics.linkage_path import LinkagePath
from sim_origami.linkage_file import read_linkage
from sim_origami.scenes.linkage_file import linkage_scene

TOML = """sim_origami_linkage = 1
form = "dh"
{extra}
[[joints]]
a = {a}
alpha = 30.0
[[joints]]
a = 1.5
alpha = 48.590377890729144
[[joints]]
a = 1.0
alpha = 30.0
[[joints]]
a = 1.5
alpha = 48.590377890729144
[input]
joint = "theta1"
range = [20.0, 140.0]
"""


def bennett(**changes) -> dict:
    doc = json.loads(json.dumps(BENNETT))
    doc.update(changes)
    return doc


def refused(capsys, tmp_path: Path, path: Path, needle: str) -> str:
    """`validate --linkage path`: exit 2, one stderr line holding needle, no output folder."""
    code = main(["validate", "--linkage", str(path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2, err
    assert len(err.strip().splitlines()) == 1, err
    assert needle in err, err
    assert not (tmp_path / "out").exists()
    return err


def write(tmp_path: Path, text: str, name: str = "linkage.json") -> Path:
    path = tmp_path / name
    path.write_text(text)
    return path


@pytest.mark.parametrize("digits", [400, 5000])
def test_integers_beyond_a_float_are_refused_in_json_and_toml(capsys, tmp_path, digits):
    big = "1" + "0" * digits
    text = json.dumps(bennett()).replace('"a": 1.0', f'"a": {big}', 1)
    needle = "joints[0].a = <an integer of 401 digits>: it must be a finite number" if digits == 400 else \
        "an integer of over 4300 digits"
    refused(capsys, tmp_path, write(tmp_path, text), needle)
    refused(capsys, tmp_path, write(tmp_path, TOML.format(extra="", a=big), "linkage.toml"), needle)


@pytest.mark.parametrize(
    ("name", "text"),
    [("linkage.json", json.dumps(bennett())[:-1] + ', "notes": ' + "[" * 5000 + "]" * 5000 + "}"),
     ("linkage.toml", TOML.format(extra="notes = " + "[" * 5000 + "]" * 5000, a=1.0)),
     ("linkage.toml", TOML.format(extra="notes = " + "{a = " * 3000 + "1" + "}" * 3000, a=1.0)),
     ("linkage.toml", TOML.format(extra="notes." + "a." * 3000 + "b = 1", a=1.0)),
     ("linkage.json", json.dumps(bennett())[:-1] + ', "notes": ' + "[" * 40 + "]" * 40 + "}")],
)
def test_documents_nested_thousands_deep_are_refused(capsys, tmp_path, name, text):
    refused(capsys, tmp_path, write(tmp_path, text, name), "lists or tables nested more than 32 deep")


def test_an_input_range_narrower_than_the_first_step_is_refused(capsys, tmp_path):
    doc = bennett(input={"joint": "theta1", "range": [1e-300, 2e-300]})
    refused(capsys, tmp_path, write(tmp_path, json.dumps(doc)), "input.range = [1e-300, 2e-300]: it must span at least")


@pytest.mark.parametrize("file", ["mesh", "m.foo", "m.xyz"])
def test_a_mesh_file_of_no_known_kind_is_refused(capsys, tmp_path, file):
    (tmp_path / file).write_text("1 2 3\n")
    doc = bennett(shapes={"meshes": {"link_1": file}})
    refused(capsys, tmp_path, write(tmp_path, json.dumps(doc)), "a mesh file ends in .stl, .obj, .ply")


ONE_TRIANGLE = ("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                "endfacet\nendsolid t\n")
INF_VERTEX = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 inf\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n"


@pytest.mark.parametrize(
    ("files", "shapes", "needle"),
    [({}, {"width": 1e-300}, "shapes.width = 1e-300: it must lie within 0.00015 .. 1e+04 m"),
     ({}, {"width": 1e6}, "shapes.width = 1000000.0: it must lie within"),
     ({"t.stl": ONE_TRIANGLE}, {"meshes": {"link_1": "t.stl"}}, "'t.stl' is no solid MuJoCo can simulate"),
     ({"i.obj": INF_VERTEX}, {"meshes": {"link_2": "i.obj"}}, "shapes.meshes.link_2: 'i.obj'")],
)
def test_solids_mujoco_cannot_compile_are_refused_as_the_file_is_read(tmp_path, files, shapes, needle):
    for name, text in files.items():
        (tmp_path / name).write_text(text)
    start = time.process_time()
    with pytest.raises(ParameterError) as err:
        read_linkage(write(tmp_path, json.dumps(bennett(shapes=shapes))))
    assert needle in str(err.value)
    assert time.process_time() - start < 0.5


@pytest.mark.parametrize(
    ("changes", "needle"),
    [({"name": "a\0b"}, r"name = 'a\x00b': it holds the control character '\x00'"),
     ({"notes": "a\0b"}, r"notes = 'a\x00b': it holds the control character '\x00'"),
     ({"notes": "two\nlines"}, r"notes = 'two\nlines': it holds the control character '\n'"),
     ({"notes": "\ud800"}, r"notes = '\ud800': it holds the control character")],
)
def test_control_characters_in_names_and_notes_are_refused(capsys, tmp_path, changes, needle):
    refused(capsys, tmp_path, write(tmp_path, json.dumps(bennett(**changes))), needle)


def test_a_nul_in_a_joint_name_is_refused(tmp_path):
    doc = bennett()
    doc["joints"][2]["name"] = "x\0"
    with pytest.raises(ParameterError, match=r"joints\[2\]\.name = 'x\\x00': it holds the control character"):
        read_linkage(write(tmp_path, json.dumps(doc)))


@pytest.mark.parametrize("anchor", [1e-300, 1e-5, 1e5])
def test_an_anchor_beyond_the_length_limits_is_refused_as_the_file_is_read(tmp_path, anchor):
    with pytest.raises(ParameterError, match=rf"anchor = {anchor!r}: it must lie within 0.00015 \.\. 1e\+04 m"):
        read_linkage(write(tmp_path, json.dumps(bennett(anchor=anchor))))


def test_forty_dh_rows_are_refused_before_any_solve(capsys, tmp_path):
    doc = bennett()
    doc["joints"] = [{"a": j["a"], "alpha": j["alpha"]} for j in doc["joints"] * 10]
    start = time.process_time()
    refused(capsys, tmp_path, write(tmp_path, json.dumps(doc)),
            "joints: 40 joint freedoms in 1 loop leave at least 34 freedoms (Kutzbach)")
    assert time.process_time() - start < 1.0


def test_a_goldberg_linkage_with_every_axis_parallel_is_refused_quickly(capsys, tmp_path):
    """A planar 5R: 2 freedoms (Kutzbach's spatial count, -1, does not see it; the closure rank does)."""
    doc = json.loads((EXAMPLES / "goldberg-5r.json").read_text())
    for joint in doc["joints"]:
        joint["direction"], joint["point"][2] = [0, 0, 1], 0.0
    start = time.process_time()
    path = write(tmp_path, json.dumps(doc))
    refused(capsys, tmp_path, path, "joints: the linkage moves with 2 freedoms at C = 80 deg")
    assert time.process_time() - start < 2.0


@pytest.mark.parametrize(
    ("args", "needle"),
    [((123,), "source = 123: give the linkage file's path"),
     ((None,), "source = None"),
     (("",), "source = ''"),
     (("a\0b",), "source = 'a\\x00b'"),
     ((EXAMPLES / "bennett.toml", [1.0]), "values = [1.0]: give a table"),
     ((EXAMPLES / "bennett.toml", {"joints[9].a": 1.0}), "joints[9].a: the file has no such number"),
     ((EXAMPLES / "bennett.toml", {"joints[0].a": "x"}), "values['joints[0].a'] = 'x': it must be a number"),
     ((EXAMPLES / "bennett.toml", {3: 1.0}), "3: not a geometry field")],
)
def test_read_linkage_refuses_wrong_types_with_a_parameter_error(args, needle):
    with pytest.raises(ParameterError) as err:
        read_linkage(*args)
    assert needle in str(err.value)


def test_linkage_scene_refuses_a_path_of_the_wrong_type():
    with pytest.raises(ParameterError, match=r"source = 1\.5"):
        linkage_scene(1.5)


@pytest.mark.parametrize(
    ("change", "needle"),
    [({"loops": None}, "loops = NoneType"),
     ({"joint_names": ("a",)}, "joint_names: give 4 names"),
     ({"input_joint": 7}, "input_joint = 7: it must be a joint index from 0 to 3"),
     ({"input_joint": "theta1"}, "input_joint = 'theta1'"),
     ({"input_range": (0.0,)}, "input_range = (0.0,): give (lo, hi)"),
     ({"input_range": (0.0, float("nan"))}, "input_range = (0.0, nan)"),
     ({"start": [0.0, 1.0]}, "start: it must hold 4 finite joint angles (rad), not shape (2,)"),
     ({"start": "abc"}, "start: it must be an array of joint angles")],
)
def test_linkage_path_refuses_wrong_types_and_shapes(change, needle):
    spec = read_linkage(EXAMPLES / "bennett.toml")
    args = {"loops": spec.mechanism.loop_system(), "joint_names": spec.joint_names, "input_joint": 0,
            "input_range": (0.4, 2.0), "start": None} | change
    with pytest.raises(ParameterError) as err:
        LinkagePath(args.pop("loops"), args.pop("joint_names"), args.pop("input_joint"), args.pop("input_range"),
                    args.pop("start"))
    assert needle in str(err.value)
