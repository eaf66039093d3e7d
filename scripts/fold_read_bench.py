"""Seconds to read large FOLD files (`fold.read_fold`) and to check them (the pattern's loop system).

Files are generated the way crease-pattern editors write them: a Miura-ori grid given as coordinates, edges and
M/V letters only (faces built from the planar edge graph), the same grid with faces_vertices, a triangulated
square grid with faces, and a folded (3-D) Miura-ori that is unfolded. "check" = `CreasePattern.loop_system()`
(one closure per interior vertex) and its residual at the flat state. Wall-clock seconds on the 2-core machine
shared with other jobs, best of `repeat`; no test asserts them.

Measured (issue 15): see docs/fold_files.md. Before CreasePattern indexed its vertices once, a 10k-vertex file
took 22 s to read.

    python scripts/fold_read_bench.py [repeat]
"""

import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

from sim_origami.fold import read_fold

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from fold_fixtures import miura_letters_only  # the tests' fixture: a CP editor's letters-only Miura


def miura(rows: int, cols: int, faces: bool, fold: float = 0.0) -> dict:
    """A Miura-ori of rows x cols parallelograms (zig 0.3, unit sides) as the tests write it; `fold` > 0 folds it
    rigidly (3-D)."""
    zig = 0.3
    doc = miura_letters_only(rows, cols, zig=zig)
    vid = lambda i, j: j * (cols + 1) + i  # noqa: E731
    if faces or fold:
        doc["faces_vertices"] = [[vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)]
                                 for j in range(rows) for i in range(cols)]
    if fold:
        doc["vertices_coords"] = folded_miura(rows, cols, zig, fold).tolist()
    return doc


def folded_miura(rows: int, cols: int, zig: float, theta: float) -> np.ndarray:
    """Vertices of the rigidly folded Miura-ori (unit parallelograms, offset zig) at fold parameter theta."""
    # Standard Miura-ori kinematics: each strip between horizontal creases is a zig-zag of parallelograms.
    a, b = 1.0, np.hypot(1.0, zig)
    gamma = np.arctan2(1.0, zig)  # sector angle between the horizontal and zig-zag creases
    H = a * np.sin(theta) * np.sin(gamma)
    S = b * np.cos(theta) * np.tan(gamma) / np.sqrt(1 + np.cos(theta) ** 2 * np.tan(gamma) ** 2)
    L = a * np.sqrt(1 - np.sin(theta) ** 2 * np.sin(gamma) ** 2)
    V = b / np.sqrt(1 + np.cos(theta) ** 2 * np.tan(gamma) ** 2)
    out = []
    for j in range(rows + 1):
        for i in range(cols + 1):
            out.append([i * S, j * L + (V if i % 2 else 0.0), (H if j % 2 else 0.0)])
    return np.array(out)


def triangulated(n: int) -> dict:
    """An n x n square grid, each square split by a diagonal; creases U inside, B on the border."""
    vid = lambda i, j: j * (n + 1) + i  # noqa: E731
    xy = [[i / n, j / n] for j in range(n + 1) for i in range(n + 1)]
    faces = []
    for j in range(n):
        for i in range(n):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            faces += [[a, b, c], [a, c, d]]
    count = Counter(frozenset(side) for f in faces for side in zip(f, f[1:] + f[:1], strict=True))
    pairs = [sorted(e) for e in count]
    return {"vertices_coords": xy, "edges_vertices": pairs, "faces_vertices": faces,
            "edges_assignment": ["B" if count[frozenset(e)] == 1 else "U" for e in pairs]}


def best(work, repeat: int) -> tuple[float, object]:
    times, out = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        out = work()
        times.append(time.perf_counter() - start)
    return min(times), out


def main(repeat: int = 3) -> None:
    cases = [
        ("Miura 70 x 70, letters only (faces built)", miura(70, 70, faces=False)),
        ("Miura 70 x 70, faces_vertices", miura(70, 70, faces=True)),
        ("Miura 99 x 99 (10k vertices), faces_vertices", miura(99, 99, faces=True)),
        ("triangulated 50 x 50 (5,000 faces)", triangulated(50)),
        ("triangulated 99 x 99 (10k vertices)", triangulated(99)),
        ("Miura 50 x 50 folded in 3-D (unfolded)", miura(50, 50, faces=True, fold=0.8)),
    ]
    print(f"{'file':48s} {'vertices':>8s} {'faces':>6s} {'creases':>7s} {'read s':>7s} {'check s':>7s}")
    for name, doc in cases:
        read_s, got = best(lambda doc=doc: read_fold(doc), repeat)
        pattern = got.pattern

        def check(pattern=pattern):
            system = pattern.__class__(pattern.vertices, pattern.faces, pattern.creases, pattern.face_names,
                                       pattern.border_heights).loop_system()
            return float(system.residual_norm(np.zeros((1, len(pattern.creases)))).max())

        check_s, residual = best(check, repeat)
        assert residual <= 1e-12, residual
        print(f"{name:48s} {len(pattern.vertices):8d} {len(pattern.faces):6d} {len(pattern.creases):7d} "
              f"{read_s:7.2f} {check_s:7.2f}")


if __name__ == "__main__":
    main(*(int(a) for a in sys.argv[1:]))
