"""Zero-thickness waterbomb tessellation of rows x cols bases in the symmetric folding of Feng 2018, §5.3.

Layout (reconstructed here, as in `waterbomb`): base (i, j) is centred on A = (2 t j + t (i mod 2), i H) with
H = t cot(alpha) + h_C, so each row is shifted by half a base; its six triangles are those of
`waterbomb.unit_cell`. Every interior edge is a crease of one of nine types: A1 ... A6 (the creases at A), B2
(a top edge C -> B+, and C -> B-, which is B6 of the neighbouring B) and B4 (a side edge). The symmetric
folding of eqn 5-3 (every base alike, C an inverted B) gives every crease the fold angle of its type in the cell
(`waterbomb.path_folds`), on each of the cell's four branches; the tessellation's own per-vertex closure (at A, B
and C vertices) is the check that this is a motion of the sheet. Crease names: <type>_<i>_<j> for the base
(i, j) that owns it (side edges belong to the base on their left).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Coupling, LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from .base import Branch, Event, JointSpaceKinematics
from .waterbomb import CREASES, Waterbomb

# Cell crease whose fold angle each tessellation crease type takes (B6 folds as B2).
TYPE_OF = {"A1": "A1", "A2": "A2", "A3": "A3", "A4": "A4", "A5": "A5", "A6": "A6", "B2": "B2", "B6": "B2",
           "B4": "B4"}
# Creases that the symmetric folding makes equal (the cell's A3 = A5 = A6 = A2 and B6 = B2).
SYMMETRY_CLASS = {"A1": "A1", "A2": "A2", "A3": "A2", "A4": "A4", "A5": "A2", "A6": "A2", "B2": "B2", "B6": "B2",
                  "B4": "B4"}
ASSIGNMENT = {"A1": "M", "A2": "V", "A3": "V", "A4": "M", "A5": "V", "A6": "V", "B2": "M", "B6": "M", "B4": "M"}


def tessellation(alpha: float, beta: float, t: float, rows: int, cols: int) -> tuple[CreasePattern, tuple[str, ...]]:
    """The sheet's crease pattern and each crease's cell type (module docstring)."""
    cot = 1.0 / np.tan(alpha)
    hc = t * np.sin(beta) / (np.sin(alpha) * np.sin(alpha + beta))
    index: dict[tuple[int, int], int] = {}
    points: list[tuple[float, float]] = []

    def vertex(x: float, y: float) -> int:
        key = (round(x / t * 1e6), round(y / t * 1e6))
        if key not in index:
            index[key] = len(points)
            points.append((x, y))
        return index[key]

    faces, names, edges = [], [], {}
    for i in range(rows):
        for j in range(cols):
            ax, ay = 2 * t * j + t * (i % 2), i * (t * cot + hc)
            A = vertex(ax, ay)
            C, Bp, Cbp = vertex(ax, ay + hc), vertex(ax + t, ay + t * cot), vertex(ax + t, ay - t * cot)
            Bb, Cbm, Bm = vertex(ax, ay - hc), vertex(ax - t, ay - t * cot), vertex(ax - t, ay + t * cot)
            for k, tri in enumerate(((A, Bp, C), (A, C, Bm), (A, Bm, Cbm), (A, Cbm, Bb), (A, Bb, Cbp), (A, Cbp, Bp))):
                faces.append(tri)
                names.append(f"f{k}_{i}_{j}")
            for kind, a, b in (("A1", A, C), ("A2", A, Bp), ("A3", A, Cbp), ("A4", A, Bb), ("A5", A, Cbm),
                               ("A6", A, Bm), ("B2", Bp, C), ("B6", Bm, C), ("B4", Bp, Cbp)):
                edges.setdefault(frozenset((a, b)), (f"{kind}_{i}_{j}", kind, a, b))
    directed = {(a, b) for f in faces for a, b in zip(f, f[1:] + f[:1], strict=True)}
    creases, kinds = [], []
    for name, kind, a, b in edges.values():
        if (a, b) in directed and (b, a) in directed:  # interior: a crease between two faces
            creases.append(Crease(name, a, b, ASSIGNMENT[kind]))
            kinds.append(kind)
    return CreasePattern(np.array(points), tuple(faces), tuple(creases), tuple(names)), tuple(kinds)


class WaterbombSheet(JointSpaceKinematics):
    """
    The symmetric zero-thickness tessellation driven by x = rho of the A4 crease of base (0, 0) (the cell's
    input; frames, signs and branches as in `waterbomb.Waterbomb`).

    Parameters
    ----------
    alpha, beta, t : as `waterbomb.Waterbomb`.
    rows, cols : int
      Bases along y and x, each >= 1; at least one B vertex must be interior (rows >= 2, cols >= 2).
    """

    input_name = "rhoA4"

    def __init__(self, alpha: float, beta: float, t: float, rows: int, cols: int):
        for name, value in (("rows", rows), ("cols", cols)):
            if int(value) != value or value < 2:
                raise ParameterError(f"{name} = {value:g}; the tessellation needs an integer >= 2 (an interior B)")
        self.cell = Waterbomb(alpha, beta, t)
        self.rows, self.cols = int(rows), int(cols)
        self.pattern, self.kinds = tessellation(alpha, beta, t, self.rows, self.cols)
        self.joint_names = tuple(f"rho_{c.name}" for c in self.pattern.creases)
        self._columns = np.array([CREASES.index(TYPE_OF[k]) for k in self.kinds])
        names = [c.name for c in self.pattern.creases]
        self.input_crease = "A4_1_1" if "A4_1_1" in names else names[self.kinds.index("A4")]

    def branches(self) -> tuple[Branch, ...]:
        return self.cell.branches()

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        values, valid = self.cell.evaluate(branch, x)
        return values[:, self._columns], valid

    def events(self) -> tuple[Event, ...]:
        return self.cell.events()

    def gruebler(self) -> int:
        """Kutzbach: creases - 3 per interior vertex - one per symmetry coupling."""
        return len(self.joint_names) - 3 * len(self.pattern.interior_vertices()) - len(self.couplings())

    def classes(self) -> dict[str, list[str]]:
        """Creases that fold alike in the symmetric folding (eqn 5-3), by class: A1, A4, A2 (= A3, A5, A6), B2 (and
        B6), B4."""
        out: dict[str, list[str]] = {}
        for crease, kind in zip(self.pattern.creases, self.kinds, strict=True):
            out.setdefault(SYMMETRY_CLASS[kind], []).append(crease.name)
        return out

    def couplings(self) -> tuple[tuple[str, str], ...]:
        """Every crease coupled to the first of its class."""
        return tuple((name, names[0]) for names in self.classes().values() for name in names[1:])

    def loop_system(self) -> LoopSystem:
        """Per-vertex closure of the tessellation with the symmetric-folding couplings."""
        index = {c.name: k for k, c in enumerate(self.pattern.creases)}
        return self.pattern.loop_system(tuple(Coupling(index[a], index[b]) for a, b in self.couplings()))

    def loop_input(self) -> tuple[int, float]:
        return [c.name for c in self.pattern.creases].index(self.input_crease), 1.0
