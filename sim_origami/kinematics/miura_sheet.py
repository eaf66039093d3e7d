"""Miura-ori sheet: rows x cols parallelogram panels, every vertex a flat-foldable degree-4 vertex (numpy only).

Flat layout (metres). Vertex (i, j), i = 0..cols, j = 0..rows, sits at (i a, j b + (i mod 2) h) with
h = a cot(gamma): the "vertical" crease lines x = i a are straight, the "zigzag" lines zig by h between
columns, and gamma in (0, 90) deg is the panel angle between a vertical edge and a zigzag edge. Panel (i, j)
is the parallelogram with lower-left corner (i, j).

Every interior vertex has the creases up, left, down, right (counter-clockwise) with sectors
(gamma, pi - gamma, pi - gamma, gamma) in even columns and (pi - gamma, gamma, gamma, pi - gamma) in odd ones:
flat-foldable, folding in the mode S of Peng 2018, §3.2.1 (rho_down = -rho_up, rho_right = rho_left) with the
tan-half multiplier m = tan(rho_left/2) / tan(rho_up/2) of `vertex4.flat_foldable_multipliers` (even
columns; the odd columns' is -m). Propagating along the lines gives the closed form of the whole sheet
in the input x = rho of the vertical crease above vertex (i0, j0), the interior vertex nearest the centre with
i0 even (i0 = 1 for one column), so that the drive sits mid-sheet:

    vertical crease above (i, j):          rho = (-1)^(i + j - i0 - j0) x
    zigzag crease from (i, j) to (i + 1, j): rho = (-1)^(j - j0 + i0) 2 atan(m tan(x/2))

Fold angles follow `sim_origami.creases` (rho > 0 valley seen from +z); x > 0 makes the vertical crease above
(i0, j0) a valley. Branch 'miura' spans (-pi, pi) (every crease folds flat together at +-pi) and crosses the
flat state, where each vertical line could also fold alone (a multi-DOF bifurcation, not listed).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from .base import Branch, Event, JointSpaceKinematics
from .vertex4 import flat_foldable_multipliers

BRANCH = "miura"


def vertex_index(i: int, j: int, rows: int) -> int:
    """Index of flat-layout vertex (i, j) (column i, row j)."""
    return i * (rows + 1) + j


def miura_pattern(
    rows: int, cols: int, a: float, b: float, gamma: float, signs: NDArray | None = None
) -> CreasePattern:
    """
    The sheet's crease pattern (module docstring); creases named v<i>_<j> (vertical, above vertex (i, j)) and
    z<i>_<j> (zigzag, from (i, j) to (i + 1, j)); M/V from `signs` (+1 valley) when given, else U.
    """
    h = a / np.tan(gamma)
    vertices = np.array([(i * a, j * b + (i % 2) * h) for i in range(cols + 1) for j in range(rows + 1)])
    faces, names = [], []
    for i in range(cols):
        for j in range(rows):
            v = [vertex_index(i, j, rows), vertex_index(i + 1, j, rows), vertex_index(i + 1, j + 1, rows),
                 vertex_index(i, j + 1, rows)]
            faces.append(tuple(v))
            names.append(f"p{i}_{j}")
    creases = []
    for i in range(1, cols):
        for j in range(rows):
            creases.append((f"v{i}_{j}", vertex_index(i, j, rows), vertex_index(i, j + 1, rows)))
    for i in range(cols):
        for j in range(1, rows):
            creases.append((f"z{i}_{j}", vertex_index(i, j, rows), vertex_index(i + 1, j, rows)))
    mv = ["U"] * len(creases) if signs is None else ["V" if s > 0 else "M" for s in signs]
    return CreasePattern(
        vertices,
        tuple(faces),
        tuple(Crease(n, s, e, m) for (n, s, e), m in zip(creases, mv, strict=True)),
        tuple(names),
    )


class MiuraSheet(JointSpaceKinematics):
    """
    The Miura-ori sheet driven by one vertical crease (module docstring for frames, signs and the closed form).

    Parameters
    ----------
    rows, cols : int
      Panels along y and along x, each >= 2 (so that the sheet has an interior vertex).
    a, b : float
      Panel width along x and vertical edge length (m), > 0.
    gamma : float
      Panel angle (rad) in (0, pi/2).
    """

    input_name = "rho_input"

    def __init__(self, rows: int, cols: int, a: float, b: float, gamma: float):
        for name, value in (("rows", rows), ("cols", cols)):
            if int(value) != value or value < 2:
                raise ParameterError(f"{name} = {value:g}; a Miura sheet needs an integer >= 2 (an interior vertex)")
        if not 0 < gamma < np.pi / 2:
            raise ParameterError(f"gamma = {np.rad2deg(gamma):.6g} deg; the panel angle must lie in (0, 90) deg")
        for name, value in (("a", a), ("b", b)):
            if not value > 0:
                raise ParameterError(f"{name} = {value:g} m; panel sides must be positive")
        self.rows, self.cols, self.a, self.b, self.gamma = int(rows), int(cols), float(a), float(b), float(gamma)
        self.i0, self.j0 = (2 * max(1, self.cols // 4) if self.cols > 2 else 1), max(1, self.rows // 2)
        self.m = float(flat_foldable_multipliers([gamma, np.pi - gamma, np.pi - gamma, gamma])["S"][0])
        self.pattern = miura_pattern(self.rows, self.cols, a, b, gamma, self._signs(0.5))
        self.joint_names = tuple(f"rho_{c.name}" for c in self.pattern.creases)
        self.input_crease = f"v{self.i0}_{self.j0}"

    def _parity(self) -> tuple[NDArray, NDArray]:
        """(-1)^(i + j - i0 - j0) of the vertical creases and (-1)^(j - j0 + i0) of the zigzag ones."""
        vertical = [(-1) ** (i + j - self.i0 - self.j0) for i in range(1, self.cols) for j in range(self.rows)]
        zigzag = [(-1) ** (j - self.j0 + self.i0) for i in range(self.cols) for j in range(1, self.rows)]
        return np.array(vertical, dtype=float), np.array(zigzag, dtype=float)

    def _signs(self, x: float) -> NDArray:
        return np.sign(self.folds(np.array([x]))[0])

    def folds(self, x: NDArray) -> NDArray:
        """Fold angles (n, n_creases) at inputs x (n,), creases in pattern order."""
        vertical, zigzag = self._parity()
        z = 2 * np.arctan(self.m * np.tan(x / 2))
        return np.concatenate([x[:, None] * vertical, z[:, None] * zigzag], axis=1)

    def branches(self) -> tuple[Branch, ...]:
        return (
            Branch(BRANCH, "every vertex in mode S (vertical lines zig, zigzag lines fold alike)", (-np.pi, np.pi)),
        )

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        values = self.folds(x)
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        """Locks at +-pi. The flat state is singular (each straight vertical line could also fold alone) but
        those motions are not listed branches, so it is not reported as a bifurcation between branches."""
        return tuple(
            Event("lock", end, (BRANCH,), "every crease folds flat: the sheet is folded") for end in (-np.pi, np.pi)
        )

    def gruebler(self) -> int:
        """Kutzbach: creases - 3 per interior vertex."""
        return len(self.joint_names) - 3 * (self.rows - 1) * (self.cols - 1)

    def loop_system(self) -> LoopSystem:
        return self.pattern.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return [c.name for c in self.pattern.creases].index(self.input_crease), 1.0
