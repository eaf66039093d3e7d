"""Scene `four-bar`: the planar four-bar of `kinematics.FourBar`, registered when sim_origami loads plugins.

The mechanism comes from sim_origami's D-H blocks (one bar per link, link 4 fixed, joint 4 cut and closed by two
anchors on its axis); `custom_scene` checks that the closed form fits it and drives joint 1 with theta1.
"""

from sim_origami.linkage import dh_mechanism
from sim_origami.scenes import Param, Scene, Tuning, custom_scene, register

from .kinematics import FourBar

PARAMS = (
    Param("a1", "m", 0.4, "crank (joint 1 -> joint 2)"),
    Param("a2", "m", 1.2, "coupler (joint 2 -> joint 3)"),
    Param("a3", "m", 0.9, "rocker (joint 3 -> joint 4)"),
    Param("a4", "m", 1.0, "ground (joint 4 -> joint 1)"),
)


@register("four-bar", "planar four-bar crank-rocker (user package example), input theta1, joints theta1..theta4",
          PARAMS)
def build(a1: float, a2: float, a3: float, a4: float) -> Scene:
    kinematics = FourBar(a1, a2, a3, a4)
    return custom_scene(
        "four-bar",
        kinematics,
        dh_mechanism(kinematics.rows, anchor=0.25),
        params={"a1": a1, "a2": a2, "a3": a3, "a4": a4},
        path=(-2.5, 2.5),
        tuning=Tuning(sweep_time_scale=4.0, why="fast (RK4 8 ms) at the preset's 2 s for these 5 rad: 3.0e-6 rad; 4x "
                      "slower: 1.8e-7 (error ~ 1 / time^2)"),
        notes="planar: every axis along +z; theta_i is the D-H joint angle, link 4 is the ground",
    )
