"""Scene parameters as people type them: exact conditions held to the typed precision, the nearest exact model
validated and every move reported; the README's tour as pasted."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.cli.options import parse_params
from sim_origami.errors import AssemblyError
from sim_origami.precision import Typed, half_unit, nearest_exact
from sim_origami.scenes.base import EXACT_RESIDUAL

ROOT = Path(__file__).resolve().parents[1]
CLI = [sys.executable, "-m", "sim_origami"]

# Scenes with an exact condition on their parameters, each with values printed to 4 significant digits that meet
# it only within that precision, and the exact values (API units) they stand for.
ROUNDED = {
    "bennett": ({"beta": "48.59"}, {"beta": float(np.arcsin(0.75))}),
    "waterbomb-twist": ({"row": "1", "beta": "42.01"}, {"beta": np.deg2rad(42.0105238)}),
}


def test_every_scene_with_an_exact_condition_has_a_rounded_case():
    with_condition = {name for name in scenes.names() if scenes.get(name).condition is not None}
    assert with_condition == set(ROUNDED)


def test_typed_values_carry_half_a_unit_in_their_last_digit():
    values = parse_params(["beta=48.5904", "a=2", "b=1.50", "c=-2.5e-3"])
    assert all(isinstance(v, Typed) for v in values.values())
    assert values["beta"] == 48.5904 and values["beta"].precision == pytest.approx(5e-5)
    assert values["a"].precision == 0.5 and values["b"].precision == pytest.approx(0.005)
    assert values["c"].precision == pytest.approx(5e-5) == half_unit("-2.5e-3")


def test_nearest_exact_is_the_projection_in_units_of_the_precision():
    """A linear condition x + y = 1 from (0.6, 0.6) with precisions (1, 2): the weighted projection moves y four
    times as far as x (moves proportional to precision squared): (0.56, 0.44)."""
    nearest = nearest_exact(lambda p: np.array([p[0] + p[1] - 1.0]), [0.6, 0.6], [1.0, 2.0], 1e-15)
    assert nearest.values == pytest.approx([0.56, 0.44], abs=1e-9)  # measured 1.8e-12: a difference Jacobian
    assert nearest.ratio == pytest.approx(0.08) and nearest.residual <= 1e-15


@pytest.mark.parametrize("name", sorted(ROUNDED))
def test_rounded_parameters_build_the_nearest_exact_scene(name):
    typed, exact = ROUNDED[name]
    kind = scenes.get(name)
    scene = kind.build_from_user({key: Typed(text) for key, text in typed.items()})
    assert abs(kind.condition.residual(scene.params)) <= EXACT_RESIDUAL
    for key, value in exact.items():  # the exact model these digits stand for
        assert scene.params[key] == pytest.approx(value, abs=2e-9)
    (moved,) = scene.adjustments  # beta alone was typed with a fraction to move
    assert moved.name == "beta" and moved.unit == "deg" and 0 < moved.ratio <= 1
    assert moved.given == float(typed["beta"]) and moved.precision == pytest.approx(0.005)
    # Given exactly (the API's plain floats) the same digits are not moved: the kinematics refuse them
    with pytest.raises((AssemblyError, ValueError)):
        kind.build_from_user({key: float(text) for key, text in typed.items()})


def test_values_beyond_their_precision_are_refused_with_the_distance():
    with pytest.raises(AssemblyError, match=r"move beta 42\.1 -> 42\.0105238 deg .*1\.8 of its precision 0\.05"):
        scenes.get("waterbomb-twist").build_from_user({"row": Typed("1"), "beta": Typed("42.1")})


def test_more_digits_move_less():
    """The digits the Bennett refusal suggests (48.5903779) and the README's 48.5904 both validate: the first
    moves beta by 0.19 of its 5e-8 deg precision."""
    kind = scenes.get("bennett")
    scene = kind.build_from_user({"beta": Typed("48.5903779")})
    (moved,) = scene.adjustments
    assert moved.ratio == pytest.approx(0.19, abs=0.01) and moved.precision == pytest.approx(5e-8)


@pytest.mark.slow
def test_rounded_bennett_validates_with_the_adjustment_reported(tmp_path):
    """`validate bennett -p beta=48.59` (the default printed to 4 digits): exit 0, the move on the terminal and in
    report.json, every check passing on the exact linkage (closed-form residual at its rounding floor)."""
    out = tmp_path / "bennett"
    done = subprocess.run([*CLI, "validate", "bennett", "-p", "beta=48.59", "--out", str(out)],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stdout + done.stderr
    assert re.search(r"adjusted beta 48\.59 -> 48\.59037789 deg \(moved 0\.00038 deg, 0\.076 of its", done.stdout)
    doc = json.loads((out / "report.json").read_text())
    (moved,) = doc["adjustments"]
    assert moved["name"] == "beta" and moved["ratio"] == pytest.approx(0.0756, abs=1e-3)
    assert doc["params"]["beta"] == pytest.approx(np.arcsin(0.75), abs=1e-15) and doc["passed"]
    assert "Adjusted to the nearest exact model" in (out / "report.html").read_text()


def _tour() -> list[str]:
    """The README tour's commands, continuation lines joined, comments dropped."""
    block = ROOT.joinpath("README.md").read_text().split("## A five-minute tour", 1)[1].split("```bash", 1)[1]
    text = block.split("```", 1)[0].replace("\\\n", " ")
    return [line.split("  #", 1)[0].strip() for line in text.splitlines() if line.strip()]


def test_the_tour_activates_the_venv_and_names_files_that_exist():
    commands = _tour()
    assert commands[0] == ". .venv/bin/activate"
    for path in re.findall(r"docs/\S+", " ".join(commands)):
        assert (ROOT / path).is_file(), path


@pytest.mark.slow
def test_the_readme_tour_runs_as_pasted(tmp_path):
    """Every command of the tour exits 0 in a fresh bash from the checkout, with the venv's sim-origami (this
    interpreter's) on the PATH as `. .venv/bin/activate` puts it; outputs go to a copy's runs/."""
    work = tmp_path / "checkout"
    work.mkdir()
    (work / "docs").symlink_to(ROOT / "docs")
    venv = work / ".venv" / "bin"
    venv.mkdir(parents=True)
    (venv / "activate").write_text(f'export PATH="{Path(sys.executable).parent}:$PATH"\n')
    env = {k: v for k, v in os.environ.items() if k != "VIRTUAL_ENV"}
    for command in _tour()[1:]:
        done = subprocess.run(["bash", "-c", f". .venv/bin/activate && {command}"], cwd=work, env=env,
                              capture_output=True, text=True, timeout=900)
        assert done.returncode == 0, f"{command}: {done.stdout[-2000:]}{done.stderr[-2000:]}"
    assert (work / "runs" / "miura" / "report.html").is_file()
