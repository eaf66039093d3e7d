"""Scene `vertex4`: a general developable degree-4 vertex driven by crease 1 (Peng 2018, ch. 2-3)."""

import numpy as np

from ..kinematics.vertex4 import Vertex4
from ..origami import vertex_mechanism
from .base import SECTOR, Param, Scene, register

PARAMS = (
    Param("alpha1", "deg", 60.0, "sector angle between creases 1 and 2", **SECTOR),
    Param("alpha2", "deg", 100.0, "sector angle between creases 2 and 3", **SECTOR),
    Param("alpha3", "deg", 90.0, "sector angle between creases 3 and 4", **SECTOR),
    Param("alpha4", "deg", 110.0, "sector angle between creases 4 and 1", **SECTOR),
    Param("length", "m", 1.0, "crease length"),
)


@register("vertex4", "degree-4 origami vertex (spherical 4R), input rho1, joints rho1..rho4", PARAMS)
def build(alpha1: float, alpha2: float, alpha3: float, alpha4: float, length: float) -> Scene:
    alpha = np.array([alpha1, alpha2, alpha3, alpha4])
    kinematics = Vertex4(alpha, input_crease=1)
    # Panel 1 is fixed; crease 1 (the input) stays in the tree, another crease closes the loop.
    mechanism = vertex_mechanism(alpha, length=length, root=1, keep=(1,))
    return Scene(
        name="vertex4",
        params={"alpha1": alpha1, "alpha2": alpha2, "alpha3": alpha3, "alpha4": alpha4, "length": length},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=("crease_1", "crease_2", "crease_3", "crease_4"),
        drive_joint="crease_1",
        drive_scale=1.0,
        path=(0.4, 1.6),
        notes="hinge qpos = fold angle rho, rho > 0 a valley seen from +z",
    )
