"""Origami as mechanisms: single vertices (sector panels) and crease patterns (face panels) joined by hinges.

Frames follow `sim_origami.conventions`: the flat sheet in the world XY plane, vertex at the
origin, crease i along d_i at angle alpha_1 + ... + alpha_(i-1). Panel i lies between creases i
and i+1 (sector alpha_i). Crease i joins panel i-1 (clockwise side, the joint's parent) to panel i
(counter-clockwise side, the child) about +d_i, so the joint angle is the fold angle rho_i.
Every body frame is the world frame of the flat sheet.
"""

import numpy as np
import trimesh
from numpy.typing import ArrayLike

from .creases import CreasePattern
from .geometry import frame_along
from .mechanism import Body, Joint, Mechanism
from .solids import hinge_hull, inset_outline, prism, sector_outline

# Panel colours by index (Menagerie-like muted palette), RGBA.
PALETTE = (
    (0.93, 0.93, 0.90, 1.0),
    (0.85, 0.55, 0.30, 1.0),
    (0.20, 0.35, 0.60, 1.0),
    (0.35, 0.60, 0.35, 1.0),
    (0.70, 0.30, 0.35, 1.0),
    (0.55, 0.45, 0.70, 1.0),
)

# Thickness (fraction of the crease length) given to zero-thickness panels so that they carry
# inertia and render; such panels never collide.
NOMINAL_THICKNESS = 0.01


def crease_directions(alpha: ArrayLike) -> np.ndarray:
    """Unit crease directions d_i (n, 3) of a flat vertex with sector angles alpha (n,)."""
    alpha = np.asarray(alpha, dtype=float)
    angles = np.concatenate([[0.0], np.cumsum(alpha)[:-1]])
    return np.stack([np.cos(angles), np.sin(angles), np.zeros_like(angles)], -1)


def vertex_mechanism(
    alpha: ArrayLike,
    *,
    length: float = 1.0,
    thickness: float = 0.0,
    inset: float = 0.0,
    root: int = 1,
    keep: tuple[int, ...] = (),
    names: tuple[str, ...] | None = None,
    heights: ArrayLike | None = None,
    anchors: tuple[float, ...] = (0.5, 1.0),
) -> Mechanism:
    """
    A single flat-sheet vertex of degree n as panels and crease hinges.

    Parameters
    ----------
    alpha : (n,) float
      Sector angles in radians.
    length : float
      Crease length in metres.
    thickness : float
      Panel thickness in metres; 0 builds zero-thickness panels (nominal solids, no collision).
    inset : float
      For thick panels: distance in metres by which the collision solid stays clear of the
      creases (and so of the vertex), so that neighbours touch only when truly folded onto each other.
    root : int
      Panel (1-based) fixed to the world.
    keep : tuple of int
      Creases (1-based) that must stay in the spanning tree (the driven ones).
    names : tuple of str, optional
      Crease names (default crease_1 ... crease_n); panels are panel_1 ... panel_n.
    heights : (n,) float, optional
      Thick-panel origami (Peng 2018, ch. 4): hinge i lies on the line through (0, 0, heights[i]) along
      d_i, and panel i is a slab filling the gap between the planes of its two hinges (thickness =
      link length). Panels then carry collision solids inset by `inset` from both creases.
    anchors : tuple of float
      Where a cut crease is closed, as fractions of `length` along its hinge from the hinge point;
      the default keeps clear of the vertex that every crease of a zero-thickness vertex shares.
    """
    alpha = np.asarray(alpha, dtype=float)
    n = len(alpha)
    d = crease_directions(alpha)
    names = names or tuple(f"crease_{i + 1}" for i in range(n))
    solid_t = thickness if thickness > 0 else NOMINAL_THICKNESS * length
    h = np.zeros(n) if heights is None else np.asarray(heights, dtype=float)
    bodies = []
    for i in range(n):
        outline = sector_outline(d[i], alpha[i], length)
        low, gap = min(h[i], h[(i + 1) % n]), abs(h[(i + 1) % n] - h[i])
        slab = (gap, low) if heights is not None and gap > 0 else (thickness, None)
        solid = prism(outline, *slab) if slab[0] > 0 else prism(outline, solid_t)
        collision = None
        if slab[0] > 0:
            distances = np.zeros(len(outline))
            distances[0] = distances[-1] = inset  # the two crease edges meet at vertex 0
            collision = prism(inset_outline(outline, distances), *slab)
        bodies.append(Body(f"panel_{i + 1}", solid, collision, PALETTE[i % len(PALETTE)]))
    joints = []
    for i in range(n):
        frame = frame_along(d[i], (0.0, 0.0, h[i]))
        joints.append(
            Joint(
                names[i],
                parent=f"panel_{(i - 1) % n + 1}",
                child=f"panel_{i + 1}",
                frame_parent=frame,
                frame_child=frame,
                anchors=tuple(a * length for a in anchors),
            )
        )
    return Mechanism(tuple(bodies), tuple(joints), f"panel_{root}", tuple(names[k - 1] for k in keep))


def _face_solid(outline: np.ndarray, heights: np.ndarray, nominal: float) -> trimesh.Trimesh:
    """A face's solid: its hinge hull if its hinges sit at several heights, else a plate `nominal` m thick."""
    if np.nanmax(heights) > np.nanmin(heights):
        return hinge_hull(outline, heights)
    return prism(outline, nominal)


def pattern_mechanism(
    pattern: CreasePattern,
    *,
    root: str,
    keep: tuple[str, ...] = (),
    couplings: tuple[tuple[str, str, float], ...] = (),
    anchors: tuple[float, ...] = (0.5, 1.0),
    collision_inset: float | None = None,
    breadth_first: bool = False,
) -> Mechanism:
    """
    A crease pattern as a mechanism: faces as bodies (frames = the flat sheet's world frame), creases as
    hinges on their hinge lines (`creases` module for signs), a spanning tree from `root` (shortest-path with
    `breadth_first`, see `Mechanism`).

    Faces whose hinges sit at several heights (thick panels) are the convex hulls of their edges lifted to
    their hinge heights (`solids.hinge_hull`, border edges at `pattern.border_heights`), so every hinge line
    lies on its panel's surface; faces flat in the sheet are nominal plates of NOMINAL_THICKNESS x the
    longest crease. With `collision_inset` (m) they also carry a collision solid: the same solid built on
    the outline inset by that much from every edge, so that neighbours touch only when folded onto each
    other. `anchors` are where a cut crease is closed, as fractions of its length from its start; the
    default keeps clear of the start vertex, which may be a point that no fold moves (a connect there has
    a zero Jacobian, and MuJoCo drops its rows).
    """
    nominal = NOMINAL_THICKNESS * max(pattern.length(c) for c in pattern.creases)
    bodies = []
    for k, (name, face) in enumerate(zip(pattern.face_names, pattern.faces, strict=True)):
        outline = pattern.vertices[list(face)]
        heights = pattern.edge_heights(k)
        collision = None
        if collision_inset is not None:
            collision = _face_solid(inset_outline(outline, np.full(len(face), collision_inset)), heights, nominal)
        bodies.append(Body(name, _face_solid(outline, heights, nominal), collision, PALETTE[k % len(PALETTE)]))
    joints = []
    for crease in pattern.creases:
        parent, child = pattern.crease_faces(crease)
        frame = pattern.hinge_frame(crease)
        span = pattern.length(crease)
        joints.append(Joint(crease.name, parent, child, frame, frame, tuple(a * span for a in anchors)))
    return Mechanism(tuple(bodies), tuple(joints), root, keep, couplings, breadth_first)


def hinge_gap(pattern: CreasePattern, mechanism: Mechanism) -> float:
    """
    Largest distance (m) from an end of a crease's hinge line to the nearest vertex of each of its two panels'
    solids: 0 when every hinge lies on the surface of both panels it joins (thick panels as hinge hulls).
    """
    bodies = {b.name: b for b in mechanism.bodies}
    gap = 0.0
    for crease in pattern.creases:
        ends = np.array([[*pattern.vertices[v], crease.height] for v in (crease.start, crease.end)])
        for face in pattern.crease_faces(crease):
            distance = np.linalg.norm(bodies[face].solid.vertices[None] - ends[:, None], axis=-1)
            gap = max(gap, float(np.max(np.min(distance, axis=1))))
    return gap
