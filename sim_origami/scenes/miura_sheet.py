"""Scene `miura-sheet`: a Miura-ori sheet of rows x cols panels, driven by one vertical crease.

Every panel is a body; the spanning tree (breadth-first from the input crease's panel) keeps rows x cols - 1
hinges and every other crease (one per interior vertex) is closed by two connects. The closed form is
`kinematics.miura_sheet` (mode S at every vertex).
"""

import numpy as np

from ..kinematics.miura_sheet import MiuraSheet
from .base import ACUTE, Param, Scene, register
from .patterns import pattern_scene

# Largest sheet accepted: 32 x 32 panels (1024 bodies, 1984 creases) builds in 1.2 s of CPU, and a validate's cost
# grows faster than the panel count (16 x 16: 3.4 s of MuJoCo CPU, scripts/miura_sheet_bench.py).
SIZE = {"lo": 2, "hi": 32, "integer": True, "limit": "at most 32 x 32 panels: 1024 bodies build in about 1 s"}
PARAMS = (
    Param("rows", "", 4, "panels along y (>= 2)", **SIZE),
    Param("cols", "", 4, "panels along x (>= 2)", **SIZE),
    Param("a", "m", 0.5, "panel width along x"),
    Param("b", "m", 0.5, "vertical panel edge"),
    Param("gamma", "deg", 60.0, "panel angle between a vertical and a zigzag edge, in (0, 90)", **ACUTE),
)
# Default sweep: 5% to 90% of the fold range (-pi, pi) of the input crease.
PATH = (0.05 * np.pi, 0.9 * np.pi)
# The spanning tree is breadth-first from the drive's panel, which sits mid-sheet (`MiuraSheet`): on 16 x 16 its
# depth is 16 instead of Kruskal's 27-31, which took the fast error (2 s sweep) from 1.2e-5 to 2.0e-6 rad and the
# CPU from 1.7 to 0.9 s.
# Collision solids are inset from every panel edge by this fraction of the shorter side: panels sharing a
# vertex are excluded anyway, the inset keeps the others from touching through the nominal plate thickness.
INSET = 0.05


@register("miura-sheet", "Miura-ori sheet of rows x cols panels (flat-foldable vertices in mode S), input one "
          "vertical crease", PARAMS)
def build(rows: float, cols: float, a: float, b: float, gamma: float) -> Scene:
    kinematics = MiuraSheet(rows, cols, a, b, gamma)
    params = {"rows": rows, "cols": cols, "a": a, "b": b, "gamma": gamma}
    return pattern_scene(
        "miura-sheet",
        params,
        kinematics,
        kinematics.pattern,
        drive=kinematics.input_crease,
        path=PATH,
        collision_inset=INSET * min(a, b),
        self_contact=True,
        breadth_first=True,
        notes=f"{int(rows)} x {int(cols)} panels; input {kinematics.input_crease}",
    )
