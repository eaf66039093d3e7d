"""model.xml: the model a run stepped, readable, and the same run when loaded in plain MuJoCo."""

import re

import mujoco
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.mjcf import ModelOptions, build_xml, preset_duration, with_keyframes
from sim_origami.mjcf_tidy import box_of, short
from sim_origami.report import write
from sim_origami.simulate import Bindings, drive_targets, scale_regularization, scene_xml, start_input, track
from sim_origami.validation import validate


@pytest.fixture(scope="module")
def bennett_run(tmp_path_factory):
    scene = scenes.get("bennett").build()
    report = validate(scene, preset="fast")
    out = tmp_path_factory.mktemp("bennett")
    write(report, out)
    return scene, report, out / "model.xml"


def replay(scene, path, branch: str, duration: float, scaled: bool = True) -> np.ndarray:
    """Plain MuJoCo: load model.xml, apply its regulariser scale, start at the keyframe, drive the run's ramp over
    `duration` s (the sweep time report.json states)."""
    model = mujoco.MjModel.from_xml_path(str(path))
    if scaled:
        scale_regularization(model, float(model.numeric("regularization_scale").data[0]))
    data = mujoco.MjData(model)
    mujoco.mj_resetDataKeyframe(model, data, model.key(f"start_{branch}").id)
    mujoco.mj_forward(model, data)
    n = round(duration / model.opt.timestep)
    start, stop = start_input(scene, branch), scene.branch_path(branch)[1]
    _, setpoints = drive_targets(scene, model, "equality", start, stop, duration, n)
    qpos_log = np.empty((n, model.nq))
    track(model, data, model.eq_data[model.equality(f"drive_{scene.drive_joint}").id], 0, setpoints, qpos_log)
    return Bindings(scene, model).angles(scene, qpos_log)


def test_model_xml_loaded_in_plain_mujoco_repeats_the_run_bitwise(bennett_run):
    scene, report, path = bennett_run
    run = report.runs[0]
    q = replay(scene, path, run.requested, run.dynamic.sweep_time_s)
    assert np.array_equal(q, run.dynamic.q)
    assert compare(scene, run.requested, q).max_error() == run.dynamic_path.max_error()
    # the scale matters: without it the same file gives another run (the regulariser is 100x larger)
    unscaled = replay(scene, path, run.requested, run.dynamic.sweep_time_s, scaled=False)
    assert compare(scene, run.requested, unscaled).max_error() != run.dynamic_path.max_error()


def test_model_xml_reads_as_a_model_file(bennett_run):
    _, _, path = bennett_run
    text = path.read_text()
    numbers = re.findall(r'="([-0-9.e ]+)"', text)
    words = [w for n in numbers for w in n.split()]
    assert words and not [w for w in words if w in ("-0", "-0.0") or re.search(r"e-1[5-9]|e-[2-9]\d", w)]
    assert not [w for w in words if len(w.lstrip("-").replace(".", "").replace("0", "")) > 16]
    comments = re.findall(r"<!--(.*?)-->", text, flags=re.S)
    assert comments and all("\n" not in c for c in comments)  # one-line comments, no measurement logs
    assert "<mesh" not in text and text.count('type="box"') == 4  # four bars as box primitives
    joints = re.findall(r'<joint name="[^"]*" pos[^>]*class="(\w+)"', text)
    assert joints == ["revolute"] * 3  # linkage joints, not creases (the fourth is cut: closed by connects)
    assert "regularization_scale" in text


def test_model_file_is_the_compiled_model_of_the_run(bennett_run):
    scene, report, path = bennett_run
    stepped = scene_xml(scene, ModelOptions(preset=report.preset))
    loaded = mujoco.MjModel.from_xml_path(str(path))
    compiled = mujoco.MjModel.from_xml_string(stepped)
    assert loaded.opt.timestep == compiled.opt.timestep == 0.008
    assert np.array_equal(loaded.body_mass, compiled.body_mass)
    assert preset_duration(report.preset) == loaded.numeric("sweep_duration").data[0]


@pytest.mark.parametrize(
    ("value", "text"),
    [(0.37499999999999994, "0.375"), (1.2246467991473532e-16, "0"), (-0.0, "0"), (100.0, "100"),
     (1e-5, "1e-5"), (0.7071067811865476, "0.707106781186548"), (-2.5, "-2.5")],
)  # fmt: skip
def test_short_numbers_snap_float_noise_only(value, text):
    assert short(value, 1e-15) == text
    assert abs(float(text) - value) <= 1e-15


def test_box_of_finds_bars_and_refuses_other_solids():
    scene = scenes.get("bennett").build()
    bar = scene.mechanism.bodies[0].solid
    centre, quat, half = box_of(bar)
    assert np.allclose(quat, [1, 0, 0, 0]) and np.allclose(2 * half, bar.extents) and np.allclose(centre, bar.centroid)
    vertex = scenes.get("vertex4").build()
    assert box_of(vertex.mechanism.bodies[0].solid) is None  # a sector prism (6 vertices)


@pytest.mark.parametrize("name", ["bennett", "waterbomb-vertex", "thick-diamond"])
def test_keyframes_added_to_a_built_model_give_the_text_built_with_them(name):
    """model.xml adds the start poses to the run's cached MJCF text rather than building the model again: the
    same text, comments, order and indentation included."""
    scene = scenes.get(name).build()
    branches = [b.name for b in scene.kinematics.branches()]
    keys = {b: scene.pose(b, scene.branch_path(b)[0]) for b in branches}
    for options in (ModelOptions(preset="fast"), ModelOptions(render=True)):
        built = build_xml(scene.mechanism, scene.model_setup(), options, keys)
        assert with_keyframes(build_xml(scene.mechanism, scene.model_setup(), options), scene.mechanism, keys) == built
        assert built.count("<key ") == len(branches)
