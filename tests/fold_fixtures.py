"""FOLD fixtures shared by several test modules, written the way other tools write them, and validate on them."""

import json
from pathlib import Path

from sim_origami.cli import main


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
