"""Scene `kokotsakis`: 3x3 Kokotsakis meshes of four degree-4 vertices (Peng 2018, §2.3-2.5).

Nine panels (central, four sides, four corners) as bodies, twelve crease hinges, the central panel fixed and
inner crease AB driven (`kinematics.kokotsakis`). The spanning tree keeps the four inner creases and one
outer crease per corner panel; the other outer crease of each corner panel is cut and closed by connects,
one per vertex loop. `case` picks Peng 2018's mesh: 1 = Example 1 (rotation case, identical generic vertices,
eqn 2-34), 2 = Example 2 (variant rotation case, flat-foldable vertices, eqn 2-38), 3 = the two-fold case with
identical (mirrored) vertices, 4 = the plane-symmetric case with identical (mirrored) vertices (both
reconstructed here):
an isosceles trapezoid with two straight crease lines, so the flat state is also the start of a 2-DOF family.
"""

from ..errors import ParameterError
from ..kinematics.kokotsakis import INPUT, Kokotsakis, example
from .base import Param, Scene, register
from .patterns import pattern_scene

PARAMS = (
    Param(
        "case",
        "",
        1.0,
        "1 = Example 1 (eqn 2-34), 2 = Example 2 (eqn 2-38), 3 = two-fold case, 4 = plane-symmetric (3, 4 ours)",
        lo=1,
        hi=4,
        integer=True,
    ),
    Param("outer", "m", 0.5, "length of the eight outer creases (central sides |AB| = |BC| = 1 m)"),
)
# Default sweep of x = rho_AB (rad) per case, clipped to each branch's domain by Scene.branch_path, kept away
# from the flat bifurcation, where the closure's smallest nonzero singular value vanishes (measured about 0.73 x
# on case 1 odd2, 0.28 x on odd3). Case 2 starts at 0.5: mode S folds BC only about 0.09 x as far as AB, so its
# smallest nonzero singular value is 0.021 at x = 0.3 (0.036 at 0.5) and the numeric solve, stopped at a 1e-14
# residual, was off by 7.4e-13 rad there (5.5e-14 from 0.5).
PATHS = {1: (0.3, 1.1), 2: (0.5, 1.5), 3: (0.3, 1.1), 4: (0.3, 1.1)}


def _case(value: float) -> int:
    """The integer case number of a float parameter; ParameterError otherwise."""
    if value not in PATHS:
        raise ParameterError(f"case = {value:g}; the Kokotsakis cases are {', '.join(str(c) for c in PATHS)}")
    return int(value)


@register("kokotsakis", "3x3 Kokotsakis mesh of four degree-4 vertices (Peng 2018, §2.5), case 1-4, input rho_AB",
          PARAMS)
def build(case: float, outer: float) -> Scene:
    number = _case(case)
    kinematics = Kokotsakis(example(number), outer=outer)
    return pattern_scene(
        "kokotsakis", {"case": float(number), "outer": outer}, kinematics, kinematics.pattern, drive=INPUT,
        path=PATHS[number], root="central",
        notes="hinge qpos = fold angle rho (> 0 valley seen from +z); central panel fixed; one connect pair per "
              "vertex loop on a cut outer crease",
    )
