"""Thick-panel four-crease vertex = Bennett linkage (Peng 2018, §4.2).

The flat-foldable vertex (alpha3 = pi - alpha1, alpha4 = pi - alpha2) gets hinge k on the line through
(0, 0, h_k) along its flat crease direction d_k, with b the thickness scale and a = b sin(alpha1)/sin(alpha2)
(eqn 4-4c). Layout 'staircase' h = (0, a, a + b, b) follows mode S only; 'zigzag' h = (0, a, a - b, -b)
follows mode C only (checked here: PoE residual <= 1.4e-15). The hinge angles q are the fold angles of the
zero-thickness vertex on that mode, so the closed form is that mode's tan-half relation (Peng 2018, eqns 3-1 and
3-3a/3-3b: tan(rho2/2) = m12 tan(rho1/2), rho3 = -/+ rho1, rho4 = +/- rho2), the same relation as eqn 1-8's; the loop
through the lifted hinges is spatial (Kutzbach 4 - 6 = -2) and, unlike the zero-thickness vertex, has
mobility 1 at the flat state: no bifurcation there. Peng 2018's (4-5c) has the wrong sign (closure error about 3 to 7
printed); eqn 1-8's sign is used here, the correction made here.

Not `Vertex4`'s roots of eqn 2-5: at the fully folded end rho1 = +/- pi of a vertex with creases 1 and 3 collinear
(alpha1 + alpha2 = 180 deg) its coefficients all vanish, the zero-thickness vertex folds any way there and the root
taken missed the thick loop by 0.027 (staircase 60/120 deg), 0.1 within 1e-8 rad of the end, and 2.2e-6 at
alpha1 = 90 deg + 1e-6 rad, alpha2 = 90 deg. The tan-half form closes to <= 1.2e-15 at every input of those and
of generic vertices (ends included); on generic vertices it agrees with eqn 2-5's roots to 5e-12 away from the ends
(measured here).
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Loop, LoopSystem
from ..errors import ParameterError
from ..geometry import frame_along, invert
from .base import Branch, Event, JointSpaceKinematics, as_inputs
from .vertex4 import ANGLE_TOL, Vertex4, flat_foldable_fold_angles

LAYOUTS = {"staircase": "S", "zigzag": "C"}
# Two hinges this close (rad) to one line are refused (`_refuse_coaxial_hinges`). The mode's multiplier m12 is then
# about the angle's distance to the coaxial case, and a fold that small next to rho1 is named unfolded by
# `vertex4.ZERO_FOLD` (1e-8): the zigzag 60/120 deg vertex 1e-8 rad off lost its branch C (measured here); 1e-6
# rad leaves a factor 100.
COAXIAL_TOL = 1e-6


def hinge_heights(alpha: ArrayLike, b: float, layout: str) -> NDArray[np.float64]:
    """Heights (4,) of the hinge lines above the sheet (m)."""
    a = b * np.sin(alpha[0]) / np.sin(alpha[1])
    if layout == "staircase":
        return np.array([0.0, a, a + b, b])
    return np.array([0.0, a, a - b, -b])


def _refuse_coaxial_hinges(alpha: NDArray[np.float64], layout: str) -> None:
    """
    ParameterError when two hinges of the layout lie on one line (within COAXIAL_TOL): staircase with
    alpha1 = alpha2 (hinges 2 and 4: creases 2 and 4 collinear, both at height a = b), zigzag with
    alpha1 + alpha2 = 180 deg (hinges 1 and 3: creases 1 and 3 collinear, h3 = a - b = 0).

    Such a loop is no Bennett linkage: it folds about the common line alone (staircase: rho1 = rho3 = 0,
    rho2 = rho4 free, closing to 2.4e-16 at 90/90 deg and 1.1e-15 at 60/60 deg; zigzag: rho2 = rho4 = 0,
    rho1 = rho3 free, 2.9e-16 at 60/120 deg; a generic 60/70 deg staircase misses by 0.35), and the mode's
    multiplier is 0 or infinite (Peng 2018, eqn 1-8's right side and eqns 3-3a/3-3b). Staircase mode S then jumps
    from flat to rho2 = +/- pi at any input (rho1 is locked at flat; the tan-half form gives NaN at rho1 = 0),
    and eqn 2-5's root at rho1 = +/- pi missed the loop by 0.1 for alpha1 = alpha2 = 90 deg. Zigzag mode C is the
    fold about line 1-3 alone (the model named no branch C). Measured here.
    """
    a1, a2 = alpha[0], alpha[1]
    deg = f"alpha1 = {np.rad2deg(a1):.9g} deg, alpha2 = {np.rad2deg(a2):.9g} deg"
    if layout == "staircase" and abs(a1 - a2) < COAXIAL_TOL:
        raise ParameterError(
            f"{deg}: staircase hinges 2 and 4 lie on one line (no Bennett linkage, rho1 locked at flat); "
            "alpha1 must differ from alpha2"
        )
    if layout == "zigzag" and abs(a1 + a2 - np.pi) < COAXIAL_TOL:
        raise ParameterError(
            f"{deg}: zigzag hinges 1 and 3 lie on one line (no Bennett linkage, mode C folds about it alone); "
            "alpha1 + alpha2 must differ from 180 deg"
        )


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
        _refuse_coaxial_hinges(self.alpha, layout)
        self.b, self.layout, self.mode = float(b), layout, LAYOUTS[layout]
        self.heights = hinge_heights(self.alpha, self.b, layout)
        assert abs(np.sum(self.alpha) - 2 * np.pi) < ANGLE_TOL

    def branches(self) -> tuple[Branch, ...]:
        zero = self.vertex.branch(self.mode)
        text = f"{self.layout} hinge layout: follows mode {self.mode} of the zero-thickness vertex only"
        return (Branch(self.mode, text, zero.domain),)

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Hinge angles (n, 4) (rad) on the layout's mode from the tan-half relation, valid on its domain."""
        self.branch(branch)
        x = as_inputs(x)
        valid = np.abs(x) <= np.pi  # an input fold angle lives in [-pi, pi]; NaN is invalid
        # The other mode's multipliers divide by zero where that mode is degenerate (alpha1 = alpha2 for S); only
        # this mode's, finite and nonzero once coaxial hinges are refused, are used.
        with np.errstate(divide="ignore"):
            folds = flat_foldable_fold_angles(self.alpha, np.where(valid, x, 0.0), self.mode)
        return self.within_domain(branch, x, np.where(valid[:, None], folds, np.nan), valid)

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
