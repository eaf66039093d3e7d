"""Scene `square-twist`: the zero-thickness square twist of Peng 2018, §3.3, input rho_AB.

Nine faces (`kinematics.square_twist`), twelve crease hinges, the central square fixed, square edge AB
driven; the four per-vertex loops are closed by connects on four cut creases. Nothing imposes an M/V
assignment, so from flat the sheet can take any of the six rigid mode strings (the kinematics' branches).

`assigned` builds the same sheet with one mode imposed per vertex by an exact linear joint coupling,
rho_4 = -rho_2 (mode C) or rho_4 = rho_2 (mode S): on a flat-foldable vertex the two modes meet only at
flat, so the coupled sheet has exactly the M/V assignment of the mode string (up to a global flip).
A rigid string then folds with one DOF, on the kinematics' branch of that name and no other; the locked ones
(all-C, all-S) keep only the flat state, so none of the kinematics' branches is theirs. It is not registered:
a locked sheet has nothing to validate, and it serves blockage runs. Measured (fast preset, the servo class
kp 50, +-20 N m, driven from flat to 1 rad and held 1 s): all-C and all-S stay within 2.4e-5 and 7.2e-5 rad of
flat with the servo saturated; CCSS and CSCS reach the target with at most 0.14 N m, on the closed form to
6.5e-8 and 1.6e-7 rad.
"""

from ..creases import CreasePattern
from ..kinematics.square_twist import EDGES, INPUT, VERTICES, SquareTwist, check_modes, crease_pattern
from .base import ANGLE_MARGIN, Param, Scene, register
from .patterns import pattern_scene

PARAMS = (
    Param("alpha", "deg", 150.0, "sector angle between pleat 1 and square edge 2 at each vertex; 90 < alpha < 180",
          lo=90 + ANGLE_MARGIN, hi=180 - ANGLE_MARGIN),
    Param("side", "m", 1.0, "side of the central square"),
    Param("pleat", "m", 1.0, "length of every pleat crease"),
)
# Default sweep of x = rho_AB (rad). Near flat the closure Jacobian has a singular value ~ x, so the soft
# closures' angle error peaks at the start of a sweep: fast preset, 2 s sweep, worst branch (SCSC) measured
# 1.8e-6 rad from x = 0.3 and 4.8e-7 from 0.5.
PATH = (0.5, 2.4)
ROOT = "square"


def _scene(
    name: str,
    kinematics: SquareTwist,
    pattern: CreasePattern,
    couplings: tuple[tuple[str, str, float], ...],
    notes: str,
) -> Scene:
    params = {"alpha": kinematics.alpha, "side": kinematics.side, "pleat": kinematics.pleat}
    return pattern_scene(name, params, kinematics, pattern, drive=INPUT, path=PATH, root=ROOT, couplings=couplings,
                         notes=notes)


@register("square-twist", "square twist, zero thickness: four flat-foldable vertices round a square "
          "(Peng 2018, §3.3), input rho_AB", PARAMS)
def build(alpha: float, side: float, pleat: float) -> Scene:
    kinematics = SquareTwist(alpha, side, pleat)
    return _scene(
        "square-twist", kinematics, kinematics.pattern, (),
        "no M/V imposed: six rigid mode strings leave the flat state; hinge qpos = fold angle rho",
    )


def assigned(modes: str, alpha: float, side: float = 1.0, pleat: float = 1.0) -> Scene:
    """
    The square twist with vertex modes `modes` (vertices A, B, C, D) imposed by joint couplings on each
    vertex's crease 4 (a pleat) against its crease 2 (a square edge); module docstring. Its pattern carries
    the M/V of `modes` at rho_AB > 0.
    """
    check_modes(modes)
    couplings = tuple(
        (f"{v}4", EDGES[k], -1.0 if mode == "C" else 1.0)
        for k, (v, mode) in enumerate(zip(VERTICES, modes, strict=True))
    )
    return _scene(
        f"square-twist-{modes}", SquareTwist(alpha, side, pleat), crease_pattern(alpha, side, pleat, modes), couplings,
        f"vertex modes {modes} imposed by couplings rho_4 = -rho_2 (C) / rho_2 (S); hinge qpos = fold angle rho",
    )
