"""Peng 2018 (PhD thesis: spherical 4R networks, thick origami): the numbers the tests check.

The thesis gives most of its examples as figures; the values below are worked values of its equations at its own
examples (marked (w)), to 6 decimals in radians unless the row says otherwise.
"""

from functools import cache

import numpy as np

from published import Correction, Number
from sim_origami.kinematics.square_twist import edge_multipliers, metamaterial_unit
from sim_origami.kinematics.thick_diamond import COUNTER, DIAMOND, ThickDiamond, diamond_folds, hinge_heights
from sim_origami.kinematics.thick_diamond import sectors as diamond_sectors
from sim_origami.kinematics.thick_vertex5 import BRANCH as VERTEX5_BRANCH
from sim_origami.kinematics.thick_vertex5 import ThickVertex5, lifted_loop
from sim_origami.kinematics.vertex4 import Vertex4, flat_foldable_multipliers
from sim_origami.studies.metamaterial import element_formulas

DOCUMENT = "Peng 2018"
DEG = np.pi / 180
# Six decimals (rad): half a unit of the last place.
SIX_DECIMALS = 5e-7
_V4 = "test_kinematics_vertex4.py::"

# The generic developable vertex (2-34) and the flat-foldable vertex of Fig 3-2 (types I and II).
GENERIC_ALPHA = (np.pi / 2, 7 * np.pi / 18, np.pi / 3, 7 * np.pi / 9)
TYPE_I_ALPHA = (3 * np.pi / 4, np.pi / 3, np.pi / 4, 2 * np.pi / 3)
TYPE_II_ALPHA = (3 * np.pi / 4, 2 * np.pi / 3, np.pi / 4, np.pi / 3)
TYPES = {"I": TYPE_I_ALPHA, "II": TYPE_II_ALPHA}


def _w(where, quantity, printed, ours, tol, test, unit="rad", **kw) -> Number:
    return Number(where, quantity, printed, ours, tol, test, unit=unit, in_text=False, **kw)


VERTEX4 = (
    *(_w("eqn 2-34, generic developable vertex", f"rho2, rho3, rho4 on {branch} at rho1 = {x} rad", printed,
         lambda x=x, branch=branch: Vertex4(np.array(GENERIC_ALPHA)).joint_angles(branch, x)[0, 1:], SIX_DECIMALS,
         _V4 + "test_published_generic_vertex_of_eqn_2_34")
      for x, branch, printed in ((0.5, "odd2", "-0.084225, 0.443379, 0.109452"),
                                 (0.5, "odd3", "0.849175, -0.443379, 1.129539"),
                                 (-0.5, "odd3", "-0.849175, 0.443379, -1.129539"),
                                 (-0.5, "odd2", "0.084225, -0.443379, -0.109452"))),
    *(_w("eqn 2-34, generic developable vertex", f"rho2, rho3, rho4 on {branch} near flat, rho1 = 1e-4 rad "
         "(7 significant digits, the last off by up to 1.1 units)", printed,
         lambda branch=branch: Vertex4(np.array(GENERIC_ALPHA)).joint_angles(branch, 1e-4)[0, 1:], 1e-6,
         _V4 + "test_published_generic_vertex_of_eqn_2_34_near_flat", relative=True)
      for branch, printed in (("odd2", "-1.656368e-5, 8.887416e-5, 2.152044e-5"),
                              ("odd3", "1.843836e-4, -8.887416e-5, 2.395610e-4"))),
    *(_w(f"Fig 3-2, type {t}", f"rho1..rho4 in mode {mode} at rho1 = 1 rad", printed,
         lambda t=t, mode=mode: Vertex4(np.array(TYPES[t])).joint_angles(mode, 1.0)[0], SIX_DECIMALS,
         _V4 + "test_published_flat_foldable_vertex_of_fig_3_2")
      for t, mode, printed in (("I", "S", "1, 1.454216, -1, 1.454216"), ("I", "C", "1, 0.179279, 1, -0.179279"),
                               ("II", "S", "1, 2.556551, -1, 2.556551"), ("II", "C", "1, 0.647286, 1, -0.647286"))),
    *(_w(f"Fig 3-2, type {t}", f"the four fold-angle multipliers of mode {mode}", printed,
         lambda t=t, mode=mode: flat_foldable_multipliers(TYPES[t])[mode], SIX_DECIMALS,
         _V4 + "test_flat_foldable_multipliers_match_table_m6", unit="")
      for t, mode, printed in (("I", "S", "1.628626, -0.614014, -1.628626, 0.614014"),
                               ("I", "C", "0.164525, 6.078116, -0.164525, -6.078116"),
                               ("II", "S", "6.078116, -0.164525, -6.078116, 0.164525"),
                               ("II", "C", "0.614014, 1.628626, -0.614014, -1.628626"))),
)


# --- chapter 4: thick panels -------------------------------------------------------------------------------------

_T5 = "test_thick_vertex5.py::"
_TD = "test_thick_diamond.py::"


@cache
def thick_vertex5(alpha_deg: float = 30.0) -> ThickVertex5:
    """The thick five-crease vertex with sector alpha (deg), a23 = 1 m (a12 = a23 sin(alpha))."""
    return ThickVertex5(alpha_deg * DEG, 1.0)


def dihedral(q: np.ndarray) -> np.ndarray:
    """Dihedral angles (4-22) of fold angles q (n, 5): phi1 = pi - q1, phi_k = q_k + pi (mod 2 pi)."""
    return np.column_stack([np.pi - q[:, 0], np.mod(q[:, 1:] + np.pi, 2 * np.pi)])


@cache
def thick_diamond() -> ThickDiamond:
    """The thick diamond vertex of the example: alpha = 30 deg, p = 0.3, q = 0.5, r = 0.8 m."""
    return ThickDiamond(np.pi / 6, 0.3, 0.5, 0.8)


def diamond_r07_dihedrals() -> np.ndarray:
    """phi2, phi3, phi4 (rad) at phi1 = pi/2 of the r = 0.7 m loop, followed from near flat next to 'diamond'."""
    loops = lifted_loop(diamond_sectors(np.pi / 6), hinge_heights(0.3, 0.5, 0.7))
    x = np.linspace(0.02, np.pi / 2, 80)
    q = loops.follow(diamond_folds(np.pi / 6, x[0])[0], 0, x)[-1]
    return (np.pi - np.abs(q))[1:4]


def _diamond_main() -> np.ndarray:
    q = thick_diamond().at(DIAMOND, np.pi / 2)
    return np.array([q["rho2"], q["rho3"], q["rho5"], q["rho6"], np.pi + q["rho2"]])


THICK = (
    _w("eqn 4-22, alpha = 30 deg, a23 = 1 m, a12 = 0.5 m", "fold angles q1..q5 at rho1 = pi/2",
       "1.570796, -1.244669, -0.785398, -0.785398, -1.244669",
       lambda: thick_vertex5().joint_angles(VERTEX5_BRANCH, np.pi / 2)[0], SIX_DECIMALS,
       _T5 + "test_thick_five_crease_vertex_angles_of_eqn_4_22"),
    _w("eqn 4-22, alpha = 30 deg, a23 = 1 m, a12 = 0.5 m", "dihedral angles phi2..phi5 at rho1 = pi/2",
       "1.896924, 2.356194, 2.356194, 1.896924",
       lambda: dihedral(thick_vertex5().joint_angles(VERTEX5_BRANCH, np.pi / 2))[0, 1:], SIX_DECIMALS,
       _T5 + "test_thick_five_crease_vertex_angles_of_eqn_4_22"),
    _w("eqn 4-38, alpha = 30 deg, p = 0.3, q = 0.5, r = 0.8 m", "rho2, rho3, rho5, rho6 and phi2 = pi + rho2 at "
       "rho1 = pi/2", "-1.714144, -1.714144, -1.714144, -1.714144, 1.427449", _diamond_main, SIX_DECIMALS,
       _TD + "test_thick_diamond_heights_and_main_branch_of_eqn_4_38"),
    _w("alpha = 30 deg, p = 0.3, q = 0.5, r = 0.8 m", "rho2..rho6 on the second flat branch at rho1 = 0.5 rad "
       "(4 decimals)", "-0.0844, 0.2242, -0.0342, 0.2242, -0.0844",
       lambda: thick_diamond().joint_angles(COUNTER, 0.5)[0, 1:], 5e-5,
       _TD + "test_thick_diamond_second_flat_branch_at_q1_0_5"),
    _w("r = 0.7 m (r != p + q)", "phi2, phi3, phi4 at phi1 = pi/2 on the curve next to 'diamond'",
       "1.257179, 1.047198, 1.010984", diamond_r07_dihedrals, SIX_DECIMALS,
       _TD + "test_thick_diamond_r_0_7_is_refused_and_moves_along_another_curve"),
)


def _tan_halves(alpha: float) -> tuple:
    al = alpha * DEG
    K, K2 = np.cos(al) / (1 - np.sin(al)), (1 + np.sin(al)) / (1 - np.sin(al))
    q = thick_vertex5(alpha).joint_angles(VERTEX5_BRANCH, np.linspace(0.2, 3.0, 57))
    return K, K2, q


def eqn_4_20_residuals(alphas=(30.0, 50.0, 70.0)) -> tuple[float, float]:
    """On rho1 from 0.2 to 3 rad at alpha = 30, 50, 70 deg: the largest |t2^2 - (2 t2/t1) K - K2| (4-21b corrected)
    and the smallest |t2^2 - (t2/(2 t1)) K - K2| (4-20 as printed), t = tan(rho/2)."""
    fixed, printed = 0.0, np.inf
    for alpha in alphas:
        K, K2, q = _tan_halves(alpha)
        t1, t2 = np.tan(q[:, 0] / 2), np.tan(q[:, 1] / 2)
        fixed = max(fixed, float(np.max(np.abs(t2**2 - (2 * t2 / t1) * K - K2))))
        printed = min(printed, float(np.min(np.abs(t2**2 - (t2 / (2 * t1)) * K - K2))))
    return fixed, printed


def eqn_4_23c_residuals(alphas=(30.0, 50.0, 70.0)) -> tuple[float, float]:
    """As eqn_4_20_residuals for 1/T2^2 + (2 T1/T2) K - K2 (4-23c, 4-28c corrected) and the printed middle sign
    '-', T = tan(phi/2) of the dihedral angles (4-22)."""
    fixed, printed = 0.0, np.inf
    for alpha in alphas:
        K, K2, q = _tan_halves(alpha)
        phi = dihedral(q)
        T1, T2 = np.tan(phi[:, 0] / 2), np.tan(phi[:, 1] / 2)
        fixed = max(fixed, float(np.max(np.abs(1 / T2**2 + (2 * T1 / T2) * K - K2))))
        printed = min(printed, float(np.min(np.abs(1 / T2**2 - (2 * T1 / T2) * K - K2))))
    return fixed, printed


CORRECTIONS_4 = (
    Correction("eqn 4-20", "t2^2 - (t2 / (2 t1)) K - K2 = 0", "t2^2 - (2 t2 / t1) K - K2 = 0 (4-21b)",
               "largest residual of the corrected form, smallest of the printed, rho1 from 0.2 to 3 rad, alpha = 30, "
               "50, 70 deg", eqn_4_20_residuals, _T5 + "test_corrected_4_21b_holds_and_printed_4_20_fails", 1e-12,
               0.1),
    Correction("eqns 4-23c, 4-28c", "1/T2^2 - (2 T1/T2) K - K2 = 0", "1/T2^2 + (2 T1/T2) K - K2 = 0",
               "largest residual of the corrected form, smallest of the printed, rho1 from 0.2 to 3 rad, alpha = 30, "
               "50, 70 deg", eqn_4_23c_residuals, _T5 + "test_corrected_4_23c_and_4_28c_hold_and_printed_sign_fails",
               1e-12, 0.5),
)

# --- chapter 3: square twist and double-corrugated metamaterials ------------------------------------------------

_SQ = "test_square_twist.py::"
_SQUARE_TWIST_TABLE = (
    (150, 30, "0.869038, 1.566987, 1.456756, 0.631854, -0.398480, 9.186190"),
    (150, 60, "1.570796, 1.383975, 1.133975, 0.933013, -0.614521, 0.856406"),
    (150, 90, "2.094395, 1.133975, 0.883975, 0.933013, -1.039382, -0.526279"),
    (150, 120, "2.498092, 0.883975, 0.733975, 0.733013, -1.729816, -1.468060"),
    (150, 150, "2.834625, 0.700962, 0.657347, 0.401085, -2.567671, -5.040666"),
    (135, 30, "1.148367, 1.905266, 1.582791, 0.998502, -0.249648, 6.159052"),
    (135, 60, "1.896924, 1.646447, 1.066352, 1.282208, -0.541313, 0.221755"),
    (135, 90, "2.356194, 1.292893, 0.792893, 1.207107, -1.226541, -0.535534"),
    (135, 120, "2.672117, 0.939340, 0.662291, 0.932281, -2.583492, -1.123755"),
    (135, 150, "2.920521, 0.680521, 0.602995, 0.508604, -4.607159, -3.462525"),
    (120, 30, "1.570796, 2.250000, 1.500000, 1.299038, -0.166667, 3.000000"),
    (120, 60, "2.272555, 1.933013, 0.940927, 1.411390, -0.625933, -0.109581"),
    (120, 90, "2.617994, 1.500000, 0.750000, 1.299038, -2.000000, -0.500000"),
    (120, 120, "2.834625, 1.066987, 0.674458, 1.011686, -5.192249, -1.013962"),
    (120, 150, "2.998245, 0.750000, 0.642857, 0.556731, -10.500000, -3.095238"),
)
_ELEMENTS = (
    (1, 60, "0.824937, 0.705701, 1.325076"),
    (1, 90, "1.137055, 0.654654, 1.467314"),
    (1, 120, "1.380314, 0.530926, 1.668058"),
    (2, 60, "0.824937, 1.411402, 2.650152"),
    (2, 90, "1.137055, 1.309307, 2.934628"),
    (2, 120, "1.380314, 1.061852, 3.336116"),
)
# the sample sectors of the corrugated elements (Fig 3-2)
CORRUGATED_ALPHA, CORRUGATED_BETA = 3 * np.pi / 4, np.pi / 3


def square_twist_unit(alpha_deg: float, theta_deg: float) -> np.ndarray:
    """phi, L, S, H, nu_SL, nu_HL of the square-twist unit (eqns 3-30 to 3-32, a = b = c = 1) at theta."""
    u = metamaterial_unit(alpha_deg * DEG, np.array([theta_deg * DEG]))
    return np.array([u.phi, u.L, u.S, u.H, u.nu_sl, u.nu_hl])[:, 0]


def element_row(element: int, phi_deg: float) -> np.ndarray:
    """W, H, L of metamaterial element 1 or 2 (eqns 3-24 to 3-28) at phi, sectors of Fig 3-2."""
    d = element_formulas(np.array([phi_deg * DEG]), CORRUGATED_ALPHA, CORRUGATED_BETA, element)
    return np.array([d.W[0], d.H[0], d.L[0]])


CHAPTER_3 = (
    *(_w("Fig 3-15, alpha = 150 deg", f"edge multiplier of mode {mode}", printed,
         lambda mode=mode: edge_multipliers(5 * np.pi / 6)[mode], SIX_DECIMALS,
         _SQ + "test_multipliers_against_peng2018", unit="") for mode, printed in (("C", "1.732051"),
                                                                                   ("S", "-0.577350"))),
    *(_w(f"eqns 3-30 to 3-32, alpha = {a} deg", f"phi, L, S, H, nu_SL, nu_HL at theta = {t} deg (a = b = c = 1)",
         printed, lambda a=a, t=t: square_twist_unit(a, t), SIX_DECIMALS,
         _SQ + "test_square_twist_metamaterial_tables_of_eqns_3_30_to_3_32", unit="")
      for a, t, printed in _SQUARE_TWIST_TABLE),
    *(_w(f"eqns 3-24 to 3-28, element {e}", f"W, H, L at phi = {p} deg (sectors 135/60 deg)", printed,
         lambda e=e, p=p: element_row(e, p), SIX_DECIMALS,
         "test_metamaterial.py::test_formulas_reproduce_the_element_table", unit="m") for e, p, printed in _ELEMENTS),
)

NUMBERS: tuple[Number, ...] = (*VERTEX4, *THICK, *CHAPTER_3)
CORRECTIONS: tuple[Correction, ...] = CORRECTIONS_4

CHECKED_ELSEWHERE = (
    ("eqns 3-30 to 3-32", "L, S, H of the square twist at alpha = 150, 135, 120 deg measured on its vertices, "
     "and the Poisson's ratios as differences of the measured geometry (rows as above)",
     "test_poisson.py::test_closed_form_geometry_reproduces_the_poisson_tables"),
    ("eqn 3-26", "element 3's theta as printed (-0.189408, -0.326128, -0.555214) and the gain 0.614014 of the reading "
     "with gamma for alpha", "test_metamaterial.py::test_element_3_theta_is_the_printed_3_26_with_gamma_for_alpha"),
)
