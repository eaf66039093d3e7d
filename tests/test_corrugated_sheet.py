"""Double-corrugated tessellation (`kinematics.corrugated_sheet`, scene `corrugated-sheet`) against the unit's closed
form (Peng 2018, §3.2.2), the numeric loop solve and MuJoCo."""

import numpy as np
import pytest

import sim_origami.scenes.corrugated_sheet  # noqa: F401  (registers `corrugated-sheet`)
from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.errors import AssemblyError, ParameterError
from sim_origami.kinematics.corrugated import VERTEX_CREASES, CorrugatedUnit
from sim_origami.kinematics.corrugated_sheet import CorrugatedSheet
from sim_origami.simulate import simulate
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import validate

SECTORS = np.deg2rad([135.0, 60.0, 45.0, 120.0])  # Peng 2018, Fig 3-2
TYPE_I = {"P": "AC", "Q": "AE"}  # vertex types I of the unit geometry (eqns 3-16, 3-22)


@pytest.mark.parametrize("unit", ["P", "Q"])
@pytest.mark.parametrize(("rows", "cols"), [(1, 1), (2, 2), (2, 3)])
def test_sheet_is_a_lattice_of_flat_foldable_vertices_of_the_unit_types(unit, rows, cols):
    sheet = CorrugatedSheet(unit, SECTORS, (1.0, 0.8, 0.6), rows, cols)
    nu, nv = 2 * cols + 1, 2 * rows + 1
    assert len(sheet.pattern.faces) == nu * nv and len(sheet.vertices) == 4 * rows * cols
    assert len(sheet.pattern.creases) == nu * (nv - 1) + (nu - 1) * nv
    alpha, beta, gamma, delta = SECTORS
    for role, _, sectors in sheet.vertices.values():
        expected = (alpha, beta, gamma, delta) if role in TYPE_I[unit] else (alpha, delta, gamma, beta)
        np.testing.assert_allclose(sectors, expected, atol=1e-13, rtol=0)  # measured 4.4e-16


@pytest.mark.parametrize("unit", ["P", "Q"])
def test_one_unit_sheet_is_the_corrugated_unit(unit):
    lengths = (1.0, 0.8, 0.6)
    sheet, model = CorrugatedSheet(unit, SECTORS, lengths, 1, 1), CorrugatedUnit(unit, SECTORS, lengths)
    p, q = sheet.pattern, model.pattern
    assert max(np.min(np.linalg.norm(q.vertices - v, axis=1)) for v in p.vertices) <= 1e-14  # measured 4.0e-16 m
    mid = np.array([(q.vertices[c.start] + q.vertices[c.end]) / 2 for c in q.creases])
    match = [int(np.argmin(np.linalg.norm(mid - (p.vertices[c.start] + p.vertices[c.end]) / 2, axis=1)))
             for c in p.creases]
    assert sorted(match) == list(range(12))
    assert q.creases[match[sheet.input]].name == model.input_name.removeprefix("rho")  # AD (P), AF (Q)
    assert tuple(sheet.ratios) == tuple(model.ratios)
    for modes, k in sheet.ratios.items():
        np.testing.assert_allclose(k, model.ratios[modes][match], atol=1e-13, rtol=0)  # measured <= 6.0e-15


def test_every_vertex_repeats_its_unit_vertex():
    """Units repeat: each vertex's four folds are those of the unit vertex of its role, up to a global sign."""
    for unit in "PQ":
        sheet, model = CorrugatedSheet(unit, SECTORS, rows=2, cols=3), CorrugatedUnit(unit, SECTORS)
        index = model.model.index
        signs = set()
        for modes in sheet.ratios:
            for v, (role, _, _) in sheet.vertices.items():
                mine = sheet.vertex_gains(modes, v)
                theirs = model.ratios[modes][[index[n] for n in VERTEX_CREASES[unit][role]]]
                sign = np.sign(mine[0] / theirs[0])
                signs.add(sign)
                np.testing.assert_allclose(mine, sign * theirs, rtol=1e-12, atol=0)  # measured relative 1.0e-14
        assert signs == {1.0, -1.0}  # some vertices repeat their unit vertex flipped (x -> -x)


@pytest.mark.slow
@pytest.mark.parametrize("unit", ["P", "Q"])
def test_closed_form_closes_and_matches_the_numeric_solve(unit):
    sheet = CorrugatedSheet(unit, SECTORS, (1.0, 0.7, 1.3), 2, 2)
    loops = sheet.loop_system()
    assert sheet.gruebler() == 40 - 3 * 16
    assert loops.mobility(np.zeros(40)) == 8  # flat: 40 - rank 32 (MuJoCo's count agrees, validate below)
    for branch in sheet.branches():
        q = sheet.joint_angles(branch.name, np.linspace(-3.1, 3.1, 41))
        assert np.max(loops.residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured <= 1.3e-14 (3 x 3)
        x = np.linspace(0.3, 2.0, 20)
        q = sheet.joint_angles(branch.name, x)
        assert loops.mobility(q[5]) == 1
        numeric = loops.follow(q[0], sheet.input, x)
        assert np.max(np.abs(numeric - q)) <= TOLERANCES.closed_form_rad  # measured <= 4.4e-14 (P)


def test_locked_mode_strings_do_not_close():
    sheet = CorrugatedSheet("P", SECTORS)
    assert "CCCC" not in sheet.ratios  # K = 0.010205 (worked here): locked in the unit, so in the sheet
    with pytest.raises(AssemblyError, match="modes 'CCCC' do not close: crease"):
        sheet.gains("CCCC")


@pytest.mark.slow
def test_validate_default_sheet_and_self_contact():
    scene = scenes.get("corrugated-sheet").build()
    report = validate(scene)
    assert report.passed, [v.name for r in report.runs for v in r.verdicts if not v.passed]
    errors = {}
    for run in report.runs:
        # fast preset, the path's sweep time (sweep_rate, timed for 2e-7) over 0.3..2.0 rad: measured <= 1.4e-7 (SSCC)
        errors[run.requested] = run.dynamic_path.max_error()
        assert errors[run.requested] <= 2.5e-7
        assert run.followed == run.requested and run.flips == 0
        flat = run.mobility["bifurcations"][0]
        assert (flat["input_rad"], flat["numeric"], flat["mujoco"]) == (0.0, 8, 8)
    # self-contact on: no panels touch before 2 rad, so the same path (measured identical; 1.3 s CPU against 1.0)
    run = simulate(scene, "CSCS", contact=True)
    assert compare(scene, "CSCS", run.q).max_error() == pytest.approx(errors["CSCS"], rel=1e-9)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"unit": 2.0}, "unit = 2; it must be a whole number from 0 to 1"),
        ({"rows": 0.0}, "rows = 0; it must be a whole number from 1 to 16"),
        ({"cols": 1.5}, "cols = 1.5"),
        ({"gamma": np.deg2rad(50.0), "delta": np.deg2rad(115.0)}, "alpha \\+ gamma = 185 deg"),
        ({"L2": 0.0}, r"L2 = 0 m; it must be a number in \[0\.0001, 10000\] m"),
    ],
)
def test_bad_input_is_refused(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("corrugated-sheet").build(**kwargs)
