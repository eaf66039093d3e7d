"""Scenes `waterbomb-vertex`, `waterbomb-thick` and `waterbomb-sheet`: the symmetric waterbomb (Feng 2018, ch. 5).

Both are the same two-vertex cell (`kinematics.waterbomb`): ten triangular faces, eleven crease hinges, the
periodic copies B1 = A4 and B5 = A6 as joint couplings, driven at crease A4. The zero-thickness cell also
carries the thesis's symmetry couplings (A3 = A5 = A6 = A2, B6 = B2) and has four branches from flat; the thick
cell (hinges on panel surfaces) carries none and has one, path I, with the same fold angles: the thick
model is kinematically equivalent to the zero-thickness path I and loses the bifurcation.
Thick faces are the convex hulls of their hinge lines (`solids.hinge_hull`; border edges at the height of the
periodic neighbour's crease): Fig. 5-8's panel placement is lost, and a slab between a face's lowest and
highest hinge would bury the middle hinge (B2 in face A12), so each hull keeps every hinge on its surface.
Faces that share no vertex collide (solids inset RELIEF x a from every edge). They never touch on path I of
the defaults (closest 0.071 m, down to rho_A4 = -3.14); they touch first for alpha > 45 deg, faces A43 and
B12, at rho_A4 = -3.14 (alpha 45.5), -2.83 (46), -2.23 (50), -1.78 (55), for every beta, mu and a tried
(beta 20-40, mu 0.5-2, a 0.005-0.05): Feng 2018's "to avoid the interference at vertex A, 0 < alpha <= pi/4"
(§5.4), which the thesis states without a collision check and these runs confirm.
`waterbomb-sheet` is the zero-thickness tessellation of rows x cols bases (`kinematics.waterbomb_sheet`): every
crease folds as its type in the cell, checked by the sheet's own closure at A, B and C vertices.
"""

import itertools

from ..kinematics.waterbomb import FACES, Waterbomb
from ..kinematics.waterbomb_sheet import WaterbombSheet
from .base import ACUTE, Param, Scene, Tuning, register
from .patterns import pattern_scene
from .thick_vertex4 import RELIEF

ANGLES = (
    Param("alpha", "deg", 40.0, "design angle alpha (sector at A next to the vertical creases)", **ACUTE),
    Param("beta", "deg", 40.0, "design angle beta; alpha + beta < 90", **ACUTE),
    Param("t", "m", 0.5, "half-width of one base"),
)
THICK = (
    Param("mu", "", 0.5, "thickness ratio mu (B's link 34 over link 23); mu = 1 with alpha = beta keeps path II",
          lo=1e-3, hi=100),
    Param("a", "m", 0.05, "thickness unit a' (B's link 23)"),
)
# Default sweep of x = rho_A4 (rad), kept where the cell is well conditioned. The cells carry joint couplings
# (symmetry, periodic copies), whose MuJoCo rows are softened through dof_invweight0, and near the flat bifurcation
# and the folded end (smallest closure singular value 0.09 -> 0.007 at -2.6) their violation is amplified: with
# MuJoCo's own regulariser, fast at 2 s measured 2.0e-2 rad over -0.4..-2.6 and 1.2e-4 over -0.5..-1.8, and stiff
# (Euler 1.25 ms) beat it (2.4e-8 at 16x). With the presets' regulariser scaled by 0.01 fast measured 1.2e-6 (cell)
# and 6.2e-7 (thick cell) at 2 s, against stiff's 2.4e-8 at 16x.
PATH = (-0.5, -1.8)
# The thick cell's closure is thin in the direction of its hinge offsets: with a = 0.02 m the projection's
# angle error was 1.9e-13 rad (0.05 m: 2.8e-14) and the fast path error 5.6e-7 (0.05 m: 1.1e-7).
ROOT, DRIVE = "A12", "A4"


def _scene(name: str, kinematics: Waterbomb, params: dict[str, float], notes: str, **contact) -> Scene:
    couplings = tuple((a, b, 1.0) for a, b in kinematics.couplings)
    return pattern_scene(
        name,
        params,
        kinematics,
        kinematics.pattern,
        drive=DRIVE,
        path=PATH,
        root=ROOT,
        couplings=couplings,
        notes=notes,
        **contact,
    )


@register("waterbomb-vertex", "symmetric waterbomb cell, zero thickness: two spherical 6R vertices (Feng 2018, §5.3), "
          "input rho_A4", ANGLES)
def build_vertex(alpha: float, beta: float, t: float) -> Scene:
    return _scene(
        "waterbomb-vertex", Waterbomb(alpha, beta, t), {"alpha": alpha, "beta": beta, "t": t},
        "couplings: periodic B1 = A4, B5 = A6; symmetry A3 = A5 = A6 = A2, B6 = B2 (eqns 5-3 to 5-5)",
    )


@register("waterbomb-thick", "symmetric waterbomb cell with thick panels: two plane-symmetric Bricard linkages "
          "(Feng 2018, §5.4), input rho_A4", ANGLES + THICK)
def build_thick(alpha: float, beta: float, t: float, mu: float, a: float) -> Scene:
    kinematics = Waterbomb(alpha, beta, t, mu, a)
    touching = set(kinematics.pattern.touching_faces())
    return _scene(
        "waterbomb-thick", kinematics, {"alpha": alpha, "beta": beta, "t": t, "mu": mu, "a": a},
        "couplings: periodic B1 = A4, B5 = A6 only; hinge heights (2 + mu) a on A's valleys, (1 + mu) a on B2, B6, "
        "2 a on B4; qpos = fold angle of the zero-thickness cell; panels are hinge hulls, faces sharing no vertex "
        "collide",
        collision_inset=RELIEF * a,
        contact_pairs=tuple(p for p in itertools.combinations(FACES, 2) if p not in touching),
    )


# The 2 x 2 sheet's 18 couplings (soft joint equalities) lag up to 5.3x more than `sweep_rate.LAG_S2` allows for its
# path's joint rates: it sweeps 3x the rule's time (docs/performance.md, "The sweep's duration"). Its former 1.25x
# fast step changed neither the path error nor the steps under the path rule (the sweep grew with the step).
SHEET_TUNING = Tuning(sweep_time_scale=3.0, why="its 18 soft couplings lag more than the path rule allows: at the "
                      "rule's time `validate` measured 1.1e-6 rad (tolerance 1e-6), at 3x 1.3e-7")
# The sheet's panels carry collision solids inset by SHEET_INSET x t from every edge, and every pair of panels that
# shares no vertex may collide (Scene.self_contact, as the Miura and corrugated sheets).
SHEET_INSET = 0.05
# Largest sheet accepted: 16 x 16 bases (1536 panels) builds in 2.6 s of CPU (8 x 8: 0.33 s).
SHEET_SIZE = {"lo": 2, "hi": 16, "integer": True, "limit": "at most 16 x 16 bases: 1536 panels build in about 3 s"}
SHEET = (
    Param("rows", "", 2, "rows of bases (>= 2)", **SHEET_SIZE),
    Param("cols", "", 2, "bases per row (>= 2)", **SHEET_SIZE),
)


@register("waterbomb-sheet", "zero-thickness waterbomb tessellation of rows x cols bases in the symmetric "
          "folding of Feng 2018, §5.3, input one A4 crease", ANGLES + SHEET)
def build_sheet(alpha: float, beta: float, t: float, rows: float, cols: float) -> Scene:
    kinematics = WaterbombSheet(alpha, beta, t, rows, cols)
    pattern, drive = kinematics.pattern, kinematics.input_crease
    # MuJoCo couples tree hinges only: each symmetry class is coupled to its first hinge in the spanning tree
    # (the cut creases follow from the closures).
    tree = {pattern.creases[k].name for k in pattern.spanning_creases((drive,))}
    couplings = []
    for names in kinematics.classes().values():
        kept = [n for n in names if n in tree]
        couplings += [(n, kept[0], 1.0) for n in kept[1:]]
    params = {"alpha": alpha, "beta": beta, "t": t, "rows": rows, "cols": cols}
    return pattern_scene(
        "waterbomb-sheet",
        params,
        kinematics,
        pattern,
        drive=drive,
        path=PATH,
        couplings=tuple(couplings),
        collision_inset=SHEET_INSET * t,
        self_contact=True,
        tuning=SHEET_TUNING,
        notes=f"{int(rows)} x {int(cols)} bases; {len(couplings)} symmetry couplings on tree hinges",
    )
