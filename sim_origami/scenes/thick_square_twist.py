"""Scene `thick-square-twist`: the square twist with thick panels, four Bennett vertices (Peng 2018, Fig 4-4).

Nine hull panels (`kinematics.thick_square_twist`), twelve crease hinges on their lifted lines, the central
square fixed, square edge AB driven; the four per-vertex loops are closed by connects on four cut creases.
No M/V coupling: the hinge heights alone select the mode string `modes` (1-based index into
`square_twist.RIGID`), default 5 = CSCS, the opposite class whose central square is a single slab. Faces that
share no vertex collide (solids inset RELIEF x b from every edge). Measured at the defaults (alpha 150 deg,
b 0.05 m, unit lengths): they stay >= 0.145 m apart over -2.4..2.4 and first touch at |rho_AB| = 2.8847085
(side_BC on corner_D, side_DA on corner_B), short of the zero-thickness flat-folded end pi; the onset moves to
3.0379 at b = 0.02 and 2.6432 at b = 0.1 (alpha 100, 120, 135, 160, 170 deg: 2.259, 2.757, 2.856, 2.863, 2.738),
and a force-limited servo driven to pi stops at 2.8847090.
"""

import itertools

from ..kinematics.square_twist import INPUT, RIGID
from ..kinematics.thick_square_twist import ThickSquareTwist
from .base import ANGLE_MARGIN, Param, Scene, choice, register
from .patterns import pattern_scene
from .thick_vertex4 import RELIEF

PARAMS = (
    Param("alpha", "deg", 150.0, "sector angle between pleat 1 and square edge 2 at each vertex; 90 < alpha < 180",
          lo=90 + ANGLE_MARGIN, hi=180 - ANGLE_MARGIN),
    Param("b", "m", 0.05, "thickness scale: square edges of a vertex b apart in height, pleat 1 a = b sin(alpha)"),
    Param(
        "modes",
        "",
        5.0,
        "rigid mode string (vertices A..D): " + ", ".join(f"{k + 1} {m}" for k, m in enumerate(RIGID)),
        lo=1,
        hi=len(RIGID),
        integer=True,
    ),
    Param("side", "m", 1.0, "side of the central square"),
    Param("pleat", "m", 1.0, "length of every pleat crease"),
)
# Default sweep of x = rho_AB (rad), as the zero-thickness scene's (the thick sheet has no flat bifurcation, but
# its closure's smallest kept singular value at flat is only 2e-2, ~ b/2).
PATH = (0.5, 2.4)
ROOT = "square"


@register("thick-square-twist", "square twist with thick panels: four Bennett vertices (Peng 2018, Fig 4-4), one rigid "
          "mode string selected by the hinge heights, input rho_AB", PARAMS)
def build(alpha: float, b: float, modes: float, side: float, pleat: float) -> Scene:
    kinematics = ThickSquareTwist(alpha, b, choice("modes", modes, RIGID), side, pleat)
    pattern = kinematics.pattern
    touching = set(pattern.touching_faces())
    return pattern_scene(
        "thick-square-twist", {"alpha": alpha, "b": b, "modes": modes, "side": side, "pleat": pleat}, kinematics,
        pattern, drive=INPUT, path=PATH, root=ROOT,
        notes=f"mode string {kinematics.modes}, no couplings; qpos = fold angle of the zero-thickness twist; panels "
        "are hinge hulls, faces sharing no vertex collide",
        collision_inset=RELIEF * b,
        contact_pairs=tuple(p for p in itertools.combinations(pattern.face_names, 2) if p not in touching),
    )
