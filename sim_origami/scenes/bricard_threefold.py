"""Scene `bricard-threefold`: the threefold-symmetric Bricard 6R linkage (Yang 2017, ch. 2 example), driven by
theta1; link 6 is ground."""

from ..kinematics.bricard_threefold import BricardThreefold
from ..linkage import dh_mechanism
from .base import ANGLE_MARGIN, Param, Scene, register

PARAMS = (
    Param("a", "m", 1.0, "common link length a12 = ... = a61"),
    # The Ch. 2 example with the axes as printed in (2-10, 2-11): twists alternate 300/60 deg
    # (Yang 2017, eqns 2-10, 2-11 and 1-27); alpha = 120 deg is the same linkage with the axes of
    # joints 2, 4, 6 reversed (phi negated).
    Param("alpha", "deg", 300.0, "twist alpha12 = alpha34 = alpha56; alpha23 = alpha45 = alpha61 = 360 - alpha",
          lo=ANGLE_MARGIN, hi=360 - ANGLE_MARGIN),
)


@register(
    "bricard-threefold",
    "threefold-symmetric Bricard 6R linkage (Yang 2017), input theta1, joints theta1..theta6",
    PARAMS,
)
def build(a: float, alpha: float) -> Scene:
    kinematics = BricardThreefold(a, alpha)
    return Scene(
        name="bricard-threefold",
        params={"a": a, "alpha": alpha},
        kinematics=kinematics,
        mechanism=dh_mechanism(kinematics.rows, anchor=0.5 * a, input_joint=1),
        loop_joints=tuple(f"joint_{k}" for k in range(1, 7)),
        drive_joint="joint_1",
        drive_scale=1.0,
        # +/-57 deg, far from the bundle (theta1 = +/-180 deg, where the closure Jacobian's 5th
        # singular value falls to 0; it stays >= 0.87 here on both branches for the default alpha).
        # A wider sweep is as valid but faster in phi: (-2, 2) measured a fast closure gap of
        # 5.8e-7 m, against 1.4e-7 m here (`presets.FAST.residual_per_m` = 2e-6).
        path=(-1.0, 1.0),
        notes="hinge qpos = D-H joint angle theta; T = Rz(theta) Tz(R) Tx(a) Rx(alpha); "
        "theta1 = theta3 = theta5, theta2 = theta4 = theta6 on the motion",
    )
