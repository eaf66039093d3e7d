"""report.json against its JSON Schema (sim_origami/report.schema.json, Draft 2020-12, docs/guide.md "report.json").
Each kind of report is made for real by `sim-origami validate` (real MuJoCo) and held to the schema: a closed-form
scene, a FOLD file with reference curves, linkage files (one with reference curves, one whose typed values were
adjusted), registered scenes with a bifurcation study, a blockage, a free run under gravity, S joints and a crease
pattern, --render with --all's thumbnail, a run that fails its checks, one MuJoCo could not finish and one stopped
before MuJoCo; reports the schema must refuse (a misspelt key, a string for a number) are refused."""

import argparse
import copy
import json
from dataclasses import replace
from importlib.resources import files
from pathlib import Path

import jsonschema
import pytest
from fold_fixtures import degree4_letters, miura_letters_only, write  # tests/ is on pytest's sys.path

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.cli import validate as validate_command
from sim_origami.presets import PRESET_NAMES
from sim_origami.scenes.fold_file import fold_scene
from sim_origami.stabilize import MODES
from sim_origami.validation import CLOSED_FORM_RESIDUAL, MUJOCO_PATH_ERROR

SCHEMA = json.loads((files("sim_origami") / "report.schema.json").read_text(encoding="utf-8"))
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "docs" / "examples"
GUIDE = ROOT / "docs" / "guide.md"


def strict_json(path: Path) -> dict:
    """A file read as JSON proper: NaN and Infinity (what json.dumps writes for a non-finite float) are refused."""

    def refuse(constant: str):
        raise AssertionError(f"{path}: {constant} is no JSON number (a non-finite value not written as null)")

    return json.loads(path.read_text(encoding="utf-8"), parse_constant=refuse)


def problems(doc: dict) -> list[str]:
    """Every way `doc` breaks the schema, each as 'path: message'."""
    return [f"{'/'.join(map(str, e.absolute_path)) or '(top)'}: {e.message}" for e in VALIDATOR.iter_errors(doc)]


def conforming(path: Path) -> dict:
    """report.json at `path`, checked to be strict JSON that the schema accepts."""
    doc = strict_json(path)
    found = problems(doc)
    assert not found, f"{path} breaks report.schema.json:\n" + "\n".join(found[:20])
    return doc


def validated(tmp_path: Path, *argv: str) -> tuple[int, dict]:
    """`sim-origami validate ARGV --out tmp_path/out`: exit code and its report.json, held to the schema."""
    out = tmp_path / "out"
    code = main(["validate", *argv, "--out", str(out)])
    return code, conforming(out / "report.json")


def verdict(name: str = "B: closed-form closure residual", check: str = CLOSED_FORM_RESIDUAL) -> dict:
    return {"id": check, "branch": "B", "name": name, "measured": 1e-15, "tolerance": 1e-12, "passed": True,
            "detail": "", "compared": 400}


def provenance() -> dict:
    return {"sim_origami": "0.1.0", "git_commit": None, "mujoco": "4.0.1", "python": "3.11.7", "numpy": "2.4.6",
            "command": None, "date_utc": "2026-01-02T03:04:05+00:00", "preset": "fast",
            "machine": {"os": "Linux", "arch": "x86_64", "cores": 2}}


def minimal_report() -> dict:
    """The smallest completed report the schema takes: one branch, no events, no optional part."""
    point = {"input_rad": 0.5, "numeric": 1, "mujoco": 1, "truss": 1, "truss_self_stress": 0}
    branch = {"branch_requested": "B", "branch_followed": "B", "branch_flips": 0, "input_range_rad": [0.1, 2.9],
              "angle_error_max_rad": 1e-7, "angle_error_max_by_joint_rad": {"theta1": 0.0, "theta2": 1e-7},
              "closure_residual_max_m": 1e-7, "projection_angle_error_max_rad": 1e-13,
              "projection_closure_residual_max_m": None, "sweep_time_s": 4.0, "steps": 500,
              "step_cpu_time_s": 0.02, "events": [],
              "mobility": {"gruebler": -2, "idle_spins": 0, "inputs": 1, "start": point, "bifurcations": []},
              "verdicts": [verdict("B: MuJoCo fast path error (rad)", MUJOCO_PATH_ERROR)]}
    return {"sim_origami": "0.1.0", "scene": "bennett", "params": {"a": 1.0}, "adjustments": [], "notes": "",
            "preset": "fast",
            "stabilize": "none", "seed": "closed", "input": {"name": "theta1", "drive_joint": "theta1"},
            "joints": ["theta1", "theta2"], "angle_error_max_rad": 1e-7, "closure_residual_max_m": 1e-7,
            "branches": [branch], "events": [], "bifurcation_study": [], "free_run": None, "verdicts": [verdict()],
            "timings_s": {"closed_form_and_numeric_cpu_s": 0.4, "mujoco_step_cpu_s": 0.02, "mujoco_steps": 500.0,
                          "bifurcation_study_cpu_s": 0.0, "total_cpu_s": 0.6},
            "passed": True, "provenance": provenance()}


def minimal_failed_report() -> dict:
    """The smallest report of a run that stopped: before MuJoCo (with the trace's events) or as MuJoCo failed."""
    return {"scene": "fold-grid", "params": {"size_m": 1.4}, "preset": "fast", "passed": False, "notes": "",
            "verdicts": [verdict() | {"passed": False, "measured": None}], "provenance": provenance()}


# The schema itself, and what it must refuse ---------------------------------------------------------------------


def test_the_schema_is_a_draft_2020_12_schema_with_its_identity_and_version():
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    assert SCHEMA["$schema"] == "https://json-schema.org/draft/2020-12/schema"
    assert SCHEMA["$id"].endswith(SCHEMA["version"]) and SCHEMA["title"] == "sim_origami report.json"
    assert problems(minimal_report()) == [] and problems(minimal_failed_report()) == []


def guide_section() -> str:
    return GUIDE.read_text(encoding="utf-8").split("### report.json\n", 1)[1].split("\n## ", 1)[0]


def test_the_guide_states_the_schemas_place_and_version():
    section = guide_section()
    assert "`sim_origami/report.schema.json`" in section and f"version {SCHEMA['version']}" in section
    assert f"`$id` `{SCHEMA['$id']}`" in section


def test_the_schemas_presets_and_modes_are_the_codes():
    """A preset or stabilisation mode added to the code is added to the schema too."""
    assert SCHEMA["$defs"]["preset"]["enum"] == list(PRESET_NAMES)
    assert SCHEMA["$defs"]["completed_run"]["properties"]["stabilize"]["enum"] == list(MODES)


def broken(change) -> dict:
    doc = minimal_report()
    change(doc)
    return doc


@pytest.mark.parametrize(
    ("doc", "needle"),
    [
        (broken(lambda d: d.update(angle_eror_max_rad=d.pop("angle_error_max_rad"))),
         "'angle_error_max_rad' is a required property"),
        (broken(lambda d: d.update(angle_eror_max_rad=0.0)), "'angle_eror_max_rad' was unexpected"),
        (broken(lambda d: d["verdicts"][0].update(measured="1e-15")), "verdicts/0/measured: '1e-15' is not of type"),
        (broken(lambda d: d["branches"][0].update(steps=500.5)), "branches/0/steps: 500.5 is not of type 'integer'"),
        (broken(lambda d: d["branches"][0]["verdicts"][0].update(tolerence=1.0)), "'tolerence' was unexpected"),
        (broken(lambda d: d.update(passed="true")), "passed: 'true' is not of type 'boolean'"),
        (broken(lambda d: d["provenance"]["machine"].pop("cores")), "'cores' is a required property"),
        (broken(lambda d: d["timings_s"].update(render_cpu_s=1.0)), "'render_cpu_s' was unexpected"),
        (broken(lambda d: d.update(preset="fastest")), "preset: 'fastest' is not one of"),
        (broken(lambda d: d["verdicts"][0].pop("id")), "'id' is a required property"),
        (broken(lambda d: d["verdicts"][0].update(id="Swept range")), "verdicts/0/id: 'Swept range' does not match"),
        (broken(lambda d: d["events"].append({"kind": "lock", "input_rad": "pi", "branches": ["B"], "detail": ""})),
         "events/0/input_rad: 'pi' is not of type 'number'"),
        (minimal_failed_report() | {"passed": True}, "passed: False was expected"),
        (minimal_failed_report() | {"seed": "closed"}, "'seed' was unexpected"),
    ],
    ids=["misspelt-required", "unknown-key", "string-number", "fractional-count", "verdict-misspelt", "string-bool",
         "missing-nested", "unknown-timing", "unknown-preset", "verdict-without-id", "display-text-id",
         "string-event-input", "failed-passing",
         "failed-extra-key"],
)
def test_a_report_off_the_schema_is_refused_naming_where(doc, needle):
    found = problems(doc)
    assert any(needle in p for p in found), found


def test_non_finite_numbers_are_refused_as_json(tmp_path):
    """json.dumps writes NaN for a float NaN, which JSON has not: the reports' reader refuses it."""
    path = tmp_path / "report.json"
    path.write_text(json.dumps(minimal_report() | {"angle_error_max_rad": float("nan")}))
    with pytest.raises(AssertionError, match="NaN is no JSON number"):
        strict_json(path)


# Reports made by the command ------------------------------------------------------------------------------------
# Unmarked: the kinds the inner loop keeps (a registered scene, FOLD file with reference curves, linkage file, a run
# stopped before MuJoCo; 0.5 - 2.6 s each measured alone); the rest are marked slow.


@pytest.mark.slow
def test_a_closed_form_scenes_report_conforms_and_a_spoilt_copy_does_not(tmp_path):
    code, doc = validated(tmp_path, "bennett")
    assert code == 0 and doc["passed"] and "summary" in doc and "params_user" in doc
    assert doc["provenance"]["command"] is not None and "reference" not in doc and doc["free_run"] is None
    spoilt = copy.deepcopy(doc)
    spoilt["branches"][0]["angle_eror_max_rad"] = spoilt["branches"][0].pop("angle_error_max_rad")
    spoilt["verdicts"][0]["tolerance"] = str(spoilt["verdicts"][0]["tolerance"])
    found = problems(spoilt)
    assert any("'angle_error_max_rad' is a required property" in p for p in found), found
    assert any(p.startswith("verdicts/0/tolerance:") and "is not of type 'number'" in p for p in found), found
    # docs/guide.md's snippet, as printed, on this report and on the spoilt copy
    code = guide_section().split("```python\n", 1)[1].split("```", 1)[0]
    assert '"runs/bennett/report.json"' in code
    exec(code.replace('"runs/bennett/report.json"', repr(str(tmp_path / "out" / "report.json"))), {})
    (tmp_path / "spoilt.json").write_text(json.dumps(spoilt))
    with pytest.raises(jsonschema.ValidationError):
        exec(code.replace('"runs/bennett/report.json"', repr(str(tmp_path / "spoilt.json"))), {})


@pytest.mark.slow
def test_a_fold_files_report_with_reference_curves_conforms(tmp_path):
    code, doc = validated(tmp_path, "--fold", str(EXAMPLES / "reference" / "vertex4.fold"), "--reference",
                          str(EXAMPLES / "reference" / "vertex4_curves.csv"))
    assert code == 0 and doc["reference"]["compared_samples"] > 0 and "reference_cpu_s" in doc["timings_s"]
    assert all("along_path" in b["mobility"] for b in doc["branches"]) and "params_user" not in doc


@pytest.mark.slow
def test_a_linkage_files_report_conforms(tmp_path):
    code, doc = validated(tmp_path, "--linkage", str(EXAMPLES / "linkages" / "bennett.toml"))
    assert code == 0 and doc["passed"] and doc["adjustments"] == []


def test_a_run_stopped_before_mujoco_conforms_with_its_events(tmp_path):
    """A 4 x 4 Miura sheet with one vertex moved off the flat-foldable geometry: the trace stalls at its start,
    no MuJoCo run is made, exit 1 with report.json's shorter form (tests/test_fold_issue27.py)."""
    doc = miura_letters_only(4, 4)
    doc["vertices_coords"][6] = [doc["vertices_coords"][6][0] + 0.05, doc["vertices_coords"][6][1] + 0.03]
    code, report = validated(tmp_path, "--fold", str(write(tmp_path, "moved", doc)), "--preset", "fast")
    assert code == 1 and "branches" not in report and report["events"][0]["kind"] == "stall"


@pytest.mark.slow  # 7.6 s (each time measured alone on this 2-core machine; up to 2x with it shared)
def test_a_linkage_files_report_with_reference_curves_conforms(tmp_path):
    code, doc = validated(tmp_path, "--linkage", str(EXAMPLES / "linkages" / "rssr.json"), "--reference",
                          str(EXAMPLES / "linkages" / "rssr_curves.csv"))
    assert code == 0 and doc["reference"]["branches"] and doc["reference"]["worst"] is not None


@pytest.mark.slow  # 3.6 s
def test_a_report_with_adjusted_values_conforms(tmp_path):
    code, doc = validated(tmp_path, "--linkage", str(EXAMPLES / "linkages" / "bennett-typed.toml"))
    assert code == 0 and doc["adjustments"] and all(a["ratio"] <= 1.0 for a in doc["adjustments"])


@pytest.mark.slow  # 2.3 - 6.2 s each
@pytest.mark.parametrize(
    ("name", "shown"),
    [
        ("vertex4", lambda d: d["bifurcation_study"] and d["branches"][0]["mobility"]["bifurcations"]),
        ("bricard-threefold", lambda d: len(d["bifurcation_study"]) == 2),
        ("thick-vertex4", lambda d: "blockage" in d and d["events"][-1]["kind"] == "blockage"),
        ("iftomm-a04", lambda d: d["free_run"] is not None and "peer" in d["free_run"]),
        ("cuboctahedron", lambda d: "blockage" in d and d["branches"][0]["mobility"]["idle_spins"] >= 0),
        ("miura-sheet", lambda d: len(d["joints"]) > 4),
    ],
)
def test_registered_scenes_reports_conform(tmp_path, name, shown):
    """Scenes of different kinds, each with the part of the report it alone has."""
    code, doc = validated(tmp_path, name)
    assert code == 0 and doc["passed"] and shown(doc)


@pytest.mark.slow  # 3.0 s
def test_a_report_failing_its_checks_conforms(tmp_path):
    """Four mountains at -160 deg on a degree-4 vertex: MuJoCo runs, the folded state's check fails (exit 1)."""
    four = degree4_letters() | {"edges_assignment": ["M"] * 4 + ["B"] * 4, "edges_foldAngle": [-160.0] * 4 + [0] * 4}
    code, doc = validated(tmp_path, "--fold", str(write(tmp_path, "four", four)), "--preset", "fast")
    assert code == 1 and not doc["passed"] and doc["branches"]


@pytest.mark.slow  # 2.0 s
def test_a_run_mujoco_could_not_finish_conforms(tmp_path, capsys):
    """The 7 x 7 triangulated grid of tests/test_fold_gallery.py at 15 of its 55 freedoms, swept 100x too fast:
    MuJoCo warns (mjWARN_BADQACC), exit 1 with report.json's shorter form, no events."""
    from test_fold_gallery import GRID7_INPUTS, triangulated

    path = write(tmp_path, "grid", triangulated(7))
    parser = argparse.ArgumentParser()
    validate_command.add_args(parser)
    args = parser.parse_args(["--fold", str(path), "--preset", "fast", "--out", str(tmp_path / "out")])
    scene = fold_scene(path, GRID7_INPUTS.rsplit(",", 3)[0])
    scene = replace(scene, tuning=replace(scene.tuning, sweep_time_scale=0.01))
    assert validate_command.validate_scene(scene, args) == 1
    doc = conforming(tmp_path / "out" / "report.json")
    assert doc["verdicts"][-1]["id"] == validate_command.MUJOCO_RUN_FINISHED and "events" not in doc
    assert doc["provenance"]["command"] is None  # validate_scene called, not the command line


@pytest.mark.slow  # 2.9 s
def test_a_report_with_render_and_thumbnail_conforms(tmp_path):
    """--render adds `render`, --all each scene's `thumbnail` (run_one of one scene, as --all runs each)."""
    parser = argparse.ArgumentParser()
    validate_command.add_args(parser)
    args = parser.parse_args(["--all", "--render", "--size", "64x48"])
    validate_command.run_one(scenes.get("bennett").build(), args, tmp_path)
    doc = conforming(tmp_path / "report.json")
    assert doc["render"]["frames"] == 60 and doc["render"]["stills"] == 3 and doc["thumbnail"] == "thumb.png"


def test_the_json_writer_writes_non_finite_numbers_as_null_never_nan():
    """report.py wrote some numbers (a verdict's tolerance, an adjustment's ratio, free-run values) without `_num`:
    a non-finite one became NaN or Infinity, which is not JSON. The one writer (`report.json_text`) makes them null."""
    import numpy as np

    from sim_origami.report import json_text

    doc = {"a": float("nan"), "b": [np.float64(np.inf), 1.5, np.int64(3)], "c": {"d": np.array([1.0, -np.inf])}}
    text = json_text(doc)
    assert json.loads(text) == {"a": None, "b": [None, 1.5, 3], "c": {"d": [1.0, None]}}
    assert "NaN" not in text and "Infinity" not in text
