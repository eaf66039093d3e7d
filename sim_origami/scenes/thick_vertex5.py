"""Scene `thick-vertex5`: a thick-panel symmetric five-crease vertex = Myard linkage (Peng 2018, §4.3).

Panels are slabs between their hinge planes and collide (relieved from the creases as in `thick-vertex4`).
Panel 3 lies between hinges 3 and 4 at one height (a34 = 0), so it gets a slab of its own: thickness
a23 below its hinges, flush with panels 2 and 4. With the heights h = (0, a12, a12 + a23, ...) creases 1, 3
and 4 join the same faces and fold freely for rho1 < 0 (rho3 = rho4 = -rho1/2 > 0) but collide at once the
other way; the mixed-face creases 2 and 5 collide at |rho2| = pi/2 (derived here, as for `thick-vertex4`),
i.e. rho1 = -2 pi/3 for any alpha: tan(pi/4 + alpha/2) tan(|rho1|/4) = 1.
"""

import dataclasses
import itertools

import numpy as np

from ..kinematics.thick_vertex5 import ThickVertex5
from ..mechanism import Body, Mechanism
from ..origami import PALETTE, crease_directions, vertex_mechanism
from ..solids import inset_outline, prism, sector_outline
from .base import ACUTE, Param, Scene, register
from .thick_vertex4 import RELIEF

PARAMS = (
    Param("alpha", "deg", 30.0, "sector angle alpha12 = alpha51 in (0, 90); sectors a, 90, 180 - 2a, 90, a", **ACUTE),
    Param("b", "m", 0.05, "thickness scale: a23 = a45 = b between hinges 2, 3 and 4, 5; a12 = a51 = b sin(alpha)"),
    Param("length", "m", 1.0, "crease length"),
)

# Default sweep of rho1 (rad): the collision-free direction, clear of flat (where the thin loop is
# ill-conditioned, as in thick-vertex4) and of the mixed-face contact at rho1 = -2.094 (-2 pi/3).
PATH = (-0.4, -1.6)

# MuJoCo layout. The zero-thickness vertex has 2 DOF, so the thick loop keeps a singular value of about
# b/length (0.031) along the whole motion, and the soft closure's violation is amplified by its inverse. Fast
# path error by fixed panel / cut crease, default sweep (closure points at 0.5 and 1 x length, as in
# thick-vertex4): panel 1 / crease 5 2.0e-5 rad, panel 1 / crease 2 3.9e-6, panel 3 / crease 3 5.9e-7; with
# the closure points at both ends of the hinge (0 and 1 x length) 1.4e-5, 2.6e-6 and 3.6e-7. Panel 3 (the
# largest) is fixed and the loop is cut at crease 3 with the points spanning the whole hinge.
ROOT, CUT = 3, 3
ANCHORS = (0.0, 1.0)  # fractions of the crease length


def panel3_slab(kinematics: ThickVertex5, length: float, inset: float) -> Body:
    """Panel 3 as a slab of thickness a23 hanging below hinges 3 and 4, relieved by `inset` from both creases."""
    d = crease_directions(kinematics.sectors)
    outline = sector_outline(d[2], kinematics.sectors[2], length)
    top = kinematics.heights[2]
    distances = np.zeros(len(outline))
    distances[0] = distances[-1] = inset
    collision = prism(inset_outline(outline, distances), kinematics.a23, top - kinematics.a23)
    return Body("panel_3", prism(outline, kinematics.a23, top - kinematics.a23), collision, PALETTE[2])


def thick_vertex5_mechanism(kinematics: ThickVertex5, length: float) -> Mechanism:
    """Slab panels on the lifted hinges; panel ROOT fixed, every crease but CUT (so crease 1, the input) in the tree."""
    inset = RELIEF * kinematics.b
    keep = tuple(k for k in range(1, 6) if k != CUT)
    mechanism = vertex_mechanism(
        kinematics.sectors,
        length=length,
        inset=inset,
        root=ROOT,
        keep=keep,
        heights=kinematics.heights,
        anchors=ANCHORS,
    )
    bodies = tuple(panel3_slab(kinematics, length, inset) if b.name == "panel_3" else b for b in mechanism.bodies)
    return dataclasses.replace(mechanism, bodies=bodies)


@register("thick-vertex5", "thick-panel five-crease vertex = Myard linkage (Peng 2018, §4.3), input rho1", PARAMS)
def build(alpha: float, b: float, length: float) -> Scene:
    kinematics = ThickVertex5(alpha, b)
    return Scene(
        name="thick-vertex5",
        params={"alpha": alpha, "b": b, "length": length},
        kinematics=kinematics,
        mechanism=thick_vertex5_mechanism(kinematics, length),
        loop_joints=tuple(f"crease_{k}" for k in range(1, 6)),
        drive_joint="crease_1",
        drive_scale=1.0,
        path=PATH,
        contact_pairs=tuple(itertools.combinations([f"panel_{i}" for i in range(1, 6)], 2)),
        notes="hinge k on the line through (0, 0, h_k) along d_k, h = (0, a12, a12 + a23, a12 + a23, a12); "
        "qpos = fold angle of the zero-thickness vertex; rho3 = rho4 = -rho1/2, rho2 = rho5",
    )
