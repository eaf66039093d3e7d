"""
Output folders (issue 27, "files lost"): a refused, failed or interrupted run leaves the previous results whole; only
files a valid manifest lists, unchanged and inside the folder, are ever removed; a damaged manifest is a one-line
refusal; every refusal comes before the folder is claimed and leaves no manifest behind.
"""

import hashlib
import json
import os
import shutil
from pathlib import Path

import pytest

from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.files import LOCK, MANIFEST, claimed_folder, write_text

REPO = Path(__file__).resolve().parents[1]
VERTEX4_FOLD = REPO / "docs" / "examples" / "reference" / "vertex4.fold"
RSSR = REPO / "docs" / "examples" / "linkages" / "rssr.json"
# The cheapest real run: vertex4 on one branch (about 2 s).
RUN = ("validate", "vertex4", "--branch", "odd2")


def cli(capsys, *argv: str) -> tuple[int, str]:
    """Run the command line in this process; returns its exit status and its stderr."""
    code = main(list(argv))
    return code, capsys.readouterr().err


def refused_in_one_line(capsys, *argv: str, naming: str) -> str:
    code, err = cli(capsys, *argv)
    lines = err.strip().splitlines()
    assert code == 2 and len(lines) == 1 and naming in lines[0], err
    return lines[0]


def contents(folder: Path) -> dict[str, str]:
    """Every file under `folder` (hidden ones included) -> the sha256 of its bytes."""
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def previous_run(tmp_path_factory) -> Path:
    """A finished real run's output folder, copied by the tests that need one."""
    out = tmp_path_factory.mktemp("previous") / "run"
    assert main([*RUN, "--out", str(out)]) == 0
    return out


def earlier_run(out: Path) -> dict[str, str]:
    """A previous run's files written through the output folder's API (report.json and a frame); their contents."""
    with claimed_folder(out):
        write_text(out / "report.json", '{"passed": true}\n')
        write_text(out / "frames" / "frame_0000.png", "png")
    return contents(out)


@pytest.mark.slow
def test_a_refused_run_leaves_the_previous_results_whole(capsys, tmp_path, previous_run):
    """A run into a folder holding the last run's results plus one file of the user's was refused after deleting
    the report, curves, model and page."""
    out = tmp_path / "run"
    shutil.copytree(previous_run, out)
    (out / "notes.txt").write_text("mine")
    before = contents(out)
    assert {"report.json", "curves.csv", "model.xml", "report.html", MANIFEST} <= set(before)
    refused_in_one_line(capsys, *RUN, "--out", str(out), naming="notes.txt")
    assert contents(out) == before


@pytest.mark.slow
def test_a_finished_run_replaces_the_previous_one(capsys, tmp_path, previous_run):
    out = tmp_path / "run"
    shutil.copytree(previous_run, out)
    assert main(["validate", "vertex4", "--branch", "odd1", "--out", str(out)]) == 0
    assert json.loads((out / "report.json").read_text())["branches"][0]["branch_requested"] == "odd1"
    manifest = json.loads((out / MANIFEST).read_text())
    assert sorted(p.name for p in out.iterdir()) == sorted([MANIFEST, *manifest["files"]])
    assert all(hashlib.sha256((out / n).read_bytes()).hexdigest() == h for n, h in manifest["sha256"].items())


DAMAGED = {
    "files a string": {"tool": "sim_origami", "files": "ab"},
    "numbers and null": {"tool": "sim_origami", "version": 2, "files": [1, None], "sha256": {}},
    "a parent path": {"tool": "sim_origami", "version": 2, "files": ["../a"], "sha256": {"../a": "0" * 64}},
    "an absolute path": {"tool": "sim_origami", "version": 2, "files": ["/a"], "sha256": {"/a": "0" * 64}},
    "no hashes (an earlier version)": {"tool": "sim_origami", "pid": 1, "files": ["a", "b"]},
}


@pytest.mark.parametrize("doc", DAMAGED.values(), ids=DAMAGED.keys())
def test_a_damaged_manifest_is_refused_and_removes_nothing(capsys, tmp_path, doc):
    """A manifest whose `files` was the string "ab" made the run delete the user's files a and b."""
    out = tmp_path / "run"
    out.mkdir()
    for name in "ab":
        (out / name).write_text(f"the user's {name}")
    (out / MANIFEST).write_text(json.dumps(doc))
    before = contents(out)
    refused_in_one_line(capsys, *RUN, "--out", str(out), "--force", naming=MANIFEST)
    assert contents(out) == before
    assert not (out / LOCK).exists()


def test_a_folder_in_the_manifest_s_place_is_refused_in_one_line(capsys, tmp_path):
    """It was an internal error (exit 3)."""
    out = tmp_path / "run"
    (out / MANIFEST).mkdir(parents=True)
    (out / "a").write_text("the user's a")
    refused_in_one_line(capsys, *RUN, "--out", str(out), "--force", naming=MANIFEST)
    assert (out / "a").read_text() == "the user's a" and (out / MANIFEST).is_dir()


def test_a_changed_file_is_never_removed(tmp_path):
    """A file the user changed since a run wrote it refuses the next run; with --force it is left where it is."""
    out = tmp_path / "run"
    earlier_run(out)
    (out / "report.json").write_text('{"passed": true, "my note": 1}\n')
    with pytest.raises(ParameterError, match=r"report\.json \(changed since this tool wrote it\)"):
        with claimed_folder(out):
            pass
    assert (out / "frames" / "frame_0000.png").exists()
    with claimed_folder(out, force=True):
        pass
    assert (out / "report.json").read_text() == '{"passed": true, "my note": 1}\n'
    assert not (out / "frames").exists()  # the unchanged frame was the earlier run's


def test_a_file_of_the_user_s_in_a_run_s_folder_is_named_and_kept(tmp_path):
    out = tmp_path / "run"
    before = earlier_run(out)
    (out / "frames" / "mine.png").write_text("my annotated frame")
    with pytest.raises(ParameterError, match=r"frames/mine\.png"):
        with claimed_folder(out):
            pass
    assert contents(out) == before | {"frames/mine.png": hashlib.sha256(b"my annotated frame").hexdigest()}
    with claimed_folder(out, force=True):
        pass
    assert sorted(contents(out)) == [MANIFEST, "frames/mine.png"]


def test_a_listed_link_is_not_followed(tmp_path):
    """A listed name that is now a link, even to a file with the listed content, is not the tool's file."""
    out = tmp_path / "run"
    earlier_run(out)
    (out / "data.csv").write_text('{"passed": true}\n')  # the user's file, with the report's content
    (out / "report.json").unlink()
    (out / "report.json").symlink_to(out / "data.csv")
    with claimed_folder(out, force=True):
        pass
    assert (out / "data.csv").read_text() == '{"passed": true}\n' and (out / "report.json").is_symlink()
    assert not (out / "frames").exists()  # the earlier run's frame, unchanged, is removed


def test_an_interrupted_run_leaves_the_previous_results_whole(tmp_path):
    out = tmp_path / "run"
    before = earlier_run(out)
    with pytest.raises(KeyboardInterrupt):
        with claimed_folder(out) as stage:
            write_text(stage / "report.json", "half a new report")
            raise KeyboardInterrupt
    assert contents(out) == before


def test_nested_run_folders_are_claimed_and_swapped_together(tmp_path):
    """validate --all's layout: a summary beside one run folder per scene, each with its own manifest."""
    out = tmp_path / "runs"
    for again in (False, True):  # the second run replaces the first, without calling its folders foreign
        with claimed_folder(out) as stage, claimed_folder(out / "vertex4") as scene:
            write_text(scene / "report.json", "{}")
            write_text(stage / "index.html", "<p>index</p>")
            assert (out / "index.html").exists() == (out / "vertex4" / "report.json").exists() == again
    assert json.loads((out / MANIFEST).read_text())["files"] == ["index.html"]
    assert json.loads((out / "vertex4" / MANIFEST).read_text())["files"] == ["report.json"]


SWEEP = ["sweep", "vertex4", "--grid", "alpha1=55:60:5", "--workers", "1"]
REFUSED_AFTER_CLAIM = [
    pytest.param(["validate", "vertex4", "--branch", "nosuch"], "nosuch", id="unknown branch"),
    pytest.param(
        ["validate", "--fold", str(VERTEX4_FOLD), "--seed", "flat"],
        "--seed flat",
        id="flat start on a FOLD file",
        marks=pytest.mark.slow,
    ),
    pytest.param([*SWEEP, "--scheduler", "tcp://127.0.0.1:9"], "--scheduler", id="unreachable scheduler"),
]


@pytest.mark.parametrize("argv, naming", REFUSED_AFTER_CLAIM)
def test_a_refusal_comes_before_the_folder_is_claimed(capsys, tmp_path, argv, naming):
    """These refusals came after the folder was claimed and left an empty manifest behind."""
    out = tmp_path / "run"
    refused_in_one_line(capsys, *argv, "--out", str(out), naming=naming)
    assert not out.exists()


@pytest.mark.slow
def test_a_refusal_during_the_run_leaves_no_manifest(capsys, tmp_path):
    """A linkage whose anchor (1e-300) is refused only when its truss is built, seconds into the run."""
    doc = json.loads(RSSR.read_text())
    doc["anchor"] = 1e-300
    path = tmp_path / "anchor.json"
    path.write_text(json.dumps(doc))
    out = tmp_path / "run"
    refused_in_one_line(capsys, "validate", "--linkage", str(path), "--out", str(out), naming="anchor")
    assert not out.exists()


def test_an_out_name_too_long_for_the_file_system_is_refused(capsys, tmp_path):
    refused_in_one_line(capsys, *RUN, "--out", str(tmp_path / ("x" * (os.pathconf(tmp_path, "PC_NAME_MAX") + 1))),
                        naming="too long")


def test_an_empty_out_is_refused(capsys, tmp_path):
    """--out '' wrote into the current folder."""
    refused_in_one_line(capsys, *RUN, "--out", "", naming="--out")
    refused_in_one_line(capsys, *SWEEP, "--out", "", naming="--out")
    assert list(tmp_path.iterdir()) == []
