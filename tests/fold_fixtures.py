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
            "edges_assignment": assign}  # fmt: skip


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
            "faces_vertices": [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]]}  # fmt: skip


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
                  "faces_vertices": faces}  # fmt: skip
