"""Scene `triangle-twist`: the generalised triangle twist of Feng 2018, §3.2-3.3, input rho_AB.

Seven faces (`kinematics.triangle_twist`), nine crease hinges, the triangle T fixed, edge AB driven; the three
per-vertex loops are closed by connects on three cut creases. `scheme` (1 to 8) picks one of Feng 2018's
rigid-foldable scheme classes RIGID_SCHEMES (PPQ, PQQ, PRS, PSS, QRS, QRR, PSR, QSR) and builds its EXAMPLES
realisation, epsilon from the thesis's formula (eqns 3-12 to 3-37); scheme 4 (PSS) is its Fig. 3-5 pattern
(55, 50, 50, 45 deg, epsilon = 35.4368 deg). Nothing imposes the M/V assignment: the sheet's only motion is the
rigid scheme.

`assigned` builds a sheet with one scheme imposed by exact linear joint couplings rho_z3 = rho_z1 (mode C) or
-rho_z1 (mode S) at every vertex: a flat-foldable vertex's two modes meet only at flat, so the coupled sheet has
the scheme's M/V assignment (up to a global flip). A scheme whose loop gain is not 1 keeps only the flat state.
Not registered: a locked sheet has nothing to validate; it serves blockage runs.
"""

from ..kinematics.triangle_twist import (
    INPUT,
    RIGID_SCHEMES,
    VERTICES,
    Z1,
    TriangleTwist,
    TwistAngles,
    example_angles,
    modes_of,
)
from .base import Param, Scene, choice, register
from .patterns import pattern_scene

PARAMS = (
    Param("scheme", "", 4.0, "rigid scheme class: " + ", ".join(f"{k + 1} {s}" for k, s in enumerate(RIGID_SCHEMES)),
          lo=1, hi=len(RIGID_SCHEMES), integer=True),
    Param("d", "m", 1.0, "side AB of the central triangle"),
    Param("pleat", "m", 0.5, "pleat length (shorter where two pleats of a panel converge)"),
)
# Default sweep of x = rho_AB (rad). Near flat the closure Jacobian has singular values ~ x (flat mobility 3), so
# the soft closures' angle error peaks at the start of a sweep: fast preset, 2 s sweep, measured 1.2e-7 (PQQ) to
# 1.7e-6 (QSR) rad, always near x = 0.55.
PATH = (0.5, 2.4)
ROOT = "T"


def _scene(name: str, kinematics: TriangleTwist, params: dict, couplings: tuple, notes: str) -> Scene:
    return pattern_scene(name, params, kinematics, kinematics.pattern, drive=INPUT, path=PATH, root=ROOT,
                         couplings=couplings, notes=notes)


@register("triangle-twist", "generalised triangle twist, zero thickness: three flat-foldable vertices round a "
          "triangle (Feng 2018, §3.2-3.3), one rigid M-V scheme per `scheme`, input rho_AB", PARAMS)
def build(scheme: float, d: float, pleat: float) -> Scene:
    name = choice("scheme", scheme, RIGID_SCHEMES)
    types, angles = example_angles(name)
    kinematics = TriangleTwist(angles, d, pleat, types)
    return _scene(
        "triangle-twist", kinematics, {"scheme": scheme, "d": d, "pleat": pleat}, (),
        f"scheme class {name} realised as {types}; no M/V imposed; hinge qpos = fold angle rho",
    )


def assigned(types: str, angles: TwistAngles, d: float = 1.0, pleat: float = 0.5) -> Scene:
    """
    The triangle twist at `angles` with scheme `types` (at A, B, C) imposed by joint couplings (module docstring).
    Its kinematics are the angles' rigid schemes (which need not include `types`); its creases carry `types`' M/V.
    """
    modes = modes_of(angles, types)
    kinematics = TriangleTwist(angles, d, pleat, types)
    couplings = tuple((f"{v}3", Z1[v], 1.0 if m == "C" else -1.0) for v, m in zip(VERTICES, modes, strict=True))
    return _scene(
        f"triangle-twist-{types}", kinematics, {"d": d, "pleat": pleat}, couplings,
        f"scheme {types} imposed by couplings rho_z3 = rho_z1 (mode C) / -rho_z1 (mode S); hinge qpos = rho",
    )
