"""Scene `iftomm-a04`: the IFToMM multibody benchmark A04, Bricard's mechanism.

Five 1 m, 1 kg rods of square section 0.1 m and six revolute joints on the edges of a unit cube
(OpenSim re-implementation RehabEngGroup/MBSbenchmarksInOpenSim, src/A04-BricardsMechanism): joints at
(0,0,0) about y, (1,0,0) about z, (1,-1,0) about x, (1,-1,1) about y, (0,-1,1) about z, (0,0,1) about x;
the rod from (0,0,1) to (0,0,0) is ground, gravity -9.81 m/s^2 along y, released at rest. Through
`dh_from_axes` these axes are the threefold-symmetric Bricard linkage with a = 1 m and alpha = 90 deg,
all joint angles -90 deg at the start. Grubler counts 0 degrees of freedom; the mobility is 1.
"""

import numpy as np

from ..kinematics.bricard_threefold import BricardThreefold
from ..kinematics.dh import dh_from_axes
from ..linkage import dh_mechanism
from .base import Scene, register

AXIS_POINTS = np.array([[0, 0, 0], [1, 0, 0], [1, -1, 0], [1, -1, 1], [0, -1, 1], [0, 0, 1]], float)
AXIS_DIRS = np.array([[0, 1, 0], [0, 0, 1], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 0, 0]], float)
# Rods of 1 m x 0.1 m x 0.1 m at the panel class density of 100 kg/m^3 weigh the benchmark's 1 kg.
ROD_SECTION = 0.1
START = -np.pi / 2


@register("iftomm-a04", "IFToMM benchmark A04: Bricard mechanism under gravity (threefold Bricard, alpha 90)", ())
def build() -> Scene:
    rows, angles = dh_from_axes(AXIS_POINTS, AXIS_DIRS)
    kinematics = BricardThreefold(1.0, np.pi / 2)
    mechanism = dh_mechanism(rows, width=ROD_SECTION, anchor=0.5)
    # Joint 1's axis is the benchmark's +y (vertical); in the ground link's frame it is the z axis of
    # the ground-to-joint-1 transform, so gravity is -9.81 along it.
    up = rows[-1].link()[:3, 2]
    branch = next(b.name for b in kinematics.branches() if np.allclose(kinematics.at(b.name, START)["theta2"], START))
    assert np.allclose(angles, START), "the benchmark starts with every D-H angle at -90 deg"
    return Scene(
        name="iftomm-a04",
        params={},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=tuple(f"joint_{i}" for i in range(1, 7)),
        drive_joint="joint_1",
        drive_scale=1.0,
        path=(START, START + 1.0),
        gravity=tuple(-9.81 * up),
        free_start=START,
        free_branch=branch,
        notes="IFToMM A04; gravity -9.81 m/s^2 along the benchmark's y; released at rest from all angles -90 deg",
    )
