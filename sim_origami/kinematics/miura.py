"""Asymmetric Miura vertex (Kamrava et al. 2021).

Paper frame: vertex at the origin, flat in the XY plane. Spinal creases a = (1, 0, 0) (free) and
c = (-1, 0, 0); peripheral creases b at angle alpha1 and d at -alpha2. The input theta tilts the
two panels that contain c by +theta and -theta about X, so the fold at c is 2 theta (eqns
9-10). Outputs: phi = atan2(a_z, a_x) and psi = atan2(a_y, a_x), projection angles of the
unit crease a (eqns 38-39), and the fold angles rho_a, rho_b, rho_c, rho_d in the convention of
`sim_origami.conventions` (creases a, b, c, d = creases 1, 2, 3, 4 of a degree-4 vertex with
sectors alpha1, pi - alpha1, pi - alpha2, alpha2; rho > 0 a valley seen from +z).

Corrections applied (made here): K3 has squares, (K2/cos)^2 + (K1/sin)^2 (eqn 24 is printed without them, eqn 23 has
them; with them phi and psi match two independent numerical solutions to 1e-13 rad); psi uses atan2 (the printed arctan
jumps by pi once f_x < 0, e.g. 50/80 deg); the fold limit uses tan(min(alpha))/tan(max(alpha)) (eqn 40 holds only for
alpha1 <= alpha2). The scaled vector f = (K3 + 1) a is multiplied here by sin^2 cos^2 theta, which leaves the angles
unchanged and removes the 1/sin theta singularity, so theta = 0 gives phi = psi = 0 exactly.

Branches: 'miura' (a_x = (K3 - 1)/(K3 + 1), the paper's branch; crease a folds opposite to b, c, d)
and 'straight' (a_x = 1: the sheet folds about the line a-c only, rho_b = rho_d = 0). They cross at
the flat state. 'miura' locks at +/- theta_limit, where the peripheral crease next to the smaller
sector folds flat (panel on panel); 'straight' locks at +/- pi/2 (rho_c = pi).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..errors import ParameterError
from ..geometry import rot_x, rotation, signed_angle, unit
from .base import Branch, Event, Kinematics
from .vertex4 import Vertex4

BRANCHES = ("miura", "straight")


def fold_limit(alpha1: float, alpha2: float) -> float:
    """theta at which the crease next to the smaller sector folds flat (eqn 40, general form)."""
    small, large = sorted((alpha1, alpha2))
    return float(np.pi / 2 - 0.5 * np.arccos(np.tan(small) / np.tan(large)))


def peripheral_creases(alpha1: float, alpha2: float, theta: ArrayLike) -> tuple[NDArray, NDArray]:
    """Unit creases b and d, (n, 3), in the paper frame (eqns 9-10)."""
    t = np.atleast_1d(np.asarray(theta, dtype=float))
    b = np.stack([np.full_like(t, np.cos(alpha1)), np.sin(alpha1) * np.cos(t), np.sin(alpha1) * np.sin(t)], -1)
    d = np.stack([np.full_like(t, np.cos(alpha2)), -np.sin(alpha2) * np.cos(t), np.sin(alpha2) * np.sin(t)], -1)
    return b, d


def spinal_crease(alpha1: float, alpha2: float, theta: ArrayLike) -> NDArray[np.float64]:
    """
    Unit crease a, (n, 3), on the Miura branch (eqns 17-28 with eqn 24 corrected).

    Notes
    -----
    f = (K3 + 1) a with f = (K3 - 1, 2 K2 / cos, 2 K1 / sin); multiplied by sin^2 cos^2 > 0:
    f' = (K2^2 s^2 + K1^2 c^2 - s^2 c^2, 2 K2 s^2 c, 2 K1 s c^2), |f'| = K2^2 s^2 + K1^2 c^2 + s^2 c^2.
    """
    t = np.atleast_1d(np.asarray(theta, dtype=float))
    k1 = 0.5 * (1 / np.tan(alpha1) + 1 / np.tan(alpha2))
    k2 = 0.5 * (1 / np.tan(alpha1) - 1 / np.tan(alpha2))
    s, c = np.sin(t), np.cos(t)
    f = np.stack([k2**2 * s**2 + k1**2 * c**2 - s**2 * c**2, 2 * k2 * s**2 * c, 2 * k1 * s * c**2], -1)
    return f / (k2**2 * s**2 + k1**2 * c**2 + s**2 * c**2)[:, None]


def fold_angles_from_creases(a: NDArray, b: NDArray, d: NDArray) -> NDArray[np.float64]:
    """Fold angles (n, 4) of creases a, b, c, d from the panel normals (signed angles between them)."""
    c = np.broadcast_to([-1.0, 0.0, 0.0], a.shape)
    n_ab, n_bc, n_cd, n_da = (
        unit(np.cross(a, b)),
        unit(np.cross(b, c)),
        unit(np.cross(c, d)),
        unit(np.cross(d, a)),
    )
    return np.stack(
        [
            signed_angle(n_da, n_ab, a),
            signed_angle(n_ab, n_bc, b),
            signed_angle(n_bc, n_cd, c),
            signed_angle(n_cd, n_da, d),
        ],
        -1,
    )


def projection_angles(a: NDArray) -> NDArray[np.float64]:
    """(phi, psi), (n, 2): phi = atan2(a_z, a_x), psi = atan2(a_y, a_x) (eqns 38-39, atan2)."""
    return np.stack([np.arctan2(a[:, 2], a[:, 0]), np.arctan2(a[:, 1], a[:, 0])], -1)


class MiuraVertex(Kinematics):
    """
    Asymmetric Miura vertex driven by theta (half the fold angle of the spinal crease c).

    Parameters
    ----------
    alpha1, alpha2 : float
      Sector angles next to crease a, in radians, each in (0, pi/2).
    """

    input_name = "theta"
    joint_names = ("phi", "psi", "rho_a", "rho_b", "rho_c", "rho_d")

    def __init__(self, alpha1: float, alpha2: float):
        for name, value in (("alpha1", alpha1), ("alpha2", alpha2)):
            if not 0.0 < value < np.pi / 2:
                raise ParameterError(
                    f"{name} = {np.rad2deg(value):.6g} deg; a Miura vertex needs each sector angle "
                    "next to the spinal crease in (0, 90) deg"
                )
        self.alpha1 = float(alpha1)
        self.alpha2 = float(alpha2)
        self.theta_limit = fold_limit(self.alpha1, self.alpha2)
        self.vertex = Vertex4(self.sectors, input_crease=3)

    @property
    def sectors(self) -> NDArray[np.float64]:
        """Sector angles (4,) of the degree-4 vertex a, b, c, d."""
        return np.array([self.alpha1, np.pi - self.alpha1, np.pi - self.alpha2, self.alpha2])

    def branches(self) -> tuple[Branch, ...]:
        lim = self.theta_limit
        return (
            Branch("miura", "the paper's branch: crease a folds opposite to b, c and d", (-lim, lim)),
            Branch(
                "straight",
                "fold about the straight line a-c only: rho_b = rho_d = 0",
                (-np.pi / 2, np.pi / 2),
            ),
        )

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        t, valid = self.in_domain(branch, x)
        b, d = peripheral_creases(self.alpha1, self.alpha2, t)
        if branch == "miura":
            a = spinal_crease(self.alpha1, self.alpha2, t)
        else:
            a = np.broadcast_to([1.0, 0.0, 0.0], b.shape)
        values = np.concatenate([projection_angles(a), fold_angles_from_creases(a, b, d)], -1)
        if branch == "straight":
            values[:, 3] = values[:, 5] = 0.0  # exactly unfolded, not 1e-17
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        crease = "b" if self.alpha1 <= self.alpha2 else "d"
        if abs(self.alpha1 - self.alpha2) < 1e-12:
            crease = "b, c and d"
        events = [Event("bifurcation", 0.0, BRANCHES, "flat state: the Miura and straight-fold branches cross")]
        for sign in (-1, 1):
            events.append(
                Event(
                    "lock",
                    sign * self.theta_limit,
                    ("miura",),
                    f"crease {crease} folds flat (Kamrava et al. 2021, eqn 40)",
                )
            )
            events.append(Event("lock", sign * np.pi / 2, ("straight",), "crease c folds flat (rho_c = pi)"))
        return tuple(events)

    def gruebler(self) -> int:
        return self.vertex.gruebler()

    def loop_system(self) -> LoopSystem:
        return self.vertex.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return 2, 2.0

    def observe(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        """
        Outputs from fold angles (n, 4): crease a is carried from flat by panel P_ab, which is
        P_bc (tilted by theta = rho_c / 2 about X) turned back by rho_b about b.
        """
        rho = np.asarray(q_loop, dtype=float).reshape(-1, 4)
        b0 = np.array([np.cos(self.alpha1), np.sin(self.alpha1), 0.0])
        R_ab = rot_x(rho[:, 2] / 2) @ rotation(b0, -rho[:, 1])
        a = R_ab[:, :, 0]  # R_ab @ (1, 0, 0)
        return np.concatenate([projection_angles(a), rho], -1)

    def loop_angles(self, values: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(values, dtype=float).reshape(-1, 6)[:, 2:]
