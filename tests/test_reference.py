"""User reference curves (`--reference`): reading, the verdict against the numeric loop solve, and the CLI.

The Miura reference is written here from Kamrava et al. 2021's formulas for the spinal crease a (eqns 17-28,
K3 with squares) and its projection angles phi = atan2(a_z, a_x), psi = atan2(a_y, a_x), with rho_c = 2 theta:
none of the package's code is used to make it.
"""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.reference import (
    REFERENCE_BRANCH_JUMPS,
    REFERENCE_OUTSIDE_DOMAINS,
    REFERENCE_OVER_TOLERANCE,
    compare_reference,
    read_reference,
)
from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.precision import half_unit

HEADER = "theta[deg],phi[deg],psi[deg],rho_c[deg]"


def kamrava(theta_deg: np.ndarray, alpha1: float = 30.0, alpha2: float = 60.0) -> np.ndarray:
    """(n, 4) theta, phi, psi, rho_c in degrees on the Miura branch of the 30/60 vertex."""
    a1, a2 = np.deg2rad(alpha1), np.deg2rad(alpha2)
    k1 = 0.5 * (1 / np.tan(a1) + 1 / np.tan(a2))
    k2 = 0.5 * (1 / np.tan(a1) - 1 / np.tan(a2))
    t = np.deg2rad(theta_deg)
    k3 = (k2 / np.cos(t)) ** 2 + (k1 / np.sin(t)) ** 2
    f = np.stack([k3 - 1, 2 * k2 / np.cos(t), 2 * k1 / np.sin(t)], -1)
    return np.rad2deg(np.column_stack([t, np.arctan2(f[:, 2], f[:, 0]), np.arctan2(f[:, 1], f[:, 0]), 2 * t]))


def write_csv(path, rows: np.ndarray, header: str = HEADER, digits: int = 10) -> str:
    body = "\n".join(",".join(f"{v:.{digits}f}" for v in row) for row in rows)
    path.write_text(f"# Kamrava et al. 2021, 30/60 vertex\n{header}\n{body}\n")
    return str(path)


@pytest.fixture(scope="module")
def miura():
    return scenes.get("miura").build()


# Through the flat bifurcation at theta = 0 (left out: there phi, psi are 0/0 in the printed formula).
THETA = np.array([t for t in np.arange(-50.0, 50.1, 2.5) if t != 0.0])


def check(tmp_path, miura, rows, **kw):
    ref = read_reference(write_csv(tmp_path / "ref.csv", rows), miura.kinematics, **kw)
    return compare_reference(ref, miura)


def _by_id(result, check: str):
    """The result's one check of kind `check` (its `Verdict.id`)."""
    (verdict,) = [v for v in result.verdicts if v.id == check]
    return verdict


def test_half_unit_of_printed_numbers():
    assert half_unit("30") == 0.5
    assert half_unit("12.50") == pytest.approx(0.005)
    assert half_unit("1.5e-3") == pytest.approx(5e-5)
    assert half_unit("-2.0E+2") == pytest.approx(5.0)


def test_correct_reference_passes_through_the_bifurcation(tmp_path, miura):
    result = check(tmp_path, miura, kamrava(THETA))
    doc = result.doc
    assert all(v.passed for v in result.verdicts), [v.detail for v in result.verdicts]
    assert [s["branch"] for s in doc["branches"]] == ["miura"]  # followed across theta = 0, not switched
    assert doc["compared_samples"] == len(THETA)
    assert doc["reference_vs_numeric_max_rad"] < 1e-11  # 10 printed decimals of a degree: 8.7e-13 rad
    assert doc["kinematics_vs_numeric_max_rad"] < 1e-12


def test_a_sample_at_the_bifurcation_itself(tmp_path, miura):
    """Samples symmetric about the flat state, one of them at it: the numeric solve starts away from the bifurcation
    (where its first step could take either branch) and is allowed SINGULAR_RAD there, where it converges only to
    about the square root of its residual (measured 4.5e-7 rad); 1e-3 rad off there still fails."""
    x = np.arange(-20.0, 20.1, 5.0)
    rows = np.column_stack([x, np.rad2deg(miura.kinematics.joint_angles("miura", np.deg2rad(x)))])
    header = "theta[deg],phi[deg],psi[deg],rho_a[deg],rho_b[deg],rho_c[deg],rho_d[deg]"
    result = compare_reference(read_reference(write_csv(tmp_path / "a.csv", rows, header), miura.kinematics), miura)
    assert all(v.passed for v in result.verdicts) and result.doc["singular_samples"] == [7]  # theta = 0
    assert [s["branch"] for s in result.doc["branches"]] == ["miura"]
    rows[4, 3] += np.rad2deg(1e-3)
    result = compare_reference(read_reference(write_csv(tmp_path / "b.csv", rows, header), miura.kinematics), miura)
    assert not _by_id(result, REFERENCE_OVER_TOLERANCE).passed and result.doc["worst"]["line"] == 7


def test_sign_error_fails(tmp_path, miura):
    rows = kamrava(THETA)
    rows[:, 2] *= -1  # psi with the wrong sign
    result = check(tmp_path, miura, rows)
    assert not _by_id(result, REFERENCE_OVER_TOLERANCE).passed
    assert result.doc["over_tolerance"]["samples"] == len(THETA)
    assert result.doc["reference_vs_numeric_max_rad"] > 0.1


def test_small_perturbation_fails_naming_the_worst_sample(tmp_path, miura):
    rows = kamrava(THETA)
    k = 30
    rows[k, 2] += np.rad2deg(1e-3)
    result = check(tmp_path, miura, rows)
    verdict = _by_id(result, REFERENCE_OVER_TOLERANCE)
    assert not verdict.passed and verdict.measured == 1.0
    worst = result.doc["worst"]
    assert worst["joint"] == "psi" and worst["line"] == k + 3  # comment, header, then the samples
    assert worst["input_as_written"] == pytest.approx(THETA[k])
    assert worst["error_rad"] == pytest.approx(1e-3, rel=1e-6)
    assert f"line {k + 3}" in verdict.detail and "psi" in verdict.detail
    assert result.doc["disagreeing"] == [worst]


def test_a_looser_given_tolerance_lets_the_perturbation_pass(tmp_path, miura):
    rows = kamrava(THETA)
    rows[30, 2] += np.rad2deg(1e-3)
    assert _by_id(check(tmp_path, miura, rows, tol=2e-3), REFERENCE_OVER_TOLERANCE).passed
    assert not _by_id(check(tmp_path, miura, rows, tol=5e-4), REFERENCE_OVER_TOLERANCE).passed


def test_samples_outside_every_branch_are_reported(tmp_path, miura):
    rows = kamrava(np.array([20.0, 30.0, 40.0]))
    rows = np.vstack([rows, [95.0, 0.0, 0.0, 190.0]])  # beyond both the miura (54.7) and straight (90) locks
    result = check(tmp_path, miura, rows)
    assert result.doc["outside_every_branch"] == [{"line": 6, "input_rad": pytest.approx(np.deg2rad(95.0))}]
    assert _by_id(result, REFERENCE_OVER_TOLERANCE).passed and not _by_id(result, REFERENCE_OUTSIDE_DOMAINS).passed


def test_decreasing_inputs_in_radians_from_the_option(tmp_path, miura):
    rows = np.deg2rad(kamrava(THETA))[::-1]
    path = write_csv(tmp_path / "rad.csv", rows, header="theta,phi,psi,rho_c", digits=12)
    result = compare_reference(read_reference(path, miura.kinematics, units="rad"), miura)
    assert all(v.passed for v in result.verdicts)


GOOD = f"{HEADER}\n10,1,2,20\n20,2,3,40\n"


@pytest.mark.parametrize(
    ("text", "kw", "needle"),
    [
        (None, {}, "no such file"),
        (b"\x89PNG\r\n\x1a\n\xff\xfe", {}, "not a text CSV"),
        ("theta phi psi\n1 2 3\n2 3 4\n", {}, "not a CSV header"),
        ("theta[deg],rho_q[deg]\n1,2\n2,3\n", {}, "unknown column 'rho_q'"),
        ("phi[deg],psi[deg]\n1,2\n2,3\n", {}, "no input column 'theta'"),
        ("theta[deg],phi[deg],phi[deg]\n1,2,3\n2,3,4\n", {}, "'phi' appears twice"),
        ("theta,phi\n1,2\n2,3\n", {}, "states no unit"),
        ("theta[grad],phi[deg]\n1,2\n2,3\n", {}, "unit [grad]"),
        ("theta[rad],phi[rad]\n1,2\n2,3\n", {"units": "deg"}, "states [rad] but the units given are deg"),
        ("theta,phi\n1,2\n2,3\n", {"units": "turns"}, "units 'turns' are unknown"),
        (f"{HEADER}\n10,1,x,20\n20,2,3,40\n", {}, "line 2, column psi: 'x' is not a number"),
        (f"{HEADER}\n10,1,nan,20\n20,2,3,40\n", {}, "line 2, column psi: nan is not a finite"),
        (f"{HEADER}\n10,1,2,20\n20,inf,3,40\n", {}, "line 3, column phi: inf is not a finite"),
        (f"{HEADER}\n10,1,2,20\n20,2,3\n", {}, "line 3 has 3 values"),
        (f"{HEADER}\n10,1,2,20\n20,2,3,40\n15,2,3,30\n", {}, "line 4: theta does not increase"),
        (f"{HEADER}\n10,1,2,20\n", {}, "1 sample(s); a curve needs at least 2"),
        ("# only a comment\n", {}, "no header and no samples"),
        ("theta[deg]\n1\n2\n", {}, "not a CSV header"),
        (GOOD, {"tol": 0.0}, "tolerance 0.0 rad; it must be a finite number > 0"),
    ],
)
def test_bad_reference_names_the_field(tmp_path, miura, text, kw, needle):
    path = tmp_path / "ref.csv"
    if isinstance(text, bytes):
        path.write_bytes(text)
    elif text is not None:
        path.write_text(text)
    with pytest.raises(ParameterError, match=None) as err:
        read_reference(path, miura.kinematics, **kw)
    assert needle in str(err.value)


def test_cli_bad_reference_exits_2_before_simulating(tmp_path, capsys):
    path = tmp_path / "ref.csv"
    path.write_text(f"{HEADER}\n10,1,2,20\n20,2,3,40\n15,2,3,30\n")
    out = tmp_path / "run"
    code = main(["validate", "miura", "--reference", str(path), "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1 and "does not increase" in err
    assert not out.exists()  # refused before MuJoCo ran or anything was written
    assert main(["validate", "miura", "--reference-tol", "0.1"]) == 2
    assert main(["validate", "--all", "--reference", str(path)]) == 2


@pytest.mark.slow
def test_cli_reference_verdicts_in_report_and_printout(tmp_path, capsys):
    good = write_csv(tmp_path / "good.csv", kamrava(THETA))
    rows = kamrava(THETA)
    rows[30, 2] += np.rad2deg(1e-3)
    bad = write_csv(tmp_path / "bad.csv", rows)
    assert main(["validate", "miura", "--branch", "miura", "--reference", good, "--out", str(tmp_path / "a")]) == 0
    doc = json.loads((tmp_path / "a" / "report.json").read_text())["reference"]
    assert doc["over_tolerance"]["samples"] == 0 and doc["mujoco_samples"] > 5
    assert doc["numeric_vs_mujoco_max_rad"] < 1e-6  # MuJoCo fast at the reference's inputs in its range
    capsys.readouterr()
    assert main(["validate", "miura", "--branch", "miura", "--reference", bad, "--out", str(tmp_path / "b")]) == 1
    printed = capsys.readouterr().out
    assert "FAIL reference curves vs numeric loop closure" in printed and "line 33" in printed
    report = json.loads((tmp_path / "b" / "report.json").read_text())
    assert report["passed"] is False and report["reference"]["worst"]["line"] == 33
    table = (tmp_path / "b" / "reference.csv").read_text().splitlines()
    assert len(table) == 1 + len(THETA) and table[0].startswith("line,input_rad,branch,phi_reference_rad")
    row = dict(zip(table[0].split(","), table[31].split(","), strict=True))
    assert row["line"] == "33" and float(row["psi_error_rad"]) == pytest.approx(1e-3, rel=1e-6)


def test_fold_file_scene_takes_a_reference_through_the_same_interface(tmp_path):
    """A FOLD pattern's scene (numeric path, input rho_e0 = one of its joints) checked against a degree-4 vertex's
    closed form written to CSV; the same curve with crease 3 off by 1e-3 rad fails."""
    from test_patterns import vertex_pattern  # the degree-4 vertex as a crease pattern

    from sim_origami.fold import write_fold
    from sim_origami.kinematics.vertex4 import Vertex4
    from sim_origami.scenes.fold_file import fold_scene

    alpha = np.deg2rad([60.0, 100.0, 90.0, 110.0])
    vertex = Vertex4(alpha)
    scene = fold_scene(write_fold(tmp_path / "v4.fold", vertex_pattern(alpha), vertex.joint_angles("odd2", [0.5, 1.2])))
    x = np.linspace(0.6, 1.1, 11)
    rows = np.column_stack([x, vertex.joint_angles("odd2", x)[:, 1:]])
    header = ",".join(f"{n}[rad]" for n in scene.kinematics.joint_names)
    result = compare_reference(read_reference(write_csv(tmp_path / "ok.csv", rows, header, 12), scene.kinematics),
                               scene)
    assert all(v.passed for v in result.verdicts) and result.doc["reference_vs_numeric_max_rad"] < 1e-11
    rows[4, 2] += 1e-3
    result = compare_reference(read_reference(write_csv(tmp_path / "bad.csv", rows, header, 12), scene.kinematics),
                               scene)
    assert not _by_id(result, REFERENCE_OVER_TOLERANCE).passed
    assert result.doc["worst"]["joint"] == scene.kinematics.joint_names[2]


EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples"


@pytest.mark.slow
def test_fold_example_with_its_reference_passes(tmp_path, capsys):
    """docs/extending.md's FOLD example, as printed there."""
    fold, curves = EXAMPLES / "reference" / "vertex4.fold", EXAMPLES / "reference" / "vertex4_curves.csv"
    assert main(["validate", "--fold", str(fold), "--reference", str(curves), "--out", str(tmp_path / "run")]) == 0
    doc = json.loads((tmp_path / "run" / "report.json").read_text())["reference"]
    assert doc["compared_samples"] == doc["mujoco_samples"] == 13
    assert doc["reference_vs_numeric_max_rad"] < 2e-11  # measured 8.5e-12 (9 printed decimals of a degree)


@pytest.mark.parametrize(
    ("script", "outputs"),
    [("reference/make_vertex4_curves.py", ("vertex4_curves.csv",)),
     ("user_package/make_curves.py", ("four_bar_curves.csv", "four_bar_curves_misprinted.csv"))],
)
def test_example_curves_are_what_their_scripts_write(tmp_path, script, outputs):
    source = EXAMPLES / script
    shutil.copy(source, tmp_path / source.name)
    subprocess.run([sys.executable, source.name], cwd=tmp_path, check=True)
    for name in outputs:
        assert (tmp_path / name).read_text() == (source.parent / name).read_text()


def test_spreadsheet_export_with_byte_order_mark_and_spaces_is_read(tmp_path, miura):
    path = tmp_path / "excel.csv"
    path.write_bytes("\ufefftheta [deg], rho_c [deg]\r\n10, 20\r\n20, 40.0\r\n".encode())
    ref = read_reference(path, miura.kinematics)
    assert ref.joints == ("rho_c",) and np.allclose(ref.values[:, 0], np.deg2rad([20.0, 40.0]))
    assert ref.printed[1, 0] == pytest.approx(np.deg2rad(0.05))


@pytest.mark.parametrize("branch", ["miura", "straight"])
def test_a_curve_starting_at_the_bifurcation_is_one_stretch_on_its_branch(tmp_path, miura, branch):
    x = np.arange(0.0, 20.1, 5.0)
    rows = np.column_stack([x, np.rad2deg(miura.kinematics.joint_angles(branch, np.deg2rad(x)))])
    header = "theta[deg],phi[deg],psi[deg],rho_a[deg],rho_b[deg],rho_c[deg],rho_d[deg]"
    result = compare_reference(read_reference(write_csv(tmp_path / "a.csv", rows, header), miura.kinematics), miura)
    assert all(v.passed for v in result.verdicts)
    assert [(s["branch"], s["samples"]) for s in result.doc["branches"]] == [(branch, 5)]


# --- a comparison that covers nothing cannot pass (issue: vacuous passes) ---------------------------------------


def test_a_branch_restriction_restricts_the_reference(tmp_path, miura):
    """Curves of the miura branch checked on the straight branch alone (validate --branch straight) fail: they are
    compared with that branch, not quietly with the one they fit."""
    ref = read_reference(write_csv(tmp_path / "r.csv", kamrava(np.arange(10.0, 40.1, 5.0))), miura.kinematics)
    assert all(v.passed for v in compare_reference(ref, miura).verdicts)
    result = compare_reference(ref, miura, branches=("straight",))
    assert {s["branch"] for s in result.doc["branches"]} == {"straight"}
    assert not _by_id(result, REFERENCE_OVER_TOLERANCE).passed and result.doc["over_tolerance"]["samples"] == 7


def test_a_curve_jumping_between_branches_that_do_not_meet_fails(tmp_path, miura):
    """First the miura branch, then the straight one, at inputs where the two are apart (they meet only at flat):
    each stretch matches its own branch, but no motion jumps between them."""
    x = np.array([10.0, 15.0, 20.0, 25.0, 30.0, 35.0])
    straight = miura.kinematics.joint_angles("straight", np.deg2rad(x[3:]))
    names = list(miura.kinematics.joint_names)
    rows = kamrava(x)
    rows[3:, 1:] = np.rad2deg(straight[:, [names.index(j) for j in ("phi", "psi", "rho_c")]])
    result = check(tmp_path, miura, rows)
    assert [s["branch"] for s in result.doc["branches"]] == ["miura", "straight"]
    assert _by_id(result, REFERENCE_OVER_TOLERANCE).passed  # each sample is on a branch ...
    jump = _by_id(result, REFERENCE_BRANCH_JUMPS)
    assert not jump.passed and "miura -> straight between lines 5 and 6" in jump.detail  # ... but not one motion


def test_a_value_printed_as_an_overflowing_exponent_is_not_its_own_tolerance(tmp_path, miura):
    """'1e+308' once gave its value a tolerance of half a unit in its exponent's digit (5e307 rad): it passed."""
    path = tmp_path / "huge.csv"
    rows = kamrava(np.arange(10.0, 40.1, 5.0))
    body = [",".join(f"{v:.10f}" for v in row) for row in rows]
    body[3] = body[3].rsplit(",", 1)[0] + ",1e+308"
    path.write_text(HEADER + "\n" + "\n".join(body) + "\n")
    result = compare_reference(read_reference(str(path), miura.kinematics), miura)
    assert not _by_id(result, REFERENCE_OVER_TOLERANCE).passed and result.doc["worst"]["tolerance_rad"] <= 0.1 + 1e-9


@pytest.mark.parametrize(
    ("cell", "match"),
    [
        ("1" * 140_000, r"line 2 is not a CSV row \(field larger than field limit"),
        ("1" * 5_000, r"line 2, column phi: 1{20}\.\.\.\(5000 characters\) is not a finite number"),
        ("3e" + "9" * 5_000, r"line 2, column phi: 3e9{18}\.\.\.\(5002 characters\) is not a finite number"),
    ],
)
def test_huge_cells_are_refused_in_one_line(tmp_path, miura, cell, match):
    """Cells that raised internal errors (the CSV module's field limit, a 5,000-digit exponent) or echoed thousands
    of digits back."""
    path = tmp_path / "huge.csv"
    path.write_text(f"{HEADER}\n10,{cell},1,20\n20,1,1,40\n")
    with pytest.raises(ParameterError, match=match) as err:
        read_reference(str(path), miura.kinematics)
    assert len(str(err.value)) < 200


def test_a_zero_with_an_overflowing_exponent_is_compared(tmp_path, miura):
    """'0e400' is 0; its printing's half unit (0.5e400) overflowed a float and raised OverflowError."""
    path = tmp_path / "zero.csv"
    rows = kamrava(np.array([10.0, 20.0, 30.0]))
    body = [",".join(f"{v:.10f}" for v in row) for row in rows]
    body[1] = body[1].split(",", 1)[0] + ",0e400," + body[1].split(",", 2)[2]
    path.write_text(HEADER + "\n" + "\n".join(body) + "\n")
    result = compare_reference(read_reference(str(path), miura.kinematics), miura)
    assert not _by_id(result, REFERENCE_OVER_TOLERANCE).passed and result.doc["worst"]["line"] == 3


def test_more_samples_than_the_limit_are_refused_before_any_solve(tmp_path, miura):
    from sim_origami.checks.reference import MAX_SAMPLES

    path = tmp_path / "long.csv"
    x = np.linspace(1.0, 50.0, MAX_SAMPLES + 1)
    path.write_text(HEADER + "\n" + "\n".join(f"{v:.6f},0,0,{2 * v:.6f}" for v in x) + "\n")
    with pytest.raises(ParameterError, match=rf"more than {MAX_SAMPLES} samples \(line {MAX_SAMPLES + 2}\)"):
        read_reference(str(path), miura.kinematics)
