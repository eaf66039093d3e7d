"""Scene `waterbomb-twist`: the generalized waterbomb tube twisting from its fully folded middle row (Feng, Ma and
Chen 2020, §3; Feng 2018, §6.4).

The mechanism is the tube's (`scenes.waterbomb_tube.tube_mechanism`: every triangular face a body, every crease a
hinge, the seam creases closed by connects), driven at the middle row's upper-right diagonal A<r0>_0_2 (eta02 =
pi - rho), with the twist's symmetry imposed by joint couplings (`WaterbombTwist.couplings`: the dihedral group D_n
of the twisted tube plus the plane symmetry of each half; 163 on the 6 x 5 tube, 97 on the 6 x 3). The radial
contraction keeps those symmetries too, so the coupled mechanism carries both motions; the scene's branches are the
two twist senses and the contraction, which meet at the fully folded middle row (the sweeps stay clear of it).
`tube_mechanism` reads only pattern, layout, input_crease and couplings, which `WaterbombTwist` has as well.
With `row` != 0 (at beta = beta_max, e.g. `-p row=1 -p beta=42.0105238`) that row twists instead, driven at its
own A<row + r0>_0_2 (Feng, Ma and Chen 2020, Fig 16 paths I, III; `WaterbombTwist`, "Other rows"), on the two
twist senses only.
"""

from ..kinematics.waterbomb_tube import beta_max_residual
from ..kinematics.waterbomb_twist import WaterbombTwist
from .base import ACUTE, Condition, Param, Scene, register
from .waterbomb_tube import TUBE_ROWS, TUBE_UNITS, check_size, tube_mechanism

PARAMS = (
    Param("n", "", 6, "units round the tube (>= 3)", **TUBE_UNITS),
    # 3 rows by default: a full `validate` of the 6 x 5 tube (3 branches, 258 creases) measured 7.6 min of CPU, 2.3 of
    # them in the bifurcation study (since shortened to the preset's own sweep time), against 1.4 min for 6 x 3;
    # `-p m=5` gives the 6 x 5 tube of Feng, Ma and Chen 2020 (numbers below)
    Param("m", "", 3, "rows, odd (a middle row to fold)", **TUBE_ROWS),
    Param("alpha", "deg", 40.0, "design angle alpha, below atan(1 / cos(180/n)) (Feng, Ma and Chen 2020, eqn 38)",
          **ACUTE),
    Param("beta", "deg", 40.0, "design angle beta, at most beta_max(alpha) (Feng, Ma and Chen 2020, eqn 40)",
          **ACUTE),
    Param("a", "m", 0.5, "half-width of a unit"),
    # rows other than 0 twist from the contraction's end only at beta = beta_max (Feng, Ma and Chen 2020, Fig 16
    # paths I, III)
    Param("row", "", 0.0, "row that twists: 0 the middle row, +1 .. (m-1)/2 above, -1 .. below",
          lo=-TUBE_ROWS["hi"], hi=TUBE_ROWS["hi"], integer=True),
)
# The symmetry couplings are soft (MuJoCo joint equalities) and set the path error, which falls as the square of
# the sweep time. Default sweeps (each branch's domain less Scene.branch_path's margins: the counter-clockwise twist
# from 9 deg of input past the fully folded middle row, the clockwise one up to 6.6 deg before it), every crease,
# 6 x 5 tube: stiff 8x 7.2e-8 (ccw), 1.1e-7 (cw), 1.3e-7 rad (contraction), 12800 steps, 19-22 s CPU each; stiff
# 4x 2.9e-7 (ccw), 4.4e-7 (cw), 9-10 s; fast 8x 1.6e-6 (ccw, over the 1e-6 tolerance). 6 x 3 tube, stiff 8x:
# 2.6e-8 (ccw), 3.5e-8 rad (cw), 6.4 s; 6 x 1: 1.4e-8 rad, 0.5 s. Those fast figures were with MuJoCo's own
# regulariser; with the presets' (scaled 0.01) fast 8x on 6 x 3 measured 4.9e-9 rad (ccw) in 3.8 s of CPU against
# stiff's 2.6e-8 in 7.1 s, so the scene runs fast.


# A row other than the middle one twists only at beta = beta_max (eqn 40): beta as typed (e.g. 42.01 for
# 42.0105238) is moved onto it within its precision.
CONDITION = Condition(
    "beta = beta_max(alpha, n) (Feng, Ma and Chen 2020, eqn 40), which a row other than 0 needs to twist",
    lambda v: float(beta_max_residual(v["alpha"], v["beta"], int(v["n"]))) if v["row"] else 0.0,
)


@register("waterbomb-twist", "generalized waterbomb tube, n units x m rows (m odd), twist of the fully folded middle "
          "row (any row at beta_max, Fig 16) under the twist's symmetry (Feng, Ma and Chen 2020, §3; Feng 2018, "
          "§6.4), input rho of the twisting row's upper-right diagonal", PARAMS, CONDITION)
def build(n: float, m: float, alpha: float, beta: float, a: float, row: float) -> Scene:
    check_size(n, m)
    kinematics = WaterbombTwist(n, m, alpha, beta, a, row)
    lo, hi = kinematics.branch("twist-cw").domain[0], kinematics.branch("twist-ccw").domain[1]
    return Scene(
        name="waterbomb-twist", params={"n": n, "m": m, "alpha": alpha, "beta": beta, "a": a, "row": row},
        kinematics=kinematics, mechanism=tube_mechanism(kinematics), loop_joints=kinematics.crease_names,
        drive_joint=kinematics.input_crease, drive_scale=1.0, path=(lo, hi),
        pattern=kinematics.pattern,
        notes=f"{int(n)} x {int(m)} tube, row {kinematics.row} twisting; {len(kinematics.couplings)} "
        "twist-symmetry couplings; "
        f"{len(kinematics.layout.seam)} seam creases closed by connects",
    )
