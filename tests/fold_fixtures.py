"""FOLD fixtures shared by several test modules, written the way other tools write them, and validate on them."""

import json
from pathlib import Path

import numpy as np

from sim_origami.cli import main
from sim_origami.fold import read_fold
from sim_origami.kinematics.numeric_pattern import BRANCH, PatternPath, assignment_signs
from sim_origami.origami import pattern_mechanism
from sim_origami.studies.poisson import vertex_positions


def miura_letters_only(rows: int, cols: int, dx: float = 1.0, dy: float = 1.0, zig: float = 0.3) -> dict:
    """
    A Miura-ori crease pattern as a CP editor (Rabbit Ear) exports it: coordinates, edges and lower-case letters, no
    faces. Columns dx apart, rows dy apart, every odd column raised by zig; straight creases along x.
    """
    verts = [[i * dx, j * dy + (zig if i % 2 else 0.0)] for j in range(rows + 1) for i in range(cols + 1)]
    vid = lambda i, j: j * (cols + 1) + i  # noqa: E731
    edges, assign = [], []
    for j in range(rows + 1):
        for i in range(cols):
            edges.append([vid(i, j), vid(i + 1, j)])
            assign.append("b" if j in (0, rows) else ("m" if j % 2 else "v"))
    for j in range(rows):
        for i in range(cols + 1):
            edges.append([vid(i, j), vid(i, j + 1)])
            assign.append("b" if i in (0, cols) else ("v" if (i + j) % 2 else "m"))
    return {"file_spec": 1.1, "file_creator": "Rabbit Ear", "vertices_coords": verts, "edges_vertices": edges,
            "edges_assignment": assign}


def write(tmp_path: Path, name: str, doc: dict) -> Path:
    """`doc` as a .fold file in tmp_path, named after `name`."""
    path = tmp_path / (name.replace(" ", "_").replace(",", "") + ".fold")
    path.write_text(json.dumps(doc))
    return path


def validated(tmp_path: Path, name: str, doc: dict, *options: str) -> tuple[int, dict]:
    """`sim-origami validate --fold` (preset fast) on `doc` written as a file: exit code and report.json."""
    out = tmp_path / "out"
    path = write(tmp_path, name, doc)
    code = main(["validate", "--fold", str(path), "--preset", "fast", "--out", str(out), *options])
    return code, json.loads((out / "report.json").read_text())


def degree4_letters() -> dict:
    """A degree-4 vertex (sectors about 79, 110, 80, 91 deg), MVVV, as a text editor writes it: four triangles."""
    return {"file_spec": 1.2, "file_creator": "A text editor",
            "vertices_coords": [[0.0, 0.0], [1.0, 0.0], [0.2, 1.0], [-1.0, -0.1], [0.1, -1.0]],
            "edges_vertices": [[0, 1], [0, 2], [0, 3], [0, 4], [1, 2], [2, 3], [3, 4], [4, 1]],
            "edges_assignment": ["M", "V", "V", "V", "B", "B", "B", "B"],
            "faces_vertices": [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]}


def folded_xyz(doc: dict, crease: str, fraction: float) -> np.ndarray:
    """
    The exact 3-D vertex coordinates (n, 3) of the flat pattern `doc` folded rigidly along its M/V letters' motion
    driven by `crease`, at `fraction` of the way to where that motion ends (every vertex of the file, in its order).
    """
    fold = read_fold(doc)
    pattern = fold.pattern
    path = PatternPath(pattern, crease, signs=assignment_signs(pattern))
    lo, hi = path.branches()[0].domain
    q = path.evaluate(BRANCH, [fraction * (hi if abs(hi) >= abs(lo) else lo)])[0][0]
    poses = pattern_mechanism(pattern, root=pattern.face_names[0]).body_poses(q)
    xyz, _ = vertex_positions(pattern, {name: poses[name] for name in pattern.face_names})
    return xyz[0]


def folded_form(doc: dict, xyz: np.ndarray, decimals: int | None = None) -> dict:
    """`doc` as a folded form only (3-D coordinates, faces, letters), as Rabbit Ear or a FOLD example writes one;
    coordinates rounded to `decimals` (None: full precision)."""
    coords = xyz if decimals is None else np.round(xyz, decimals)
    faces = doc.get("faces_vertices") or [list(f) for f in read_fold(doc).pattern.faces]
    return doc | {"frame_classes": ["foldedForm"], "frame_attributes": ["3D"], "vertices_coords": coords.tolist(),
                  "faces_vertices": faces}


# Bases as crease-pattern editors write them (issue 27) ------------------------------------------------------------


def ccw_faces(coords: list[list[float]], edges: list[list[int]]) -> list[list[int]]:
    """The bounded faces of a planar straight-line graph, each counter-clockwise (what an editor's face builder
    writes): half-edge walk, turning at each vertex to the edge just clockwise of the way back."""
    xy = np.asarray(coords, dtype=float)
    around: dict[int, list[int]] = {}
    for a, b in edges:
        around.setdefault(a, []).append(b)
        around.setdefault(b, []).append(a)
    for v, ws in around.items():
        ws.sort(key=lambda w: np.arctan2(*(xy[w] - xy[v])[::-1]))
    faces, seen = [], set()
    for a, b in [(a, b) for a, b in edges] + [(b, a) for a, b in edges]:
        if (a, b) in seen:
            continue
        face, (u, v) = [], (a, b)
        while (u, v) not in seen:
            seen.add((u, v))
            face.append(u)
            ws = around[v]
            u, v = v, ws[ws.index(u) - 1]
        p = xy[face]
        if np.sum(p[:, 0] * np.roll(p[:, 1], -1) - np.roll(p[:, 0], -1) * p[:, 1]) > 0:  # not the outer boundary
            faces.append(face)
    return faces


def _crease_pattern(creator: str, coords: list, edges: list, letters: list, spec: float = 1.1) -> dict:
    """A FOLD crease-pattern frame: 2-D coordinates, edges, letters and counter-clockwise faces."""
    faces = ccw_faces(coords, edges)
    return {"file_spec": spec, "file_creator": creator, "file_classes": ["singleModel"],
            "frame_classes": ["creasePattern"], "frame_attributes": ["2D"], "vertices_coords": coords,
            "edges_vertices": edges, "edges_assignment": letters, "faces_vertices": faces}


def waterbomb_base() -> dict:
    """
    The traditional waterbomb base on the unit square as Rabbit Ear exports it, with edges_foldAngle +-180 deg (V
    positive, M negative, borders 0). Both diagonals and one midline (the other is no crease of this base): a
    degree-6 centre, sectors 45, 90, 45, 45, 90, 45 deg (alternate sums 180: Kawasaki), the four diagonal halves V and
    the two midline halves M (|M - V| = 2: Maekawa).
    """
    coords = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.5], [1.0, 1.0], [0.0, 1.0], [0.0, 0.5], [0.5, 0.5]]
    edges = [[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [6, 0], [6, 1], [6, 3], [6, 4], [6, 2], [6, 5]]
    letters = list("BBBBBBVVVVMM")
    doc = _crease_pattern("Rabbit Ear", coords, edges, letters)
    doc["edges_foldAngle"] = [{"V": 180.0, "M": -180.0}.get(a, 0.0) for a in letters]
    return doc


def frog_base() -> dict:
    """
    The traditional frog base on the unit square (a preliminary base, its four flaps squashed and petal-folded) as an
    editor writes it: 29 vertices, 16 border edges, 42 M/V creases and 10 F lines (creased on the way, flat in the
    base; Rabbit Ear's frog writes them so), every edge split where lines cross, 40 faces. Exact 22.5-deg geometry,
    t = tan(pi/8) = sqrt(2) - 1, centre O; each flap k (its spine the midline half towards edge midpoint M_k, turned
    by k x 90 deg) has
    - the spine O-H M and H-M V, H at sqrt(2)/4 from O where the petal's hinge crosses it;
    - the squash lines O-E+- V from O at +-22.5 deg off the spine to E+- = O + (sqrt(2)/4, +-t sqrt(2)/4), and on
      from E+- to the border at Q+- = O + (1/2, +-t/2) F;
    - the petal hinge E- - H - E+ M and the petal's kite lines M-E+- V;
    - a line V from each E to the square's corner beside it (22.5 deg off the border);
    and the diagonals: the one through corners (0, 0) and (1, 1) F (the preliminary base's flat faces), the other M.
    Interior vertices (their F lines left out): O 14 creases, 6 M 8 V; each H 4 (3 M, 1 V); each E 4 (1 M, 3 V).
    """
    root2, t = np.sqrt(2.0), np.tan(np.pi / 8)
    rot = [np.array([[c, -s], [s, c]], dtype=float) for c, s in ((1, 0), (0, 1), (-1, 0), (0, -1))]  # k x 90 deg
    coords: list[list[float]] = []

    def at(k: int, x: float, y: float) -> int:
        p = (0.5 + rot[k] @ np.array([x, y])).tolist()
        for i, q in enumerate(coords):
            if abs(q[0] - p[0]) < 1e-12 and abs(q[1] - p[1]) < 1e-12:
                return i
        coords.append(p)
        return len(coords) - 1

    h = root2 / 4
    centre = at(0, 0.0, 0.0)
    edges, letters = [], []

    def line(a: int, b: int, letter: str) -> None:
        edges.append([a, b])
        letters.append(letter)

    for k in range(4):
        M, H = at(k, 0.5, 0.0), at(k, h, 0.0)
        Ep, Em, Qp, Qm = at(k, h, h * t), at(k, h, -h * t), at(k, 0.5, 0.5 * t), at(k, 0.5, -0.5 * t)
        Cp, Cm = at(k, 0.5, 0.5), at(k, 0.5, -0.5)
        line(Cm, Qm, "B")
        line(Qm, M, "B")
        line(M, Qp, "B")
        line(Qp, Cp, "B")
        line(centre, H, "M")
        line(H, M, "V")
        for E, Q, C in ((Ep, Qp, Cp), (Em, Qm, Cm)):
            line(centre, E, "V")
            line(E, Q, "F")
            line(H, E, "M")
            line(M, E, "V")
            line(E, C, "V")
        line(centre, Cp, "F" if k % 2 == 0 else "M")
    return _crease_pattern("ORIPA", coords, edges, letters)


def three_flap_base() -> dict:
    """
    A three-flap base: the rabbit-ear molecule of a scalene triangle of paper, corners A (0, 0), B (1, 0), C (0.3, 0.8)
    (angles 69.4, 48.8, 61.8 deg). The three angle bisectors meet at the incentre I, and the perpendicular from I to
    AB ends at its foot P: a degree-4 vertex, sectors 90 - B/2 (P to B), 90 + A/2, 90 + B/2, 90 - A/2 (A to P), whose
    alternate sums are 180 deg (Kawasaki). Folded flat, the three corners are the three flaps. Letters: the bisectors
    V, the perpendicular M (the odd one out bounds the smallest sector: 3 V 1 M, Maekawa).
    """
    A, B, C = np.array([0.0, 0.0]), np.array([1.0, 0.0]), np.array([0.3, 0.8])
    a, b, c = np.linalg.norm(B - C), np.linalg.norm(C - A), np.linalg.norm(A - B)
    incentre = (a * A + b * B + c * C) / (a + b + c)
    foot = np.array([incentre[0], 0.0])
    coords = [A.tolist(), foot.tolist(), B.tolist(), C.tolist(), incentre.tolist()]
    edges = [[0, 1], [1, 2], [2, 3], [3, 0], [4, 0], [4, 2], [4, 3], [4, 1]]
    return _crease_pattern("fold-validator", coords, edges, list("BBBBVVVM"), spec=1.2)


def slit_crane(doubled: bool = False) -> dict:
    """
    A crane's bird base (Rabbit Ear's, `test_fold_bird.bird`, its marks F) with one wing slit: the diagonal from
    the corner (0, 0) to the petal's hinge point 13 (0.354, 0.354) is a cut C, and the diagonal's inner part e27
    (13 to the centre) a valley V, so the two halves of the slit wing fold up about it, hinged along the cut's own
    line (not a flat-foldable base then: 7 folded creases at the centre). `doubled`: the cut as two coincident edges
    on a doubled corner vertex (15 = vertex 0), one per side, each bordering one face; else one C edge between the
    two faces (the reader doubles the corner itself).
    """
    from test_fold_bird import RABBIT_EAR, bird

    doc = bird(RABBIT_EAR[:26] + "CV" + RABBIT_EAR[28:])
    faces = ccw_faces(doc["vertices_coords"], doc["edges_vertices"])
    if doubled:  # the side of the cut towards vertex 12 takes the copy of the corner
        doc["vertices_coords"].append(list(doc["vertices_coords"][0]))
        copy = len(doc["vertices_coords"]) - 1
        for face in faces:
            if 0 in face and (12 in face or 7 in face):
                face[face.index(0)] = copy
        doc["edges_vertices"] = [[copy if v == 0 else v for v in e] if sorted(e) in ([0, 12], [0, 7]) else e
                                 for e in doc["edges_vertices"]]
        doc["edges_vertices"].append([13, copy])
        doc["edges_assignment"].append("C")
    doc["faces_vertices"] = faces
    return doc
