"""The three-way cross-check (`sim_origami.validation`): verdicts, reports and argument checks."""

import dataclasses
import functools

import pytest

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.checks.verdict import Verdict
from sim_origami.errors import ParameterError
from sim_origami.presets import FAST, STIFF
from sim_origami.scenes import Tuning
from sim_origami.simulate import simulate
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import BLOCKAGE_STOP, validate


@functools.cache
def report_of(name: str, thickness: float = 0.0, branch: str | None = None):
    scene = scenes.get(name).build(**({"thickness": thickness} if thickness else {}))
    return validate(scene, branch=branch)


def every_verdict(report) -> list[Verdict]:
    return list(report.verdicts) + [v for run in report.runs for v in run.verdicts]


@pytest.mark.slow
def test_validate_vertex4_passes_every_verdict_on_every_branch():
    report = report_of("vertex4")
    branches = [b.name for b in report.scene.kinematics.branches()]
    assert [run.requested for run in report.runs] == branches
    assert [(run.followed, run.flips) for run in report.runs] == [(b, 0) for b in branches]
    failed = [(v.name, v.measured, v.tolerance) for v in every_verdict(report) if not v.passed]
    assert failed == []
    assert report.passed
    assert report.blockage is None  # zero thickness: nothing to block
    # Two closed-form verdicts per branch plus one per bifurcation point (the flat state);
    # six verdicts per run (swept range, path, residual, projection, branch followed, mobility ranks).
    assert len(report.verdicts) == 2 * len(branches) + len(report.bifurcations) == 2 * len(branches) + 1
    assert all(len(run.verdicts) == 6 for run in report.runs)
    point = report.bifurcations[0]
    assert point["input_rad"] == 0.0 and set(point["seed_offset_followed_rad"]) == set(branches)


@pytest.mark.slow
def test_validate_thick_miura_adds_a_passing_blockage_verdict():
    report = report_of("miura", 0.02)
    assert report.passed
    assert report.blockage is not None and report.blockage.stopped
    assert report.blockage.contact_input < report.blockage.analytic_limit
    blockage = [v for v in report.verdicts if v.id == BLOCKAGE_STOP]
    assert len(blockage) == 1 and blockage[0].tolerance == TOLERANCES.blockage_rad
    assert blockage[0].measured == report.blockage.error <= TOLERANCES.blockage_rad


def test_run_of_one_branch_compared_against_the_other_branch_fails_the_tolerance():
    report = report_of("vertex4", branch="odd1")
    (run,) = report.runs
    assert run.requested == "odd1"
    assert run.dynamic_path.max_error() <= FAST.angle_rad
    assert compare(report.scene, "odd2", run.dynamic.q).max_error() > FAST.angle_rad


def test_report_with_one_failing_verdict_does_not_pass():
    report = report_of("vertex4", branch="odd1")
    wrong = Verdict("deliberately wrong", measured=2.0, tolerance=1.0, id="deliberately-wrong")
    assert not dataclasses.replace(report, verdicts=(*report.verdicts, wrong)).passed
    run = dataclasses.replace(report.runs[0], verdicts=(*report.runs[0].verdicts, wrong))
    assert not dataclasses.replace(report, runs=(run,)).passed


def test_validate_rejects_an_unknown_branch_naming_it():
    with pytest.raises(ParameterError, match="'odd9'"):
        validate(scenes.get("vertex4").build(), branch="odd9")


def test_validate_rejects_an_unknown_preset_naming_it():
    with pytest.raises(ParameterError, match="'turbo'"):
        validate(scenes.get("vertex4").build(), preset="turbo")


def test_a_scene_runs_its_own_preset_unless_told_otherwise():
    # every registered scene now runs fast (the truncated octahedron, the last on stiff, switched with the 3 s
    # blockage hold); a scene that picks stiff gets it
    assert {scenes.get(name).build().tuning.preset for name in ("vertex4", "truncated-octahedron")} == {FAST}
    scene = dataclasses.replace(scenes.get("vertex4").build(), tuning=Tuning(preset=STIFF))
    run = simulate(scene, "odd1", stop=0.5)
    assert run.preset == STIFF and simulate(scene, "odd1", stop=0.5, preset=FAST).preset == FAST
