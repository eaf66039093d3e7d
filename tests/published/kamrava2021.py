"""Kamrava et al. 2021 (closed form of the asymmetric Miura vertex): the numbers the tests check.

The preprint gives its results as plots; every value below is a worked value of its equations (eqns 17-28, eqn 24
corrected) at the sector angles it plots, to the places shown.
"""

from functools import cache

import numpy as np

from published import Correction, Number
from sim_origami.kinematics.miura import MiuraVertex, spinal_crease

DOCUMENT = "Kamrava et al. 2021"

PHI, PSI, RHO = 0, 1, slice(2, 6)
RHO_B, RHO_D = 3, 5
# Four decimals in degrees: half a unit of the last digit.
FOUR_DECIMALS_DEG = 5e-5
_TEST = "test_kinematics_miura.py::"


@cache
def miura(alpha1_deg: float, alpha2_deg: float) -> MiuraVertex:
    """The vertex with sectors alpha1, alpha2 (deg)."""
    return MiuraVertex(np.deg2rad(alpha1_deg), np.deg2rad(alpha2_deg))


def deg_outputs(vertex: MiuraVertex, branch: str, theta_deg) -> np.ndarray:
    """Outputs (n, 6) in degrees at inputs theta given in degrees."""
    return np.rad2deg(vertex.joint_angles(branch, np.deg2rad(theta_deg)))


def phi_maximum() -> np.ndarray:
    """(max phi, theta there) in degrees over 100001 inputs from 0 to the lock (5.5e-4 deg steps), 30/60."""
    vertex = miura(30, 60)
    theta = np.linspace(0.0, vertex.theta_limit, 100001)
    phi = np.rad2deg(vertex.joint_angles("miura", theta)[:, PHI])
    k = int(np.argmax(phi))
    return np.array([phi[k], np.rad2deg(theta[k])])


def _worked(where, quantity, printed, ours, tol, test, **kw) -> Number:
    return Number(where, quantity, printed, ours, tol, _TEST + test, unit=kw.pop("unit", "deg"), in_text=False, **kw)


SWEEP_THETA = [10, 20, 30, 40, 45, 50, 54]
_LOCKS = (((30, 60), "54.7356"), ((60, 30), "54.7356"), ((20, 70), "48.8063"), ((40, 50), "67.3780"),
          ((50, 80), "51.0652"), ((70, 80), "59.4884"), ((45, 45), "90.0"), ((60, 60), "90.0"))
_FOLDS = ((10, "-20, 34.4709, 20, 19.6999"), (30, "-60, 100.3889, 60, 52.6590"), (50, "-100, 164.0130, 100, 69.7434"))

NUMBERS: tuple[Number, ...] = (
    _worked("sectors 30/60", "phi at theta = 10, 20, 30, 40, 45, 50, 54 deg",
            "16.9774, 32.0720, 44.0307, 52.1183, 54.4567, 55.4107, 54.9574",
            lambda: deg_outputs(miura(30, 60), "miura", SWEEP_THETA)[:, PHI], FOUR_DECIMALS_DEG,
            "test_published_projection_angles_of_the_30_60_vertex"),
    _worked("sectors 30/60", "psi at theta = 10, 20, 30, 40, 45, 50, 54 deg",
            "1.5418, 6.5056, 15.5928, 28.3376, 34.9864, 40.8309, 44.4588",
            lambda: deg_outputs(miura(30, 60), "miura", SWEEP_THETA)[:, PSI], FOUR_DECIMALS_DEG,
            "test_published_projection_angles_of_the_30_60_vertex"),
    _worked("sectors 30/60", "spinal crease unit vector a at theta = 30 deg", "0.704918, 0.196721, 0.681463",
            lambda: spinal_crease(np.deg2rad(30), np.deg2rad(60), np.deg2rad(30))[0], 5e-7,
            "test_published_spinal_crease_of_the_30_60_vertex", unit=""),
    *(_worked("sectors 30/60", f"fold angles rho_a, rho_b, rho_c, rho_d at theta = {t} deg (tolerance 1e-3 deg)",
              printed, lambda t=t: deg_outputs(miura(30, 60), "miura", [t])[0, RHO], 1e-3,
              "test_published_fold_angles_of_the_30_60_vertex") for t, printed in _FOLDS),
    _worked("sectors 30/60", "rho_b, rho_d near the lock, theta = 54 deg (tolerance 1e-3 deg)", "177.4631, 70.5089",
            lambda: deg_outputs(miura(30, 60), "miura", [54])[0, [RHO_B, RHO_D]], 1e-3,
            "test_published_fold_angles_near_the_lock"),
    *(_worked(f"sectors {a}/{b}", "lock angle theta_limit", printed,
              lambda a=a, b=b: np.rad2deg(miura(a, b).theta_limit), FOUR_DECIMALS_DEG,
              "test_published_lock_angles") for (a, b), printed in _LOCKS),
    _worked("sectors 30/60", "phi at the lock theta_limit", "54.7356",
            lambda: np.rad2deg(miura(30, 60).joint_angles("miura", miura(30, 60).theta_limit)[0, PHI]),
            FOUR_DECIMALS_DEG, "test_phi_at_lock_equals_lock_angle"),
    *(_worked(f"sectors {a}/{a}", "phi at theta = 30 deg (symmetric vertex)", printed,
              lambda a=a: deg_outputs(miura(a, a), "miura", [30])[0, PHI], FOUR_DECIMALS_DEG,
              "test_symmetric_vertex_has_zero_psi_and_closed_form_phi") for a, printed in ((45, "53.1301"),
                                                                                           (60, "81.7868"))),
    _worked("sectors 30/60", "phi's interior maximum, and theta there (tolerance 0.01 deg, grid step 5.5e-4 deg)",
            "55.4185, 50.475", phi_maximum, 0.01, "test_phi_is_non_monotonic_with_published_maximum"),
    _worked("sectors 50/80", "phi, psi at theta = 45 deg (psi past 90 deg: atan2)", "100.4486, 105.7768",
            lambda: deg_outputs(miura(50, 80), "miura", [45])[0, [PHI, PSI]], FOUR_DECIMALS_DEG,
            "test_psi_uses_atan2_past_ninety_degrees"),
)


def eqn_24_unit_residuals() -> tuple[float, float]:
    """Largest | |a| - 1 | of eqns 25-28's crease a = f / (K3 + 1) over the 30/60 vertex's theta in (0, limit),
    with K3 of eqn 24 corrected, (K2/cos)^2 + (K1/sin)^2, and as printed, K2/cos + K1/sin."""
    alpha1, alpha2 = np.deg2rad(30.0), np.deg2rad(60.0)
    t = np.linspace(0.0, miura(30, 60).theta_limit, 201)[1:-1]
    k1 = 0.5 * (1 / np.tan(alpha1) + 1 / np.tan(alpha2))
    k2 = 0.5 * (1 / np.tan(alpha1) - 1 / np.tan(alpha2))
    out = []
    for k3 in ((k2 / np.cos(t)) ** 2 + (k1 / np.sin(t)) ** 2, k2 / np.cos(t) + k1 / np.sin(t)):
        f = np.stack([k3 - 1, 2 * k2 / np.cos(t), 2 * k1 / np.sin(t)], -1)
        out.append(float(np.max(np.abs(np.linalg.norm(f, axis=1) / (k3 + 1) - 1))))
    return out[0], out[1]


def eqn_39_psi_residuals() -> tuple[float, float]:
    """Angle (rad) between psi's direction and the projection of crease a on the XY plane, 50/80 vertex at
    theta = 45 deg (f_x < 0 there): psi = atan2(a_y, a_x) and, as printed, arctan(a_y / a_x)."""
    a = spinal_crease(np.deg2rad(50), np.deg2rad(80), np.deg2rad(45))[0]
    out = []
    for psi in (np.arctan2(a[1], a[0]), np.arctan(a[1] / a[0])):
        u = np.array([np.cos(psi), np.sin(psi)])
        out.append(float(np.arccos(np.clip(u @ a[:2] / np.linalg.norm(a[:2]), -1.0, 1.0))))
    return out[0], out[1]


CORRECTIONS: tuple[Correction, ...] = (
    Correction("eqn 24", "K3 = K2/cos(theta) + K1/sin(theta)", "K3 = (K2/cos(theta))^2 + (K1/sin(theta))^2",
               "largest | abs(a) - 1 | of the crease a of eqns 25-28, sectors 30/60, theta over (0, theta_limit)",
               eqn_24_unit_residuals, _TEST + "test_corrections_of_printed_equations", 1e-14, 0.1),
    Correction("eqn 39", "psi = arctan(a_y / a_x)", "psi = atan2(a_y, a_x)",
               "angle (rad) between psi's direction and crease a projected on XY, sectors 50/80, theta = 45 deg",
               eqn_39_psi_residuals, _TEST + "test_corrections_of_printed_equations", 1e-12, 3.0),
)

CHECKED_ELSEWHERE = (
    ("sectors 50/80", "a_x of the spinal crease changes sign at theta = 33.6005 deg (a bracket)",
     _TEST + "test_spinal_crease_x_changes_sign_at_published_angle"),
)
