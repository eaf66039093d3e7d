"""Scene `triangle-twist-6r`: the 6R linkage of the triangle-twist kirigami (Feng 2018, §3.4), input theta1.

Six D-H links (`kinematics.twist_6r`, eqn 3-38, or eqn 3-40 when gamma = delta) built by `linkage.dh_mechanism`:
link 6 (panel O_A) is ground, joint 1 (pleat A3) driven, joint 6 cut and closed by two connects on its axis.
epsilon is not a parameter: eqn 3-12 fixes it (the loop moves only with the compatible pleat angle).
"""

import numpy as np

from ..kinematics.twist_6r import TwistSixR, compatible_angles
from ..linkage import dh_mechanism
from .base import SECTOR, Param, Scene, register

PARAMS = (
    Param("alpha", "deg", 55.0, "triangle corner at A", **SECTOR),
    Param("beta", "deg", 50.0, "triangle corner at B", **SECTOR),
    Param("gamma", "deg", 50.0, "pleat angle at A; gamma = delta gives Feng 2018's 'new' 6R (eqn 3-40)", **SECTOR),
    Param("delta", "deg", 45.0, "pleat angle at B", **SECTOR),
    Param("d", "m", 1.0, "triangle side AB"),
)
# Sweep of psi1 = theta1 - theta1(flat) (rad), clear of the singular flat state.
PATH = (0.5, 2.4)


@register("triangle-twist-6r", "6R linkage of the triangle-twist kirigami (Feng 2018, §3.4): octahedral Bricard "
          "(gamma != delta) or the thesis's 'new' 6R (gamma = delta), input theta1", PARAMS)
def build(alpha: float, beta: float, gamma: float, delta: float, d: float) -> Scene:
    kinematics = TwistSixR(compatible_angles(alpha, beta, gamma, delta), d)
    start, stop = np.array(PATH) + kinematics.flat_input
    return Scene(
        name="triangle-twist-6r",
        params={"alpha": alpha, "beta": beta, "gamma": gamma, "delta": delta, "d": d},
        kinematics=kinematics,
        mechanism=dh_mechanism(kinematics.rows, width=0.05 * d, anchor=0.5 * d),
        loop_joints=tuple(f"joint_{i}" for i in range(1, 7)),
        drive_joint="joint_1",
        drive_scale=1.0,
        path=(float(start), float(stop)),
        notes=f"epsilon = {np.rad2deg(kinematics.angles.epsilon):.6g} deg (eqn 3-12); hinge qpos = D-H theta",
    )
