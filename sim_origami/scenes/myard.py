"""Scene `myard`: the Myard 5R linkage (Yang 2017, eqn 1-19), driven by theta3; link 5 is ground.

Joints 3 and 4 meet at one point (a34 = 0): link 3 is drawn as a cube of the bar width there
(`linkage.bar`). The loop is cut at joint 5, closed by two connects at +-a23/2 along its axis.
"""

from ..kinematics.myard import Myard
from ..linkage import dh_mechanism
from .base import ACUTE, Param, Scene, register

PARAMS = (
    Param("a23", "m", 1.0, "link length a23 = a45; a12 = a51 = a23 sin(alpha12), a34 = 0"),
    Param("alpha12", "deg", 50.0, "twist alpha12 in (0, 90) deg; alpha51 = 180 - alpha12, alpha34 = 180 - 2 alpha12",
          **ACUTE),
)

# Default sweep of theta3 (rad). The motion has no singular pose (closure Jacobian rank 4, 4th
# singular value >= 0.3 for alpha12 = 30..70 deg); the sweep stays 0.5 rad clear of theta3 = 0 and
# +-pi, the folded poses where every joint lies on one line and links 1 and 5 lie on top of each
# other. Measured fast path error 3.9e-7 rad at the defaults, 3.0e-7..4.0e-7 for other
# 2 rad sweeps tried (alpha12 = 30 and 50 deg).
PATH = (0.5, 2.5)


@register("myard", "Myard 5R linkage (Yang 2017), input theta3, joints theta1..theta5", PARAMS)
def build(a23: float, alpha12: float) -> Scene:
    kinematics = Myard(a23, alpha12)
    return Scene(
        name="myard",
        params={"a23": a23, "alpha12": alpha12},
        kinematics=kinematics,
        mechanism=dh_mechanism(kinematics.rows, anchor=0.5 * a23, input_joint=3),
        loop_joints=("joint_1", "joint_2", "joint_3", "joint_4", "joint_5"),
        drive_joint="joint_3",
        drive_scale=1.0,
        path=PATH,
        notes="hinge qpos = D-H joint angle theta; T = Rz(theta) Tz(R) Tx(a) Rx(alpha); "
        "closed form theta4 = theta3 + pi, theta1 = pi - 2 theta3, theta5 = -theta2",
    )
