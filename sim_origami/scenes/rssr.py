"""Scene `rssr`: the RSSR linkage, the non-overconstrained form of the Bennett linkage (Yang 2017, §3.3).

Ground DA, input theta1 at A (hinge `joint_1`), R at B (`joint_2`), balls at C (a MuJoCo ball joint) and D (one
connect). Any a1 = AB = CD, a2 = BC = DA and twist alpha of AB (a2 sin alpha < a1) moves like the Bennett linkage
of implied beta = asin(a2 sin alpha / a1): so a built RSSR with fabrication errors stays mobile where the Bennett
locks (`sim_origami.fabrication`; `scripts/fabrication_errors.py`). Yang 2017's 1.5 mm length error (§3.5;
k = +1, lengths scaled 100 mm -> 1 m) is `-p a1=1.015 -p a2=0.6922`. Outputs: theta1 and theta2 (rad); points: the
joint origins.
"""

import numpy as np

from ..kinematics.rssr import RSSR
from ..linkage_forms import rssr_mechanism, rssr_motion
from .base import SECTOR, Param, Scene, register
from .polyhedra import AssemblyKinematics, kutzbach

PARAMS = (
    Param("a1", "m", 1.0, "AB = CD, the link with twist alpha (Yang 2017, §3.5: 100 mm)"),
    Param("a2", "m", 0.7072, "BC = DA (70.72 mm)"),
    Param("alpha", "deg", 45.0, "twist of AB", **SECTOR),
)


@register("rssr", "RSSR linkage, the Bennett linkage's non-overconstrained form (Yang 2017, §3.3), input theta1",
          PARAMS)
def build(a1: float, a2: float, alpha: float) -> Scene:
    rssr = RSSR(a1, a2, alpha)
    mechanism = rssr_mechanism(rssr)
    kinematics = AssemblyKinematics(
        rssr_motion(rssr), mechanism, reference=0.0, revolute=("joint_1", "joint_2"), input_joint="joint_1",
        branch=("bennett", "the RSSR's Bennett branch (3-5): tan(theta1/2) tan(theta2/2) = K"),
        vertex_bodies={v: f"link_{k + 1}" for k, v in enumerate("ABCD")}, reference_points=np.zeros((4, 3)),
        gruebler=kutzbach(mechanism),
    )
    return Scene(
        name="rssr", params={"a1": a1, "a2": a2, "alpha": alpha}, kinematics=kinematics, mechanism=mechanism,
        loop_joints=tuple(j.name for j in mechanism.joints), drive_joint="joint_1", drive_scale=1.0,
        path=(0.5, 2.9),
        notes="hinge qpos = D-H joint angle; balls at C (in the tree) and D (one connect); idle spin of CD",
    )
