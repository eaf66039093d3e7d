"""Closed form of a planar four-bar linkage, written against sim_origami's `Kinematics` contract (numpy only).

The loop is a D-H chain (sim_origami.kinematics.dh): joint i turns link i about +z by theta_i, and link i has
length a_i with no twist and no offset, so every axis is parallel and the loop is planar. Link 4 is the ground,
from joint 4 (the origin) to joint 1 at (a4, 0); link 1 is the crank, link 2 the coupler, link 3 the rocker.
The absolute direction of link k is phi_k = theta_1 + ... + theta_k, and the loop closes when

    a4 + a1 exp(i phi_1) + a2 exp(i phi_2) + a3 exp(i phi_3) = 0,    theta_1 + ... + theta_4 = 0 (mod 2 pi).

Given theta_1, joint 2 sits at B = a4 + a1 exp(i theta_1); joint 3 is where the circles of radius a2 about B and
a3 about the origin meet, C = a3 exp(i (arg B +/- gamma)), cos gamma = (|B|^2 + a3^2 - a2^2) / (2 |B| a3).
The two signs are the two assemblies, named by geometry: joint 3 on the counter-clockwise side of the diagonal
from joint 4 to joint 2 ('elbow-ccw') or on its clockwise side ('elbow-cw'). With the Grashof crank (a1 the
shortest link and a1 + max <= the other two) both close for every crank angle.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from sim_origami.errors import ParameterError
from sim_origami.kinematics.base import Branch, Event
from sim_origami.kinematics.dh import DHKinematics, DHRow

BRANCHES = {"elbow-ccw": 1.0, "elbow-cw": -1.0}


class FourBar(DHKinematics):
    """Planar four-bar driven by the crank angle theta1 (rad); lengths a1..a4 in metres."""

    input_name = "theta1"
    joint_names = ("theta1", "theta2", "theta3", "theta4")

    def __init__(self, a1: float, a2: float, a3: float, a4: float):
        lengths = {"a1": a1, "a2": a2, "a3": a3, "a4": a4}
        for name, value in lengths.items():
            if not value > 0:
                raise ParameterError(f"link length {name} = {value:g} m; it must be positive")
        longest = max(a2, a3, a4)
        if a1 >= min(a2, a3, a4) or a1 + longest > a2 + a3 + a4 - longest:
            raise ParameterError(f"a1 = {a1:g} m is not a Grashof crank for a2, a3, a4 = {a2:g}, {a3:g}, {a4:g} m: "
                                 "the crank must be the shortest link and shortest + longest <= the other two")
        self.a1, self.a2, self.a3, self.a4 = float(a1), float(a2), float(a3), float(a4)
        self.rows = (DHRow(0.0, a1, 0.0), DHRow(0.0, a2, 0.0), DHRow(0.0, a3, 0.0), DHRow(0.0, a4, 0.0))

    def branches(self) -> tuple[Branch, ...]:
        full = (-np.pi, np.pi)
        return (
            Branch("elbow-ccw", "joint 3 on the counter-clockwise side of the diagonal joint 4 -> joint 2", full),
            Branch("elbow-cw", "joint 3 on the clockwise side of the diagonal joint 4 -> joint 2", full),
        )

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        sign = BRANCHES[self.branch(branch).name]
        t1, valid = self.in_domain(branch, x)
        B = self.a4 + self.a1 * np.exp(1j * t1)
        d = np.abs(B)
        gamma = np.arccos(np.clip((d**2 + self.a3**2 - self.a2**2) / (2 * d * self.a3), -1.0, 1.0))
        C = self.a3 * np.exp(1j * (np.angle(B) + sign * gamma))
        phi2 = np.angle(C - B)  # coupler direction: it rocks, so atan2 never wraps on the way round
        phi3 = np.angle(-C)  # rocker direction, joint 3 -> joint 4
        # theta2 = phi2 - theta1 stays continuous over the crank's whole turn (no wrap); theta3, the turn from the
        # coupler to the rocker, stays inside (-pi, pi) as long as joint 3 never folds back (Grashof crank)
        values = np.stack([t1, phi2 - t1, np.angle(-C / (C - B)), -phi3], -1)
        values[~valid] = np.nan
        return values, valid

    def events(self) -> tuple[Event, ...]:
        return ()
