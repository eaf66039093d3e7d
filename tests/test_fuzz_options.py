"""
Property-based test of `validate`'s options together and of the output folder it is pointed at (issue 27, item 5):
random combinations of the options (valid, refused and alone without their companions) with random values, run in
process into a folder in one of the states a user leaves one in (absent, empty, a finished run, a run plus a file of
the user's, a file of the user's only, a damaged manifest).

Contract: exit 0, 1 or 2 only, within a time limit (no hang); on exit 2 exactly one stderr line and the folder as it
was; a folder never loses a file this tool did not write (with or without --force); on exit 0 or 1 a report.json
whose `passed` agrees with the exit code.

The default profile runs a fixed seed and a fixed example count (about a minute on 2 cores: most draws are refused at
parse, the rest are one cheap run each); SIM_ORIGAMI_FUZZ=big runs 5x as many.
"""

import contextlib
import hashlib
import io
import json
import os
import shutil
import signal
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim_origami.cli import main
from sim_origami.files import MANIFEST

REPO = Path(__file__).resolve().parents[1]
VERTEX4_FOLD = REPO / "docs" / "examples" / "reference" / "vertex4.fold"
VERTEX4_CURVES = REPO / "docs" / "examples" / "reference" / "vertex4_curves.csv"
EXAMPLES = 40 * (5 if os.environ.get("SIM_ORIGAMI_FUZZ") == "big" else 1)
# A run here takes 2-6 s of CPU; a draw that runs longer than this hangs.
LIMIT_S = 120
USER_FILE = "my_notes.txt"

# The sources: a registered scene on one branch (the cheapest real run), a FOLD file, a scene with reference curves.
SOURCES = {
    "scene": ["vertex4", "--branch", "odd2"],
    "fold": ["--fold", str(VERTEX4_FOLD)],
    "reference": ["vertex4", "--reference", str(VERTEX4_CURVES)],
}
# Options and the values drawn for them: valid ones, refused ones, and the empty string.
VALUES = {
    "--preset": ["fast", "stiff", "accurate", "fast-projected", "bogus", ""],
    "--seed": ["closed", "flat", "sideways"],
    "--branch": ["odd1", "odd2", "nosuch", ""],
    "--reference-units": ["deg", "rad", "furlong"],
    "--reference-tol": ["0.1", "0", "-1", "nan", "inf", "-inf", "abc", "1e400"],
    "--frames-tolerance": ["0.5", "-1", "nan", "inf", "x"],
    "--input": ["e1", "e0,e1", "e99", "", "e1,e1"],
    "--size": ["64x48", "0x0", "64", "abcxdef", "100000x100000"],
    "-p": ["alpha1=80", "nosuch=3", "alpha1=nan", "alpha1", "alpha1=1e400"],
}
FLAGS = ["--render", "--json", "--full-curves", "--force"]
STATES = ["absent", "empty", "finished run", "run and a user file", "user file only", "damaged manifest"]


def contents(folder: Path) -> dict[str, str]:
    """Every file under `folder` -> the sha256 of its bytes ({} when there is no folder)."""
    if not folder.is_dir():
        return {}
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def finished_run(tmp_path_factory) -> Path:
    """A finished real run's folder, copied into the states that hold one."""
    out = tmp_path_factory.mktemp("finished") / "run"
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["validate", *SOURCES["scene"], "--out", str(out)]) == 0
    return out


def prepare(out: Path, state: str, finished: Path) -> None:
    """Leave `out` in `state`."""
    if state == "absent":
        return
    if state in ("finished run", "run and a user file"):
        shutil.copytree(finished, out)
    else:
        out.mkdir(parents=True)
    if state in ("run and a user file", "user file only"):
        (out / USER_FILE).write_text("the user's notes")
    if state == "damaged manifest":
        (out / USER_FILE).write_text("the user's notes")
        (out / MANIFEST).write_text(json.dumps({"tool": "sim_origami", "files": USER_FILE}))


@st.composite
def command_lines(draw) -> tuple[list[str], str]:
    """A `validate` command line (without --out) and the folder state it runs into."""
    argv = ["validate", *SOURCES[draw(st.sampled_from(sorted(SOURCES)))]]
    for option in draw(st.lists(st.sampled_from(sorted(VALUES)), max_size=3, unique=True)):
        argv += [option, draw(st.sampled_from(VALUES[option]))]
    for flag in draw(st.lists(st.sampled_from(FLAGS), max_size=2, unique=True)):
        if flag != "--render" or "--size" in argv:  # frames only at a small size: a full render costs seconds
            argv.append(flag)
    return argv, draw(st.sampled_from(STATES))


class HangError(Exception):
    pass


def _alarm(signum, frame):
    raise HangError


@pytest.mark.slow
@settings(max_examples=EXAMPLES, derandomize=True, deadline=None, database=None, print_blob=False,
          suppress_health_check=list(HealthCheck))
@given(case=command_lines())
def test_option_combinations_into_any_folder_state_keep_the_contract(tmp_path_factory, finished_run, case):
    argv, state = case
    out = tmp_path_factory.mktemp("fuzz") / "run"
    prepare(out, state, finished_run)
    before = contents(out)
    user = {name: sha for name, sha in before.items() if name == USER_FILE}
    err = io.StringIO()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(LIMIT_S)
    try:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
            code = main([*argv, "--out", str(out)])
    except HangError:
        pytest.fail(f"no answer in {LIMIT_S} s: {argv} into {state}")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    after = contents(out)
    shown = f"{argv} into {state}: exit {code}, stderr {err.getvalue()!r}"
    assert code in (0, 1, 2), shown
    assert all(after.get(name) == sha for name, sha in user.items()), f"a user's file was lost: {shown}"
    if code == 2:
        lines = [line for line in err.getvalue().splitlines() if line.strip()]
        assert len(lines) == 1 and "Traceback" not in err.getvalue(), shown
        assert after == before, f"a refusal changed the folder: {shown}"
    else:
        report = json.loads((out / "report.json").read_text())
        assert report["passed"] == (code == 0), shown
