"""Feng, Ma and Chen 2020 (generalized waterbomb tubes): the numbers the tests check.

The paper prints its ranges, thresholds and limits to one or two decimals; the dihedral angles and radii at its
example tubes (marked (w)) are worked values of its equations, to 4 decimals (degrees) and 5 (lengths, a = 1).
"""

from functools import cache

import numpy as np

from published import Correction, Number
from sim_origami.kinematics.waterbomb_tube import (
    WaterbombTube,
    alpha_limit,
    beta_max,
    dihedrals,
    folds_at,
    motion_range,
    row_coordinates,
    tube_layout,
)
from sim_origami.kinematics.waterbomb_twist import CCW, CW, WaterbombTwist

DOCUMENT = "Feng, Ma and Chen 2020"
DEG = np.pi / 180
# Four decimals (deg) and five (lengths, a = 1): half a unit of the last digit.
TUBE_DEG = 5e-5
TUBE_LENGTH = 5e-6
_TUBE = "test_waterbomb_tube.py::"


def tube_dihedrals(n: int, m: int, alpha: float, beta: float, theta: float, names) -> np.ndarray:
    """Dihedrals (deg) of the named creases at theta (deg) of the n x m tube with sectors alpha, beta (deg), a = 1."""
    layout = tube_layout(n, m, alpha * DEG, beta * DEG, 1.0)
    phi = dihedrals(layout, folds_at(layout, np.array([theta * DEG])))[0] / DEG
    return np.array([phi[layout.index(name)] for name in names])


def a_vertex(r: int, k: int = 0) -> list[str]:
    """Creases 1..6 of unit k's A in row r (names count rows from the bottom)."""
    return [f"A{r}_{k}_{j}" for j in range(1, 7)]


def row_radius(n, m, alpha, beta, theta, kind, row, coordinate=0) -> float:
    """Radius (coordinate 0) or height (1) of the row's vertex of `kind` at theta (deg), a = 1."""
    return row_coordinates(n, m, alpha * DEG, beta * DEG, 1.0, theta * DEG)[kind, row][coordinate][0]


@cache
def tube(n: int, m: int, alpha: float, beta: float) -> WaterbombTube:
    return WaterbombTube(n, m, alpha * DEG, beta * DEG)


def uniform_inputs(n, m, alpha, beta) -> np.ndarray:
    """theta (deg) of the tube's uniform-radius states."""
    return np.array([180 + e.input / DEG for e in tube(n, m, alpha, beta).events() if e.kind == "uniform_radius"])


def uniform_radii(k: int) -> np.ndarray:
    """Every row's r_A at the n6 m5 40/40 tube's k-th uniform-radius state."""
    model = tube(6, 5, 40, 40)
    e = [e for e in model.events() if e.kind == "uniform_radius"][k]
    return model.radii(e.input)[0]


def contraction_end(m: int, alpha: float, beta: float) -> float:
    """Upper end (deg) of the n = 6 tube's radial contraction."""
    return motion_range(tube_layout(6, m, alpha * DEG, beta * DEG, 1.0))[1] / DEG


def _w(where, quantity, printed, ours, tol, test, unit="deg", test_file=_TUBE, **kw) -> Number:
    return Number(where, quantity, printed, ours, tol, test_file + test, unit=unit, in_text=False, **kw)


_B0 = ["A2_0_4", "T1_0_r", "A1_0_2", "V1_0", "A1_1_6", "T1_1_l"]
_M3_40_35, _M3_ROW1, _M3_45_40, _M5 = (
    "test_tube_n6_m3_40_35_dihedrals_and_radii",
    "test_tube_n6_m3_40_35_row1_against_eta01",
    "test_tube_n6_m3_45_40_dihedrals_and_radius",
    "test_tube_radii_uniform_states_and_axial_lengths",
)
_EVEN = "test_even_tube_equator_with_eqn_18_corrected"
_N3_40_35 = "n6 m3 40/35, eta01 = 90 deg"

TUBES = (
    _w(_N3_40_35, "A0 dihedrals 1..6", "90, 74.9074, 74.9074, 90, 74.9074, 74.9074",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, a_vertex(1)), TUBE_DEG, _M3_40_35),
    _w(_N3_40_35, "B0 dihedrals 1..6", "83.2454, 67.6797, 74.9074, 30.0, 74.9074, 67.6797",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, _B0), TUBE_DEG, _M3_40_35),
    _w(_N3_40_35, "C0 dihedrals 1..6", "90, 67.6797, 79.2123, 40.8206, 79.2123, 67.6797",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, ["A1_0_1", "T1_0_r", "A2_0_5", "V2_5", "A2_5_3", "T1_0_l"]),
       TUBE_DEG, _M3_40_35),
    _w(_N3_40_35, "A1 dihedrals 1..6", "119.4914, 92.4303, 79.2123, 83.2454, 79.2123, 92.4303",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, a_vertex(2)), TUBE_DEG, _M3_40_35),
    _w(_N3_40_35, "radii r_A0, r_A1, r_B0", "0.51764, 0.69748, 1.41421",
       lambda: [row_radius(6, 3, 40, 35, 90, "A", 0), row_radius(6, 3, 40, 35, 90, "A", 1),
                row_radius(6, 3, 40, 35, 90, "B", 0)], TUBE_LENGTH, _M3_40_35, unit="m"),
    *(_w("n6 m3 40/35", f"kappa_B1,4 and eta_1,1 at eta01 = {t} deg (3 decimals)", printed,
         lambda t=t: tube_dihedrals(6, 3, 40, 35, t, ["V2_0", "A2_0_1"]), 5e-4, _M3_ROW1)
      for t, printed in ((60, "12.132, 90.760"), (70, "21.744, 100.436"), (80, "31.256, 109.873"),
                         (100, "50.685, 130.159"), (110, "61.239, 143.850"), (120, "73.049, 171.015"))),
    _w("n6 m3 45/40, eta01 = 90 deg", "B0 dihedrals 1..6", "87.0990, 51.8944, 70.5288, 30, 70.5288, 51.8944",
       lambda: tube_dihedrals(6, 3, 45, 40, 90, _B0), TUBE_DEG, _M3_45_40),
    _w("n6 m3 45/40, eta01 = 90 deg", "C0's dihedrals 3, 4", "72.4735, 33.9445",
       lambda: tube_dihedrals(6, 3, 45, 40, 90, ["A2_0_5", "V2_5"]), TUBE_DEG, _M3_45_40),
    _w("n6 m3 45/40, eta01 = 90 deg", "A1 dihedrals 1..4", "100.6946, 75.9759, 72.4735, 87.0990",
       lambda: tube_dihedrals(6, 3, 45, 40, 90, a_vertex(2)[:4]), TUBE_DEG, _M3_45_40),
    _w("n6 m3 45/40, eta01 = 90 deg", "radius r_A1", "0.58382", lambda: row_radius(6, 3, 45, 40, 90, "A", 1),
       TUBE_LENGTH, _M3_45_40, unit="m"),
    _w("n6 m5 45/40, eta01 = 100 deg", "A2 dihedrals 1..6", "115.0126, 91.1117, 86.5277, 101.7818, 86.5277, 91.1117",
       lambda: tube_dihedrals(6, 5, 45, 40, 100, a_vertex(4)), TUBE_DEG, _M5),
    _w("n6 m5 45/40, eta01 = 100 deg", "radii r_A0, r_A1, r_A2", "0.68404, 0.72047, 0.81883",
       lambda: [row_radius(6, 5, 45, 40, 100, "A", i) for i in range(3)], TUBE_LENGTH, _M5, unit="m"),
    _w("n6 m5 40/40", "theta of the two uniform-radius states", "98.7248, 111.2752",
       lambda: uniform_inputs(6, 5, 40, 40), TUBE_DEG, _M5),
    _w("n6 m5 40/40", "every row's r_A at the first uniform state", "0.66308", lambda: uniform_radii(0),
       2 * TUBE_LENGTH, _M5, unit="m"),
    _w("n6 m5 40/40", "every row's r_A at the second uniform state (0.8653552 truncated)", "0.86535",
       lambda: uniform_radii(1), 2 * TUBE_LENGTH, _M5, unit="m"),
    _w("n6 m5 40/40", "axial length (free-edge midpoints) at theta = 60, 90, 120 deg", "6.8962, 7.7583, 9.2507",
       lambda: tube(6, 5, 40, 40).length(np.array([60, 90, 120]) * DEG - np.pi), 5e-5, _M5, unit="m"),
    _w("n6 m4 45/40, eta01 = 80 deg (m even)", "A0 dihedrals 1..6", "80, 64.4835, 66.3380, 88.9804, 66.3380, 64.4835",
       lambda: tube_dihedrals(6, 4, 45, 40, 80, a_vertex(1)), TUBE_DEG, _EVEN),
    _w("n6 m4 45/40, eta01 = 80 deg (m even)", "B0 dihedrals 1..4", "80, 47.7495, 64.4835, 24.5376",
       lambda: tube_dihedrals(6, 4, 45, 40, 80, _B0[:4]), TUBE_DEG, _EVEN),
    *(_w(f"n6 m4 45/40, eta01 = {t} deg (m even)", "equatorial radius r_A0 (eqn 18 corrected)", r,
         lambda t=t: row_radius(6, 4, 45, 40, t, "A", 0), TUBE_LENGTH, _EVEN, unit="m")
      for t, r in ((80, "0.42500"), (100, "0.71331"), (120, "1.00452"))),
    *(_w(f"n6 m4 45/40, eta01 = {t} deg (m even)", "kappa of V1_0", k,
         lambda t=t: tube_dihedrals(6, 4, 45, 40, t, ["V1_0"]), TUBE_DEG, _EVEN)
      for t, k in ((80, "24.5376"), (100, "41.7897"), (120, "60.2994"))),
    *(Number("§2.1, Figs 6-7", f"end of the radial contraction, n6 m{m} {a}/{b}", printed,
             lambda m=m, a=a, b=b: contraction_end(m, a, b), 0.1, _TUBE + "test_feng_ma_chen2020_contraction_ranges",
             unit="deg", truncated=True)
      for m, a, b, printed in ((3, 40, 35, "120.6"), (3, 45, 40, "139.8"), (5, 45, 40, "131.1"))),
    _w("§2.1, n6 m5 40/35", "the island where the chain is real (top diagonals reversed), 2 decimals", "119.98, 120.19",
       lambda: np.array(motion_range(tube_layout(6, 5, 40 * DEG, 35 * DEG, 1.0), strict=False)) / DEG, 0.005,
       "test_feng_ma_chen2020_model_that_cannot_fold_rigidly"),
    *(Number("eqn 40, Fig 15", f"beta_max at alpha = {a} deg, n = 6 (2 decimals)", printed,
             lambda a=a: beta_max(a * DEG, 6) / DEG, 0.005,
             _TUBE + "test_twist_limits_and_thresholds_closed_forms", unit="deg")
      for a, printed in ((40, "42.01"), (45, "45.59"), (50, "49.17"))),
    Number("eqn 38", "alpha limit of the twist, n = 6 (1 decimal)", "49.1", lambda: alpha_limit(6) / DEG, 0.05,
           _TUBE + "test_twist_limits_and_thresholds_closed_forms", unit="deg"),
)

NUMBERS: tuple[Number, ...] = TUBES
CORRECTIONS: tuple[Correction, ...] = ()

CHECKED_ELSEWHERE = (
    (
        "Fig 8c, 8d",
        "six thresholds in alpha or beta (1 decimal): the property switches within the printed precision",
        _TUBE + "test_feng_ma_chen2020_fig8_thresholds_within_printed_precision",
    ),
)


# --- §3: the twist from the fully folded middle row ------------------------------------------------------------

_TWIST = "test_waterbomb_twist.py::"
# m = 5: rows 0..4 from the bottom are the paper's rows -2..2; the middle row (its row 0) is row 2. eta06 = A2_0_6,
# eta01 = A2_0_1, eta04 = A2_0_4; at B_0 (slot 1): kappa_1 = A3_0_4 (the down midline of row 3's unit 0),
# kappa_2 = T2_0_r, kappa_4 = V2_0; kappa_C0,4 = V3_0 (row 3's vertical edge).
TWIST_CREASES = ["A2_0_6", "A2_0_1", "A2_0_4", "A3_0_4", "T2_0_r", "V3_0"]


@cache
def twist(n: int, m: int, alpha: float, beta: float) -> WaterbombTwist:
    return WaterbombTwist(n, m, alpha * DEG, beta * DEG)


def twist_angles(model: WaterbombTwist, branch: str, eta02: float, names: list[str]) -> np.ndarray:
    """Dihedrals (deg) of the named creases at eta02 (deg) on `branch`."""
    q = model.joint_angles(branch, np.pi - eta02 * DEG)
    phi = dihedrals(model.layout, q)[0] / DEG
    return np.array([phi[model.layout.index(name)] for name in names])


def _limit_angles(branch: str, names: list[str]) -> np.ndarray:
    """Dihedrals (deg) of the n6 m5 40/40 twist at its limit on `branch` (cw: eta02 largest; ccw: eta02 = 0)."""
    model = twist(6, 5, 40, 40)
    x = model.domain[0] if branch == CW else model.domain[1]
    return twist_angles(model, branch, np.rad2deg(np.pi - x), names)


_STATES = "test_clockwise_twist_states_of_fig_13b"
_ENDS = "test_twist_start_and_limits_of_the_n6_m5_40_40_tube"
_TWIST_STATES = (
    (60, "35.7835, 60.8729, 60.8729, 57.9237, 45.7725, 4.3649", "18.493"),
    (70, "26.5514, 62.8522, 62.8522, 58.3068, 46.1970, 6.7363", "32.944"),
    (80, "17.6997, 65.9920, 65.9920, 58.8755, 46.8342, 10.5694", "46.689"),
    (90, "9.1382, 70.3573, 70.3573, 59.5810, 47.6364, 16.0552", "59.577"),
    (100, "0.6819, 76.0328, 76.0328, 60.3295, 48.5024, 23.4977", "71.448"),
)
_N5 = "n6 m5 40/40"

TWISTS = (
    *(_w(_N5, f"eta06, eta01, eta04, kappa_B0,1, kappa_B0,2, kappa_C0,4 at eta02 = {e} deg (clockwise twist)",
         printed, lambda e=e: twist_angles(twist(6, 5, 40, 40), CW, e, TWIST_CREASES), TUBE_DEG, _STATES,
         test_file=_TWIST)
      for e, printed, _ in _TWIST_STATES),
    *(_w(_N5, f"end twist, clockwise (3 decimals) at eta02 = {e} deg", end,
         lambda e=e: -twist(6, 5, 40, 40).end_twist(CW, np.pi - e * DEG)[0] / DEG, 5e-4, _STATES, test_file=_TWIST)
      for e, _, end in _TWIST_STATES),
    _w(_N5, "start of the twist, eta02 = eta06 at eta01 = 60 deg (eqn 39a)", "47.7173",
       lambda: 180 - twist(6, 5, 40, 40).start / DEG, TUBE_DEG, _ENDS, test_file=_TWIST),
    _w(_N5, "limit of the clockwise twist, eta02", "100.8002", lambda: 180 - twist(6, 5, 40, 40).domain[0] / DEG,
       TUBE_DEG, _ENDS, test_file=_TWIST),
    _w(_N5, "eta01 at the limit", "76.5459", lambda: _limit_angles(CW, ["A2_0_1"]), TUBE_DEG, _ENDS, test_file=_TWIST),
    _w(_N5, "eta_2,1 at the limit (3 decimals)", "149.522", lambda: _limit_angles(CW, ["A4_0_1"]), 5e-4, _ENDS,
       test_file=_TWIST),
    _w(_N5, "end twist at the limit, clockwise (2 decimals)", "72.35",
       lambda: -twist(6, 5, 40, 40).end_twist(CW, twist(6, 5, 40, 40).domain[0])[0] / DEG, 5e-3, _ENDS,
       test_file=_TWIST),
    _w(_N5, "r_A1, r_A2 at the limit (4 decimals)", "0.4191, 0.9194",
       lambda: twist(6, 5, 40, 40).radii(CW, twist(6, 5, 40, 40).domain[0])[0, 3:], 5e-5, _ENDS, unit="m",
       test_file=_TWIST),
    _w(_N5, "eta02, eta06, eta01 at the mirror end (counter-clockwise)", "0, 100.8002, 76.5459",
       lambda: _limit_angles(CCW, ["A2_0_2", "A2_0_6", "A2_0_1"]), TUBE_DEG, _ENDS, test_file=_TWIST),
    *(_w(f"eqn 41 (W corrected), n{n} m1 {a}/40", "the middle row's limit, eta02", printed,
         lambda n=n, a=a: np.rad2deg(np.pi - twist(n, 1, a, 40).domain[0]), TUBE_DEG, "test_middle_row_limits",
         test_file=_TWIST)
      for n, a, printed in ((6, 45, "90.0"), (5, 40, "130.9559"), (7, 40, "83.7207"), (8, 40, "72.0213"))),
    _w(_N5, "the contraction's uniform states seen from eta02 (eqn 9)", "98.7248, 111.2752",
       lambda: sorted(twist(6, 5, 40, 40).contraction_theta(
           np.array([e.input for e in twist(6, 5, 40, 40).events() if e.kind == "uniform_radius"])) / DEG),
       TUBE_DEG, "test_events", test_file=_TWIST),
)

NUMBERS: tuple[Number, ...] = (*TUBES, *TWISTS)
CORRECTIONS: tuple[Correction, ...] = ()

CHECKED_ELSEWHERE = (
    ("Fig 8c, 8d", "six thresholds in alpha or beta (1 decimal): the property switches within the printed precision",
     _TUBE + "test_feng_ma_chen2020_fig8_thresholds_within_printed_precision"),
    ("Figs 14a, 14b", "twist ranges of n6 m7, m9, m11 and n5 m5 (2 decimals): ours contain them, within 0.11 deg",
     _TWIST + "test_fig14_twist_ranges_where_the_top_row_deploys"),
    ("Fig 14", "no twist for m = 13 or n = 4; the n6 m5 beta = 40 tube twists from alpha = 26.85 deg (worked)",
     _TWIST + "test_fig14_no_twist_and_alpha_threshold"),
)
