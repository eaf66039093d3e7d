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


def _w(where, quantity, printed, ours, tol, test, unit="deg", **kw) -> Number:
    return Number(where, quantity, printed, ours, tol, _TUBE + test, unit=unit, in_text=False, **kw)


_B0 = ["A2_0_4", "T1_0_r", "A1_0_2", "V1_0", "A1_1_6", "T1_1_l"]
_C9, _C10, _C11, _C12 = (
    "test_case9_dihedrals_and_radii",
    "test_case10_row1_against_eta01",
    "test_case11_alpha45_beta40",
    "test_case12_and_case14_radii_and_uniform_states",
)
_C22 = "test_case22_even_tube_equator"
_N9 = "n6 m3 40/35, eta01 = 90 deg"

TUBES = (
    _w(_N9, "A0 dihedrals 1..6", "90, 74.9074, 74.9074, 90, 74.9074, 74.9074",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, a_vertex(1)), TUBE_DEG, _C9),
    _w(_N9, "B0 dihedrals 1..6", "83.2454, 67.6797, 74.9074, 30.0, 74.9074, 67.6797",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, _B0), TUBE_DEG, _C9),
    _w(_N9, "C0 dihedrals 1..6", "90, 67.6797, 79.2123, 40.8206, 79.2123, 67.6797",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, ["A1_0_1", "T1_0_r", "A2_0_5", "V2_5", "A2_5_3", "T1_0_l"]),
       TUBE_DEG, _C9),
    _w(_N9, "A1 dihedrals 1..6", "119.4914, 92.4303, 79.2123, 83.2454, 79.2123, 92.4303",
       lambda: tube_dihedrals(6, 3, 40, 35, 90, a_vertex(2)), TUBE_DEG, _C9),
    _w(_N9, "radii r_A0, r_A1, r_B0", "0.51764, 0.69748, 1.41421",
       lambda: [row_radius(6, 3, 40, 35, 90, "A", 0), row_radius(6, 3, 40, 35, 90, "A", 1),
                row_radius(6, 3, 40, 35, 90, "B", 0)], TUBE_LENGTH, _C9, unit="m"),
    *(_w("n6 m3 40/35", f"kappa_B1,4 and eta_1,1 at eta01 = {t} deg (3 decimals)", printed,
         lambda t=t: tube_dihedrals(6, 3, 40, 35, t, ["V2_0", "A2_0_1"]), 5e-4, _C10)
      for t, printed in ((60, "12.132, 90.760"), (70, "21.744, 100.436"), (80, "31.256, 109.873"),
                         (100, "50.685, 130.159"), (110, "61.239, 143.850"), (120, "73.049, 171.015"))),
    _w("n6 m3 45/40, eta01 = 90 deg", "B0 dihedrals 1..6", "87.0990, 51.8944, 70.5288, 30, 70.5288, 51.8944",
       lambda: tube_dihedrals(6, 3, 45, 40, 90, _B0), TUBE_DEG, _C11),
    _w("n6 m3 45/40, eta01 = 90 deg", "C0's dihedrals 3, 4", "72.4735, 33.9445",
       lambda: tube_dihedrals(6, 3, 45, 40, 90, ["A2_0_5", "V2_5"]), TUBE_DEG, _C11),
    _w("n6 m3 45/40, eta01 = 90 deg", "A1 dihedrals 1..4", "100.6946, 75.9759, 72.4735, 87.0990",
       lambda: tube_dihedrals(6, 3, 45, 40, 90, a_vertex(2)[:4]), TUBE_DEG, _C11),
    _w("n6 m3 45/40, eta01 = 90 deg", "radius r_A1", "0.58382", lambda: row_radius(6, 3, 45, 40, 90, "A", 1),
       TUBE_LENGTH, _C11, unit="m"),
    _w("n6 m5 45/40, eta01 = 100 deg", "A2 dihedrals 1..6", "115.0126, 91.1117, 86.5277, 101.7818, 86.5277, 91.1117",
       lambda: tube_dihedrals(6, 5, 45, 40, 100, a_vertex(4)), TUBE_DEG, _C12),
    _w("n6 m5 45/40, eta01 = 100 deg", "radii r_A0, r_A1, r_A2", "0.68404, 0.72047, 0.81883",
       lambda: [row_radius(6, 5, 45, 40, 100, "A", i) for i in range(3)], TUBE_LENGTH, _C12, unit="m"),
    _w("n6 m5 40/40", "theta of the two uniform-radius states", "98.7248, 111.2752",
       lambda: uniform_inputs(6, 5, 40, 40), TUBE_DEG, _C12),
    _w("n6 m5 40/40", "every row's r_A at the first uniform state", "0.66308", lambda: uniform_radii(0),
       2 * TUBE_LENGTH, _C12, unit="m"),
    _w("n6 m5 40/40", "every row's r_A at the second uniform state (0.8653552 truncated)", "0.86535",
       lambda: uniform_radii(1), 2 * TUBE_LENGTH, _C12, unit="m"),
    _w("n6 m5 40/40", "axial length (free-edge midpoints) at theta = 60, 90, 120 deg", "6.8962, 7.7583, 9.2507",
       lambda: tube(6, 5, 40, 40).length(np.array([60, 90, 120]) * DEG - np.pi), 5e-5, _C12, unit="m"),
    _w("n6 m4 45/40, eta01 = 80 deg (m even)", "A0 dihedrals 1..6", "80, 64.4835, 66.3380, 88.9804, 66.3380, 64.4835",
       lambda: tube_dihedrals(6, 4, 45, 40, 80, a_vertex(1)), TUBE_DEG, _C22),
    _w("n6 m4 45/40, eta01 = 80 deg (m even)", "B0 dihedrals 1..4", "80, 47.7495, 64.4835, 24.5376",
       lambda: tube_dihedrals(6, 4, 45, 40, 80, _B0[:4]), TUBE_DEG, _C22),
    *(_w(f"n6 m4 45/40, eta01 = {t} deg (m even)", "equatorial radius r_A0 (eqn 18 corrected)", r,
         lambda t=t: row_radius(6, 4, 45, 40, t, "A", 0), TUBE_LENGTH, _C22, unit="m")
      for t, r in ((80, "0.42500"), (100, "0.71331"), (120, "1.00452"))),
    *(_w(f"n6 m4 45/40, eta01 = {t} deg (m even)", "kappa of V1_0", k,
         lambda t=t: tube_dihedrals(6, 4, 45, 40, t, ["V1_0"]), TUBE_DEG, _C22)
      for t, k in ((80, "24.5376"), (100, "41.7897"), (120, "60.2994"))),
    *(Number("§2.1, Figs 6-7", f"end of the radial contraction, n6 m{m} {a}/{b}", printed,
             lambda m=m, a=a, b=b: contraction_end(m, a, b), 0.1, _TUBE + "test_seed004_contraction_ranges",
             unit="deg", truncated=True)
      for m, a, b, printed in ((3, 40, 35, "120.6"), (3, 45, 40, "139.8"), (5, 45, 40, "131.1"))),
    _w("§2.1, n6 m5 40/35", "the island where the chain is real (top diagonals reversed), 2 decimals", "119.98, 120.19",
       lambda: np.array(motion_range(tube_layout(6, 5, 40 * DEG, 35 * DEG, 1.0), strict=False)) / DEG, 0.005,
       "test_seed004_model_that_cannot_fold_rigidly"),
    *(Number("eqn 40, Fig 15", f"beta_max at alpha = {a} deg, n = 6 (2 decimals)", printed,
             lambda a=a: beta_max(a * DEG, 6) / DEG, 0.005,
             _TUBE + "test_twist_limits_and_thresholds_closed_forms", unit="deg")
      for a, printed in ((40, "42.01"), (45, "45.59"), (50, "49.17"))),
    Number("eqn 38", "alpha limit of the twist, n = 6 (1 decimal)", "49.1", lambda: alpha_limit(6) / DEG, 0.05,
           _TUBE + "test_twist_limits_and_thresholds_closed_forms", unit="deg"),
)  # fmt: skip

NUMBERS: tuple[Number, ...] = TUBES
CORRECTIONS: tuple[Correction, ...] = ()

CHECKED_ELSEWHERE = (
    (
        "Fig 8c, 8d",
        "six thresholds in alpha or beta (1 decimal): the property switches within the printed precision",
        _TUBE + "test_seed004_fig8_thresholds_within_printed_precision",
    ),
)
