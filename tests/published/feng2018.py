"""Feng 2018 (PhD thesis: waterbomb, Bricard linkages, triangle twist): the published numbers the tests check."""

from functools import cache

import numpy as np

from published import Correction, Number
from published.feng_ma_chen2020 import tube, twist, twist_angles
from sim_origami.geometry import wrap
from sim_origami.kinematics.bricard_plane import (
    FIG_4_5,
    TABLE_4_1,
    Geometry,
    PlaneSymmetricBricard,
    closure_coefficients,
    theta1_fractions,
    theta4_fraction,
)
from sim_origami.kinematics.triangle_twist import epsilon_formula
from sim_origami.kinematics.twist_6r import TwistSixR, compatible_angles
from sim_origami.kinematics.vertex4 import Vertex4
from sim_origami.kinematics.waterbomb import CREASES as WATERBOMB_CREASES
from sim_origami.kinematics.waterbomb import LINE as WATERBOMB_LINE
from sim_origami.kinematics.waterbomb import PLANE as WATERBOMB_PLANE
from sim_origami.kinematics.waterbomb import Waterbomb, plane_blockage
from sim_origami.kinematics.waterbomb_tube import alpha_limit, alpha_min, row_coordinates
from sim_origami.kinematics.waterbomb_twist import CCW as TWIST_CCW
from sim_origami.kinematics.waterbomb_twist import middle_input

DOCUMENT = "Feng 2018"
DEG = np.pi / 180

# A geometry with offsets R2, R3 (worked here, not in the thesis): it exposes the sign of eqn 4-6c.
OFFSETS = Geometry(1.3, 0.7, 1.1, 0.9, 0.4, 1.2, 0.3, -0.5)
# Chapter 4 prints angles to 4 decimals (degrees): half a unit of the last place, plus rounding of the printed
# inputs (e.g. 158.5428 deg); the largest difference measured is 5.0e-5 deg.
BRICARD_DEG = 6e-5


def bricard_model(g: Geometry, **options) -> PlaneSymmetricBricard:
    """The plane-symmetric Bricard 6R of a chapter 4 geometry."""
    return PlaneSymmetricBricard(g.a, g.b, g.c, g.alpha, g.beta, g.gamma, g.R2, g.R3, **options)


@cache
def _bricard(name: str | int) -> PlaneSymmetricBricard:
    return bricard_model({"fig": FIG_4_5, "offsets": OFFSETS}.get(name) or TABLE_4_1[name])


def bricard_angles_deg(kin: PlaneSymmetricBricard, branch: str, theta2_deg: float) -> np.ndarray:
    """theta1..theta6 (deg, wrapped) on a branch at theta2 (deg)."""
    return np.rad2deg(wrap(kin.joint_angles(branch, np.deg2rad(theta2_deg))[0]))


def case_9_bennett_theta3(theta1: np.ndarray) -> np.ndarray:
    """theta3 of case 9's Bennett branch theta2 = theta6 = pi (Fig 4-4): tan(theta3/2) = -tan(theta1/2) / sqrt 2."""
    return 2 * np.arctan(-np.tan(theta1 / 2) / np.sqrt(2))


PATH_WORDS = {
    "theta1_eq_theta4": "path I (theta1 = theta4)",
    "theta1_plus_theta4_eq_2theta2": "path II (theta1 + theta4 = 2 theta2)",
    "all_joints_move": "all joints move",
    "theta3_180_at_theta2_180": "the half where theta3 = 180 at theta2 = 180 (deg)",
    "theta3_0_at_theta2_180": "the half where theta3 = 0 at theta2 = 180 (deg)",
    "bennett_theta3_pi": "the Bennett branch theta3 = theta5 = 180",
    "theta3_m63_at_theta2_m80": "first root",
    "theta3_m124_at_theta2_m80": "second root",
}


def _bricard_row(where: str, geometry, branch: str, theta2: float, printed: str, test: str, label: str = "") -> Number:
    shown = label or f"{theta2:.10g} deg"
    return Number(
        where,
        f"theta1..theta6 at theta2 = {shown} on {PATH_WORDS[branch]}",
        printed,
        lambda: bricard_angles_deg(_bricard(geometry), branch, theta2),
        BRICARD_DEG,
        f"test_bricard_plane.py::{test}",
        unit="deg",
        angle=True,
        in_text=False,
    )


_T41 = "test_published_configurations_of_table_4_1"
_F45 = "test_published_configurations_of_the_fig_4_5_geometry_and_the_offset_case"
_OFFSETS_WHERE = "eqns 4-5, 4-6 (4-6c corrected), our geometry with offsets R2, R3"
_BEN = "test_fig_4_5_bennett_branch_published_values"
_BIF = "test_case_10_bifurcations_are_the_two_collinear_configurations_on_both_paths"
_C9 = "test_case_9_bennett_branch_closes_and_meets_both_halves_at_the_published_configurations"

BRICARD = (
    _bricard_row("Table 4-1, case 10", 10, "theta1_eq_theta4", 60,
                 "-147.7958, 60, 143.1301, -147.7958, 143.1301, 60", _T41),
    _bricard_row("Table 4-1, case 10", 10, "theta1_plus_theta4_eq_2theta2", 60,
                 "-133.1736, 60, 126.8699, -106.8264, 126.8699, 60", _T41),
    _bricard_row("Table 4-1, case 10", 10, "theta1_eq_theta4", 120, "-98.2132, 120, 90, -98.2132, 90, 120", _T41),
    _bricard_row("Table 4-1, case 10", 10, "theta1_plus_theta4_eq_2theta2", 120,
                 "-75.1782, 120, 67.3801, -44.8218, 67.3801, 120", _T41),
    _bricard_row("Table 4-1, case 5", 5, "all_joints_move", 60, "144.8396, 60, 16.2602, -177.6924, 16.2602, 60", _T41),
    _bricard_row("Table 4-1, case 5", 5, "all_joints_move", 120,
                 "80.5145, 120, 46.3972, -174.1674, 46.3972, 120", _T41),
    _bricard_row("Table 4-1, case 6", 6, "all_joints_move", 60, "-46.8264, 60, 101.5370, 46.8264, 101.5370, 60", _T41),
    _bricard_row("Table 4-1, case 6", 6, "all_joints_move", 120, "0, 120, 0, 120, 0, 120", _T41),
    # case 8's inputs are 0.5 and 2 rad (printed as 28.6479 and 114.5916 deg)
    _bricard_row("Table 4-1, case 8", 8, "theta1_eq_theta4", np.rad2deg(0.5),
                 "-165.4487, 28.6479, 163.2275, -165.4487, 163.2275, 28.6479", _T41, "0.5 rad"),
    _bricard_row("Table 4-1, case 8", 8, "theta1_eq_theta4", np.rad2deg(2.0),
                 "-104.1839, 114.5916, 96.0782, -104.1839, 96.0782, 114.5916", _T41, "2 rad"),
    _bricard_row("Table 4-1, case 9", 9, "theta3_180_at_theta2_180", 90,
                 "140.7460, 90, 150.3342, 71.4318, 150.3342, 90", _T41),
    _bricard_row("Table 4-1, case 9", 9, "theta3_0_at_theta2_180", 90,
                 "101.5496, 90, 69.0589, -132.7723, 69.0589, 90", _T41),
    _bricard_row("Table 4-1, case 9", 9, "theta3_180_at_theta2_180", 150,
                 "157.9355, 150, 173.0647, -90.2700, 173.0647, 150", _T41),
    _bricard_row("Table 4-1, case 9", 9, "theta3_0_at_theta2_180", 150,
                 "33.2749, 150, 17.8935, -40.4613, 17.8935, 150", _T41),
    _bricard_row("Fig 4-5", "fig", "all_joints_move", 60, "113.7818, 60, -136.7224, 170.0617, -136.7224, 60", _F45),
    _bricard_row("Fig 4-5", "fig", "all_joints_move", 120, "138.8478, 120, 146.9081, 37.1804, 146.9081, 120", _F45),
    _bricard_row(_OFFSETS_WHERE, "offsets", "theta3_m63_at_theta2_m80", -110,
                 "-80.8970, -110, -49.5009, 96.0363, -49.5009, -110", _F45),
    _bricard_row(_OFFSETS_WHERE, "offsets", "theta3_m124_at_theta2_m80", -110,
                 "97.6558, -110, -97.2543, -29.8270, -97.2543, -110", _F45),
    _bricard_row("Fig 4-5", "fig", "bennett_theta3_pi", 158.5428, "30, 158.5428, 180, 30, 180, 158.5428", _BEN),
    _bricard_row("Fig 4-5", "fig", "bennett_theta3_pi", 109.4712, "90, 109.4712, 180, 90, 180, 109.4712", _BEN),
    _bricard_row("Fig 4-5", "fig", "bennett_theta3_pi", 41.5071, "150, 41.5071, 180, 150, 180, 41.5071", _BEN),
    Number("Fig 4-4, case 9", "theta3 on the Bennett branch (theta2 = 180) at theta1 = 30, 60, 90, 120, 150, 170 deg",
           "-21.4572, -44.4153, -70.5288, -101.5370, -138.4929, -165.8935",
           lambda: np.rad2deg(case_9_bennett_theta3(np.deg2rad([30.0, 60.0, 90.0, 120.0, 150.0, 170.0]))),
           BRICARD_DEG, f"test_bricard_plane.py::{_C9}", unit="deg", in_text=False),
    _bricard_row("Table 4-1, case 9", 9, "theta3_0_at_theta2_180", 180, "0, 180, 0, 0, 0, 180", _C9),
    _bricard_row("Table 4-1, case 9", 9, "theta3_180_at_theta2_180", 180, "180, 180, 180, 180, 180, 180", _C9),
    _bricard_row("Table 4-1, case 10 (bifurcation)", 10, "theta1_eq_theta4", 0, "180, 0, 180, 180, 180, 0", _BIF),
    _bricard_row("Table 4-1, case 10 (bifurcation)", 10, "theta1_plus_theta4_eq_2theta2", 0,
                 "180, 0, 180, 180, 180, 0", _BIF),
    _bricard_row("Table 4-1, case 10 (bifurcation)", 10, "theta1_eq_theta4", 180, "0, 180, 0, 0, 0, 180", _BIF),
    _bricard_row("Table 4-1, case 10 (bifurcation)", 10, "theta1_plus_theta4_eq_2theta2", 180,
                 "0, 180, 0, 0, 0, 180", _BIF),
    Number("Table 4-1, case 9", "lower end of theta2's domain (Delta >= 0 iff |theta2| >= 71.67 deg)", "71.6692",
           lambda: np.rad2deg(_bricard(9).branches()[0].domain[0]), 1e-4,
           "test_bricard_plane.py::test_case_9_theta2_covers_only_part_of_the_circle_and_turns_back", unit="deg",
           in_text=False),
)


def textbook_configurations(g: Geometry, theta2: np.ndarray, printed_c: bool) -> np.ndarray:
    """Both roots by eqn 4-15 with n = tan(theta3/2), theta1 by eqn 4-7, theta4 by appendix (3,1)."""
    A, B, C = closure_coefficients(g, theta2, printed_c=printed_c)
    with np.errstate(invalid="ignore"):  # the printed C leaves Delta < 0 at some inputs
        root = np.sqrt(B * B - 4 * A * C)
    out = []
    for sign in (1.0, -1.0):
        t3 = 2 * np.arctan((-B + sign * root) / (2 * A))
        Y13, X13, _, _ = theta1_fractions(g, theta2, t3)
        Y31, X31 = theta4_fraction(g, theta2, t3)
        t1, t4 = 2 * np.arctan2(Y13, X13), 2 * np.arctan2(Y31, X31)
        out.append(np.stack([t1, theta2, t3, t4, t3, theta2], -1))
    return np.concatenate(out)


def eqn_4_6c_residuals() -> tuple[float, float]:
    """Largest loop closure residual of eqns 4-15, 4-7 and appendix (3,1) on the offsets case, theta2 from -120 to
    -30 deg (inside both its domains), with C's linear term corrected and as printed (finite roots only)."""
    theta2 = np.deg2rad(np.linspace(-120.0, -30.0, 91))
    loops = _bricard("offsets").loop_system()
    out = []
    for printed_c in (False, True):
        q = textbook_configurations(OFFSETS, theta2, printed_c)
        out.append(float(np.max(loops.residual_norm(q[np.all(np.isfinite(q), axis=1)]))))
    return out[0], out[1]


# --- chapter 3: the triangle twist and its 6R linkages ---------------------------------------------------------

FIG_3_5 = (55.0, 50.0, 50.0, 45.0)  # alpha, beta, gamma, delta (deg)
_TT = "test_triangle_twist.py::"


@cache
def twist_6r(alpha: float, beta: float, gamma: float, delta: float) -> TwistSixR:
    """The 6R derived from the triangle twist with these angles (deg) and its compatible epsilon."""
    return TwistSixR(compatible_angles(*(v * DEG for v in (alpha, beta, gamma, delta))))


def held_joint_pose(joint: int) -> np.ndarray:
    """The one configuration (deg) the Fig 3-5 6R closes with joint `joint` held at 0.3 rad (numeric solve)."""
    found = twist_6r(*FIG_3_5).loop_system().assemblies(joint, 0.3, starts=32, seed=1)
    return np.rad2deg(found[0])


def _tt(where, quantity, printed, ours, tol, test, unit="deg") -> Number:
    return Number(where, quantity, printed, ours, tol, _TT + test, unit=unit, in_text=False)


_VERTEX = "test_spherical_4r_vertex_i_and_ii_of_eqn_3_3"
_EPS = "test_compatible_epsilon_against_feng2018"
_SOLID = "test_dh_data_and_motion_against_feng2018"
_DASHED = "test_new_6r_of_eqn_3_40_with_parallel_pleats"
_HELD = "test_derived_6r_with_one_held_joint_admits_one_configuration"
_NEW_6R = "eqn 3-40, 55/50/45/45"  # the 6R of Fig 3-14's dashed lines
_SOLID_PATH = (
    (30, "-66.0696, -47.4736"),
    (60, "-108.9688, -86.9116"),
    (90, "-135.2111, -117.2886"),
    (120, "-153.2360, -141.2359"),
    (150, "-167.3989, -161.4540"),
)
_SOLID_HELD = (
    (0, "17.19, -40.28, -27.86, 17.19, -40.28, 27.86"),
    (1, "-7.13, 17.19, 11.67, -7.13, 17.19, -11.67"),
    (2, "-10.52, 25.20, 17.19, -10.52, 25.20, -17.19"),
    (5, "10.52, -25.20, -17.19, 10.52, -25.20, 17.19"),
)


def _solid_row(t1: int, t2_t3: str) -> Number:
    t2, t3 = t2_t3.split(", ")
    return _tt(
        "Fig 3-14, solid lines (55/50/50/45)",
        f"theta1..theta6 at theta1 = {t1} deg (theta4 = theta1, theta5 = theta2, theta6 = -theta3)",
        f"{t1}, {t2}, {t3}, {t1}, {t2}, {-float(t3):.4f}",
        lambda: np.rad2deg(twist_6r(*FIG_3_5).joint_angles("SSP", t1 * DEG)[0]),
        5e-5,
        _SOLID,
    )


TRIANGLE_TWIST = (
    *(_tt("eqn 3-3", f"mode {mode} vertex (twists 0.6, 1.2 rad) rho1..rho4 at rho1 = 0.3 rad", printed,
          lambda mode=mode: Vertex4([0.6, 1.2, np.pi - 0.6, np.pi - 1.2]).joint_angles(mode, 0.3)[0], 5e-5, _VERTEX,
          unit="rad") for mode, printed in (("S", "0.3, -0.7621, -0.3, -0.7621"), ("C", "0.3, -0.1960, 0.3, 0.1960"))),
    *(_tt(f"eqn 3-12, {scheme} {angles}", "compatible epsilon", printed,
          lambda scheme=scheme, angles=angles: epsilon_formula(scheme, *(v * DEG for v in angles)) / DEG, 5e-5, _EPS)
      for scheme, angles, printed in (("SSP", (55, 50, 50, 45), "35.4368"), ("SSP", (55, 50, 45, 45), "33.5166"),
                                      ("PSR", (30, 80, 90, 45), "7.0355"), ("PSR", (60, 60, 90, 45), "-25.5288"))),
    _tt("eqn 3-38, 55/50/50/45", "D-H twists alpha12..alpha61", "-5, 130, -9.5632, 105, 14.5632, 125",
        lambda: np.rad2deg(wrap([r.alpha for r in twist_6r(*FIG_3_5).rows])), 5e-5, _SOLID),
    _tt("eqn 3-38, 55/50/50/45", "D-H offsets R1..R6 (d = 1)",
        "8.11314, -8.789374, 2.959639, -3.609461, -2.416104, 1.828703",
        lambda: [r.R for r in twist_6r(*FIG_3_5).rows], 5e-6, _SOLID, unit=""),
    _tt("eqn 3-39, 55/50/50/45", "Ka, Kb", "1.641116, 1.478778", lambda: [twist_6r(*FIG_3_5).ka, twist_6r(*FIG_3_5).kb],
        5e-7, _SOLID, unit=""),
    _tt("eqn 3-39, 55/50/50/45", "Ka Kb", "2.4268", lambda: twist_6r(*FIG_3_5).ka * twist_6r(*FIG_3_5).kb, 5e-5, _SOLID,
        unit=""),
    *(_solid_row(t1, t2_t3) for t1, t2_t3 in _SOLID_PATH),
    *(_tt("§3.4, 55/50/50/45", f"the only configuration with joint {j + 1} held at 0.3 rad (numeric solve, 2 decimals)",
          printed, lambda j=j: held_joint_pose(j), 0.005, _HELD) for j, printed in _SOLID_HELD),
    _tt("Fig 3-14, dashed lines (55/50/45/45)", "compatible epsilon of the 6R with gamma = delta = 45", "33.5166",
        lambda: twist_6r(55, 50, 45, 45).angles.epsilon / DEG, 5e-5, _DASHED),
    _tt(_NEW_6R, "D-H twists alpha12..alpha61", "0, 130, -11.4834, 105, 11.4834, 125",
        lambda: np.rad2deg(wrap([r.alpha for r in twist_6r(55, 50, 45, 45).rows])), 5e-5, _DASHED),
    _tt(_NEW_6R, "D-H offsets R1..R6 (d = 1)", "0, -0.707107, 2.352154, -3.012110, -2.816828, 2.199659",
        lambda: [r.R for r in twist_6r(55, 50, 45, 45).rows], 5e-7, _DASHED, unit=""),
    _tt(_NEW_6R, "D-H length a12", "0.707107", lambda: twist_6r(55, 50, 45, 45).rows[0].a, 5e-7, _DASHED, unit=""),
    _tt(_NEW_6R, "eqn 2-14's sum with R1 = 0", "4.685016", lambda: twist_6r(55, 50, 45, 45).bricard_sum(), 5e-7,
        _DASHED, unit=""),
    _tt(_NEW_6R, "Ka, Ka Kb", "1.5498, 2.2918",
        lambda: [twist_6r(55, 50, 45, 45).ka, twist_6r(55, 50, 45, 45).ka * twist_6r(55, 50, 45, 45).kb], 5e-5, _DASHED,
        unit=""),
    _tt(_NEW_6R, "theta1..theta6 at theta1 = 0.5 rad", "28.648, -60.977, -138.111, 118.648, -150.977, 138.111",
        lambda: np.rad2deg(twist_6r(55, 50, 45, 45).joint_angles("SSP", 0.5)[0]), 5e-4, _DASHED),
)


def eqn_3_39_residuals() -> tuple[float, float]:
    """Largest loop closure residual of the Fig 3-5 6R over theta1 from -3 to 3 rad: the corrected closed form and
    eqn 3-39 as printed (tan(theta2/2) = +Ka Kb tan(theta1/2), tan(theta3/2) = Ka tan(theta1/2), theta4 = -theta1)."""
    model = twist_6r(*FIG_3_5)
    loops, x = model.loop_system(), np.linspace(-3, 3, 61)
    t2, t3 = 2 * np.arctan(model.ka * model.kb * np.tan(x / 2)), 2 * np.arctan(model.ka * np.tan(x / 2))
    printed = np.stack([x, t2, t3, -x, t2, t3], -1)
    return float(np.max(loops.residual_norm(model.joint_angles("SSP", x)))), float(np.max(loops.residual_norm(printed)))


def eqn_3_4a_residuals() -> tuple[float, float]:
    """|tan(phi4/2) / tan(phi1/2) - ratio| of the mode S vertex (twists 0.6, 1.2 rad) at rho1 = 0.3 rad, phi =
    pi - |rho|: the corrected ratio s-/s+ = sin((a23 - a12)/2) / sin((a23 + a12)/2) and the printed s-/s- = 1."""
    a12, a23 = 0.6, 1.2
    got = Vertex4([a12, a23, np.pi - a12, np.pi - a23]).joint_angles("S", 0.3)[0]
    ratio = np.tan((np.pi - abs(got[3])) / 2) / np.tan((np.pi - abs(got[0])) / 2)
    return float(abs(ratio - np.sin((a23 - a12) / 2) / np.sin((a23 + a12) / 2))), float(abs(ratio - 1.0))


CORRECTIONS_3 = (
    Correction("eqn 3-4a", "fourth ratio tan(phi4/2) / tan(phi1/2) = s-/s- (= 1)", "s-/s+",
               "the ratio's error, mode S vertex with twists 0.6, 1.2 rad at rho1 = 0.3 rad", eqn_3_4a_residuals,
               _TT + _VERTEX, 3e-14, 0.5),
    Correction("eqn 3-39", "tan(theta2/2) = +Ka Kb tan(theta1/2), theta4 = -theta1, theta5 = theta2, theta6 = theta3",
               "the closed form of kinematics/twist_6r.py (theta4 = theta1, theta6 = -theta3)",
               "loop closure residual (m and rad), Fig 3-5 6R, theta1 from -3 to 3 rad", eqn_3_39_residuals,
               _TT + _SOLID, 1e-12, 1.0),
)


# --- chapter 5: the symmetric waterbomb cell -------------------------------------------------------------------

B_ORDER = ("B1", "B2", "A2", "B4", "B5", "B6")  # B's creases 1..6 (B3 is A2)
_WB = "test_waterbomb.py::"
# Four decimals (deg): half a unit of the last digit.
WATERBOMB_DEG = 5e-5


@cache
def waterbomb(alpha: float, beta: float, *thick: float) -> Waterbomb:
    """The cell with sectors alpha, beta (deg), a = 0.5 and optionally (mu, thickness)."""
    return Waterbomb(alpha * DEG, beta * DEG, 0.5, *thick)


def dihedrals(model: Waterbomb, branch: str, phi1_deg: float, order=B_ORDER) -> np.ndarray:
    """Dihedrals phi = pi - |rho| (deg) of the creases in `order` at phi1 (deg)."""
    q = dict(zip(WATERBOMB_CREASES, model.joint_angles(branch, -(np.pi - phi1_deg * DEG))[0], strict=True))
    return np.rad2deg([np.pi - abs(q[c]) for c in order])


def vertex_b_sweep_row(alpha: float, beta: float, phi1: float) -> np.ndarray:
    """(phi3, path I phi2, path II phi2, path II phi4) in degrees at phi1 (deg); phi4 < 0 is crease B4 folded past
    flat (rho_B4 beyond -pi, wrapped to (0, pi])."""
    model = waterbomb(alpha, beta)
    line = dihedrals(model, WATERBOMB_LINE, phi1)
    q = dict(zip(WATERBOMB_CREASES, model.joint_angles(WATERBOMB_PLANE, -(np.pi - phi1 * DEG))[0], strict=True))
    phi4 = np.rad2deg(np.pi + q["B4"]) if q["B4"] < 0 else np.rad2deg(q["B4"] - np.pi)
    return np.array([line[2], line[1], dihedrals(model, WATERBOMB_PLANE, phi1)[1], phi4])


def thick_vertex_b_omega() -> np.ndarray:
    """Vertex B's D-H angles omega1..omega6 (deg, modulo 360) of the thick cell 35/45, mu = 0.5, t = 0.05 at
    phi1 = 90 deg (eqn 5-12)."""
    fb = dihedrals(waterbomb(35, 45, 0.5, 0.05), WATERBOMB_LINE, 90)
    return np.array([360 - fb[0], 180 - fb[1], fb[2], 360 - fb[3], fb[4], 180 - fb[5]]) % 360


def _wb(where, quantity, printed, ours, tol, test, **kw) -> Number:
    return Number(where, quantity, printed, ours, tol, _WB + test, unit="deg", in_text=False, **kw)


_VERTEX_B = "test_waterbomb_vertex_b_dihedrals_on_paths_i_and_ii"
WATERBOMB = (
    *(_wb(f"eqns 5-8, 5-9, alpha/beta = {a}/{b}", f"vertex B dihedrals phi1..phi6 on path {p} at phi1 = 90 deg",
          printed, lambda a=a, b=b, branch=branch: dihedrals(waterbomb(a, b), branch, 90), WATERBOMB_DEG, _VERTEX_B)
      for a, b, p, branch, printed in (
          (40, 40, "I", WATERBOMB_LINE, "90, 19.7022, 74.9074, 90, 74.9074, 19.7022"),
          (40, 40, "II", WATERBOMB_PLANE, "90, 60.8109, 74.9074, 31.6217, 74.9074, 60.8109"),
          (35, 45, "I", WATERBOMB_LINE, "90, 19.7022, 78.6454, 90, 78.6454, 19.7022"),
          (35, 45, "II", WATERBOMB_PLANE, "90, 83.2113, 78.6454, 1.2332, 78.6454, 83.2113"))),
    *(_wb("eqn 5-4, alpha = beta = 40", f"vertex A's phi2 at phi1 = {phi1} deg (path I)", printed,
          lambda phi1=phi1: dihedrals(waterbomb(40, 40), WATERBOMB_LINE, phi1, order=("A2",)), WATERBOMB_DEG,
          "test_waterbomb_vertex_a_of_section_5_3")
      for phi1, printed in ((90, "74.9074"), (150, "141.4421"), (30, "23.1990"))),
    *(_wb(f"eqns 5-8, 5-9, alpha/beta = {a}/{b}", f"phi3, path I phi2, path II phi2, path II phi4 at phi1 = {phi1} deg "
          "(3 decimals)", printed, lambda a=a, b=b, phi1=phi1: vertex_b_sweep_row(a, b, phi1), 5e-4,
          "test_waterbomb_vertex_b_sweeps_including_blocked_phi4")
      for a, b, phi1, printed in ((40, 40, 150, "141.442, 65.892, 130.916, 111.833"),
                                  (40, 40, 60, "47.717, 11.450, 37.433, 14.866"),
                                  (35, 45, 120, "109.647, 33.479, 105.903, 48.135"),
                                  (35, 45, 60, "50.622, 11.450, 71.965, -44.050"))),
    *(_wb(f"§5.3 (blockage, eqn 5-9c), alpha/beta = {a}/{b}", "phi1 where path II blocks (pi + x*)", printed,
          lambda a=a, b=b: 180 + np.rad2deg(plane_blockage(a * DEG, b * DEG)), 5e-4,
          "test_waterbomb_blockage_onsets_of_path_two")
      for a, b, printed in ((35, 45, "89.148"), (50, 50, "90.488"), (40, 55, "109.972"))),
    _wb("§5.4, eqn 5-12", "thick vertex B's D-H angles omega1..omega6 (35/45, mu = 0.5, t = 0.05, phi1 = 90 deg)",
        "-90, 160.2978, 78.6454, -90, 78.6454, 160.2978", thick_vertex_b_omega, WATERBOMB_DEG,
        "test_thick_waterbomb_vertex_b_dh_angles_of_eqn_5_12", angle=True),
)


# --- chapter 6: the generalized waterbomb tube ------------------------------------------------------------------

_TUBE = "test_waterbomb_tube.py::"


def m7_events(kind: str) -> np.ndarray:
    """theta (deg) of the n6 m7 45/45 tube's events of one kind."""
    return np.array([180 + e.input / DEG for e in tube(6, 7, 45, 45).events() if e.kind == kind])


def m7_state(theta: float) -> np.ndarray:
    """r_A, r_B and z_A (a = 1) of rows 0..3 from the equator outward, n6 m7 45/45 at theta (deg), flattened."""
    rows = row_coordinates(6, 7, 45 * DEG, 45 * DEG, 1.0, theta * DEG)
    return np.array([[rows[kind, i][c][0] for i in range(4)] for kind, c in (("A", 0), ("B", 0), ("A", 1))]).ravel()


_M_7_EVENTS = "test_feng2018_m7_events_against_the_thesis"
_LIMITS = "test_twist_limits_and_thresholds_closed_forms"
TUBE = (
    Number("ch. 6, eqn 6-18", "corner-to-corner length (eqn 6-18), n6 m3 45/45 at theta = 60, 100 deg",
           "4.28477, 4.78041", lambda: tube(6, 3, 45, 45).length(np.array([60, 100]) * DEG - np.pi, corners=True),
           5e-6, _TUBE + "test_tube_radii_uniform_states_and_axial_lengths", unit="m", in_text=False),
    *(Number("ch. 6, n6 m7 45/45", f"r_A, r_B, z_A of rows 0..3 from the equator outward at theta = {t} deg", printed,
             lambda t=t: m7_state(t), 5e-6, _TUBE + "test_feng2018_m7_tube_states", unit="m", in_text=False)
      for t, printed in (
          (60, "0, 0.01361, 0.05118, 0.10327, 1.0, 1.0333, 1.08128, 1.13116, 0, 1.1644, 2.33061, 3.50043"),
          (100, "0.68404, 0.5642, 0.27854, -0.05363, 1.53209, 1.27821, 0.94061, 0.64657, "
                "0, 1.25137, 2.41594, 3.53001"),
          (140, "1.28558, 1.2151, 0.9167, 0.43918, 1.87939, 1.79301, 1.43821, 0.83989, "
                "0, 1.74748, 3.26954, 4.39813"))),
    Number("eqn 6-47", "alpha limit of the twist for n = 5, 6, 8, 12", "51.0266, 49.1066, 47.2658, 45.9930",
           lambda: [alpha_limit(n) / DEG for n in (5, 6, 8, 12)], 5e-5, _TUBE + _LIMITS, unit="deg", in_text=False),
    Number("eqn 6-33", "alpha_min for n = 5, 6, 8, 12", "44.1788, 44.6530, 44.9024, 44.9822",
           lambda: [alpha_min(n) / DEG for n in (5, 6, 8, 12)], 5e-5, _TUBE + _LIMITS, unit="deg", in_text=False),
    Number("ch. 6, n6 m7 45/45", "uniform-radius states (the thesis samples theta on a 0.06-0.12 deg grid)",
           "65.88, 144.0", lambda: m7_events("uniform_radius"), 0.12, _TUBE + _M_7_EVENTS, unit="deg"),
    Number("ch. 6, n6 m7 45/45", "locks: fully folded, interference begins and ends (0.12 deg grid)",
           "60, 90.72, 128.52", lambda: m7_events("lock"), 0.12, _TUBE + _M_7_EVENTS, unit="deg"),
    Number("ch. 6, n6 m7 45/45", "theta_max, the turning point (0.12 deg grid)", "144.24",
           lambda: m7_events("turning_point"), 0.12, _TUBE + _M_7_EVENTS, unit="deg"),
    Number("ch. 6, n6 m7 45/45", "uniform-radius states and interference limits, exact (3 decimals)",
           "65.937, 144.063, 90.751, 128.475",
           lambda: np.concatenate([m7_events("uniform_radius"), m7_events("lock")[1:]]), 5e-4, _TUBE + _M_7_EVENTS,
           unit="deg", in_text=False),
    Number("ch. 6, n6 m7 45/45", "top row's r_A at theta = 100 deg", "-0.05363",
           lambda: tube(6, 7, 45, 45).radii(100 * DEG - np.pi)[0, -1], 5e-6, _TUBE + _M_7_EVENTS, unit="m",
           in_text=False),
)


def _square_twist_end(names: list[str]) -> np.ndarray:
    """Dihedrals (deg) of the n6 m3 45/45 twist at its eta02 = 0 end (counter-clockwise)."""
    model = twist(6, 3, 45, 45)
    return twist_angles(model, TWIST_CCW, np.rad2deg(np.pi - model.domain[1]), names)


def _square_twist_at_tilt(zeta: float, names: list[str]) -> np.ndarray:
    """Dihedrals (deg) of the n6 m3 45/45 twist where the side edge tilts to zeta (deg)."""
    x = middle_input(6, 45 * DEG, 45 * DEG, 1.0, np.array([zeta * DEG]))
    return twist_angles(twist(6, 3, 45, 45), TWIST_CCW, np.rad2deg(np.pi - x[0]), names)


_TW = "test_waterbomb_twist.py::test_feng2018_square_tube_twist"
SQUARE_TWIST = (
    Number("ch. 6, n6 m3 45/45", "eta02 where the tube is untwisted (3 decimals)", "44.415",
           lambda: 180 - twist(6, 3, 45, 45).start / DEG, 5e-4, _TW, unit="deg", in_text=False),
    Number("ch. 6, n6 m3 45/45", "eta03, eta06, eta01 at eta02 = 0 (3 decimals)", "90, 90, 70.529",
           lambda: _square_twist_end(["A1_0_3", "A1_0_6", "A1_0_1"]), 5e-4, _TW, unit="deg", in_text=False),
    Number("ch. 6, n6 m3 45/45", "eta01, eta02, eta03 where the side edge tilts to zeta = 80 deg (3 decimals)",
           "60.993, 30.510, 58.514", lambda: _square_twist_at_tilt(80, ["A1_0_1", "A1_0_2", "A1_0_3"]), 5e-4, _TW,
           unit="deg", in_text=False),
)


NUMBERS: tuple[Number, ...] = (*BRICARD, *TRIANGLE_TWIST, *WATERBOMB, *TUBE, *SQUARE_TWIST)
CORRECTIONS: tuple[Correction, ...] = (
    Correction("eqn 4-6c", "C's linear term +2 sin(alpha) (R3 sin(gamma) + R2 sin(beta + gamma)) m",
               "the same term with -2 sin(alpha)", "loop closure residual (m and rad) of both roots, offsets case "
               "(R2 = 0.3, R3 = -0.5), theta2 from -120 to -30 deg", eqn_4_6c_residuals,
               "test_bricard_plane.py::test_corrected_c_closes_with_offsets_and_the_printed_c_does_not", 1e-12, 0.01),
    *CORRECTIONS_3,
)
