"""The trace stops at the first self-contact (issue 15 item 1): zero-thickness faces that meet before any crease
reaches +-180 deg end the motion there, with the faces and the crease named; patterns that fold flat stop at
their lock and the built-in sheets never read a false contact. Real MuJoCo where a verdict is asserted."""

import json

import numpy as np
import pytest
from fold_fixtures import slit_crane
from test_fold_path import fan, strip, vertex

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.creases import Crease, CreasePattern
from sim_origami.fold import read_fold, write_fold
from sim_origami.geometry import triangles_cross
from sim_origami.kinematics.numeric_pattern import PatternPath, assignment_signs
from sim_origami.kinematics.self_contact import SelfContact, triangulate
from sim_origami.kinematics.vertex4 import Vertex4
from sim_origami.path import STOP_WHEN_TOL

NAN = np.nan


def flapped_vertex(alpha_deg: list[float], letters: str, length: float = 0.6) -> CreasePattern:
    """A degree-n vertex (`vertex`) with a flap on the middle of sector p0's rim, hinged by the V crease `f`:
    a closed loop (the vertex) and a panel that folds over p0 into p1's way."""
    v = vertex(alpha_deg, letters)
    rim1, rim2 = v.vertices[1], v.vertices[2]
    a, b = rim1 + 0.3 * (rim2 - rim1), rim1 + 0.7 * (rim2 - rim1)
    d = rim2 - rim1
    out = np.array([d[1], -d[0]]) / np.linalg.norm(d)
    xy = np.vstack([v.vertices, a, b, a + length * out, b + length * out])
    n = len(v.vertices)
    faces = ((0, 1, n, n + 1, 2), *v.faces[1:], (n + 1, n, n + 2, n + 3))
    return CreasePattern(xy, faces, (*v.creases, Crease("f", n, n + 1, "V")), (*v.face_names, "flap"))


def test_two_strip_ends_meet_at_120_deg_and_the_trace_stops_there():
    """Panels p0 and p2 of a 3-panel strip (share no vertex) folded alike meet edge on edge at rho = 2 pi / 3."""
    path = PatternPath(strip(2, "VV"), ("c1", "c2"), np.array([2.8, 2.8]))
    stop = path.stops[0]
    assert stop.kind == "contact" and "faces p0 and p2 touch" in stop.detail
    np.testing.assert_allclose(path.nodes[-1], 2 * np.pi / 3, atol=STOP_WHEN_TOL)  # measured 1.5e-10 short
    event = [e for e in path.events() if e.kind == "contact"]
    assert len(event) == 1 and event[0].input == pytest.approx(np.sqrt(2) * 2 * np.pi / 3, abs=1e-8)
    assert "contact at 2.96192 rad: faces p0 and p2 touch" in path.summary()


def test_fan_panels_sharing_only_the_apex_meet_where_their_rims_lie_in_the_mirror_plane():
    """Three 60-deg sectors from a border vertex, both creases folded alike: the outer panels (sharing only the apex,
    where they touch at every pose) meet when the rim ray (1, 0, 0) turned about c1 reaches the mirror plane x = 0:
    1/4 + 3/4 cos rho = 0. Their crossing segment ends on both panels' rims at once (the mirror symmetry)."""
    path = PatternPath(fan([60.0, 60.0, 60.0], "VV"), ("c1", "c2"), np.array([2.8, 2.8]))
    assert path.stops[0].kind == "contact" and "faces p0 and p2 touch" in path.stops[0].detail
    np.testing.assert_allclose(path.nodes[-1], np.arccos(-1.0 / 3.0), atol=STOP_WHEN_TOL)


def test_a_flap_on_a_closed_vertex_meets_the_neighbouring_sector_before_any_crease_folds_flat():
    """Closed loop plus a flap, two inputs (c2, f): the flap and sector p1 both fold over p0 and meet mid-fold. The
    stop is checked against the closed form of the degree-4 vertex (`Vertex4`) and the edge-through-face test."""
    alpha = [60.0, 100.0, 90.0, 110.0]
    pattern = flapped_vertex(alpha, "MVMV")
    path = PatternPath(pattern, ("c2", "f"), np.array([NAN, 2.5, NAN, NAN, 2.5]))
    stop = path.stops[0]
    assert stop.kind == "contact" and "faces p1 and flap touch" in stop.detail and "crease f at" in stop.detail
    q = path.nodes[-1]
    assert np.max(np.abs(q)) < 2.4 and path.loop_system().residual_norm(q) <= 1e-13  # measured: |rho| <= 2.33
    # the same vertex from its closed form (branch odd1: crease 1 opposite) a little before and after the stop
    sc, kin = SelfContact(pattern), Vertex4(np.deg2rad(alpha))
    grid = np.linspace(-1.12, 0.0, 200001)
    rho2 = kin.joint_angles("odd1", grid)[:, 1]
    tri = {}
    for delta in (-1e-3, 1e-3):
        x = grid[np.argmin(np.abs(rho2 - (q[1] + delta)))]
        state = np.r_[kin.joint_angles("odd1", x)[0], q[4] + delta]
        corners = sc.corners(state)
        tri[delta] = [corners[sc.triangles[sc.tri_face == f]] for f in (1, 4)]  # p1, flap
    crossed = {d: bool(np.any(triangles_cross(t[0][:, None], t[1][None]))) for d, t in tri.items()}
    assert crossed == {-1e-3: False, 1e-3: True}


def test_flat_folding_stops_at_the_lock_not_at_a_contact():
    """A flat-foldable (Miura) vertex and a single crease folded to 180 deg: faces end up on each other, which is the
    lock (|rho| -> pi), not a crossing."""
    miura = PatternPath(vertex([60.0, 120.0, 120.0, 60.0], "MVVV"), "c2", np.array([NAN, np.pi, NAN, NAN]))
    single = PatternPath(strip(1, "V"), "c1", np.array([np.pi]))
    for path in (miura, single):
        assert [e.kind for e in path.events() if e.kind in ("lock", "contact")] == ["lock"]
        assert path.s_nodes[-1] > 3.1


@pytest.mark.parametrize(("name", "values"), [("miura-sheet", {"rows": 2, "cols": 2}), ("square-twist", {}),
                                              ("corrugated-unit", {})])
def test_no_false_contact_on_built_in_motions_up_to_their_ends(name, values):
    """Every branch from flat to 1e-3 rad short of +-pi (the faces end stacked on each other, never crossing)."""
    scene = scenes.get(name).build(**values)
    sc = SelfContact(scene.pattern)
    for branch in scene.kinematics.branches():
        x = np.linspace(max(branch.domain[0], -np.pi + 1e-3), min(branch.domain[1], np.pi - 1e-3), 41)
        for q in scene.kinematics.joint_angles(branch.name, x):
            assert sc(q) is None, (branch.name, q)


def test_waterbomb_sheet_contact_onset_agrees_with_the_edge_through_face_test():
    """The 2 x 2 waterbomb sheet's straight-line branch folds into itself at |rho| = 2 pi / 5 (tests/test_waterbomb.py
    finds it with `triangles_cross` on the MuJoCo body poses); this placement from the crease angles alone agrees."""
    scene = scenes.get("waterbomb-sheet").build()
    sc = SelfContact(scene.pattern)
    for onset in (-2 * np.pi / 5, 2 * np.pi / 5):
        before, after = scene.kinematics.joint_angles("two-straight-lines", [onset * (1 - 1e-6), onset * (1 + 1e-6)])
        assert sc(before) is None and "touch" in sc(after)


def test_placement_closes_every_crease_and_triangulates_non_convex_faces():
    """On a closed square-twist state every crease's ends, placed from either face, coincide (the loops close, so
    the spanning tree does not matter); an L-shaped face is split into triangles covering its area."""
    scene = scenes.get("square-twist").build()
    q = scene.kinematics.joint_angles(scene.kinematics.branches()[0].name, 1.7)[0]
    sc = SelfContact(scene.pattern)
    xyz = sc.corners(q)
    ends = {}
    for corner, v in enumerate(sc.corner_vertex):
        ends.setdefault(int(v), []).append(xyz[corner])
    spread = max(np.max(np.ptp(np.array(p), axis=0)) for p in ends.values())
    assert spread <= 1e-13  # measured 2e-16
    ell = np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], dtype=float)
    tris = triangulate(ell)
    area = sum(0.5 * abs(np.linalg.det(np.c_[ell[[a, b, c]], np.ones(3)])) for a, b, c in tris)
    assert len(tris) == 4 and area == pytest.approx(3.0)


@pytest.mark.slow
def test_contact_is_reported_and_validated_three_ways_up_to_it(tmp_path, capsys):
    """The FOLD file's target (150 deg each) lies beyond the contact: the report names it, the sweep ends there and
    MuJoCo agrees with the numeric trace up to it."""
    fold = write_fold(tmp_path / "strip.fold", strip(2, "VV"), fold_angles=np.deg2rad([150.0, 150.0]))
    code = main(["validate", "--fold", str(fold), "--out", str(tmp_path / "out")])
    text = "".join(capsys.readouterr())
    doc = json.loads((tmp_path / "out" / "report.json").read_text())
    contact = [e for e in doc["events"] if e["kind"] == "contact"]
    assert code == 0, text
    assert "contact at 2.96192 rad: faces f0 and f2 touch" in text  # FOLD faces are f<index>
    assert len(contact) == 1 and "faces f0 and f2 touch" in contact[0]["detail"]
    assert contact[0]["input_rad"] == pytest.approx(np.sqrt(2) * 2 * np.pi / 3, abs=1e-8)
    lo, hi = doc["branches"][0]["input_range_rad"]
    assert 0.9 * contact[0]["input_rad"] < hi < contact[0]["input_rad"] and hi - lo > 1.0  # the scene's margin


def cut_square() -> CreasePattern:
    """The square [0, 2]^2 with its centre joined to the four corners: the spoke to (0, 0) a cut C, the others V
    creases e1 (to (2, 0)), e2 (to (2, 2), on the cut's line) and e3 (to (0, 2)). Faces f0 and f3 are the cut's
    sides, sharing the centre and copies of the corner (0, 0)."""
    doc = {"vertices_coords": [[1, 1], [0, 0], [2, 0], [2, 2], [0, 2]],
           "edges_vertices": [[0, 1], [0, 2], [0, 3], [0, 4], [1, 2], [2, 3], [3, 4], [4, 1]],
           "edges_assignment": ["C", "V", "V", "V", "B", "B", "B", "B"],
           "faces_vertices": [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]}
    return read_fold(doc).pattern


def sides_cross(sc: SelfContact, q, a: int, b: int) -> bool:
    """Whether an edge of face a's triangles passes through face b's or back (`triangles_cross`), at angles q."""
    xyz = sc.corners(q)
    ta, tb = (xyz[sc.triangles[sc.tri_face == f]] for f in (a, b))
    return bool(np.any(triangles_cross(ta[:, None], tb[None])))


def test_the_sides_of_a_closed_cut_touch_along_it_and_of_an_open_one_are_tested(tmp_path):
    """Issue 27. With e2 alone folded the square's halves turn about the diagonal, the cut's own line: the cut's
    sides f0 and f3 stay edge to edge, hinged apart as faces across a crease are. The whole cut lay on both planes and
    read as 'faces f0 and f3 touch' at every angle; it is now one shared edge while its two corner copies coincide.
    Opened, the sides are tested as any faces: at (1, 1, 0.9) rad f0 and f3 cross (an edge through a face), at
    (1, 1, 0.5) f3 passes over f0."""
    sc = SelfContact(cut_square())
    for rho in (1e-9, 1e-3, 0.5, 2.0, 3.1):
        for q in ([0.0, rho, 0.0], [0.0, -rho, 0.0]):
            assert sc(q) is None, q
    corner = [k for k, v in enumerate(sc.corner_vertex) if np.all(sc.pattern.vertices[v] == 0.0)]
    for q, crossed in (([1.0, 1.0, 0.9], True), ([1.0, 1.0, 0.5], False)):
        assert np.ptp(sc.corners(q)[corner], axis=0).max() > 0.1  # the cut open: its corner copies apart
        assert sides_cross(sc, q, 0, 3) == crossed
        assert (sc(q) is not None and "faces f0 and f3 touch" in sc(q)) == crossed


@pytest.mark.slow
def test_a_slit_crane_folds_on_past_its_own_cut():
    """Issue 27: a bird base with one wing slit along its diagonal (`fold_fixtures.slit_crane`), the slit's halves
    folding up about the valley e27 that continues the cut. Its letters' motion (e18 driven, as `validate` picks it)
    stopped at its first node on 'faces f8 and f15 touch; crease e27 at 0.0403883 rad ... already at the start', f8
    and f15 being the two sides of the cut. The cut stays closed all along (its corner copies 5e-14 of the size
    apart at most, measured) while e27 folds to 0.79 rad, and the motion runs to s = -2.1514 rad, where the neck and
    tail flaps f1 and f6 do cross: no edge passes through a face 5e-3 rad before, one does 5e-3 rad after (a trace
    on through the contact)."""
    pattern = read_fold(slit_crane()).pattern
    signs = assignment_signs(pattern)
    path = PatternPath(pattern, "e18", signs=signs)
    stop = path.stops[-1]
    assert stop.kind == "contact" and stop.detail.startswith("faces f1 and f6 touch")
    assert stop.s == pytest.approx(-2.1514, abs=1e-3) and len(path.s_nodes) > 10  # measured -2.151355, 43 nodes
    sc = SelfContact(pattern)
    copies = [k for k, v in enumerate(sc.corner_vertex) if np.all(pattern.vertices[v] == 0.0)]
    assert max(np.ptp(sc.corners(q)[copies], axis=0).max() for q in path.nodes) < 1e-12
    assert np.max(path.nodes[:, [c.name for c in pattern.creases].index("e27")]) > 0.75
    through = PatternPath(pattern, "e18", signs=signs, contact=False)
    before, after = through.evaluate(through.branches()[0].name, [stop.s + 5e-3, stop.s - 5e-3])[0]
    assert not sides_cross(sc, before, 1, 6) and sides_cross(sc, after, 1, 6)
