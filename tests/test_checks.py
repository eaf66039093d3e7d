"""Checks (`sim_origami.checks`): verdicts, branch labels, path comparison and blockage assessment."""

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.blockage import assess
from sim_origami.checks.branches import classify
from sim_origami.checks.paths import compare
from sim_origami.checks.verdict import Verdict
from sim_origami.tolerances import TOLERANCES

SCENE_NAMES = scenes.names()
# Scenes whose branches cross at the flat state (origami vertices), and those with one branch.
FLAT_SCENES = [
    n
    for n in SCENE_NAMES
    if any(e.kind == "bifurcation" and e.input == 0.0 for e in scenes.get(n).build().kinematics.events())
]
MULTI_BRANCH_SCENES = [n for n in SCENE_NAMES if len(scenes.get(n).build().kinematics.branches()) > 1]
SINGLE_BRANCH_SCENES = [n for n in SCENE_NAMES if len(scenes.get(n).build().kinematics.branches()) == 1]
FORCE_LIMIT = 20.0


def branch_names(scene) -> list[str]:
    return [b.name for b in scene.kinematics.branches()]


def closed_form_q(scene, branch: str, x: np.ndarray) -> np.ndarray:
    """Mechanism angles (n, n_joints) of the closed form on `branch` at inputs x."""
    return scene.loop_to_mechanism(scene.kinematics.loop_angles(scene.kinematics.joint_angles(branch, x)))


def symmetric_inputs(scene) -> np.ndarray:
    """Inputs through the flat state (x = 0 at index 10), inside every branch's domain."""
    half = min(min(abs(lo), hi) for lo, hi in (b.domain for b in scene.kinematics.branches()))
    return np.linspace(-0.9 * half, 0.9 * half, 21)


@pytest.mark.parametrize(
    ("measured", "tolerance", "passed"),
    [(0.5, 1.0, True), (1.0, 1.0, True), (1.0 + 1e-12, 1.0, False), (0.0, 0.0, True), (np.nan, 1.0, False),
     (np.inf, 1.0, False), (-np.inf, 0.0, True)],
)
def test_verdict_passes_exactly_when_measured_is_at_most_tolerance(measured, tolerance, passed):
    verdict = Verdict("check", measured, tolerance, id="check")
    assert verdict.passed is passed


@pytest.mark.parametrize("name", FLAT_SCENES)
def test_classify_leaves_flat_state_unlabelled_and_labels_the_branch_elsewhere(name):
    scene = scenes.get(name).build()
    x = symmetric_inputs(scene)
    for branch in branch_names(scene):
        labels = classify(scene.kinematics, x, scene.kinematics.joint_angles(branch, x))
        assert labels.labels[10] == ""  # every branch passes through the flat state
        assert labels.labels[:10] + labels.labels[11:] == (branch,) * 20
        assert (labels.followed, labels.flips) == (branch, 0)


@pytest.mark.slow
@pytest.mark.parametrize("name", SINGLE_BRANCH_SCENES)
def test_classify_labels_every_sample_of_a_single_branch_linkage(name):
    scene = scenes.get(name).build()
    branch = branch_names(scene)[0]
    x = np.linspace(*scene.branch_path(branch), 20)
    labels = classify(scene.kinematics, x, scene.kinematics.joint_angles(branch, x))
    assert labels.labels == (branch,) * 20 and labels.flips == 0


@pytest.mark.parametrize("name", FLAT_SCENES)
def test_classify_counts_a_switch_of_branch_as_a_flip(name):
    scene = scenes.get(name).build()
    first, second = branch_names(scene)[:2]
    x = np.linspace(0.1, 0.5, 20)
    outputs = np.vstack([scene.kinematics.joint_angles(first, x[:12]), scene.kinematics.joint_angles(second, x[12:])])
    labels = classify(scene.kinematics, x, outputs)
    assert labels.labels == (first,) * 12 + (second,) * 8
    assert (labels.followed, labels.flips) == (first, 1)


def test_classify_of_a_path_that_never_leaves_flat_follows_no_branch():
    scene = scenes.get("vertex4").build()
    x = np.zeros(5)
    labels = classify(scene.kinematics, x, np.zeros((5, 4)))
    assert labels == type(labels)(("",) * 5, "", 0)


@pytest.mark.parametrize("name", MULTI_BRANCH_SCENES)
def test_path_against_its_own_branch_agrees_and_against_another_branch_differs(name):
    scene = scenes.get(name).build()
    own, other = branch_names(scene)[:2]
    x = np.linspace(*scene.branch_path(own), 30)
    q = closed_form_q(scene, own, x)
    assert compare(scene, own, q).max_error() <= TOLERANCES.closed_form_rad
    # Measured 2.9 rad (vertex4), 3.6 rad (miura); case 10's Bricard paths are at most 0.962 rad apart.
    assert compare(scene, other, q).max_error() > 0.5


def test_compare_measures_the_input_from_the_drive_joint():
    scene = scenes.get("miura").build()  # drive_scale 2: rho_c = 2 theta
    x = np.linspace(0.3, 0.6, 7)
    path = compare(scene, "miura", closed_form_q(scene, "miura", x))
    np.testing.assert_allclose(path.input, x, atol=TOLERANCES.closed_form_rad, rtol=0)


def test_path_outside_the_branch_domain_has_infinite_error():
    scene = scenes.get("vertex4").build()
    odd1, odd2 = branch_names(scene)[:2]
    hi = scene.kinematics.branch(odd1).domain[1]
    assert scene.kinematics.branch(odd2).domain[1] > hi + 0.2
    q = closed_form_q(scene, odd2, np.array([0.5 * hi, hi + 0.1]))
    assert compare(scene, odd1, q).max_error() == np.inf


def assessed(stop: float, target: float = 1.0, peak_force: float = 5.0):
    """A synthetic run ramping from 0 to `stop` against a ramp to `target`, contact at 0.8."""
    x = np.linspace(0.0, stop, 50)
    force = np.linspace(0.0, peak_force, 50)
    return assess(x, np.linspace(0.0, target, 50), force, FORCE_LIMIT, 0.8, 1.2)


def test_blockage_assess_sees_a_run_that_reached_its_target_as_not_stopped():
    result = assessed(stop=1.0 - 5e-4)
    assert not result.stopped and not result.drive_saturated
    assert (result.contact_input, result.analytic_limit) == (0.8, 1.2)


def test_blockage_assess_sees_a_run_that_fell_short_as_stopped_with_its_error():
    result = assessed(stop=0.805, peak_force=FORCE_LIMIT)
    assert result.stopped and result.drive_saturated
    assert result.stop_input == 0.805
    np.testing.assert_allclose(result.error, 0.005, atol=1e-15, rtol=0)


@pytest.mark.parametrize(("peak", "saturated"), [(0.998 * FORCE_LIMIT, False), (0.9995 * FORCE_LIMIT, True)])
def test_blockage_assess_flags_saturation_at_the_force_limit(peak, saturated):
    assert assessed(stop=0.9, peak_force=-peak).drive_saturated is saturated


def test_blockage_without_contact_is_measured_against_the_end_of_the_path():
    # No contact on the path (contact input nan): a drive that got there has error 0, one that stopped short
    # is as far off as it fell short of the lock (never nan).
    x = np.linspace(0.0, 1.2, 50)
    clear = assess(x, x, np.zeros(50), FORCE_LIMIT, float("nan"), 1.2)
    assert not clear.stopped and clear.error == 0.0
    stuck = assess(np.minimum(x, 0.9), x, np.zeros(50), FORCE_LIMIT, float("nan"), 1.2)
    assert stuck.stopped
    np.testing.assert_allclose(stuck.error, 0.3, atol=1e-15, rtol=0)


def test_a_check_that_compared_nothing_cannot_pass():
    from sim_origami.checks.verdict import Verdict

    assert Verdict("error (rad)", 0.0, 1e-6, compared=200, id="error").passed
    assert not Verdict("error (rad)", 0.0, 1e-6, compared=0, id="error").passed  # an empty max is no agreement
    assert Verdict("events", 0.0, 0.0, id="events").passed  # a count of events compares no samples
    assert not Verdict("error (rad)", float("nan"), 1e-6, compared=5, id="error").passed


def test_every_verdict_made_has_its_own_stable_kebab_case_id_constant():
    """Each `Verdict(...)` the package makes names its kind by a module constant (`id=SWEPT_RANGE`), never a string
    literal; the constants are short kebab-case (the schema's pattern) and no two kinds share one."""
    import ast
    import importlib
    import re
    from pathlib import Path

    ids = {}
    for module in ("sim_origami.validation", "sim_origami.checks.reference", "sim_origami.cli.validate"):
        mod = importlib.import_module(module)
        tree = ast.parse(Path(mod.__file__).read_text(encoding="utf-8"))
        calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call)
                 and (getattr(n.func, "id", None) == "Verdict" or getattr(n.func, "attr", None) == "replace")]
        for call in calls:
            assert getattr(call.func, "id", None) != "Verdict" or any(k.arg == "id" for k in call.keywords), \
                (module, ast.unparse(call)[:80])
            for keyword in (k for k in call.keywords if k.arg == "id"):
                assert isinstance(keyword.value, ast.Name), (module, ast.unparse(call)[:80])
                ids[keyword.value.id] = getattr(mod, keyword.value.id)
    assert len(ids) >= 25 and len(set(ids.values())) == len(ids), ids
    assert all(re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", value) for value in ids.values()), ids
