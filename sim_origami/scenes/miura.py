"""Scene `miura`: the asymmetric Miura vertex of Kamrava et al. 2021, driven by theta (half the fold at c).

Creases a, b, c, d are crease_1 .. crease_4 of a vertex with sectors (alpha1, pi - alpha1,
pi - alpha2, alpha2). Panel P_bc (panel_2) is fixed; the spinal crease c (crease_3) is driven with
rho_c = 2 theta. With `thickness` > 0 the panels are solids and collide, so the fold stops where
P_ab meets P_bc, before the zero-thickness lock theta_limit.
"""

from ..kinematics.miura import MiuraVertex
from ..origami import vertex_mechanism
from .base import ACUTE, Param, Scene, register

PARAMS = (
    Param("alpha1", "deg", 30.0, "sector angle between creases a and b", **ACUTE),
    Param("alpha2", "deg", 60.0, "sector angle between creases d and a", **ACUTE),
    Param("length", "m", 1.0, "crease length"),
    Param("thickness", "m", 0.0, "panel thickness; > 0 makes panels solid and collide", zero_ok=True),
)

# Collision solids keep this many thicknesses clear of the creases (and so of the vertex).
INSET_PER_THICKNESS = 1.5


@register("miura", "asymmetric Miura vertex (Kamrava et al. 2021), input theta, joints phi, psi, rho_a..rho_d", PARAMS)
def build(alpha1: float, alpha2: float, length: float, thickness: float) -> Scene:
    kinematics = MiuraVertex(alpha1, alpha2)
    mechanism = vertex_mechanism(
        kinematics.sectors,
        length=length,
        thickness=thickness,
        inset=INSET_PER_THICKNESS * thickness,
        root=2,
        keep=(3,),
        names=("crease_a", "crease_b", "crease_c", "crease_d"),
    )
    pairs = ()
    if thickness > 0:
        # Panels that fold onto each other at the lock: P_ab on P_bc about b, P_cd on P_da about d.
        pairs = (("panel_1", "panel_2"), ("panel_3", "panel_4"))
    lim = kinematics.theta_limit
    return Scene(
        name="miura",
        params={"alpha1": alpha1, "alpha2": alpha2, "length": length, "thickness": thickness},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=("crease_a", "crease_b", "crease_c", "crease_d"),
        drive_joint="crease_c",
        drive_scale=2.0,
        # Near the flat bifurcation the closure Jacobian has a singular value ~ theta, so the
        # angle error of soft closures grows like residual / theta (fast preset: 6.5e-7 rad from
        # 0.1 theta_limit, 1e-7 from 0.25); the default sweep starts where the loop is well posed.
        path=(0.25 * lim, 0.95 * lim),
        contact_pairs=pairs,
        notes="theta = rho_c / 2; phi, psi are projection angles of crease a in the paper frame",
    )
