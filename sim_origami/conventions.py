"""Units and sign conventions shared by every layer.

Angles are radians everywhere inside the package and in JSON; degrees only at the command-line
edge (`deg_to_rad`, `rad_to_deg`).

Origami vertex (product of exponentials): the vertex sits at the origin of the flat sheet, normal
+z. Crease i points along d_i at angle alpha_1 + ... + alpha_(i-1) from +x (counter-clockwise);
sector alpha_i lies between crease i and crease i+1. The fold angle rho_i is the right-handed
rotation about +d_i of the panel on the counter-clockwise side of crease i relative to the panel on
its clockwise side; flat is rho = 0. Seen from +z, rho > 0 lifts the counter-clockwise panel: a
valley (FOLD's `edges_foldAngle` sign). The closure is Rot(d_1, rho_1) ... Rot(d_n, rho_n) = I.

This rho equals a MuJoCo hinge qpos when the hinge axis is +d_i, the child body is the
counter-clockwise panel and the reference pose is the flat sheet.

Branches are named by geometry (e.g. which crease folds opposite to the other three, or the
flat-foldable modes S and C) and followed by continuity, never by the +/- label of a root.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

# Lengths every model accepts (m), scenes and linkage files alike. MuJoCo, the collision meshes (qhull) and the
# solvers' floors work in absolute units: below 1e-4 m a thick panel's hull falls under trimesh's volume floor and
# qhull's precision, above 1e4 m the closure sites' 1e-15 m projection floor is lost in rounding. Inside, every
# tolerance scales with the model's size.
LENGTH_RANGE = (1e-4, 1e4)
# Largest ratio of two positive lengths of one model: beyond it the small one (a thickness) is rounding on the large.
LENGTH_RATIO_MAX = 1e4
# A motion whose input moves less than this (rad) is no motion to validate: its swept-range check fails, and a
# numeric trace that ends within it of its start is stuck there (no MuJoCo run is made of it).
MIN_SWEEP_RAD = 1e-3


def deg_to_rad(value_deg: ArrayLike) -> NDArray[np.float64]:
    """Degrees (command line, tables) to radians (API, JSON)."""
    return np.deg2rad(np.asarray(value_deg, dtype=float))


def rad_to_deg(value_rad: ArrayLike) -> NDArray[np.float64]:
    """Radians (API, JSON) to degrees (command line, tables, plots)."""
    return np.rad2deg(np.asarray(value_rad, dtype=float))
