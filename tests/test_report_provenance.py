"""report.json's provenance outside a full run: the commit of this checkout, and a run MuJoCo could not finish."""

import argparse
import json
import subprocess
from pathlib import Path

import pytest

from sim_origami import scenes
from sim_origami.cli.validate import failed_run
from sim_origami.errors import SimulationError
from sim_origami.presets import FAST
from sim_origami.report import git_commit, provenance


def test_the_commit_is_this_checkouts_head():
    root = Path(__file__).resolve().parents[1]
    head = subprocess.run(["git", "-C", str(root), "rev-parse", "--short", "HEAD"], capture_output=True, text=True,
                          check=True).stdout.strip()
    assert git_commit() in (head, f"{head}+dirty")


@pytest.mark.slow  # 0.8 s: the scene's build
def test_a_run_mujoco_could_not_finish_still_says_what_made_it(tmp_path):
    scene = scenes.get("bennett").build()
    args = argparse.Namespace(preset=None, command_line="sim-origami validate bennett")
    failed_run(scene, args, tmp_path, SimulationError("MuJoCo diverged at step 12"))
    doc = json.loads((tmp_path / "report.json").read_text())
    assert not doc["passed"] and doc["provenance"]["command"] == "sim-origami validate bennett"
    assert doc["provenance"]["preset"] == scene.tuning.preset.name
    assert doc["provenance"].keys() == provenance(FAST).keys()
