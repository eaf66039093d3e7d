"""The 6R linkages of the triangle-twist kirigami (Feng 2018, §3.4): the pleat panels without the triangle.

Loop: P_AB -B2- O_B -B3- P_BC -C2- O_C -C3- P_CA -A2- O_A -A3- P_AB, joints z1..z6 = A3, B2, B3, C2, C3, A2 of
`kinematics.triangle_twist`, each z_i pointing away from the triangle corner it passes through. D-H rows in Feng 2018's
convention (eqns 2-1 to 2-5; `kinematics.dh`, T = Rz(theta) Tz(R) Tx(a) Rx(alpha)); with the x axes on the
flat sheet's +z every theta_i is the fold angle rho of its crease (its left face is link i(i+1)), 0 flat.

gamma != delta (eqn 3-38, "R45" read as the twist alpha45): a = 0; twists alpha12 = 2 pi - gamma + delta,
alpha23 = pi - beta, alpha34 = 2 pi - delta + epsilon, alpha45 = alpha + beta, alpha56 = gamma - epsilon,
alpha61 = pi - alpha; offsets from the intersection points of consecutive pleat lines, with BC = d sin(alpha) /
sin(alpha + beta) and CA = d sin(beta) / sin(alpha + beta):

    R1 = d sin(delta) / sin(gamma - delta),     R2 = -d sin(gamma) / sin(gamma - delta),
    R3 = BC sin(epsilon) / sin(delta - epsilon),  R4 = -BC sin(delta) / sin(delta - epsilon),
    R5 = -CA sin(gamma) / sin(gamma - epsilon),   R6 = CA sin(epsilon) / sin(gamma - epsilon).

The thesis prints each ratio in absolute value; that equals these signed offsets only for gamma > delta > epsilon
and gamma > epsilon (its example) (derived here: with gamma < delta the absolute values miss closure, the test
shows it).
R1 R3 R5 + R2 R4 R6 = 0: the doubly collapsible octahedral Bricard condition.

gamma = delta (eqn 3-40, z1 parallel to z2): a12 = d sin(delta), alpha12 = 0; R1 = 0 and R2 = -d cos(delta) (only R1 +
R2 is defined; the thesis's choice), R5 (garbled in print) reconstructed here from the geometry, the rest as above with
gamma -> delta. x2 then lies in the sheet, so the flat state is theta1 = -pi/2, theta2 = +pi/2 (offsets o below).

Closed form (eqn 3-39 CORRECTED here: the printed signs miss closure by up to 1.9, these close to 1e-15), with
psi_i = theta_i - o_i, Ka = cos((alpha - gamma)/2) / cos((alpha + gamma)/2) and Kb likewise with beta, delta:

    tan(psi2/2) = -Ka Kb tan(psi1/2),  tan(theta3/2) = -Ka tan(psi1/2),  psi4 = psi1,  psi5 = psi2,  theta6 = -theta3.

epsilon is the compatible pleat angle of the thesis's Fig. 3-5 scheme SSP (eqn 3-12; it solves loop gain 1 for
vertex modes S, S, C whatever types those modes take at other angles). The loop is that scheme's motion, named
by the types it realises (SSP at the thesis's angles): a single branch on which every joint makes full turns. The
flat state (psi = 0) is singular (closure rank 3 of 6), no bifurcation.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ParameterError
from .base import Branch, Event
from .dh import DHKinematics, DHRow
from .triangle_twist import TwistAngles, epsilon_formula, realised_types

# Vertex modes (A, B, C) of the scheme whose pleat panels form the loop (Fig. 3-5: types S, S, P).
MODES = "SSC"
# gamma = delta is tested to this (rad): below it the pleats z1, z2 are parallel (eqn 3-40).
PARALLEL_TOL = 1e-12


def compatible_angles(alpha: float, beta: float, gamma: float, delta: float) -> TwistAngles:
    """
    The pattern angles with epsilon from eqn 3-12 (scheme SSP), radians.

    Such an epsilon always exists (derived here): two mode-S vertices have |k_A k_B| = 1/(mu_a mu_b) > 1, and mode C
    at C sweeps k_C over (-1, 1) as epsilon runs over (0, pi). `TwistAngles` still refuses collinear creases.
    """
    return TwistAngles(alpha, beta, gamma, delta, epsilon_formula("SSP", alpha, beta, gamma, delta))


def dh_rows(angles: TwistAngles, d: float) -> tuple[DHRow, ...]:
    """D-H rows of joints 1..6 (module docstring: eqn 3-38, or eqn 3-40 when gamma = delta), metres and radians."""
    a, b, g, dl, e = angles.alpha, angles.beta, angles.gamma, angles.delta, angles.epsilon
    for name, (p, q) in (("delta = epsilon", (dl, e)), ("gamma = epsilon", (g, e))):
        if abs(p - q) <= PARALLEL_TOL:
            raise ParameterError(
                f"{name} = {np.rad2deg(p):.6g} deg: two pleats of one panel are parallel; Feng 2018 gives that 6R "
                "only for gamma = delta (eqn 3-40)"
            )
    bc, ca = d * np.sin(a) / np.sin(a + b), d * np.sin(b) / np.sin(a + b)
    R3, R4 = bc * np.sin(e) / np.sin(dl - e), -bc * np.sin(dl) / np.sin(dl - e)
    R5, R6 = -ca * np.sin(g) / np.sin(g - e), ca * np.sin(e) / np.sin(g - e)
    if abs(g - dl) <= PARALLEL_TOL:
        first = (DHRow(0.0, d * np.sin(dl), 0.0), DHRow(-d * np.cos(dl), 0.0, np.pi - b))
    else:
        first = (DHRow(d * np.sin(dl) / np.sin(g - dl), 0.0, 2 * np.pi - g + dl),
                 DHRow(-d * np.sin(g) / np.sin(g - dl), 0.0, np.pi - b))
    rest = (DHRow(R3, 0.0, 2 * np.pi - dl + e), DHRow(R4, 0.0, a + b), DHRow(R5, 0.0, g - e),
            DHRow(R6, 0.0, np.pi - a))
    return first + rest


def coefficients(angles: TwistAngles) -> tuple[float, float]:
    """Ka = cos((alpha - gamma)/2) / cos((alpha + gamma)/2) and Kb likewise with beta, delta (eqn 3-39)."""
    ka = np.cos((angles.alpha - angles.gamma) / 2) / np.cos((angles.alpha + angles.gamma) / 2)
    kb = np.cos((angles.beta - angles.delta) / 2) / np.cos((angles.beta + angles.delta) / 2)
    return float(ka), float(kb)


class TwistSixR(DHKinematics):
    """
    The triangle-twist 6R driven by theta1 (joint z1 = pleat A3), joints theta1..theta6 in radians.

    Parameters
    ----------
    angles : TwistAngles
      Pattern angles; epsilon must be compatible (`compatible_angles`), or the loop does not move.
    d : float
      Triangle side AB (m), > 0.
    """

    input_name = "theta1"
    joint_names = tuple(f"theta{i}" for i in range(1, 7))

    def __init__(self, angles: TwistAngles, d: float = 1.0):
        if not d > 0:
            raise ParameterError(f"d = {d:g} m; it must be positive")
        self.angles, self.d = angles, float(d)
        self.rows = dh_rows(angles, d)
        self.ka, self.kb = coefficients(angles)
        self.parallel = abs(angles.gamma - angles.delta) <= PARALLEL_TOL
        self.branch_name = realised_types(angles, MODES)
        # D-H angles of the flat state: x2 lies in the sheet when z1 and z2 are parallel (found here)
        self.offsets = np.array([-np.pi / 2, np.pi / 2, 0, 0, 0, 0]) if self.parallel else np.zeros(6)

    @property
    def flat_input(self) -> float:
        """theta1 (rad) of the flat state: 0, or -pi/2 when gamma = delta."""
        return float(self.offsets[0])

    def branches(self) -> tuple[Branch, ...]:
        o = self.flat_input
        text = (
            f"the loop of the triangle twist's scheme {self.branch_name} (modes {MODES}, as Fig. 3-5): every joint "
            f"turns fully, flat at theta1 = {o:.6g} rad"
        )
        return (Branch(self.branch_name, text, (o - np.pi, o + np.pi)),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        t1, valid = self.in_domain(branch, x)
        h = (t1 - self.offsets[0]) / 2  # psi1 / 2
        # tan(psi/2) = k tan(psi1/2) as an angle: continuous through psi1 = +-pi
        psi2 = 2.0 * np.arctan2(-self.ka * self.kb * np.sin(h), np.cos(h))
        theta3 = 2.0 * np.arctan2(-self.ka * np.sin(h), np.cos(h))
        psi = np.stack([2 * h, psi2, theta3, 2 * h, psi2, -theta3], -1)
        values = psi + self.offsets
        values[:, 0] = t1
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        return ()

    def bricard_sum(self) -> float:
        """R1 R3 R5 + R2 R4 R6 (m^3): 0 for gamma != delta (eqn 2-14); 4.685016 for the thesis's gamma = delta case."""
        R = [r.R for r in self.rows]
        return float(R[0] * R[2] * R[4] + R[1] * R[3] * R[5])
