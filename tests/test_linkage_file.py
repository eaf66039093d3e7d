"""Linkage files (`validate --linkage FILE`): readers, the two forms, the built-in linkages, the Goldberg 5R example
with its reference curves, and bad input (one line, exit 2, the field named)."""

import dataclasses
import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from linkage_fixtures import BENNETT, EXAMPLES  # tests/linkage_fixtures.py (tests/ is on sys.path)

from sim_origami import scenes
from sim_origami.checks.reference import compare_reference, read_reference
from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.rssr import RSSR
from sim_origami.linkage_file import read_linkage
from sim_origami.linkage_forms import chain_poses
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import FAST
from sim_origami.scenes.linkage_file import linkage_scene
from sim_origami.simulate import compile_model
from sim_origami.validation import MUJOCO_CLOSURE_RESIDUAL, MUJOCO_PATH_ERROR, PROJECTION_PATH_ERROR, run_branch


def write(tmp_path: Path, doc: dict, name: str = "linkage.json") -> Path:
    path = tmp_path / name
    path.write_text(json.dumps(doc))
    return path


def numeric_path(scene, branch: str, x: np.ndarray) -> np.ndarray:
    """A scene's numeric loop solve followed from its closed form's first pose (as validation's closure check)."""
    kin = scene.kinematics
    q = kin.loop_angles(kin.joint_angles(branch, x))
    joints, held = kin.loop_inputs(x)
    return kin.loop_system().follow(q[0], joints[0], held[:, 0])


@pytest.mark.parametrize(
    ("builtin", "file"),
    [("bennett", "bennett.toml"), ("myard", "myard.toml"), ("bricard-plane", "bricard-plane.json"),
     ("bricard-threefold", "bricard-threefold.json")],
)
def test_builtin_linkage_files_give_the_builtin_numeric_paths(builtin, file):
    """Each built-in branch is one file branch, to 1e-12 rad at the built-in sweep's inputs; the others are far."""
    scene, linkage = scenes.get(builtin).build(), linkage_scene(EXAMPLES / file)
    assert len(linkage.kinematics.branches()) == len(scene.kinematics.branches())
    for branch in scene.kinematics.branches():
        x = np.linspace(*scene.branch_path(branch.name), 40)
        truth = numeric_path(scene, branch.name, x)
        errors = sorted(float(np.max(np.abs(wrap(linkage.kinematics.evaluate(b.name, x)[0] - truth))))
                        for b in linkage.kinematics.branches())
        assert errors[0] < 1e-12
        assert all(e > 0.1 for e in errors[1:])


def test_toml_and_json_readers_give_one_mechanism(tmp_path):
    toml = read_linkage(EXAMPLES / "bennett.toml")
    doc = broken(lambda d: d["input"].update(range=[-150.0, 150.0]))
    from_json = read_linkage(write(tmp_path, doc))
    assert from_json.joint_names == toml.joint_names and from_json.input_range == toml.input_range
    q = np.array([0.3, 2.0, -0.3, -2.0])
    assert np.array_equal(from_json.mechanism.loop_system().residual(q), toml.mechanism.loop_system().residual(q))


def test_axes_form_gives_the_dh_forms_motion(tmp_path):
    """The Bennett linkage drawn as axis lines at one of its poses (theta0 = that pose's D-H angles) traces the D-H
    file's path to 1e-12 rad: the hinge angle is the D-H theta in both forms."""
    dh = linkage_scene(write(tmp_path, BENNETT, "dh.json"))
    rows = scenes.get("bennett").build().kinematics.rows
    x0 = 1.2
    q0 = dh.kinematics.evaluate("path-1", [x0])[0][0]
    poses = chain_poses(rows, q0)
    joints = []
    for k in range(4):
        T = poses[f"link_{k + 1}"][0]
        joints.append({"name": f"theta{k + 1}", "bodies": [f"link_{(k - 1) % 4 + 1}", f"link_{k + 1}"],
                       "point": T[:3, 3].tolist(), "direction": T[:3, 2].tolist(),
                       "theta0": float(np.rad2deg(q0[k]))})
    doc = {"sim_origami_linkage": 1, "form": "axes", "ground": "link_4", "joints": joints,
           "input": {"joint": "theta1", "range": [20.0, 140.0]}, "units": {"angle": "deg"}}
    axes = linkage_scene(write(tmp_path, doc, "axes.json"))
    x = np.linspace(0.4, 2.4, 30)
    gap = wrap(axes.kinematics.evaluate("path-1", x)[0] - dh.kinematics.evaluate("path-1", x)[0])
    assert np.max(np.abs(gap)) < 1e-12
    assert "given start" in axes.notes and "assembled at theta1 = 65.84 deg" in dh.notes


def test_goldberg_reference_passes_and_a_perturbed_one_fails(tmp_path):
    """The Goldberg 5R's curves from the two Bennett closed forms agree with the numeric path to < 1e-11 rad; one
    value moved by 1e-6 rad fails at exactly that sample."""
    scene = linkage_scene(EXAMPLES / "goldberg-5r.json")
    assert scene.kinematics.gruebler() == -1 and int(np.max(scene.kinematics.mobility)) == 1
    csv = EXAMPLES / "goldberg-5r_curves.csv"
    good = compare_reference(read_reference(csv, scene.kinematics), scene)
    assert all(v.passed for v in good.verdicts)
    assert good.doc["reference_vs_numeric_max_rad"] < 1e-11
    lines = csv.read_text().splitlines()
    cells = lines[10].split(",")
    cells[2] = f"{float(cells[2]) + np.rad2deg(1e-6):.10f}"
    lines[10] = ",".join(cells)
    bad = tmp_path / "perturbed.csv"
    bad.write_text("\n".join(lines) + "\n")
    check = compare_reference(read_reference(bad, scene.kinematics), scene)
    assert not all(v.passed for v in check.verdicts)
    assert check.doc["over_tolerance"]["samples"] == 1


@pytest.mark.slow
def test_validate_linkage_with_reference_passes_and_writes_the_report(capsys, tmp_path):
    """The documented example end to end (docs/extending.md, 'A linkage file')."""
    code = main(["validate", "--linkage", str(EXAMPLES / "goldberg-5r.json"), "--reference",
                 str(EXAMPLES / "goldberg-5r_curves.csv"), "--out", str(tmp_path / "g")])
    out = capsys.readouterr().out
    assert code == 0, out
    doc = json.loads((tmp_path / "g" / "report.json").read_text())
    assert doc["scene"] == "linkage-goldberg-5r" and doc["passed"]
    assert doc["reference"]["numeric_vs_mujoco_max_rad"] < 1e-6
    assert (tmp_path / "g" / "curves.png").exists()


@pytest.mark.slow
def test_a_drive_too_fast_for_the_model_fails_with_a_report(capsys, tmp_path):
    """A user's sweep_time_scale of 0.01 drives the Bennett linkage 100x faster than its path's rates ask (0.08 s,
    10 steps): the loop tears apart in MuJoCo (closure gap 3.8e-2 m measured) and the angle error is not finite. That
    is a failed check (exit 1, report.json written, JSON null printed as such), not an internal error (it was exit 3:
    the summary line could not print null)."""
    text = (EXAMPLES / "bennett.toml").read_text()
    text = text.replace('name = "bennett"\n', 'name = "bennett"\nsweep_time_scale = 0.01\n')
    (tmp_path / "fast.toml").write_text(text)
    code = main(["validate", "--linkage", str(tmp_path / "fast.toml"), "--out", str(tmp_path / "fast")])
    out = capsys.readouterr().out
    assert code == 1, out
    report = json.loads((tmp_path / "fast" / "report.json").read_text())
    assert not report["passed"] and report["closure_residual_max_m"] > 1e-2
    assert "null (inf or nan)" in out


def broken(change) -> dict:
    doc = json.loads(json.dumps(BENNETT))
    change(doc)
    return doc


def _unassemblable(doc: dict) -> None:
    doc["joints"][1]["a"] = 5.0  # a 4R whose links cannot meet


def _open_axes(doc: dict) -> None:
    doc.clear()
    doc.update({"sim_origami_linkage": 1, "form": "axes", "ground": "g",
                "joints": [{"bodies": ["g", "l1"], "point": [0, 0, 0], "direction": [0, 0, 1]},
                           {"bodies": ["l1", "l2"], "point": [1, 0, 0], "direction": [0, 1, 0]}],
                "input": {"joint": "joint_1", "range": [0, 90]}})


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        (lambda d: d["joints"][2].update(type="prismatic"), "joints[2].type = 'prismatic': unknown joint type"),
        (lambda d: d["joints"][1].pop("alpha"), "joints[1].alpha: missing"),
        (lambda d: d.update(sim_origami_linkage=2), "sim_origami_linkage = 2"),
        (lambda d: d.pop("sim_origami_linkage"), "sim_origami_linkage: missing"),
        (lambda d: d["joints"][3].update(alpha=float("nan")), "joints[3].alpha = nan: it must be a finite number"),
        (lambda d: d["joints"][0].update(alhpa=3), "joints[0].alhpa: unknown field"),
        (lambda d: d["input"].update(joint="theta9"), "input.joint = 'theta9'"),
        (lambda d: d["input"].update(range=[90, 10]), "input.range"),
        (_unassemblable, "joints: the loops cannot be assembled at theta1 = 65.84 deg: no closed pose from 24 random "
                         "starts, the smallest closure residual reached is 1.14 "),
        (_open_axes, "joints: the axes form no closed loop"),
    ],
)
@pytest.mark.slow
def test_bad_linkage_files_exit_2_naming_the_field(capsys, tmp_path, change, needle):
    path = write(tmp_path, broken(change))
    code = main(["validate", "--linkage", str(path), "--out", str(tmp_path / "out")])
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1
    assert needle in err, err
    assert not (tmp_path / "out").exists()


def test_a_start_that_does_not_close_is_refused_with_its_residual(tmp_path):
    doc = broken(lambda d: [j.update(theta0=30.0 + 10.0 * k) for k, j in enumerate(d["joints"])])
    with pytest.raises(ParameterError, match=r"joints\[\]\.theta0: the loops cannot be closed .* closure residual"):
        linkage_scene(write(tmp_path, doc))


@pytest.mark.slow
def test_branches_meeting_inside_the_range_are_a_bifurcation():
    """The plane-symmetric Bricard over theta2 = -60 .. 60 deg: its two motions cross at 0 (Feng 2018, Table 4-1
    case 10); the file's two paths meet there, the poses there match both closed forms, the sweep stays clear."""
    scene = linkage_scene(EXAMPLES / "bricard-plane-crossing.json")
    builtin = scenes.get("bricard-plane").build().kinematics
    (event,) = [e for e in scene.kinematics.events() if e.kind == "bifurcation"]
    assert abs(event.input) < 1e-9 and set(event.branches) == {"path-1", "path-2"}
    for branch in event.branches:
        pose = scene.kinematics.evaluate(branch, [event.input])[0][0]
        assert min(float(np.max(np.abs(wrap(pose - builtin.evaluate(b.name, [event.input])[0][0]))))
                   for b in builtin.branches()) < 1e-9
    lo, hi = scene.path
    assert hi < event.input - 0.05 or lo > event.input + 0.05


def test_goldberg_files_are_what_their_script_writes(tmp_path):
    source = EXAMPLES / "make_goldberg.py"
    shutil.copy(source, tmp_path / source.name)
    subprocess.run([sys.executable, source.name], cwd=tmp_path, check=True)
    for name in ("goldberg-5r.json", "goldberg-5r_curves.csv"):
        assert (tmp_path / name).read_text() == (EXAMPLES / name).read_text()


def test_spherical_joints_read_as_three_hinges_and_a_spinning_link_is_pinned(tmp_path):
    """A ball at joint 3 of the Bennett rows reads as theta3_x, _y, _z; balls at 3 and 4 (an RSSR) leave link 3
    spinning about the line through their centres: one idle freedom, held by theta4_x = 0 in the trace (the far
    ball's x axis is that line), and the outputs are the two revolute joints."""
    one = read_linkage(write(tmp_path, broken(lambda d: d["joints"][2].update(type="spherical")), "one.json"))
    assert one.joint_names == ("theta1", "theta2", "theta3_x", "theta3_y", "theta3_z", "theta4")
    two = linkage_scene(write(tmp_path, broken(lambda d: [d["joints"][k].update(type="spherical") for k in (2, 3)]),
                              "two.json"))
    kin = two.kinematics
    assert kin.joint_names == ("theta1", "theta2") and [kin.loop_joint_names[j] for j in kin.gauge] == ["theta4_x"]
    assert kin.gruebler() == 1 and two.mechanism.idle_spins == 1 and "Kutzbach 2 = 1 + 1 idle spin" in two.notes
    q = kin.loop_angles(kin.evaluate("path-1", [1.0])[0])
    assert np.array_equal(kin.observe(q), kin.evaluate("path-1", [1.0])[0])
    assert kin.loop_system().mobility(q[0]) == 2  # the mechanism's own loops count the spin; the report takes it off


def test_rssr_file_gives_the_builtin_closed_form_on_both_roots():
    """docs/examples/linkages/rssr.json: path-1 is the built-in rssr scene's closed form (Yang 2017, eqn 3-5, root
    3-6a) to 1e-12 rad, every loop angle included (the pinned spin is the closed form's: balls at (0, 0, theta));
    path-2 is the other root (3-6b). Measured 4.4e-15 and 4.0e-15 rad."""
    builtin, linkage = scenes.get("rssr").build(), linkage_scene(EXAMPLES / "rssr.json")
    kin = linkage.kinematics
    assert [b.name for b in kin.branches()] == ["path-1", "path-2"] and kin.joint_names == ("theta1", "theta2")
    x = np.linspace(*builtin.branch_path("bennett"), 40)
    assert np.max(np.abs(kin.evaluate("path-1", x)[0] - builtin.kinematics.evaluate("bennett", x)[0])) < 1e-12
    assert np.max(np.abs(kin.loop_angles(kin.evaluate("path-1", x)[0]) - builtin.kinematics.angles(x))) < 1e-12
    truth = numeric_path(builtin, "bennett", x)  # the built-in scene's numeric solve (its idle spin free)
    assert np.max(np.abs(kin.evaluate("path-1", x)[0] - builtin.kinematics.observe(truth))) < 1e-12
    other = RSSR(1.0, 0.7072, np.deg2rad(45.0), root=-1)
    assert np.max(np.abs(wrap(kin.evaluate("path-2", x)[0][:, 1] - other.theta2(x)))) < 1e-12


def test_rssr_as_axis_lines_gives_the_closed_form(tmp_path):
    """The RSSR drawn as axis lines at theta1 = 80 deg (balls at C and D, no direction given: triads along +z): the
    spin of CD is held by a ball hinge all the same, and path-1 is eqn 3-5 to 1e-12 rad (measured 8.9e-16)."""
    rssr = RSSR(1.0, 0.7072, np.deg2rad(45.0))
    q0 = rssr.loop_angles([np.deg2rad(80.0)])
    poses = chain_poses(rssr.bennett_rows(), q0)
    joints = []
    for k in range(4):
        T = poses[f"link_{k + 1}"][0]
        joint = {"name": f"theta{k + 1}", "bodies": [f"link_{(k - 1) % 4 + 1}", f"link_{k + 1}"],
                 "point": T[:3, 3].tolist()}
        joint |= {"direction": T[:3, 2].tolist(), "theta0": float(np.rad2deg(q0[0, k]))} if k < 2 else \
            {"type": "spherical"}
        joints.append(joint)
    doc = {"sim_origami_linkage": 1, "form": "axes", "ground": "link_4", "joints": joints,
           "input": {"joint": "theta1", "range": [25.0, 175.0]}}
    kin = linkage_scene(write(tmp_path, doc, "rssr-axes.json")).kinematics
    assert kin.joint_names == ("theta1", "theta2") and len(kin.gauge) == 1 and kin.gruebler() == 1
    x = np.linspace(0.5, 2.9, 50)
    assert np.max(np.abs(wrap(kin.evaluate("path-1", x)[0][:, 1] - rssr.theta2(x)))) < 1e-12


@pytest.mark.slow
def test_validate_rssr_file_with_its_closed_form_curves_passes(capsys, tmp_path):
    """The RSSR file through the whole validation (fast preset) with Yang 2017's eqn 3-5 as reference curves: the
    three-way check of a built-in scene (measured: reference vs numeric 8.5e-13 rad, vs MuJoCo 7.4e-8 rad), both
    roots pass, the idle spin reported and left out of the counts."""
    status = main(["validate", "--linkage", str(EXAMPLES / "rssr.json"), "--reference",
                   str(EXAMPLES / "rssr_curves.csv"), "--preset", "fast", "--out", str(tmp_path)])
    assert status == 0, capsys.readouterr().out
    report = json.loads((tmp_path / "report.json").read_text())
    assert report["reference"]["reference_vs_numeric_max_rad"] < 1e-11
    for run in report["branches"]:
        assert run["angle_error_max_rad"] < 1e-6 and run["mobility"]["idle_spins"] == 1
        assert run["mobility"]["gruebler"] == 1 and run["mobility"]["start"]["numeric"] == 1


def test_rssr_curves_are_what_their_script_writes(tmp_path):
    source = EXAMPLES / "make_rssr_curves.py"
    shutil.copy(source, tmp_path / source.name)
    subprocess.run([sys.executable, source.name], cwd=tmp_path, check=True)
    assert (tmp_path / "rssr_curves.csv").read_text() == (EXAMPLES / "rssr_curves.csv").read_text()


def test_meshes_and_contact_pairs_become_solids_and_collision_solids(tmp_path):
    import trimesh

    trimesh.creation.box(extents=(100.0, 10.0, 10.0)).export(tmp_path / "crank.stl")  # millimetres, as the file
    doc = broken(lambda d: d.update(units={"length": "mm"}, shapes={"meshes": {"link_1": "crank.stl"}, "width": 20},
                                    contact=[["link_1", "link_3"]]))
    for joint in doc["joints"]:
        joint["a"] *= 1000.0
    spec = read_linkage(write(tmp_path, doc))
    bodies = {b.name: b for b in spec.mechanism.bodies}
    assert np.allclose(bodies["link_1"].solid.extents, [0.1, 0.01, 0.01])
    assert np.allclose(bodies["link_2"].solid.extents[1:], [0.02, 0.02])  # a bar of the given width (mm)
    assert bodies["link_3"].collision is bodies["link_3"].solid and bodies["link_2"].collision is None
    assert spec.contact_pairs == (("link_1", "link_3"),)
    bad = write(tmp_path, broken(lambda d: d.update(contact=[["link_1", "link_9"]])), "bad.json")
    with pytest.raises(ParameterError, match=r"contact\[0\]: unknown body 'link_9'"):
        read_linkage(bad)


def test_two_loops_as_axes_move_as_the_goldberg_5r(tmp_path):
    """The Goldberg construction before its common link is removed: both Bennett linkages, sharing link DA and
    joints A and D, with AB and AE fixed together (six bodies, seven hinges, two loops; Kutzbach -5). It moves with
    one freedom, and its hinges B, C, E, F follow the Goldberg 5R's numeric path to 1e-12 rad."""
    goldberg = json.loads((EXAMPLES / "goldberg-5r.json").read_text())
    joints = {j["name"]: j for j in goldberg["joints"]}
    joints["D"]["bodies"] = ["CD", "DA"]  # Bennett 1's hinge D, and Bennett 2's (FD to DA) beside it
    start = {j["name"]: j["theta0"] for j in goldberg["joints"]}
    beta = np.arcsin(0.75)
    joints["D2"] = {"name": "D2", "bodies": ["DF", "DA"], "point": [0.0, 0.0, 0.0], "direction": [0.0, 0.0, 1.0],
                    "theta0": -start["E"]}  # Bennett 2's angle at D is -E
    joints["D"].update(point=[0.0, 0.0, 0.0], direction=[0.0, 0.0, 1.0], theta0=-start["B"])
    joints["A"] = {"name": "A", "bodies": ["DA", "EB"], "point": [1.5, 0.0, 0.0],
                   "direction": [0.0, -np.sin(beta), np.cos(beta)], "theta0": -start["C"]}
    doc = goldberg | {"name": "two-bennett", "ground": "DA", "joints": list(joints.values())}
    scene = linkage_scene(write(tmp_path, doc))
    assert len(scene.kinematics.loop_system().loops) == 2 and scene.kinematics.gruebler() == -5
    assert set(np.unique(scene.kinematics.mobility)) == {1}
    five = linkage_scene(EXAMPLES / "goldberg-5r.json")
    x = np.deg2rad(np.linspace(45.0, 135.0, 19))
    names = scene.kinematics.joint_names
    two = scene.kinematics.evaluate("path-1", x)[0]
    one = five.kinematics.evaluate("path-1", x)[0]
    for k, name in enumerate(five.kinematics.joint_names):
        if name != "D":
            assert np.max(np.abs(wrap(two[:, names.index(name)] - one[:, k]))) < 1e-12


def _leaves(doc, path=()):
    """Every value's path in a parsed file (tables and lists included)."""
    yield path
    children = doc.items() if isinstance(doc, dict) else enumerate(doc) if isinstance(doc, list) else ()
    for key, value in children:
        yield from _leaves(value, (*path, key))


JUNK = (None, True, "x", [], {}, [1], -1, 0, 1e308, float("nan"), [[1]], {"a": 1}, [["a"], "b"])


@pytest.mark.parametrize("source", ["bennett.toml", pytest.param("goldberg-5r.json", marks=pytest.mark.slow)])
def test_any_field_replaced_by_junk_reads_or_is_refused_in_one_line(tmp_path, source):
    """Every field of an example, replaced in turn by each JSON value of JUNK: a clean read or one ParameterError."""
    import tomllib

    text = (EXAMPLES / source).read_text()
    base = tomllib.loads(text) if source.endswith(".toml") else json.loads(text)
    for path in list(_leaves(base))[1:]:
        for junk in JUNK:
            doc = json.loads(json.dumps(base))
            target = doc
            for key in path[:-1]:
                target = target[key]
            target[path[-1]] = junk
            try:
                read_linkage(write(tmp_path, doc))
            except ParameterError as err:
                assert "\n" not in str(err)


@pytest.mark.parametrize(
    ("change", "needle"),
    [(lambda d: d["input"].update(range=[0, 1e308]), "input.range = [0, 1e+308]: it must lie within one turn"),
     (lambda d: d.update(sweep_time_scale=1e6), "sweep_time_scale = 1e+06: it must be at most 100"),
     (lambda d: d.update(sweep_time_scale=1e-4), "sweep_time_scale = 0.0001: it must be at least 0.008"),
     (lambda d: d["joints"][0].update(a=1e308), "joints[0].a = 1e+308: lengths beyond 1e+09 m are not simulated"),
     (lambda d: d.update(units={"length": "um"}), "units.length: the linkage is 1.5e-06 m across")],
)
def test_values_that_would_run_forever_or_overflow_are_refused(tmp_path, change, needle):
    with pytest.raises(ParameterError) as err:
        linkage_scene(write(tmp_path, broken(change)))
    assert needle in str(err.value)


def test_describe_linkage_prints_the_reference_header_of_the_example_curves(capsys):
    assert main(["describe", "--linkage", str(EXAMPLES / "goldberg-5r.json")]) == 0
    out = capsys.readouterr().out
    header = (EXAMPLES / "goldberg-5r_curves.csv").read_text().splitlines()[1]
    assert f"reference CSV header (validate --reference): {header}" in out
    assert "path-1     C in [40.0000, 140.0000] deg" in out
    assert main(["describe", "bennett", "--linkage", str(EXAMPLES / "bennett.toml")]) == 2
    assert "give a SCENE or --linkage FILE" in capsys.readouterr().err


@pytest.mark.slow
def test_branches_meeting_at_the_range_ends_are_bifurcations(tmp_path):
    """The threefold Bricard over a whole turn: its two motions meet at theta1 = +-180 deg (Yang 2017, section 2.5),
    the ends of the range; found there to 1e-12 rad, with closed poses (one-sided extrapolation)."""
    doc = json.loads((EXAMPLES / "bricard-threefold.json").read_text())
    doc["input"]["range"] = [-180.0, 180.0]
    kin = linkage_scene(write(tmp_path, doc)).kinematics
    meetings = sorted(e.input for e in kin.events() if e.kind == "bifurcation")
    assert np.allclose(meetings, [-np.pi, np.pi], atol=1e-12, rtol=0)
    for x in meetings:
        for branch in ("path-1", "path-2"):
            assert kin.loop_system().residual_norm(kin.evaluate(branch, [x])[0])[0] < 1e-13


@pytest.mark.slow
def test_myard_rsrrr_file_follows_the_myard_on_one_of_its_two_motions():
    """myard-rsrrr.toml (the Myard with a ball at joint 2): path-2 is the built-in myard scene's numeric path to
    1e-12 rad, its ball turning about joint 2's former axis only; path-1 tilts the ball; they meet at theta3 = 90 deg
    (a bifurcation) and the sweep stops short of it."""
    builtin, linkage = scenes.get("myard").build(), linkage_scene(EXAMPLES / "myard-rsrrr.toml")
    kin = linkage.kinematics
    x = np.linspace(np.deg2rad(30.0), np.deg2rad(85.0), 30)
    truth = numeric_path(builtin, builtin.kinematics.branches()[0].name, x)
    ball = [kin.joint_names.index(f"theta2_{a}") for a in "xyz"]
    myard = kin.evaluate("path-2", x)[0]
    hinges = [k for k in range(len(kin.joint_names)) if k not in ball]
    assert np.max(np.abs(wrap(myard[:, hinges] - np.delete(truth, 1, axis=1)))) < 1e-12
    assert np.max(np.abs(wrap(myard[:, ball[2]] - truth[:, 1]))) < 1e-12 and np.max(np.abs(myard[:, ball[:2]])) < 1e-12
    (meeting,) = [e.input for e in kin.events() if e.kind == "bifurcation"]
    assert abs(meeting - np.pi / 2) < 1e-9 and linkage.path[1] < meeting


@pytest.mark.slow
def test_a_sweep_through_the_rsrrr_singular_pose_fails_naming_it():
    """The same file swept through theta3 = 90 deg: MuJoCo's path error on the Myard motion peaks just past the
    meeting (measured 1.1e-3 rad at 90.32 deg, 2.6e-8 rad beyond 100 deg), where the closure constraints lose rank
    (mobility 2); the failing verdict names the singular pose it crossed."""
    scene = linkage_scene(EXAMPLES / "myard-rsrrr.toml")
    crossing = dataclasses.replace(scene, path=(np.deg2rad(25.0), np.deg2rad(155.0)))
    run = run_branch(crossing, "path-2", compile_model(crossing, ModelOptions(preset=FAST)), "closed")
    failed = {v.id: v for v in run.verdicts if not v.passed}
    error = failed[MUJOCO_PATH_ERROR]
    assert error.measured > 1e-4 and set(failed) <= {MUJOCO_PATH_ERROR, MUJOCO_CLOSURE_RESIDUAL, PROJECTION_PATH_ERROR}
    for verdict in [failed[k] for k in (MUJOCO_PATH_ERROR, PROJECTION_PATH_ERROR) if k in failed]:  # they say why
        assert "the sweep crosses a singular pose: the bifurcation at 1.5708 rad (branches path-1 and path-2 meet; " \
               "mobility 2 there by the closure rank, 2 by MuJoCo's)" in verdict.detail
    assert float(error.detail.split("the largest error lies ")[1].split(" rad")[0]) < 0.02
