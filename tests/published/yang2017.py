"""Yang 2017 (PhD thesis: truss method, transformable polyhedra): the numbers the tests check.

Where the thesis prints a value (marked without (w)) the test holds ours to its printed places; the rest are worked
values of its equations at its own examples, to the places shown.
"""

from functools import cache

import numpy as np

from published import Correction, Number
from sim_origami.geometry import invert, transform_z, unit
from sim_origami.kinematics.bricard_threefold import AGAINST, ALONG, BricardThreefold
from sim_origami.kinematics.cuboctahedron import AXES, VERTICES, CuboctahedronOctahedron
from sim_origami.kinematics.myard import BRANCH as MYARD_BRANCH
from sim_origami.kinematics.myard import Myard
from sim_origami.kinematics.truncated_octahedron import TruncatedOctahedronCube, volume
from sim_origami.kinematics.truncated_tetrahedron import VERTICES as TETRA_VERTICES
from sim_origami.kinematics.truncated_tetrahedron import SchemeI, SchemeII, axis_g
from sim_origami.studies.fabrication import (
    FINE_LENGTH,
    NOMINAL,
    RSSR,
    VERY_COARSE,
    FabricationError,
    max_waggle,
    output_error,
    study,
)

DOCUMENT = "Yang 2017"
DEG = np.pi / 180
# Four decimals (deg): half a unit of the last place.
FOUR_DECIMALS_DEG = 5e-5
_B3 = "test_bricard_threefold.py::"


# --- ch. 2 example (eqns 2-8 to 2-11): the threefold-symmetric Bricard linkage -----------------------------------


@cache
def threefold(alpha_deg: float) -> BricardThreefold:
    return BricardThreefold(1.0, alpha_deg * DEG)


def threefold_phi(alpha_deg: float, theta_deg: float) -> np.ndarray:
    """phi (deg) on the branches along and against at theta (deg)."""
    m = threefold(alpha_deg)
    return np.array([m.joint_angles(b, theta_deg * DEG)[0, 1] / DEG for b in (ALONG, AGAINST)])


def joint_frames(m: BricardThreefold, q: np.ndarray) -> np.ndarray:
    """World frames (6, 4, 4) of joints 1..6 from the D-H product (frame 1 = world), no closed form."""
    loop = m.loop_system().loops[0]
    out, T = [], np.eye(4)
    for k in range(6):
        out.append(T)
        T = T @ transform_z(q[k]) @ loop.links[k]
    return np.array(out)


CH2_POINTS = (
    "0, 1.1372, 0.1569, -0.4280, 0.2471, 0, -0.9848, -0.5686, 0.1569, 0, -0.4943, 0, 0.9848, -0.5686, 0.1569, "
    "0.4281, 0.2471, 0, 0, 1.1198, 0.2554, -0.3498, 0.2019, 0.0428, -0.9698, -0.5599, 0.2554, 0, -0.4039, 0.0428, "
    "0.9698, -0.5599, 0.2554, 0.3498, 0.2019, 0.0428"
)


def ch2_fitted_points() -> tuple[np.ndarray, float]:
    """Our joints A..F and second axis points X + 0.1 s_X at theta = 129.31 deg (twists 300/60), moved onto the
    printed points (2-10, 2-11) by the best proper rotation and translation (Kabsch), flattened; and the
    determinant's sign d of the best rotation (+1: the printed linkage is ours, not its mirror image)."""
    printed = np.array([float(v) for v in CH2_POINTS.split(",")]).reshape(12, 3)
    m = threefold(300.0)
    F = joint_frames(m, m.joint_angles(ALONG, 129.31 * DEG)[0])
    ours = np.concatenate([F[:, :3, 3], F[:, :3, 3] + 0.1 * F[:, :3, 2]])
    a, b = ours - ours.mean(0), printed - printed.mean(0)
    U, _, Vt = np.linalg.svd(a.T @ b)
    d = float(np.sign(np.linalg.det(Vt.T @ U.T)))
    fitted = a @ (Vt.T @ np.diag([1.0, 1.0, d]) @ U.T).T + printed.mean(0)
    return fitted.ravel(), d


_THREEFOLD_PHI = (
    (0.0, "120.0, -120.0"),
    (30.0, "103.0036, -133.5265"),
    (60.0, "80.4156, -144.8241"),
    (90.0, "48.4069, -154.6671"),
    (129.31, "-19.9903, -166.2084"),
    (150.0, "-75.3342, -171.9186"),
    (170.0, "-142.9811, -177.3189"),
    (179.0, "-176.2683, -179.7320"),
)

THREEFOLD = (
    *(Number("ch. 2 example (twists 300/60)", f"phi on the branches along and against at theta = {t:g} deg", printed,
             lambda t=t: threefold_phi(300.0, t), FOUR_DECIMALS_DEG,
             _B3 + "test_threefold_bricard_phi_of_the_chapter_2_example", unit="deg", angle=True, in_text=False)
      for t, printed in _THREEFOLD_PHI),
    Number("eqn 2-9 (axes at B, D, F reversed: twists 120/240)",
           "phi on the branches against and along at theta = 129.31 deg", "19.9903, 166.2084",
           lambda: threefold_phi(120.0, 129.31)[::-1], FOUR_DECIMALS_DEG,
           _B3 + "test_ch2_example_with_even_axes_reversed_has_phi_negated", unit="deg", in_text=False),
    Number("eqns 2-10, 2-11", "joints A..F and the points X + 0.1 s_X at theta = 129.31 deg, after the best "
           "rigid motion (4 decimals, and theta's 2)", CH2_POINTS, lambda: ch2_fitted_points()[0], 1e-4,
           _B3 + "test_ch2_joint_coordinates_are_reproduced_up_to_a_rigid_motion", unit="m", strict=True),
    *(Number("ch. 2, Myard example", f"Myard theta1..theta5 at theta3 = 40 deg, alpha12 = {a:g} deg", printed,
             lambda a=a: np.rad2deg(Myard(1.0, a * DEG).joint_angles(MYARD_BRANCH, 40 * DEG)[0]), FOUR_DECIMALS_DEG,
             "test_myard.py::test_yang2017_example_theta3_40_deg", unit="deg", angle=True, in_text=False)
      for a, printed in ((50.0, "100, 90, 40, 220, 270"), (30.0, "100, 64.4559, 40, 220, 295.5441"),
                         (70.0, "100, 128.3039, 40, 220, 231.6961"))),
)


# --- chapter 4: the cuboctahedron -------------------------------------------------------------------------------

_CO = "test_cuboctahedron.py::"


@cache
def cuboctahedron() -> CuboctahedronOctahedron:
    return CuboctahedronOctahedron()


def theta_at_bd(bd: float) -> float:
    """Input at which the diagonal BD (m) is reached (BD grows monotonically with theta), by bisection."""
    model = cuboctahedron()
    lo, hi = model.domain
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if model.diagonals(mid)["BD"][0] < bd:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def path_row(bd: float) -> np.ndarray:
    """BD, AI, EF, AC, EH, BJ (m) where BD reaches bd."""
    d = cuboctahedron().diagonals(theta_at_bd(bd))
    return np.array([d[k][0] for k in ("BD", "AI", "EF", "AC", "EH", "BJ")])


def path_maximum(key: str) -> np.ndarray:
    """(largest diagonal `key`, BD there) on 20001 samples of the path."""
    d = cuboctahedron().diagonals(np.linspace(*cuboctahedron().domain, 20001))
    k = int(np.argmax(d[key]))
    return np.array([d[key][k], d["BD"][k]])


def axis_angles_at_c() -> np.ndarray:
    """gamma1 = angle(s_C, CB) and gamma2 = angle(s_C, CF) (deg) of the printed axes (4-7, 4-8)."""
    s_c = unit(AXES["C"])
    return np.array([np.arccos(s_c @ unit(VERTICES[v] - VERTICES["C"])) / DEG for v in "BF"])


def design_terms() -> np.ndarray:
    """tan(theta3), tan(theta4) of (4-30) corrected and the terms A, B, C of (4-33), from theta_d, phi_d."""
    model = cuboctahedron()
    ct, cp = np.cos(model.theta_d), np.cos(model.phi_d)
    cos_2g1, cos_2g2 = (cp + 1) / (ct - 1), (ct + 1) / (cp - 1)
    cg1, cg2, ca = np.sqrt((1 + cos_2g1) / 2), np.sqrt((1 + cos_2g2) / 2), 0.4
    t3 = np.sqrt((1 + cp) * (1 - ct) / (-2 * (ct + cp)))
    t4 = np.sqrt((1 + ct) * (1 - cp) / (-2 * (ct + cp)))
    term_a = 1 + t3**2 + t4**2 + 2 * t3 * t4 * ca
    term_b = -t3 / cg1 + t4 / cg2 + (t3 / cg2) * ca - (t4 / cg1) * ca
    term_c = 1 / (4 * cg1**2) + 1 / (4 * cg2**2) - ca / (2 * cg1 * cg2) - 1
    return np.array([t3, t4, term_a, term_b, term_c])


_PATH = (
    "1.2000, 1.2280, 1.0261, 1.5316, 1.4955, 1.6911",
    "1.0002, 1.0011, 0.7484, 1.5490, 1.5352, 1.7759",
    "0.7994, 0.7733, 0.5338, 1.5350, 1.5490, 1.7757",
    "0.5996, 0.5591, 0.3644, 1.5094, 1.5416, 1.7262",
    "0.4993, 0.4569, 0.2912, 1.4945, 1.5308, 1.6885",
    "0.3006, 0.2650, 0.1634, 1.4634, 1.4966, 1.5947",
    "0.0995, 0.0845, 0.0510, 1.4307, 1.4454, 1.4785",
    "0.0100, 0.0084, 0.0050, 1.4159, 1.4175, 1.4209",
    "0.0010, 0.0008, 0.0005, 1.4144, 1.4145, 1.4149",
)
_BEN = _CO + "test_cuboctahedron_bennett_parameters_match_eqn_4_7"
_PT = "ch. 4, path by the truss method"
_MAXIMA = (("AC", "1.5492", "1.02"), ("EH", "1.5492", "0.78"), ("BJ", "1.7836", "0.90"))

CUBOCTAHEDRON = (
    Number("eqn 4-7", "gamma1 = angle(s_C, CB), gamma2 = angle(s_C, CF)", "71.57, 50.77", axis_angles_at_c, 5e-3,
           _BEN, unit="deg"),
    Number("eqn 4-29 (with the printed axes: the thesis's -154.79, -58.41 negated)", "theta_d, phi_d (3 decimals)",
           "154.791, 58.412", lambda: np.array([cuboctahedron().theta_d, cuboctahedron().phi_d]) / DEG, 1e-3, _BEN,
           unit="deg", in_text=False),
    Number("eqns 4-30 (corrected), 4-33", "tan(theta3), tan(theta4), and A, B, C of (4-33)",
           "1.951800, 0.243975, 5.25, -4.860556, 1.125", design_terms, 1e-6,
           _CO + "test_deployed_design_equations", in_text=False),
    *(Number("ch. 4 example", f"phi at theta = {t} deg (3 decimals)", phi,
             lambda t=t: cuboctahedron().phi(t * DEG) / DEG, 5e-4, _CO + "test_cuboctahedron_bennett_samples",
             unit="deg", in_text=False) for t, phi in ((120, "110.570"), (90, "136.397"))),
    *(Number("ch. 4 example", f"diagonals AC, BD at theta = {t} deg (tolerance 1e-5)", d,
             lambda t=t: [cuboctahedron().diagonals(t * DEG)[k][0] for k in ("AC", "BD")], 1e-5,
             _CO + "test_cuboctahedron_bennett_samples", unit="m", in_text=False)
      for t, d in ((120, "1.54826, 0.97136"), (90, "1.49712, 0.51643"))),
    Number("eqns 4-41 (corrected), 4-42", "theta_f and phi at the fold (B = D)", "58.4119, 154.7912",
           lambda: np.array([cuboctahedron().domain[0], cuboctahedron().phi(cuboctahedron().domain[0])]) / DEG, 1e-4,
           _CO + "test_cuboctahedron_bennett_fold_of_eqn_4_41_corrected", unit="deg", in_text=False),
    *(Number(_PT + " (4 decimals)", f"BD, AI, EF, AC, EH, BJ where BD = {row[:6]} (truss tolerance)", row,
             lambda row=row: path_row(float(row.split(",")[0])), 3e-4, _CO + "test_path_matches_the_worked_table",
             unit="m", strict=True, in_text=False) for row in _PATH),
    *(Number(_PT, f"largest {key} on 20001 samples", peak, lambda key=key: path_maximum(key)[0], 1e-4,
             _CO + "test_path_maxima", unit="m", in_text=False)
      for key, peak, _ in _MAXIMA),
    *(Number(_PT, f"BD where {key} is largest (2 decimals)", at, lambda key=key: path_maximum(key)[1],
             0.01, _CO + "test_path_maxima", unit="m", in_text=False)
      for key, _, at in _MAXIMA),
)


# --- chapter 3: fabrication errors of the RSSR -------------------------------------------------------------------

_FAB = "test_fabrication.py::"
D_ALPHA, D_L = VERY_COARSE
FABRICATION_ERRORS = {
    "d_alpha = 1 deg, k = +1": FabricationError(D_ALPHA, 0.0, 1),
    "d_l = 1.5 mm, k = +1": FabricationError(0.0, D_L, 1),
    "d_l = 1.5 mm, k = -1": FabricationError(0.0, D_L, -1),
    "d_l = 0.15 mm, k = +1": FabricationError(0.0, FINE_LENGTH, 1),
    "d_l = 0.15 mm, k = -1": FabricationError(0.0, FINE_LENGTH, -1),
}


@cache
def nominal_rssr() -> RSSR:
    return RSSR(*NOMINAL)


def rssr_from(a1: float, a2: float, alpha_deg: float, root: int = 1) -> RSSR:
    return RSSR(a1, a2, alpha_deg * DEG, root=root)


@cache
def fabrication_study(name: str):
    return study(nominal_rssr(), FABRICATION_ERRORS[name])


def _peaks(name: str) -> np.ndarray:
    s = fabrication_study(name)
    return np.array([s.exact.value, s.linearised.value]) / DEG


_STUDY = _FAB + "test_yang2017_output_errors"
_RSSR = (
    ((100, 70.72, 45), "30.0044", "-4.665482, 1.249732"),
    ((101.5, 69.22, 45), "28.8309", "-4.270901, 1.238316"),
    ((100, 70.72, 46), "30.5784", "-4.618156, 1.262539"),
)
_KEY = _FAB + "test_key_identity_rssr_is_the_bennett_with_implied_beta"

FABRICATION = (
    *(Number(f"ch. 3, eqns 3-3 to 3-6, RSSR a1, a2, alpha = {g}", "implied Bennett twist beta", beta,
             lambda g=g: rssr_from(*g).beta / DEG, 5e-5, _KEY, unit="deg", in_text=False) for g, beta, _ in _RSSR),
    *(Number(f"ch. 3, eqns 3-3 to 3-6, RSSR a1, a2, alpha = {g}", "K on both roots (6 decimals)", k,
             lambda g=g: [rssr_from(*g).K, rssr_from(*g, root=-1).K], 5e-7, _KEY, in_text=False)
      for g, _, k in _RSSR),
    *(Number("§3.5, eqns 3-5, 3-42", f"largest output error, exact and linearised, {name} (3 decimals)", printed,
             lambda name=name: _peaks(name), 5e-4, _STUDY, unit="deg", in_text=False)
      for name, printed in (("d_alpha = 1 deg, k = +1", "0.584, 0.577"), ("d_l = 1.5 mm, k = +1", "5.061, 5.447"),
                            ("d_l = 1.5 mm, k = -1", "5.639, 5.221"), ("d_l = 0.15 mm, k = +1", "0.530, 0.534"),
                            ("d_l = 0.15 mm, k = -1", "0.536, 0.532"))),
    *(Number("§3.5, eqn 3-5", f"theta1 of the largest exact output error, {name} (0.1 deg)", printed,
             lambda name=name: fabrication_study(name).exact.theta1 / DEG, 0.05, _STUDY, unit="deg", in_text=False)
      for name, printed in (("d_alpha = 1 deg, k = +1", "155.7"), ("d_l = 1.5 mm, k = +1", "154.7"),
                            ("d_l = 1.5 mm, k = -1", "156.9"), ("d_l = 0.15 mm, k = +1", "155.7"),
                            ("d_l = 0.15 mm, k = -1", "155.9"))),
    Number("§3.5, eqn 3-5", "output error at theta1 = 170, 179 deg, d_l = 1.5 mm, k = +1 (3 decimals)", "3.431, 0.394",
           lambda: output_error(nominal_rssr(), FABRICATION_ERRORS["d_l = 1.5 mm, k = +1"].built(nominal_rssr()),
                                np.array([170.0, 179.0]) * DEG) / DEG, 5e-4,
           _FAB + "test_output_error_falls_towards_the_half_turn", unit="deg", in_text=False),
    *(Number("eqn 3-50 (corrected)", f"largest ball waggle, {name} (3 decimals; the thesis prints {thesis})",
             printed, lambda err=err: max_waggle(nominal_rssr(), err.built(nominal_rssr())).value / DEG, 5e-4,
             _FAB + "test_waggle_corrected_3_50", unit="deg", in_text=False)
      for name, err, printed, thesis in (("d_alpha = -1 deg", FabricationError(-D_ALPHA, 0.0, 1), "0.581", "0.58"),
                                         ("d_l = 1.5 mm, k = -1", FabricationError(0.0, D_L, -1), "1.224", "1.22"))),
)


def eqn_3_49_residuals() -> tuple[float, float]:
    """Largest | |CD| - L | (mm) over theta1 of the RSSR built with d_l = 1.5 mm, k = -1, CD of eqn 3-48: L = a1R
    (corrected) and L = a2R (as printed)."""
    built = FabricationError(0.0, D_L, -1).built(nominal_rssr())
    t1, b = np.linspace(-np.pi, np.pi, 2001), nominal_rssr().beta
    T_AD = np.array([[1, 0, 0, built.a2], [0, np.cos(b), -np.sin(b), 0], [0, np.sin(b), np.cos(b), 0], [0, 0, 0, 1]])
    t2 = built.theta2(t1)
    C_B = np.stack([built.a2 * np.cos(t2), built.a2 * np.sin(t2), 0 * t2, 1 + 0 * t2], -1)
    C_D = np.einsum("ij,njk,nk->ni", T_AD, transform_z(t1) @ built.bennett_rows()[0].link(), C_B)[:, :3]
    length = np.linalg.norm(C_D, axis=1)
    return float(np.max(np.abs(length - built.a1))), float(np.max(np.abs(length - built.a2)))


CORRECTIONS_3 = (
    Correction("eqns 3-49, 3-50", "|CD| = a2R (the waggle normalised by a2R: 0.821 / 1.669 deg)",
               "|CD| = a1R (0.581 / 1.224 deg)", "largest | abs(CD) - L | (mm) over theta1, RSSR built with "
               "d_l = 1.5 mm, k = -1", eqn_3_49_residuals, _FAB + "test_waggle_corrected_3_50", 1e-11, 1.0),
)

# --- chapter 5: the truncated octahedron -------------------------------------------------------------------------

_TO = "test_truncated_octahedron.py::"


@cache
def truncated_octahedron() -> TruncatedOctahedronCube:
    return TruncatedOctahedronCube()


def theta_at_rho1(rho1: float) -> float:
    """Input at which Bricard 1's fold angle rho1 (rad) is reached (rho1 falls monotonically), by bisection."""
    model = truncated_octahedron()

    def rho(theta: float) -> float:  # angle B1 C2 C1 from Bricard 1 alone
        p = model.bricard_points(np.array([theta]))
        u, w = p["B1"][0] - p["C2"][0], p["C1"][0] - p["C2"][0]
        return float(np.arctan2(np.linalg.norm(np.cross(u, w)), u @ w))

    lo, hi = model.domain
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if rho(mid) > rho1 else (lo, mid)
    return 0.5 * (lo + hi)


def octahedron_path_row(rho1_deg: float) -> np.ndarray:
    """rho1, rho2, delta_A, delta_D and the odd joint angles of Bricard 1 and 2 (deg) where rho1 is reached."""
    model = truncated_octahedron()
    theta = theta_at_rho1(rho1_deg * DEG)
    return np.concatenate([model.fold_angles(theta)[0], [theta, model.state(theta)[0, 0]]]) / DEG


def _octahedron_ends() -> np.ndarray:
    model = truncated_octahedron()
    lo, hi = model.domain
    return np.array([lo, model.phi(lo)[0], hi, model.phi(hi)[0] % (2 * np.pi)]) / DEG


def _octahedron_volume_ratio() -> float:
    deployed, cube = volume(truncated_octahedron().vertices(np.array(truncated_octahedron().domain)))
    return deployed / cube


_TO_PATH = (
    "109.98, 106.43, 129.39, 132.34, 47.21, 51.76",
    "95.90, 95.87, 139.35, 139.37, 65.09, 65.14",
    "90.03, 93.03, 141.82, 140.71, 72.41, 68.68",
    "60.01, 84.62, 135.59, 142.97, 107.71, 79.04",
    "30.01, 68.06, 113.55, 139.87, 138.78, 98.63",
    "9.97, 37.09, 97.75, 119.12, 157.38, 131.83",
)
_TO_CASE = _TO + "test_truncated_octahedron_bricard_parameters"

TRUNCATED_OCTAHEDRON = (
    Number("ch. 5, Bricard linkage", "link length a (6 decimals)", "0.713234", lambda: truncated_octahedron().bricard.a,
           5e-7, _TO_CASE, unit="m", in_text=False),
    Number("ch. 5, Bricard linkage", "twist alpha (the example's tolerance 1e-3 deg)", "214.7865",
           lambda: truncated_octahedron().bricard.alpha / DEG, 1e-3, _TO_CASE, unit="deg", in_text=False),
    Number("ch. 5, Bricard linkage", "theta_d, phi_d (deployed) and theta_f, phi_f (cube), tolerance 1e-3 deg",
           "34.3147, 147.4964, 166.1251, 268.4470", _octahedron_ends, 1e-3, _TO_CASE, unit="deg", in_text=False),
    Number("ch. 5 abstract", "volume ratio of the truncated octahedron to the cube (1 decimal)", "11.3",
           _octahedron_volume_ratio, 0.05, _TO + "test_volume_ratio", strict=True),
    *(Number("ch. 5, path by the truss method (+/-0.1 deg)",
             f"rho1, rho2, delta_A, delta_D, Bricard 1 and 2's odd joint angles where rho1 = {row.split(',')[0]}",
             row, lambda row=row: octahedron_path_row(float(row.split(",")[0])), 0.1,
             _TO + "test_path_matches_the_worked_table", unit="deg", in_text=False) for row in _TO_PATH),
)

# --- chapter 6: the truncated tetrahedron ------------------------------------------------------------------------

_TT = "test_truncated_tetrahedron.py::"


@cache
def scheme(name: str) -> SchemeI | SchemeII:
    """Scheme II (delta2 = 0), scheme I (s_G along QG) or scheme I with its axis turned by delta1 = -5 deg."""
    return {"II": SchemeII, "I": SchemeI, "I-5": lambda: SchemeI(-5 * DEG)}[name]()


def rho_input(kinematics, rho: float) -> float:
    """Input at which rho = angle AFE (rad) is reached on the last (folding) stretch of the path (bisection)."""
    x = np.linspace(*kinematics.domain, 60)
    r = kinematics.monitors(x)["rho"] - rho
    cross = np.nonzero(np.diff(np.sign(r)))[0]
    k = cross[0] if kinematics.domain[0] == kinematics.events()[1].input else cross[-1]
    a, b, fa = x[k], x[k + 1], r[k]
    for _ in range(40):
        c = 0.5 * (a + b)
        fc = kinematics.monitors(c)["rho"][0] - rho
        a, b, fa = (c, b, fc) if np.sign(fc) == np.sign(fa) else (a, c, fa)
    return 0.5 * (a + b)


def _scheme_ii_frame_2() -> np.ndarray:
    two = scheme("II")
    return two._frame @ transform_z(two.theta_d) @ two.rows[0].link()  # joint B's D-H frame (6-26)


def _monitors(name: str, rho_deg: float, keys: tuple[str, ...]) -> np.ndarray:
    m = scheme(name).monitors(rho_input(scheme(name), rho_deg * DEG))
    return np.array([m[k][0] / DEG if k in ("delta", "lambda1", "lambda2", "rotation") else m[k][0] for k in keys])


_TABLE_II = (
    ("105.03", "129.30, 81.58, 55.08, 146.87", "1.1661, 1.5870, 1.3066"),
    ("90.05", "125.06, 64.96, 31.65, 157.01", "0.8457, 1.4148, 1.0740"),
    ("59.95", "99.06, 38.32, 8.60, 154.84", "0.3979, 0.9992, 0.6563"),
    ("29.94", "76.94, 17.29, 1.36, 140.00", "0.1430, 0.5166, 0.3005"),
    ("5.01", "62.62, 2.77, 0.11, 123.79", "0.0175, 0.0874, 0.0484"),
)
_TABLE_I = (
    ("105.02", "91.35, 65.93, 137.44", "1.3321, 1.4308"),
    ("59.94", "50.29, 26.98, 143.12", "0.7416, 0.8498"),
    ("4.99", "10.90, 9.90, 120.92", "0.1883, 0.1899"),
)
_C16 = _TT + "test_truncated_tetrahedron_bricard_parameters"
_PATH_II = _TT + "test_scheme_ii_path_matches_the_worked_table"
_PATH_I = _TT + "test_scheme_i_path_matches_the_worked_table"
_MISS = _TT + "test_scheme_i_misses_the_tetrahedron"

TRUNCATED_TETRAHEDRON = (
    Number("eqn 6-26, scheme II", "twist alpha12", "231.0378", lambda: scheme("II").rows[0].alpha % (2 * np.pi) / DEG,
           5e-5, _C16, unit="deg", in_text=False),
    Number("eqn 6-28", "G in joint B's frame (5 decimals, tolerance 1e-5)", "0.06019, -0.62767, 0.07593",
           lambda: (invert(_scheme_ii_frame_2()) @ np.append(TETRA_VERTICES["G"], 1))[:3], 1e-5, _C16, unit="m",
           in_text=False),
    Number("eqn 6-33 (corrected)", "s_G in joint B's frame (6 decimals, tolerance 1e-6)",
           "0.667325, -0.738119, -0.099286", lambda: _scheme_ii_frame_2()[:3, :3].T @ axis_g(0.0), 1e-6, _C16,
           in_text=False),
    Number("ch. 6, scheme II", "theta_d, phi_d (deployed) and theta_f, phi_f (folded), tolerance 1e-4",
           "40.4591, 143.5473, 186.9018, 266.0295",
           lambda: np.array([scheme("II").theta_d, scheme("II").phi_d, scheme("II").theta_f,
                             scheme("II").phi(scheme("II").theta_f)[0] % (2 * np.pi)]) / DEG, 1e-4, _C16,
           unit="deg", in_text=False),
    Number("ch. 6, scheme II", "phi at theta = 60, 90, 120, 150 deg (tolerance 1e-4)",
           "154.1717, 170.7849, 189.7716, 215.3841",
           lambda: scheme("II").phi(np.array([60.0, 90.0, 120.0, 150.0]) * DEG) % (2 * np.pi) / DEG, 1e-4, _C16,
           unit="deg", in_text=False),
    Number("ch. 6, scheme I", "theta_G at the deployed state (T_A's angle, 4 decimals)", "146.4427",
           lambda: scheme("I").domain[1] / DEG, 1e-4, _MISS, unit="deg", in_text=False),
    Number("ch. 6, scheme I (s_G along QG)", "theta_G where the path ends at the Bricard fold (3 decimals)", "3.708",
           lambda: scheme("I").domain[0] / DEG, 1e-3, _MISS, unit="deg", in_text=False),
    Number("ch. 6, scheme I (s_G along QG)", "|BK| at the end (4 decimals)", "0.0585",
           lambda: scheme("I").monitors(scheme("I").domain[0])["BK"][0], 1e-4, _MISS, unit="m", in_text=False),
    Number("ch. 6, scheme I (s_G along QG)", "KLM height at the end (the end sample sits a little off the fold: "
           "tolerance 3e-4)", "0.0586", lambda: scheme("I").monitors(scheme("I").domain[0])["height"][0], 3e-4, _MISS,
           unit="m", in_text=False),
    Number("ch. 6, scheme I (s_G along QG)", "KLM rotation at the end, less 90 deg (2 decimals)", "29.66",
           lambda: scheme("I").monitors(scheme("I").domain[0])["rotation"][0] / DEG - 90, 0.01, _MISS, unit="deg",
           in_text=False),
    *(Number("ch. 6, scheme II path by the truss method (2 decimals)",
             f"delta, lambda1, lambda2, KLM rotation where rho = {rho} deg (tolerance 0.02)", angles,
             lambda rho=rho: _monitors("II", float(rho), ("delta", "lambda1", "lambda2", "rotation")), 0.02, _PATH_II,
             unit="deg", in_text=False) for rho, angles, _ in _TABLE_II),
    *(Number("ch. 6, scheme II path by the truss method (4 decimals)",
             f"KLM height, |AE|, |BK| where rho = {rho} deg (tolerance 3e-4)", lengths,
             lambda rho=rho: _monitors("II", float(rho), ("height", "AE", "BK")), 3e-4, _PATH_II, unit="m",
             in_text=False) for rho, _, lengths in _TABLE_II),
    *(Number("ch. 6, scheme I (delta1 = -5 deg) path by the truss method (2 decimals)",
             f"lambda1, lambda2, KLM rotation where rho = {rho} deg (tolerance 0.02)", angles,
             lambda rho=rho: _monitors("I-5", float(rho), ("lambda1", "lambda2", "rotation")), 0.02, _PATH_I,
             unit="deg", in_text=False) for rho, angles, _ in _TABLE_I),
    *(Number("ch. 6, scheme I (delta1 = -5 deg) path by the truss method (4 decimals)",
             f"KLM height, |BK| where rho = {rho} deg (tolerance 3e-4)", lengths,
             lambda rho=rho: _monitors("I-5", float(rho), ("height", "BK")), 3e-4, _PATH_I, unit="m", in_text=False)
      for rho, _, lengths in _TABLE_I),
)


def eqn_6_17_residuals() -> tuple[float, float]:
    """|(B - G) . s - (K - G) . s|: s_G must lie in the bisecting plane of angle BGK; corrected s_G = unit(G - Q)
    and the printed direction of OG, (0, sqrt 6/3, sqrt 3/3)."""
    G, B, K = (TETRA_VERTICES[v] for v in "GBK")
    out = []
    for s in (axis_g(0.0), np.array([0, np.sqrt(6) / 3, np.sqrt(3) / 3])):
        out.append(float(abs((B - G) @ s - (K - G) @ s)))
    return out[0], out[1]


CORRECTIONS_6 = (
    Correction("eqn 6-17", "s_G along OG, (0, sqrt 6/3, sqrt 3/3)", "s_G = unit(G - Q) = (0, 4 sqrt 66/33, sqrt 33/33)",
               "| (B - G) . s_G - (K - G) . s_G | (m): s_G bisects angle BGK", eqn_6_17_residuals,
               _TT + "test_corrected_axes", 1e-15, 0.1),
)

NUMBERS: tuple[Number, ...] = (*THREEFOLD, *CUBOCTAHEDRON, *FABRICATION, *TRUNCATED_OCTAHEDRON, *TRUNCATED_TETRAHEDRON)
CORRECTIONS: tuple[Correction, ...] = (*CORRECTIONS_3, *CORRECTIONS_6)

CHECKED_ELSEWHERE = (
    ("ch. 2 example", "the closed path sampled by the truss continuation (2 decimals, tolerance scaled by the slope)",
     _B3 + "test_sampled_closed_path_crosses_to_the_other_branch_at_each_bundle"),
    *(("ch. 1-2", f"truss counts j, b, r, m, s of the {what}", f"test_truss.py::{test}")
      for what, test in (("Bennett linkage, and with a tilted axis", "test_yang2017_bennett_counts_tilt_and_release"),
                         ("RSSR", "test_yang2017_rssr_truss"),
                         ("Myard linkage and its non-overconstrained forms",
                          "test_yang2017_myard_counts_and_non_overconstrained_forms"),
                         ("threefold-symmetric Bricard linkage", "test_yang2017_threefold_bricard_counts"))),
)
