"""Scene `corrugated-sheet`: a double-corrugated tessellation of rows x cols units P or Q (Peng 2018, §3.2.2).

Every face of `kinematics.corrugated_sheet.sheet_pattern` is a body, every crease a hinge; the spanning tree
keeps the input crease u1_1 (the first unit's AD for P, AF for Q) and the first unit's central face f1_1 is
fixed. One crease per interior vertex is cut and closed by two connects. There are no M/V joint limits, so the
flat state is the bifurcation of the six rigid mode strings (the kinematics' branches); the default sweep starts
away from it. Panels carry collision solids inset from their edges, and every pair of panels that shares no
vertex may collide (Scene.self_contact, as the Miura sheet).
"""

from ..kinematics.corrugated_sheet import INPUT, ROOT, CorrugatedSheet
from .base import Param, Scene, register
from .corrugated import PARAMS as UNIT_PARAMS
from .corrugated import PATH as UNIT_PATH
from .corrugated import unit_name
from .patterns import pattern_scene

# Largest tessellation accepted: 16 x 16 units (1089 panels); 8 x 8 (289 panels) builds in 0.3 s of CPU.
SIZE = {"lo": 1, "hi": 16, "integer": True, "limit": "at most 16 x 16 units: 1089 panels build in about 2 s"}
PARAMS = (
    Param("unit", "", 0.0, "which unit repeats: 0 = P (parallelogram ABCD), 1 = Q (parallelogram ABEF)",
          lo=0, hi=1, integer=True),
    Param("rows", "", 2, "units along v (the AB direction), >= 1", **SIZE),
    Param("cols", "", 2, "units along u (the AD direction), >= 1", **SIZE),
    *UNIT_PARAMS[1:],  # the unit's design angles and lengths, as scene `corrugated-unit`
)
# Collision solids are inset from every panel edge by this fraction of the shortest length (as `miura-sheet`).
INSET = 0.05


@register("corrugated-sheet", "double-corrugated tessellation of rows x cols units P or Q (Peng 2018, §3.2.2), every "
          "vertex in the mode of its unit vertex; branches = the unit's six rigid mode strings", PARAMS)
def build(
    unit: float,
    rows: float,
    cols: float,
    alpha: float,
    beta: float,
    gamma: float,
    delta: float,
    L1: float,
    L2: float,
    L3: float,
) -> Scene:
    name = unit_name(unit)
    kinematics = CorrugatedSheet(name, (alpha, beta, gamma, delta), (L1, L2, L3), rows, cols)
    params = {"unit": unit, "rows": rows, "cols": cols, "alpha": alpha, "beta": beta, "gamma": gamma,
              "delta": delta, "L1": L1, "L2": L2, "L3": L3}
    return pattern_scene(
        "corrugated-sheet",
        params,
        kinematics,
        kinematics.pattern,
        drive=INPUT,
        path=UNIT_PATH,
        root=ROOT,
        collision_inset=INSET * min(L1, L2, L3),
        self_contact=True,
        notes=f"{int(rows)} x {int(cols)} units {name}; hinge qpos = fold angle rho (> 0 valley from +z); "
        "no M/V joint limits",
    )
