"""Scene `bricard-plane`: the plane-symmetric Bricard 6R (Feng 2018, §4.2-4.5), driven by theta2; link 6 is ground.

`case` picks a Table 4-1 preset (5 to 10) and its geometry; 0 uses a, b, c, alpha, beta, gamma, R2, R3 as given
(the case 10 values where not given). Geometry given without `case` means case 0; geometry given with a nonzero
case is refused, never silently replaced. The defaults are case 10 (two 6R paths crossing at theta2 = 0 and 180 deg).
Case 7 is a structure (Delta < 0 for every finite theta2; the loop closes only at one rigid
configuration): building it raises AssemblyError, which the command line reports with exit code 2.
"""

import numpy as np

from ..errors import AssemblyError, ParameterError
from ..geometry import wrap
from ..kinematics.bricard_plane import TABLE_4_1, Geometry, PlaneSymmetricBricard
from ..linkage import dh_mechanism
from .base import OFFSET, TWIST, Param, Scene, register

_CASE10 = TABLE_4_1[10]
PARAMS = (
    Param("a", "m", _CASE10.a, "link length a12 = a61", zero_ok=True),
    Param("b", "m", _CASE10.b, "link length a23 = a56", zero_ok=True),
    Param("c", "m", _CASE10.c, "link length a34 = a45", zero_ok=True),
    Param("alpha", "deg", float(np.rad2deg(_CASE10.alpha)), "twist alpha12 (alpha61 = 360 - alpha)", **TWIST),
    Param("beta", "deg", float(np.rad2deg(_CASE10.beta)), "twist alpha23 (alpha56 = 360 - beta)", **TWIST),
    Param("gamma", "deg", float(np.rad2deg(_CASE10.gamma)), "twist alpha34 (alpha45 = 360 - gamma)", **TWIST),
    Param("R2", "m", 0.0, "offset R2 (R6 = -R2)", **OFFSET),
    Param("R3", "m", 0.0, "offset R3 (R5 = -R3)", **OFFSET),
    Param("case", "", 10.0, "Table 4-1 case 5..10 (its geometry, R = 0), or 0 for the values given; giving any of "
          "a, b, c, alpha, beta, gamma, R2, R3 without case means case 0", lo=0, hi=10, integer=True,
          replaces=("a", "b", "c", "alpha", "beta", "gamma", "R2", "R3")),
)

# The default sweep is centred in the widest input interval shared by the branches and free of events
# (bifurcations, turning points), and spans PATH_SHARE of it, at most 2 PATH_HALF_WIDTH. MuJoCo's fast
# path error grows with the span and near singular poses: case 10 (joint lines nearly dependent along
# its whole motion, 5th/1st singular value <= 0.04) measured 5.3e-6 rad over 0.45..2.54 rad, 9.4e-7 rad
# over the 0.8 rad sweep kept (tolerance 4e-6); cases 5, 6, 9 stay below 1.3e-7.
PATH_SHARE = 0.7
PATH_HALF_WIDTH = 0.4
# The cut joint (6) is closed at +/- (a + b + c) along its axis. On case 10 (sweep 1.2..1.8 rad) anchors
# at +-0.25 m left 5.1e-5 rad of fast path error, +-1 m 3.6e-6, +-2 m 1.2e-6, +-4 m 6.7e-7: a stiffer
# closure of the cut hinge. The closure-site gap grows with the anchor distance (case 6: 1.8e-7 m).


def geometry_for(case: float, given: Geometry) -> tuple[int, Geometry]:
    """(case number, geometry): a Table 4-1 preset, or `given` for case 0."""
    number = int(np.rint(case))
    if number != case or (number != 0 and number not in TABLE_4_1):
        raise ParameterError(f"case = {case:g}; use 0 (the given geometry) or a Table 4-1 case {min(TABLE_4_1)}..10")
    return number, (given if number == 0 else TABLE_4_1[number])


def structure_message(kinematics: PlaneSymmetricBricard, number: int) -> str:
    """One line saying why this geometry has no motion driven by theta2."""
    lo, hi = kinematics.classification().delta_range
    g = kinematics.geometry
    label = f"case {number}" if number else (
        f"the geometry a = {g.a:g}, b = {g.b:g}, c = {g.c:g} m, alpha = {np.rad2deg(g.alpha):g}, beta = "
        f"{np.rad2deg(g.beta):g}, gamma = {np.rad2deg(g.gamma):g} deg, R2 = {g.R2:g}, R3 = {g.R3:g} m"
    )
    places = kinematics.isolated_assemblies()
    if places:
        conf = ", ".join(f"{v + 0.0:.4g}" for v in np.round(np.rad2deg(wrap(places[0][1])), 4))
        return (
            f"{label} is a structure: Delta < 0 for every theta2 (min {lo:.4g}, max {hi:.4g} over finite theta2); "
            f"the loop closes only at the rigid configuration theta = ({conf}) deg; it has no motion"
        )
    return (
        f"{label} cannot be assembled: Delta < 0 for every theta2 (min {lo:.4g}, max {hi:.4g}) and no configuration "
        f"closes the loop"
    )


def default_path(kinematics: PlaneSymmetricBricard) -> tuple[float, float]:
    """
    A sweep in the widest event-free input interval inside the domain of every branch that shares the
    first branch's domain (branches on other arcs of theta2, e.g. the offset geometry OFFSETS of
    tests/published/feng2018.py, cannot share one sweep: `Scene` has a single path).
    """
    branches = kinematics.branches()
    lo, hi = branches[0].domain
    grid = np.linspace(lo, hi, 7201)
    ok = np.ones(grid.shape, dtype=bool)
    for b in branches:
        inside = kinematics.evaluate(b.name, grid)[1]
        if not np.any(inside & ok):
            continue
        ok &= inside
        # Scene.branch_path clips a sweep to [0.95 lo, 0.95 hi] of the raw domain: stay inside both.
        inner_lo = 0.95 * b.domain[0] if b.domain[0] < 0 else b.domain[0]
        inner_hi = 0.95 * b.domain[1] if b.domain[1] > 0 else b.domain[1]
        ok &= (grid > inner_lo) & (grid < inner_hi)
    for e in kinematics.events():
        ok &= np.abs(wrap(grid - e.input)) > 1e-3
    best, start = (0, 0), None
    for i, flag in enumerate([*ok.tolist(), False]):
        if flag and start is None:
            start = i
        elif not flag and start is not None:
            if i - start >= best[1] - best[0]:  # ties: the later (positive) interval
                best = (start, i - 1)
            start = None
    a, b = grid[best[0]], grid[best[1]]
    centre, half = 0.5 * (a + b), min(0.5 * PATH_SHARE * (b - a), PATH_HALF_WIDTH)
    return float(centre - half), float(centre + half)


@register(
    "bricard-plane",
    "plane-symmetric Bricard 6R (Feng 2018, ch. 4, Table 4-1 cases 5..10), input theta2, joints theta1..theta6",
    PARAMS,
)
def build(
    a: float, b: float, c: float, alpha: float, beta: float, gamma: float, R2: float, R3: float, case: float
) -> Scene:
    number, g = geometry_for(case, Geometry(a, b, c, alpha, beta, gamma, R2, R3))
    kinematics = PlaneSymmetricBricard(g.a, g.b, g.c, g.alpha, g.beta, g.gamma, g.R2, g.R3)
    if not kinematics.branches():
        raise AssemblyError(structure_message(kinematics, number))
    params = {"a": g.a, "b": g.b, "c": g.c, "alpha": g.alpha, "beta": g.beta, "gamma": g.gamma, "R2": g.R2,
              "R3": g.R3, "case": float(number)}
    return Scene(
        name="bricard-plane",
        params=params,
        kinematics=kinematics,
        mechanism=dh_mechanism(kinematics.rows, anchor=g.a + g.b + g.c, input_joint=2),
        loop_joints=tuple(f"joint_{i}" for i in range(1, 7)),
        drive_joint="joint_2",
        drive_scale=1.0,
        path=default_path(kinematics),
        notes="hinge qpos = D-H angle theta; T = Rz(theta) Tz(R) Tx(a) Rx(alpha); theta5 = theta3, theta6 = theta2",
    )
