"""Panel solids: convex prisms and hinge hulls built with trimesh.

Outlines are (k, 2) convex polygons, counter-clockwise, in the plane z = 0 of the body frame; a
prism spans z in [-thickness/2, +thickness/2] (mid-surface on the crease plane), a hinge hull is the
convex hull of the outline's edges lifted to their hinge heights. MuJoCo computes mass and inertia
of such a convex mesh exactly as trimesh does (checked in tests).
"""

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray


def sector_outline(d_start: ArrayLike, angle: float, length: float) -> NDArray[np.float64]:
    """
    Convex outline (k, 2) of a panel between two creases that meet at the origin.

    The panel spans `angle` radians counter-clockwise from the unit direction `d_start`; its outer
    edge is a polygon through points at distance `length` on the arc (one more point every 45 deg).
    """
    start = np.arctan2(d_start[1], d_start[0])
    n_arc = int(np.ceil(angle / (np.pi / 4))) + 1
    phis = start + np.linspace(0.0, angle, n_arc)
    arc = length * np.stack([np.cos(phis), np.sin(phis)], -1)
    return np.vstack([[0.0, 0.0], arc])


def inset_outline(outline: ArrayLike, distances: ArrayLike) -> NDArray[np.float64]:
    """
    Move each edge i (from vertex i to vertex i+1) of a convex CCW outline inward by distances[i].

    The new vertices are the intersections of consecutive moved edge lines.
    """
    p = np.asarray(outline, dtype=float)
    e = np.roll(p, -1, axis=0) - p
    normal = np.stack([-e[:, 1], e[:, 0]], -1) / np.linalg.norm(e, axis=1, keepdims=True)  # inward
    points = p + normal * np.asarray(distances, dtype=float)[:, None]
    out = []
    for i in range(len(p)):
        j = (i - 1) % len(p)  # edge ending at vertex i
        A = np.stack([e[j], -e[i]], -1)
        s = np.linalg.solve(A, points[i] - points[j])
        out.append(points[j] + s[0] * e[j])
    return np.array(out)


def prism(outline: ArrayLike, thickness: float, bottom: float | None = None) -> trimesh.Trimesh:
    """
    Closed prism of a convex CCW outline (k, 2), z in [bottom, bottom + thickness]
    (default bottom: -thickness/2, the mid-surface on z = 0).

    Faces are written directly (fans on the caps, two triangles per side), outward-facing.
    """
    p = np.asarray(outline, dtype=float)
    k = len(p)
    z0 = -thickness / 2 if bottom is None else bottom
    low, high = np.full((k, 1), z0), np.full((k, 1), z0 + thickness)
    vertices = np.vstack([np.hstack([p, low]), np.hstack([p, high])])
    bottom = [[0, i + 1, i] for i in range(1, k - 1)]
    top = [[k, k + i, k + i + 1] for i in range(1, k - 1)]
    sides = []
    for i in range(k):
        j = (i + 1) % k
        sides += [[i, j, k + j], [i, k + j, k + i]]
    return trimesh.Trimesh(vertices, np.array(bottom + top + sides), process=False)


def hinge_hull(outline: ArrayLike, heights: ArrayLike) -> trimesh.Trimesh:
    """
    Convex hull of the edges of a convex CCW outline (k, 2), edge i (vertex i -> i+1) lifted to height
    heights[i] (m; NaN: an edge with no hinge, left out): a thick panel whose every hinge line lies on
    its surface, whatever the heights (a slab between the lowest and highest hinge buries the middle
    ones). trimesh's hull runs on scipy's qhull.
    """
    p = np.asarray(outline, dtype=float)
    h = np.asarray(heights, dtype=float)
    ends = np.stack([p, np.roll(p, -1, axis=0)], 1)[np.isfinite(h)]  # (edges, 2, 2)
    points = np.concatenate([ends, np.broadcast_to(h[np.isfinite(h)][:, None, None], (len(ends), 2, 1))], -1)
    return trimesh.convex.convex_hull(points.reshape(-1, 3))


# Mesh files a linkage file's `shapes.meshes` may name (trimesh reads them; others it refuses or misreads as points).
MESH_FORMATS = ("stl", "obj", "ply")


def mujoco_mesh_problem(mesh: trimesh.Trimesh) -> str | None:
    """
    Why MuJoCo cannot compile `mesh` (metres) as a moving body's solid, or None: a mesh of no volume (one
    triangle, coplanar points) has no inertia. A one-body model is compiled, a few ms, so the refusal comes before
    any trace.
    """
    import mujoco  # here: the solids of the built-in scenes never need it

    vertex = " ".join(f"{v:.17g}" for v in np.ravel(mesh.vertices))
    face = " ".join(str(int(i)) for i in np.ravel(mesh.faces))
    xml = (f'<mujoco><asset><mesh name="m" vertex="{vertex}" face="{face}"/></asset><worldbody><body>'
           '<freejoint/><geom type="mesh" mesh="m"/></body></worldbody></mujoco>')
    try:
        mujoco.MjModel.from_xml_string(xml)
    except ValueError as err:
        return " ".join(str(err).split())[:200]
    return None
