"""Scene `bennett`: the Bennett 4R linkage (Yang 2017, eqns 1-17, 1-18), driven by theta1; link 4 is ground."""

import numpy as np

from ..kinematics.bennett import Bennett
from ..linkage import dh_mechanism
from .base import SECTOR, Condition, Param, Scene, register

PARAMS = (
    Param("a", "m", 1.0, "link length a12 = a34"),
    Param("alpha", "deg", 30.0, "twist alpha12 = alpha34", **SECTOR),
    Param("b", "m", 1.5, "link length a23 = a41"),
    # arcsin(b sin(alpha) / a) = arcsin(0.75): the Bennett condition for the other defaults
    Param("beta", "deg", float(np.rad2deg(np.arcsin(0.75))), "twist alpha23 = alpha41; sin(alpha)/a = sin(beta)/b",
          **SECTOR),
)


# a sin(beta) = b sin(alpha) (Yang 2017, eqn 1-17), over the loop's size: the values as typed are moved onto it
# within their precision.
CONDITION = Condition(
    "the Bennett condition sin(alpha)/a = sin(beta)/b",
    lambda v: (v["a"] * np.sin(v["beta"]) - v["b"] * np.sin(v["alpha"])) / (v["a"] + v["b"]),
)


@register("bennett", "Bennett 4R linkage (Yang 2017), input theta1, joints theta1..theta4", PARAMS, CONDITION)
def build(a: float, alpha: float, b: float, beta: float) -> Scene:
    kinematics = Bennett(a, alpha, b, beta)
    return Scene(
        name="bennett",
        params={"a": a, "alpha": alpha, "b": b, "beta": beta},
        kinematics=kinematics,
        mechanism=dh_mechanism(kinematics.rows, anchor=0.5 * max(a, b)),
        loop_joints=("joint_1", "joint_2", "joint_3", "joint_4"),
        drive_joint="joint_1",
        drive_scale=1.0,
        path=(0.6, 2.4),
        notes="hinge qpos = D-H joint angle theta; T = Rz(theta) Tz(R) Tx(a) Rx(alpha)",
    )
