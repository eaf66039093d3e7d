"""Thick-panel square twist: four Bennett vertices round a central square (Peng 2018, Fig 4-4; §3.3, §4.2).

The square twist of `square_twist` (same vertices, faces, crease names and fold angles rho) with every vertex
a thick Bennett vertex (`thick_vertex4`): vertex k's hinge i lies on the line through (x_k, y_k, h_i) along
its flat crease, h = f_k (0, a, a + b, b) + z_k (staircase, mode S) or f_k (0, a, a - b, -b) + z_k (zigzag,
mode C), a = b sin(alpha) (eqn 4-4c with sectors alpha, pi/2), f_k = +1 the thesis frame and -1 its mirror
(which follows the same mode, checked here), z_k a vertex offset. A square edge is a hinge of two vertices and
sits at ONE height: walking A -> D -> C -> B, vertex k lifts its crease 3 over its crease 2 by f_k b (S) or
-f_k b (C), and the four lifts must sum to zero.

Height rule (derived and checked here): with the thesis frame at every vertex (all f_k = +1, the
pattern's 90 deg rotation maps one vertex's layout onto the next) the heights close iff #S = #C, i.e. for
exactly the six rigid mode strings (`square_twist.RIGID`), and the central square is a single slab (two
levels) only for the opposite class CSCS / SCSC; the adjacent class leaves it three levels (a hull).
Derived here: the rule holds only in the thesis frame. Mirroring single vertices (f_k = -1) reverses their lift, so
every sign-consistent mode string (even #S) has three height-consistent layouts up to the global mirror, one of them
with a single-slab square (`layouts`). Heights do not select the rigid strings, kinematics does: a thick sheet
on a non-rigid string (loop gain K != 1) is immobile, mobility 0 even at the flat state (measured for all
three layouts of CCCC and SSSS; the zero-thickness sheet has mobility 4 there).

Kinematic equivalence: each thick vertex follows only its mode of the zero-thickness vertex with the same
fold angles (Peng 2018, §4.2), so the thick sheet folds exactly like `SquareTwist` on its mode string (the thick
per-vertex PoE loops close on that closed form to ~1e-15) and on no other: it has one branch through the
flat state, where the zero-thickness sheet's six cross (mobility 1 at flat, not 4).

Faces are the convex hulls of their hinge lines (`origami.pattern_mechanism`); each border edge takes the
height of the face's hinge parallel to it (`border_heights`), so a face whose hinges lie at two levels is
a full slab between them (corners: thickness b, sides: a with the thesis frame) and every hinge line lies
on its panel's surface.
"""

from dataclasses import replace
from itertools import product

import numpy as np

from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from .base import Branch, Event
from .square_twist import (
    CLASS_OF,
    CREASES,
    EDGES,
    LOOP_ORDER,
    RIGID,
    VERTICES,
    SquareTwist,
    check_modes,
    crease_pattern,
    loop_gain,
    vertex_sectors,
)
from .thick_vertex4 import hinge_heights

LAYOUT = {"S": "staircase", "C": "zigzag"}
THESIS_FRAME = (1, 1, 1, 1)


def _check_flips(flips: tuple[int, ...]) -> None:
    if len(flips) != 4 or set(flips) - {1, -1}:
        raise ParameterError(f"flips {flips!r}: give +1 (thesis frame) or -1 (mirrored layout) for each of A, B, C, D")


def crease_heights(alpha: float, b: float, modes: str, flips: tuple[int, ...] = THESIS_FRAME) -> dict[str, float]:
    """
    Hinge height (m) of every crease name, the lowest at 0 (module docstring). Vertex k (A..D) takes its mode's
    `thick_vertex4` layout times flips[k], offset so that each square edge has one height.

    Raises ParameterError naming the mode string when the heights do not close round the central square.
    """
    check_modes(modes)
    _check_flips(flips)
    if not b > 0:
        raise ParameterError(f"thickness scale b = {b:g} m; it must be positive")
    h = {EDGES[0]: 0.0}
    for k in LOOP_ORDER:
        v, local = VERTICES[k], flips[k] * hinge_heights(vertex_sectors(alpha), b, LAYOUT[modes[k]])
        z = h[EDGES[k]] - local[1]  # crease 2 is the square edge to the next corner, already placed
        name3 = EDGES[(k - 1) % 4]
        # heights are sums of +-a and +-b: a miss is 0 (rounding) or at least 2b
        if name3 in h and abs(h[name3] - (z + local[2])) > 1e-9 * b:
            raise ParameterError(
                f"modes {modes!r} with layout flips {flips}: hinge heights do not close round the central square "
                f"(edge {name3} at {h[name3]:.6g} and {z + local[2]:.6g} m). Each vertex lifts its crease 3 over "
                "its crease 2 by +b (staircase, mode S) or -b (zigzag, mode C), reversed where mirrored; the four "
                "lifts must cancel, i.e. #S = #C in the thesis frame"
            )
        h[name3], h[f"{v}1"], h[f"{v}4"] = z + local[2], z + local[0], z + local[3]
    low = min(h.values())
    return {name: h[name] - low for name in CREASES}


def square_levels(heights: dict[str, float]) -> int:
    """Distinct hinge heights on the central square's edges: 2 means a single slab."""
    return len({round(heights[e] / max(heights.values()), 9) for e in EDGES})


def layouts(alpha: float, b: float, modes: str) -> tuple[tuple[int, ...], ...]:
    """The flips (vertex A in the thesis frame; the global mirror adds as many) whose heights close for `modes`."""
    out = []
    for rest in product((1, -1), repeat=3):
        try:
            crease_heights(alpha, b, modes, (1, *rest))
        except ParameterError:
            continue
        out.append((1, *rest))
    return tuple(out)


def thick_pattern(
    alpha: float, b: float, modes: str, side: float = 1.0, pleat: float = 1.0, flips: tuple[int, ...] = THESIS_FRAME
) -> CreasePattern:
    """The square twist with `crease_heights` on its hinges, M/V of `modes` at rho_AB > 0, and `border_heights`."""
    base = crease_pattern(alpha, side, pleat, modes)
    h = crease_heights(alpha, b, modes, flips)
    creases = tuple(replace(c, height=h[c.name]) for c in base.creases)
    return replace(base, creases=creases, border_heights=_border_heights(base, creases))


def _border_heights(base: CreasePattern, creases: tuple[Crease, ...]) -> tuple[tuple[int, int, float], ...]:
    """Each free border edge at the height of the hinge of its face parallel to it (every face is a
    parallelogram; a face with no parallel hinge, none here, would keep its border out of the hull)."""
    lines = {frozenset((c.start, c.end)): c for c in creases}
    out = []
    for face in base.faces:
        edges = list(zip(face, face[1:] + face[:1], strict=True))
        for i, (p, q) in enumerate(edges):
            opposite = lines.get(frozenset(edges[(i + 2) % 4]))
            if frozenset((p, q)) not in lines and opposite is not None:
                out.append((p, q, opposite.height))
    return tuple(out)


class ThickSquareTwist(SquareTwist):
    """
    The thick square twist on one rigid mode string, driven by x = rho_AB in [-pi, pi] (module docstring).

    Parameters
    ----------
    alpha : float
      Sector angle (rad) between pleat 1 and square edge 2 of every vertex, in (pi/2, pi).
    b : float
      Thickness scale (m): height step between a vertex's hinges 2 and 3 (a = b sin alpha between 1 and 2).
    modes : str
      Vertex modes of A, B, C, D; one of the six rigid strings (`square_twist.RIGID`).
    side, pleat : float
      Central square side and pleat length (m).
    flips : 4 of +-1
      Thesis-frame (+1) or mirrored (-1) layout per vertex.
    """

    def __init__(
        self,
        alpha: float,
        b: float,
        modes: str = "CSCS",
        side: float = 1.0,
        pleat: float = 1.0,
        flips: tuple[int, ...] = THESIS_FRAME,
    ):
        super().__init__(alpha, side, pleat)
        pattern = thick_pattern(alpha, b, modes, side, pleat, flips)
        if modes not in RIGID:
            raise ParameterError(
                f"modes {modes!r}: loop gain K = {loop_gain(alpha, modes):.6g} != 1 (a rigid string has two S and "
                "two C vertices, Peng 2018, §3.3); its thick sheet is immobile (mobility 0 at flat)"
            )
        self.pattern, self.b, self.modes, self.flips = pattern, float(b), modes, tuple(flips)
        self.heights = {c.name: c.height for c in pattern.creases}
        zero = next(br for br in self._branches if br.name == modes)
        kinds = ", ".join(f"{v} {LAYOUT[m]}" for v, m in zip(VERTICES, modes, strict=True))
        text = (f"thick Bennett vertices ({kinds}) follow the zero-thickness branch {modes} only (class "
                f"{CLASS_OF[modes]}): {zero.description}")
        self._branches = (Branch(modes, text, zero.domain),)

    def events(self) -> tuple[Event, ...]:
        """No bifurcation at flat (the hinge layout selects the mode string); both ends fold every crease flat."""
        detail = "every crease folded flat at once (|rho| = pi); thick panels touch before (scene contact)"
        return tuple(Event("lock", end, (self.modes,), detail) for end in (-np.pi, np.pi))

    def gruebler(self) -> int:
        """Kutzbach: 12 creases - 6 per spatial loop (4 vertices) = -12; the pattern moves by its geometry."""
        return len(CREASES) - 6 * 4
