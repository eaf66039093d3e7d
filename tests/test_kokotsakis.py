"""Kokotsakis meshes (`kinematics.kokotsakis`, scene `kokotsakis`) against Peng 2018, §2.3-2.5
(eqns 2-32 to 2-38, Figs 2-11 to 2-13), the per-vertex loop closure and MuJoCo."""

import itertools
import re

import numpy as np
import pytest

import sim_origami.scenes.kokotsakis  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.errors import AssemblyError, DomainError, ParameterError
from sim_origami.kinematics.kokotsakis import (
    FACES,
    INNER,
    Kokotsakis,
    MeshVertex,
    crease_pattern,
    example,
    loop_mismatch,
    straight_lines,
)
from sim_origami.kinematics.vertex4 import Vertex4, flat_foldable_fold_angles, flat_foldable_multipliers
from sim_origami.presets import FAST
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import CLOSED_FORM_VS_NUMERIC, MUJOCO_PATH_ERROR, PROJECTION_PATH_ERROR, validate

DEG = np.pi / 180
# Worked values to 6 decimals: half a unit of the last digit.
PRINTED = 5e-7
GENERIC = (90.0, 70.0, 60.0, 140.0)  # eqn 2-34, deg


def vertex(alpha_deg, previous, mirrored=False) -> MeshVertex:
    return MeshVertex(tuple(np.array(alpha_deg) * DEG), previous, mirrored)


def crease_angles_deg(pattern, v: int) -> list[float]:
    """Flat-sheet directions (deg in [0, 360)) of the creases at interior vertex v, counter-clockwise."""
    return sorted(np.round(np.rad2deg(np.arctan2(d[1], d[0])), 9) % 360 for _, d in pattern.vertex_creases(v))


def test_example1_layout_is_the_reconstructed_one():
    pattern = crease_pattern(example(1))
    np.testing.assert_allclose(
        pattern.vertices[:4], [[0, 0], [0, 1], [0.939693, 0.657980], [0.155543, 0]], atol=PRINTED, rtol=0
    )
    # layout reconstructed here from (2-32): A and C at 0, 90, 160, 220 deg; B and D at 180, 270, 340, 40 deg
    for v, table in zip(range(4), ([0, 90, 160, 220], [40, 180, 270, 340]) * 2, strict=True):
        np.testing.assert_allclose(crease_angles_deg(pattern, v), table, atol=1e-9, rtol=0)
    assert pattern.interior_vertices() == (0, 1, 2, 3)
    assert pattern.face_names == FACES and len(pattern.creases) == 12
    # shared creases a2 = b2 (AB), b3 = c3 (BC), c4 = d4 (CD), d1 = a1 (DA): each inner crease joins central
    # to a side panel; the outer ones join a side panel to a corner panel
    for crease in pattern.creases:
        faces = set(pattern.crease_faces(crease))
        if crease.name in INNER:
            assert faces == {"central", f"side_{crease.name}"}
        else:
            assert len([f for f in faces if f.startswith("side")]) == 1
            assert f"corner_{crease.name[0].upper()}" in faces
    loops = Kokotsakis(example(1)).loop_system()
    assert [len(loop.joints) for loop in loops.loops] == [4, 4, 4, 4]


def test_example2_and_two_fold_central_panels():
    """Example 2: corners 80 + 110 + 100 + 70 = 360 deg (eqn 2-32); two-fold: a square (alpha_12 = 90 deg)."""
    for case, corners in ((2, (80, 110, 100, 70)), (3, (90, 90, 90, 90))):
        pattern = crease_pattern(example(case))
        p = pattern.vertices[:4]
        for i, angle in enumerate(corners):
            u, w = p[(i - 1) % 4] - p[i], p[(i + 1) % 4] - p[i]
            got = np.arctan2(u[0] * w[1] - u[1] * w[0], u @ w) % (2 * np.pi)
            assert got == pytest.approx(angle * DEG, abs=1e-12)
    np.testing.assert_allclose(crease_pattern(example(3)).vertices[:4], [[0, 0], [0, 1], [1, 1], [1, 0]], atol=1e-15)
    # every vertex of Example 2 is the flat-foldable 80-70-100-110 vertex (b, d rotated by two positions)
    pattern = crease_pattern(example(2))
    for v in range(4):
        angles = np.array(crease_angles_deg(pattern, v))
        sectors = np.diff(np.append(angles, angles[0] + 360))
        assert sorted(np.round(sectors, 9)) == [70, 80, 100, 110]


@pytest.mark.parametrize(
    ("branch", "published"), [("odd2", (-0.084225, 0.443379, 0.109452)), ("odd3", (0.849175, -0.443379, 1.129539))]
)
def test_example1_every_vertex_carries_the_published_fold_vector(branch, published):
    """rho1 = 0.5 at a vertex of (2-34), driven through rho_AB = its rho2."""
    x = Vertex4(np.array(GENERIC) * DEG, 1).at(branch, 0.5)["rho2"]
    mesh = Kokotsakis(example(1))
    folds = mesh.vertex_folds(branch, x)[0]
    np.testing.assert_allclose(folds[0], (0.5, *published), atol=PRINTED, rtol=0)
    assert np.max(np.abs(folds - folds[0])) <= 1e-14  # A, B, C, D alike: measured 1.3e-15 (chained rounding)


def test_example2_follows_the_flat_foldable_multipliers_and_the_loop_gain():
    """Each vertex obeys the tan-half multipliers of its mode (eqns 3-1, 3-3); the loop gain
    K = m12(A) m23(B) m34(C) m41(D) is 1 only for SSSS and CCCC (eqn 2-38)."""
    mesh = Kokotsakis(example(2))
    x = np.linspace(0.5, 1.5, 21)
    for mode in ("S", "C"):
        folds = mesh.vertex_folds(mode, x)
        for i, v in enumerate(mesh.vertices):
            multiplier = flat_foldable_fold_angles(v.alpha, folds[:, i, 0], mode)
            assert np.max(np.abs(multiplier - folds[:, i])) <= 1e-13  # measured 7.0e-15
    gains = {}
    for modes in itertools.product("SC", repeat=4):
        m = [flat_foldable_multipliers(v.alpha)[mode] for v, mode in zip(mesh.vertices, modes, strict=True)]
        gains["".join(modes)] = m[0][0] * m[1][1] * m[2][2] * m[3][3]
    assert {k for k, g in gains.items() if abs(g - 1) < 1e-12} == {"SSSS", "CCCC"}
    # mixed gains measured 42.66, -0.0234, -1, 1819.7, 5.5e-4, 0.0234, -42.66
    assert min(abs(g - 1) for k, g in gains.items() if k not in ("SSSS", "CCCC")) >= 0.97


@pytest.mark.slow
def test_example2_mixed_modes_do_not_close():
    mesh = Kokotsakis(example(2))
    assert [b.name for b in mesh.branches()] == ["C", "S"]
    mixed = [m for m in itertools.product("SC", repeat=4) if len(set(m)) > 1]
    mismatch = np.array([loop_mismatch(mesh.vertices, m, 0.5)[0] for m in mixed])
    # rho_DA from D against from A after the loop: measured >= 0.0472 rad (S-S-C-S)
    assert np.min(np.abs(mismatch)) >= 0.04
    for mode in ("S", "C"):
        closed = loop_mismatch(mesh.vertices, (mode,) * 4, np.linspace(-2.5, 2.5, 101))
        assert np.max(np.abs(closed)) <= 1e-12  # measured 5.8e-15
    # the numeric loop solve at rho_AB = 0.5 from 32 random starts finds exactly the two closed forms
    # (16, 32 and 64 starts all found 2 solutions)
    loops = mesh.loop_system()
    found = loops.assemblies(mesh.loop_input()[0], 0.5, starts=32)
    assert len(found) == 2
    for mode in ("S", "C"):
        q = mesh.joint_angles(mode, 0.5)[0]
        assert min(np.max(np.abs(f - q)) for f in found) <= 1e-12  # measured 2.4e-15


@pytest.mark.slow
def test_example1_closes_only_with_every_vertex_on_one_branch():
    mesh = Kokotsakis(example(1))
    assert [b.name for b in mesh.branches()] == ["odd2", "odd3"]
    mixed = [m for m in itertools.product(("odd2", "odd3"), repeat=4) if len(set(m)) > 1]
    mismatch = np.array([loop_mismatch(mesh.vertices, m, 0.3)[0] for m in mixed])
    # two combinations leave a vertex's domain at 0.3 (NaN); the rest measured >= 0.179 rad
    assert np.sum(np.isnan(mismatch)) == 2
    assert np.nanmin(np.abs(mismatch)) >= 0.15


@pytest.mark.slow
def test_two_fold_case_closes_on_six_combinations():
    """Derived here: A mirror pair sharing a crease on one branch carries equal folds, so the loop closes whenever
    A, B and C, D (sharing crease 2) or B, C and D, A (sharing crease 1) are pairwise on one branch."""
    mesh = Kokotsakis(example(3))
    names = [b.name for b in mesh.branches()]
    assert names == ["odd2", "odd2-odd2-odd3-odd3", "odd2-odd3-odd3-odd2", "odd3", "odd3-odd2-odd2-odd3",
                     "odd3-odd3-odd2-odd2"]
    # mixed pairs end early: creases c4, d4 fold flat at |rho_AB| = 0.423290
    assert mesh.branch("odd2-odd2-odd3-odd3").domain[1] == pytest.approx(0.423290, abs=PRINTED)
    folds = mesh.vertex_folds("odd2", np.linspace(-1.1, 1.1, 51))
    assert np.max(np.abs(folds - folds[:, :1])) <= 1e-14  # every vertex alike: measured 2.6e-15


def test_plane_symmetric_case_moves_on_one_branch_and_a_two_dof_family():
    """Derived here: case 4's straight crease lines (creases 1 and 3 collinear at every vertex, which Peng 2018, §2.5
    says gives more than 1 DOF): one 1-DOF branch with every vertex alike (the thesis's A = B, C = D = -A in D-H
    angles), and a 2-DOF family folding the lines alone, meeting it at flat."""
    mesh = Kokotsakis(example(4))
    corners = crease_pattern(example(4)).vertices[:4]
    assert corners[1, 1] == pytest.approx(corners[2, 1], abs=1e-15)  # BC parallel to DA: a trapezoid
    assert corners[0, 0] + corners[3, 0] == pytest.approx(corners[1, 0] + corners[2, 0], abs=1e-15)  # isosceles
    assert [b.name for b in mesh.branches()] == ["odd1"]
    assert mesh.branch("odd1").domain == (-np.pi, np.pi)  # locks where AB and CD fold flat
    folds = mesh.vertex_folds("odd1", np.linspace(-3.0, 3.0, 61))
    assert np.max(np.abs(folds - folds[:, :1])) <= 5e-14  # measured 1.7e-14 (at |rho_AB| = 3)
    assert straight_lines(mesh.pattern) == (("b1", "BC", "c1"), ("d3", "DA", "a3"))
    loops, names = mesh.loop_system(), mesh.creases
    for first, second in ((0.7, 0.0), (0.0, -1.2), (2.5, 1.0)):
        q = np.zeros(12)
        q[[names.index(n) for n in ("d3", "DA", "a3")]] = first
        q[[names.index(n) for n in ("b1", "BC", "c1")]] = second
        assert np.max(np.abs(loops.residual(q))) <= 1e-14  # measured 1.1e-15
        assert loops.mobility(q) == 2
    assert "2-DOF family folding the straight crease lines b1-BC-c1, d3-DA-a3" in mesh.events()[0].detail
    assert straight_lines(Kokotsakis(example(1)).pattern) == ()


@pytest.mark.slow
@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_closed_form_closes_every_vertex_loop(case):
    mesh = Kokotsakis(example(case))
    loops = mesh.loop_system()
    for branch in mesh.branches():
        lo, hi = branch.domain
        q = mesh.joint_angles(branch.name, np.linspace(0.99 * lo, 0.99 * hi, 801))
        # measured <= 4.7e-14 (case 1), 3.7e-14 (2), 3.3e-14 (3), 5.2e-14 (4); at the exact locks up to 1e-12
        # (case 1) and 6e-8 (case 2, the fully folded state where every crease reaches pi)
        assert np.max(loops.residual_norm(q)) <= TOLERANCES.closed_form_residual


@pytest.mark.slow
@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_one_dof_along_every_branch_and_four_at_flat(case):
    mesh = Kokotsakis(example(case))
    loops = mesh.loop_system()
    for branch in mesh.branches():
        for x in np.linspace(0.05, 0.95 * branch.domain[1], 7):
            assert loops.mobility(mesh.joint_angles(branch.name, x)[0]) == 1
    # flat: each vertex loop's Jacobian spans only the sheet's plane (rank 2), 12 - 4 x 2 = 4
    s = np.linalg.svd(loops.jacobian(np.zeros(12)), compute_uv=False)
    assert loops.mobility(np.zeros(12)) == 4
    assert s[7] >= 0.5 and s[8] <= 1e-12  # measured s[7] = 0.657 / 0.865 / 0.707 / 0.909 (cases 1-4), s[8] <= 3.3e-16


@pytest.mark.slow
def test_events_name_the_creases_that_fold_flat():
    events = Kokotsakis(example(1)).events()
    assert events[0].kind == "bifurcation" and events[0].input == 0.0 and events[0].branches == ("odd2", "odd3")
    locks = {(e.branches[0], round(e.input, 6)): e.detail for e in events if e.kind == "lock"}
    # odd2 ends where every crease 1 (DA = a1 = d1, b1, c1) folds flat; odd3 where every crease 4 does
    assert locks["odd2", 1.171049].endswith("DA, b1, c1")
    assert locks["odd3", -1.756657].endswith("CD, a4, b4")


@pytest.mark.slow
@pytest.mark.parametrize("case", [1, 2, 3, 4])
def test_validate_closed_form_numeric_and_mujoco(case):
    scene = scenes.get("kokotsakis").build(case=float(case))
    report = validate(scene)
    measured = {(v.branch, v.id): v.measured for v in (*report.verdicts, *(v for r in report.runs for v in r.verdicts))}
    for run in report.runs:
        b = run.requested
        # closed form vs numeric: measured <= 3.0e-14 (case 1), 5.5e-14 (2, S from 0.5 rad), 2.9e-14 (3), 1.2e-14 (4)
        assert measured[b, CLOSED_FORM_VS_NUMERIC] <= TOLERANCES.closed_form_rad
        # fast: measured case 1 odd2 2.8e-8, odd3 7.3e-8 (4x sweep); case 2 C 9.0e-10, S 4.3e-8 (16x);
        # case 3 4.8e-9 to 5.6e-8 (4x); case 4 1.7e-8 (1x)
        assert measured[b, MUJOCO_PATH_ERROR] <= FAST.angle_rad
        assert measured[b, PROJECTION_PATH_ERROR] <= TOLERANCES.projection_rad  # <= 2.1e-14
        assert (run.followed, run.flips) == (b, 0)
        start = run.mobility["start"]
        assert (start["input_rad"], start["numeric"], start["mujoco"], start["truss"]) == (
            scene.branch_path(b)[0],
            1,
            1,
            1,
        )
        assert [(p["numeric"], p["mujoco"], p["truss"]) for p in run.mobility["bifurcations"]] == [(4, 4, 4)]
    # seeded 1e-4 (cases 1, 2, 4) or 1e-3 rad (case 3) from flat, MuJoCo follows every branch
    assert all(d is not None for d in report.bifurcations[0]["seed_offset_followed_rad"].values())
    assert report.passed


@pytest.mark.parametrize(
    ("vertices", "match"),
    [
        ((vertex((90, 70, 60, 150), 1), *example(1)[1:]), "vertex A: sector angles sum to 370 deg"),
        ((*example(1)[:3], vertex((90, 70, 60, 190), 4)), "vertex D: alpha4 = 190 deg"),
        # the plane-symmetric case (Path3, eqn 2-19) with the vertex of (2-34): corners alpha12, alpha23,
        # alpha23, alpha12 = 320 deg; it needs alpha12 + alpha23 = 180 (collinear creases 1 and 3: case 4)
        (
            (vertex(GENERIC, 1), vertex(GENERIC, 2), vertex(GENERIC, 3, True), vertex(GENERIC, 2, True)),
            re.escape("central panel corners (A 90, B 70, C 70, D 90 deg) sum to 320 deg"),
        ),
        # Example 1's A, B with Example 2's C, D: 90 + 70 + 100 + 70
        ((*example(1)[:2], *example(2)[2:]), "sum to 330 deg; a planar panel needs 360"),
    ],
)
def test_bad_geometry_is_refused(vertices, match):
    with pytest.raises(ParameterError, match=match):
        Kokotsakis(vertices)


def test_a_mesh_whose_loop_never_closes_is_rigid():
    # developable and planar (90 + 70 + 80 + 120 deg) but generic: smallest mismatch measured 0.138 rad
    rigid = (vertex(GENERIC, 1), vertex((80, 70, 100, 110), 2), vertex((100, 110, 80, 70), 3),
             vertex((100, 80, 60, 120), 4))
    with pytest.raises(AssemblyError, match=re.escape("smallest loop mismatch 0.138 rad")):
        Kokotsakis(rigid)


@pytest.mark.slow
def test_bad_scene_input_is_refused():
    kokotsakis = scenes.get("kokotsakis")
    for case in (0.0, 1.5, 5.0):
        with pytest.raises(ParameterError, match=f"case = {case:g}"):
            kokotsakis.build(case=case)
    # case 1: the outer creases b4 and c2 of side panel BC (60 and 70 deg from BC) meet sin 60 / sin 50 =
    # 1.1305 m from C (bisection of the convexity check: 1.130516)
    with pytest.raises(ParameterError, match=re.escape("outer crease length 1.2 m makes panel 'side_BC' non-convex")):
        kokotsakis.build(case=1.0, outer=1.2)
    with pytest.raises(ParameterError, match=re.escape("outer = -1 m; it must be a number in [0.0001, 10000] m")):
        kokotsakis.build(outer=-1.0)
    mesh = Kokotsakis(example(1))
    with pytest.raises(DomainError, match=re.escape("rhoAB = 1.2 rad is outside branch 'odd2'")):
        mesh.joint_angles("odd2", 1.2)
    with pytest.raises(ParameterError, match="unknown branch 'S'; this model has: odd2, odd3"):
        mesh.joint_angles("S", 0.1)
