"""Scene `corrugated-unit`: double-corrugated unit P or Q as a 3 x 3 Kokotsakis mesh (Peng 2018, §3.2.2).

Nine parallelogram faces (`kinematics.corrugated.unit_pattern`), twelve crease hinges, the central face
fixed and the thesis's input crease driven (P: AD = theta_1a, Q: AF = theta_2f). The spanning tree keeps
the four inner creases and one outer crease per corner face; the other four outer creases are closed by
connects, one loop per vertex. There are no M/V joint limits, so the flat state is the bifurcation of
all six rigid mode combinations (the kinematics' branches); the default sweep starts away from it.
"""

from ..errors import ParameterError
from ..kinematics.corrugated import CorrugatedUnit
from .base import SECTOR, Param, Scene, register
from .patterns import pattern_scene

PARAMS = (
    Param("unit", "", 0.0, "which unit: 0 = P (parallelogram ABCD), 1 = Q (parallelogram ABEF)",
          lo=0, hi=1, integer=True),
    Param("alpha", "deg", 135.0, "design angle alpha (largest sector, P's angle at A); Peng 2018, Fig 3-2", **SECTOR),
    Param("beta", "deg", 60.0, "design angle beta (Q's angle at A)", **SECTOR),
    Param("gamma", "deg", 45.0, "design angle gamma = 180 - alpha, the smallest sector", **SECTOR),
    Param("delta", "deg", 120.0, "design angle delta = 180 - beta", **SECTOR),
    Param("L1", "m", 1.0, "|AB|"),
    Param("L2", "m", 1.0, "|AD| (P), and Q's outer creases"),
    Param("L3", "m", 1.0, "|AF| (Q), and P's outer creases"),
)
# Default sweep of the input (rad): from 0.3 (the closure's smallest singular value grows with the fold
# from 0 at flat) to 2.0, short of the fully folded lock at pi where the largest gains (9.9 on Q's SSCC)
# drive some creases towards pi fast.
PATH = (0.3, 2.0)


def unit_name(unit: float) -> str:
    """'P' for unit = 0, 'Q' for 1; ParameterError otherwise."""
    if unit not in (0.0, 1.0):
        raise ParameterError(f"unit = {unit:g}; use 0 for P or 1 for Q")
    return "PQ"[int(unit)]


@register("corrugated-unit", "double-corrugated unit P or Q (Peng 2018, §3.2.2), 3 x 3 mesh of 4 flat-foldable "
          "vertices; branches = the six rigid vertex-mode combinations", PARAMS)
def build(unit: float, alpha: float, beta: float, gamma: float, delta: float, L1: float, L2: float, L3: float) -> Scene:
    name = unit_name(unit)
    kinematics = CorrugatedUnit(name, (alpha, beta, gamma, delta), (L1, L2, L3))
    drive = kinematics.input_name.removeprefix("rho")
    params = {"unit": unit, "alpha": alpha, "beta": beta, "gamma": gamma, "delta": delta, "L1": L1, "L2": L2, "L3": L3}
    return pattern_scene(
        "corrugated-unit",
        params,
        kinematics,
        kinematics.pattern,
        drive=drive,
        path=PATH,
        root=name,
        notes=f"unit {name}; hinge qpos = fold angle rho (> 0 valley from +z); no M/V joint limits",
    )
