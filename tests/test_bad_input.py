"""
The bad-input contract, one test per reproduction of issue 16: a typed error in the API; on the command line one
line on stderr naming the value and the rule, exit 2, before any work; never NaN or inf in JSON; never a silent
override; output folders checked first and owned by one run; signals clean up and exit 130 / 143.
"""

import json
import os
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.files import LOCK, MANIFEST, STAGING, claimed_folder, write_text


def cli(capsys, *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    captured = capsys.readouterr()
    return code, captured.out, captured.err


def refused(capsys, *argv: str, naming: str) -> str:
    """Run argv; assert exit 2 with exactly one stderr line that names `naming`; return that line."""
    code, _, err = cli(capsys, *argv)
    lines = err.strip().splitlines()
    assert code == 2, err
    assert len(lines) == 1, err
    assert naming in lines[0], lines[0]
    assert "Traceback" not in err
    return lines[0]


def no_nonfinite_json(text: str) -> dict:
    def reject(name):
        raise AssertionError(f"non-finite JSON constant {name}")

    return json.loads(text, parse_constant=reject)


# Item 1: --out problems are refused before any work, in one line.


def test_out_that_is_a_file_is_refused_before_the_run(capsys, tmp_path):
    target = tmp_path / "report.txt"
    target.write_text("mine")
    refused(capsys, "validate", "bennett", "--out", str(target), naming=str(target))
    assert target.read_text() == "mine"


def test_out_under_a_file_is_refused(capsys, tmp_path):
    (tmp_path / "file").write_text("x")
    refused(capsys, "validate", "bennett", "--out", str(tmp_path / "file" / "run"), naming="is a file")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_out_in_a_read_only_folder_is_refused(capsys, tmp_path):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        refused(capsys, "validate", "bennett", "--out", str(locked / "a" / "b"), naming="not writable")
    finally:
        locked.chmod(0o700)
    assert not (locked / "a").exists()


def test_out_whose_folder_cannot_be_made_is_refused(capsys):
    # /proc takes no new folders, even for root (who passes every permission check).
    refused(capsys, "validate", "bennett", "--out", "/proc/sim-origami-run/x", naming="/proc/sim-origami-run")


def test_sweep_out_checked_before_the_grid_runs(capsys, tmp_path):
    (tmp_path / "f").write_text("x")
    refused(capsys, "sweep", "vertex4", "--grid", "alpha1=55:60:5", "--workers", "1", "--out", str(tmp_path / "f"),
            naming="is a file")


# Item 2 and 3: non-finite, overflowing or degenerate values are refused naming the parameter.


@pytest.mark.parametrize(
    "scene, param",
    [
        ("miura-sheet", "rows=-inf"), ("waterbomb-sheet", "rows=1e400"), ("waterbomb-tube", "n=1e400"),
        ("triangle-twist", "scheme=Infinity"), ("triangle-twist", "scheme=NaN"), ("waterbomb-twist", "m=NaN"),
        ("thick-square-twist", "pleat=1e-300"), ("thick-vertex5", "length=0"), ("square-twist", "side=Infinity"),
        ("thick-square-twist", "pleat=1e308"), ("waterbomb-thick", "mu=inf"), ("thick-vertex5", "length=1e-9"),
        ("myard", "a23=Infinity"), ("triangle-twist", "pleat=1e400"), ("corrugated-unit", "L1=1e+308"),
        ("square-twist", "side=inf"), ("waterbomb-sheet", "rows=720"), ("waterbomb-tube", "n=1e308"),
        ("miura", "thickness=-0.01"), ("vertex4", "length=-1"), ("bennett", "alpha=180"), ("bricard-threefold",
        "alpha=360"), ("kokotsakis", "case=2.5"),
    ],
)
def test_bad_values_are_refused_naming_the_parameter(capsys, scene, param):
    name = param.split("=")[0]
    refused(capsys, "analytic", scene, "-p", param, "--input=10", "--json", naming=name)


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -float("inf"), 1e308, "ten", None, True])
def test_api_refuses_non_numbers_and_non_finite_values_with_parameter_error(value):
    with pytest.raises(ParameterError, match="alpha1"):
        scenes.get("vertex4").build_from_user({"alpha1": value})
    with pytest.raises(ParameterError, match="alpha1"):
        scenes.get("vertex4").build(alpha1=value)


def test_waterbomb_thick_with_a_tiny_alpha_is_refused_by_its_range(capsys):
    with pytest.raises(ParameterError, match="alpha"):
        scenes.get("waterbomb-thick").build(alpha=1e-300)


def test_every_scene_states_its_limits_in_describe(capsys):
    code, out, _ = cli(capsys, "describe", "waterbomb-tube")
    assert code == 0 and "a whole number from 3 to 24" not in out  # describe lists values; refusals state the rule
    line = refused(capsys, "describe", "waterbomb-tube", "-p", "n=20", "-p", "m=11", naming="at most 120")
    assert "n = 20" in line


# Item 4: a preset never replaces a value the user gave.


def test_bricard_plane_geometry_without_case_is_the_users():
    kind = scenes.get("bricard-plane")
    assert kind.build().params["case"] == 10
    own = kind.build_from_user({"a": 2.0000001})  # off case 10's a = 2 m: the user's linkage, not case 10
    assert own.params["case"] == 0 and own.kinematics.geometry.a == 2.0000001
    # every parameter listed with its default (case 10's geometry) conflicts with nothing
    assert kind.build_from_user({p.name: p.default for p in kind.params}).params["case"] == 10


def test_bricard_plane_geometry_with_a_case_is_refused_naming_it(capsys):
    refused(capsys, "describe", "bricard-plane", "-p", "b=1.5", "-p", "case=9", naming="b is given with case = 9")


def test_bricard_plane_user_geometry_that_cannot_move_names_its_values(capsys):
    line = refused(capsys, "describe", "bricard-plane", "-p", "a=2.5", naming="a = 2.5")
    assert "case 10" not in line


# Item 5: evaluate's validity mask is the domain describe prints.


def test_bricard_plane_outside_its_domain_is_null(capsys):
    code, out, _ = cli(capsys, "analytic", "bricard-plane", "--input=-1e10", "--json")
    assert code == 0
    doc = no_nonfinite_json(out)
    assert all(v == [None] for b in doc["branches"] for v in b["joints"].values())


@pytest.mark.parametrize("scene, params", [("thick-vertex4", {"alpha2": 46.0, "b": 0.025}),
                                           ("kokotsakis", {"case": 2.0})])
def test_domain_ends_are_valid_and_close_the_loop(scene, params):
    kin = scenes.get(scene).build_from_user(params).kinematics
    loops = kin.loop_system()
    for b in kin.branches():
        lo, hi = b.domain
        x = np.array([lo, lo + 1e-9, 0.5 * (lo + hi), hi - 1e-9, hi, np.nextafter(lo, -4), np.nextafter(hi, 4)])
        values, valid = kin.evaluate(b.name, x)
        assert valid.tolist() == [True] * 5 + [False] * 2, b.name
        # At a lock the roots' discriminant vanishes: rounding of 1e-16 becomes sqrt(1e-16) there (7.8e-8 measured).
        assert np.max(loops.residual_norm(kin.loop_angles(values[:5]))) < 1e-6


# Items 6 and 7: tolerances relative to the model's size.


def test_numeric_solve_of_a_10_km_bricard_closes_like_a_1_m_one():
    from sim_origami.validation import closed_form_verdicts

    for a in (1.0, 10000.0):
        scene = scenes.get("bricard-threefold").build(a=a)
        branch = scene.kinematics.branches()[0].name
        verdicts = closed_form_verdicts(scene, branch, np.linspace(*scene.branch_path(branch), 20))
        assert all(v.passed for v in verdicts), (a, verdicts)


def test_length_scale_is_the_largest_body_dimension():
    assert scenes.get("bennett").build().length_scale == pytest.approx(1.5, rel=0.1)
    assert scenes.get("bennett").build(a=1000.0, b=1500.0, beta=np.arcsin(0.75)).length_scale == pytest.approx(
        1500.0, rel=0.1
    )


@pytest.mark.slow
def test_validate_a_1500_m_bennett_passes_like_a_1_m_one(capsys, tmp_path):
    code, out, _ = cli(capsys, "validate", "bennett", "-p", "a=1000", "-p", "b=1500", "--preset", "fast",
                         "--out", str(tmp_path / "big"), "--json")
    doc = json.loads(out)
    assert code == 0, [v for v in doc["verdicts"] + [v for b in doc["branches"] for v in b["verdicts"]]
                       if not v["passed"]]


# Item 8: sweep grids refused in one line before any work.


def _closed_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize(
    "extra, naming",
    [
        (["--grid", "alpha1=20:70:1e-9"], "at most 10000"), (["--grid", "alpha1=0:inf:1"], "finite"),
        (["--grid", "alpha1=inf:inf:1"], "finite"), (["--grid", "alpha1=50:60:5", "--grid", "alpha1=50:60:5"], "twice"),
        (["--grid", "alpha1=50:60:5", "--workers", "-1"], "--workers -1"),
        (["--grid", "alpha1=50:60:5", "--workers", "0"], "--workers 0"),
        (["--grid", "alpha1=50:60:5", "--scheduler", "not a url"], "--scheduler"),
        (["--grid", "alpha1=170:200:10"], "alpha1"),
        (["--grid", "alpha1=1:100:1", "--grid", "alpha2=1:100:1", "--grid", "alpha3=1:10:1"], "at most 10000"),
    ],
)
def test_bad_sweep_grids_are_refused_before_any_work(capsys, tmp_path, extra, naming):
    refused(capsys, "sweep", "vertex4", *extra, "--out", str(tmp_path / "s"), naming=naming)
    assert not (tmp_path / "s" / "sweep.csv").exists()


def test_unreachable_scheduler_is_refused_in_one_line(capsys, tmp_path):
    address = f"tcp://127.0.0.1:{_closed_port()}"
    refused(capsys, "sweep", "vertex4", "--grid", "alpha1=50:60:5", "--scheduler", address,
            "--out", str(tmp_path / "s"), naming=address)


# Item 9: the largest sizes are stated and enforced up front.


@pytest.mark.parametrize(
    "scene, param, limit",
    [("waterbomb-sheet", "rows=720", "16"), ("waterbomb-tube", "n=1e308", "24"), ("miura-sheet", "cols=33", "32"),
     ("corrugated-sheet", "rows=17", "16")],
)
def test_sizes_beyond_the_stated_limit_are_refused(capsys, scene, param, limit):
    line = refused(capsys, "analytic", scene, "-p", param, "--input=10", naming=param.split("=")[0])
    assert f"to {limit}" in line and "at most" in line


# Item 10: a run owns its output folder; signals clean up.


def test_a_second_run_removes_what_the_first_wrote_and_nothing_else(tmp_path):
    out = tmp_path / "run"
    with claimed_folder(out) as stage:
        write_text(stage / "report.json", "{}")
        write_text(stage / "frames" / "frame_0000.png", "png")
    assert sorted(json.loads((out / MANIFEST).read_text())["files"]) == ["frames/frame_0000.png", "report.json"]
    assert not (out / LOCK).exists()
    with claimed_folder(out) as stage:
        assert (out / "frames").exists() and (out / "report.json").exists()  # until the new run finishes
        write_text(stage / "report.json", "{}")
    assert not (out / "frames").exists()
    assert json.loads((out / MANIFEST).read_text())["files"] == ["report.json"]


def test_a_folder_with_foreign_files_is_refused_without_force(tmp_path):
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("keep")
    with pytest.raises(ParameterError, match=r"notes\.txt"):
        with claimed_folder(out):
            pass
    with claimed_folder(out, force=True):
        write_text(out / "report.json", "{}")
    with claimed_folder(out, force=True):
        pass
    assert (out / "notes.txt").read_text() == "keep" and not (out / "report.json").exists()


def test_two_runs_into_one_folder_do_not_mix(tmp_path):
    out = tmp_path / "shared"
    with claimed_folder(out):
        with pytest.raises(ParameterError, match="another run"):
            with claimed_folder(out):
                pass
    # A lock left by a process that died is taken over.
    (out / LOCK).write_text("999999999")
    with claimed_folder(out):
        pass


def test_validate_refuses_a_folder_it_did_not_write(capsys, tmp_path):
    (tmp_path / "data.csv").write_text("x")
    refused(capsys, "validate", "vertex4", "--out", str(tmp_path), naming="--force")


def _render_run(tmp_path: Path, sig: int) -> tuple[subprocess.CompletedProcess, Path]:
    out = tmp_path / "render"
    argv = [str(Path(sys.executable).parent / "sim-origami"), "validate", "vertex4", "--branch", "odd2", "--render",
            "--out", str(out)]
    proc = subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=tmp_path)
    frames = out / STAGING / "frames"
    for _ in range(6000):  # wait (up to 10 min, never asserted) until frames are being written
        if (frames.exists() and len(list(frames.iterdir())) >= 3) or proc.poll() is not None:
            break
        time.sleep(0.1)
    proc.send_signal(sig)
    stdout, stderr = proc.communicate(timeout=600)
    return subprocess.CompletedProcess(argv, proc.returncode, stdout, stderr), out


@pytest.mark.slow
@pytest.mark.parametrize("sig, code, name", [(signal.SIGTERM, 143, "SIGTERM"), (signal.SIGINT, 130, "SIGINT")])
def test_a_signal_during_render_cleans_up_and_exits_in_one_line(tmp_path, sig, code, name):
    done, out = _render_run(tmp_path, sig)
    assert done.returncode == code, done.stderr
    lines = [ln for ln in done.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and name in lines[0], done.stderr
    # the run's files, staged, are removed with the folder it made: nothing is left half-written
    assert not out.exists(), sorted(p.name for p in out.rglob("*"))


# Item 11: the command line.


def test_negative_input_after_a_space_is_a_value(capsys):
    code, out, _ = cli(capsys, "analytic", "vertex4", "--input", "-30,10", "--json")
    assert code == 0
    assert no_nonfinite_json(out)["input"]["values"] == pytest.approx(np.deg2rad([-30, 10]).tolist())


@pytest.mark.slow
def test_negative_values_work_for_other_options(capsys):
    code, out, _ = cli(capsys, "describe", "truncated-tetrahedron-i", "-p", "delta=-2")
    assert code == 0 and "delta      = -2" in out


@pytest.mark.parametrize("scene", ["truncated-tetrahedron-i", "truncated-tetrahedron-ii"])
def test_a_delta_whose_path_misses_the_fold_names_delta(capsys, scene):
    """delta = 89.999 deg (inside the declared range) sends the path to the Bricard's fold B = D = F: it exited 2 with
    "the closure did not converge ... (residual 1.33e-14 m)", naming no parameter; now the rule and its limits."""
    line = refused(capsys, "describe", scene, "-p", "delta=89.999", naming="delta")
    assert "B = D = F" in line and "(measured)" in line


def test_the_same_parameter_twice_is_refused(capsys):
    refused(capsys, "describe", "bennett", "-p", "a=1", "-p", "a=2", naming="a is given twice")


@pytest.mark.parametrize("text", ["1_0", "0x10", "inf", "nan", "1e400", "ten", ""])
def test_only_plain_decimal_numbers(capsys, text):
    refused(capsys, "describe", "miura-sheet", "-p", f"rows={text}", naming="rows")


def test_a_refusal_carries_no_warning_lines(capsys):
    # Sector angles that sum to 360 only after rounding: numpy warns deep inside before the refusal.
    refused(capsys, "analytic", "vertex4", "-p", "alpha1=179.9999999", "-p", "alpha2=0.0000001", "--input=10",
            naming="alpha")
