"""Scene `thick-vertex4`: a thick-panel flat-foldable four-crease vertex = Bennett linkage (Peng 2018, §4.2).

Panels are slabs between their hinge planes and collide (inset from the creases), so the fold that the
thickness blocks is found by contact; with zero-thickness panels the same sheet bifurcates at flat.
"""

import itertools

import numpy as np

from ..errors import ParameterError
from ..kinematics.thick_vertex4 import ThickVertex4
from ..origami import vertex_mechanism
from .base import SECTOR, Param, Scene, register

# Collision solids stop this fraction of b short of the hinge lines, so hinged neighbours do not touch
# along their shared edge at flat. Slabs reaching the hinge line collide at |rho2| = pi/2, i.e.
# rho1 = -pi/6 = -0.523599 for 60/90 deg (derived here); with this relief: -0.524599 (b = 0.05 m).
RELIEF = 2e-3

PARAMS = (
    Param("alpha1", "deg", 60.0, "sector angle between creases 1 and 2 (alpha3 = 180 - alpha1)", **SECTOR),
    Param("alpha2", "deg", 90.0, "sector angle between creases 2 and 3 (alpha4 = 180 - alpha2)", **SECTOR),
    Param("b", "m", 0.05, "thickness scale: hinge 3 sits b above hinge 2; a = b sin(alpha1)/sin(alpha2)"),
    Param("length", "m", 1.0, "crease length"),
    Param("zigzag", "", 0.0, "0: staircase hinges (mode S), 1: zigzag hinges (mode C)", lo=0, hi=1, integer=True),
)


@register("thick-vertex4", "thick-panel four-crease vertex = Bennett linkage (Peng 2018, §4.2), input rho1",
          PARAMS)
def build(alpha1: float, alpha2: float, b: float, length: float, zigzag: float) -> Scene:
    if zigzag not in (0.0, 1.0):
        raise ParameterError(f"zigzag = {zigzag:g}; use 0 (staircase) or 1 (zigzag)")
    alpha = np.array([alpha1, alpha2, np.pi - alpha1, np.pi - alpha2])
    kinematics = ThickVertex4(alpha, b, "zigzag" if zigzag else "staircase")
    mechanism = vertex_mechanism(alpha, length=length, inset=RELIEF * b, root=1, keep=(1,), heights=kinematics.heights)
    return Scene(
        name="thick-vertex4",
        params={"alpha1": alpha1, "alpha2": alpha2, "b": b, "length": length, "zigzag": zigzag},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=("crease_1", "crease_2", "crease_3", "crease_4"),
        drive_joint="crease_1",
        drive_scale=1.0,
        # Both layouts fold crease 1 as a valley (the thesis's mode S does): the other way their slabs overlap at
        # once (zigzag, 60/90 deg: contact distance -6.0 mm at rho1 = +0.52 rad, +0.19 mm at -0.52, first contact at
        # -1.5728; `simulate.contact_distance`), and the blockage run stopped at its start.
        # Near flat the thin loop inherits the zero-thickness bifurcation's conditioning (singular value
        # ~ b/length): fast error 1.1e-6 rad from rho1 = 0.2, so the sweep starts at 0.4.
        path=(-0.4, -1.5),
        contact_pairs=tuple(itertools.combinations([f"panel_{i}" for i in range(1, 5)], 2)),
        notes="hinge k on the line through (0, 0, h_k) along d_k; qpos = fold angle of the zero-thickness vertex",
    )
