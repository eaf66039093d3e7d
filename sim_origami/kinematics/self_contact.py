"""Self-contact of a folded crease pattern's faces, zero thickness (numpy only).

A configuration (crease angles rho, radians, the signs of `sim_origami.creases`) places every face by composing
the crease rotations along a breadth-first spanning tree of the faces from a central face; with closed loops any
tree gives the same placement. Faces are triangulated (ear clipping, so non-convex faces are allowed) and two
triangles of different faces are in contact when they meet along a segment longer than OVERLAP (`triangles_meet`):
an edge through the other's interior, and also rims crossing edge on edge, as mirror-symmetric folds do.

Which pairs count. Faces that share a crease touch along it in every pose and are never tested (nor triangles of
faces that share two vertices without a crease, across a slit). Faces that share only a vertex touch there
legitimately, so each triangle is taken relative to its own copy of that vertex (the copies differ by rounding of
the placement, ~1e-14 of the size on a 480-crease sheet, which near a flat fold would otherwise read as a crossing
right at the vertex); a penetration still shows as a segment from the vertex. Faces that lie on each other exactly
(a fold of +-pi) are coplanar and not reported: the trace stops before, at a lock.

Cuts. A cut's vertices are doubled (`fold.split_cuts`: one copy per side, at the same flat point), so its two sides
share no crease and at most its inner end. Two copies of a vertex count as one shared vertex where they coincide
(within CUT_CLOSED): while the cut stays closed, its two sides share its edge as faces across a crease do, lying
edge to edge at flat and hinged apart about the cut's line when a crease continuing it folds, touching along that
line only (it was read as a crossing at the start, the whole edge lying on both planes). Once the cut opens, the
sides are tested as any others, so a side folded through the other is reported. Like faces across a crease, sides
of a closed cut folded through each other about its line (through +-pi) are not seen: that takes the motion's
history, not one pose (for a crease it is its lock).

Cost: a sweep over the faces' bounding boxes along the longest axis, then the boxes of their triangles and each
triangle's plane (all three corners of the other on one side: apart), and the interval test on what is left.
Lengths are scaled to the pattern's longest extent, so the tolerances are relative. Patterns with thick panels
(hinges off the mid-plane) are not tested: their panels are not the zero-thickness faces placed here.
"""

from collections import deque

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..creases import CreasePattern
from ..geometry import rotation
from ..graph import breadth_first_depths, spanning_edges

# Two triangles meet when their intersection is a segment longer than OVERLAP (units of the pattern's size), with
# their planes more than COPLANAR apart in angle (rad): coplanar faces (a fold of exactly +-pi) are not reported.
OVERLAP = 1e-9
COPLANAR = 1e-12
# Bounding boxes are widened by this (units of the size) so that a crossing is never lost in the broad phase.
BOX_MARGIN = 1e-9
# Copies of one vertex (a cut's two sides) closer than this (units of the size) are the same point: the cut is closed.
CUT_CLOSED = 1e-9


def triangulate(polygon: NDArray[np.float64]) -> list[tuple[int, int, int]]:
    """Triangles (local corner indices) of a simple counter-clockwise polygon (n, 2) by ear clipping."""
    left = list(range(len(polygon)))
    out = []
    while len(left) > 3:
        for k in range(len(left)):
            a, b, c = left[k - 1], left[k], left[(k + 1) % len(left)]
            pa, pb, pc = polygon[a], polygon[b], polygon[c]
            if _turn(pa, pb, pc) <= 0:
                continue  # a reflex (or straight) corner is no ear
            others = [polygon[j] for j in left if j not in (a, b, c)]
            if not any(_inside(p, pa, pb, pc) for p in others):
                out.append((a, b, c))
                left.pop(k)
                break
        else:  # only straight corners left (collinear points on a side): fan the rest
            break
    out.extend((left[0], left[k], left[k + 1]) for k in range(1, len(left) - 1))
    return out


def _turn(a: NDArray, b: NDArray, c: NDArray) -> float:
    """Twice the signed area of triangle abc (2-D): > 0 counter-clockwise."""
    return float((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))


def _inside(p: NDArray, a: NDArray, b: NDArray, c: NDArray) -> bool:
    """Whether p lies in the closed counter-clockwise triangle abc."""
    return _turn(a, b, p) >= 0 and _turn(b, c, p) >= 0 and _turn(c, a, p) >= 0


class SelfContact:
    """
    The zero-thickness self-contact test of a crease pattern. `crossing(q)` gives the face pairs that cross at
    crease angles q (rad); calling it gives a one-line reason for the first pair, or None (a `path.trace`
    `stop_when`).
    """

    def __init__(self, pattern: CreasePattern):
        self.pattern = pattern
        self.active = not any(c.height != 0.0 for c in pattern.creases)
        v = pattern.vertices
        self.size = float(max(np.max(np.ptp(v, axis=0)), 1e-300))
        n_faces = len(pattern.faces)
        index = {name: f for f, name in enumerate(pattern.face_names)}
        # (right, left) face of each crease: rho turns the left one relative to the right one about start -> end
        sides = [tuple(index[n] for n in pattern.crease_faces(c)) for c in pattern.creases]
        self._crease_pairs = sides
        # the placement tree: shortest paths from the face nearest the centre (few products per face)
        centre = v.mean(axis=0)
        root = int(np.argmin([np.linalg.norm(v[list(f)].mean(axis=0) - centre) for f in pattern.faces]))
        depth = breadth_first_depths(range(n_faces), sides, root)
        by_level: dict[int, list[tuple[int, int, int, float]]] = {}
        for k in spanning_edges(range(n_faces), sides, root=root):
            right, left = sides[k]
            if right not in depth:
                continue  # a piece cut off from the root's: not placed, not tested
            child, parent = (left, right) if depth[left] > depth[right] else (right, left)
            by_level.setdefault(depth[child], []).append((child, parent, k, 1.0 if child == left else -1.0))
        self.levels: list[tuple[NDArray, NDArray, NDArray, NDArray]] = []  # (child, parent, crease, sign) per depth
        for d in sorted(by_level):
            rows = np.array(by_level[d], dtype=float)
            self.levels.append((rows[:, 0].astype(int), rows[:, 1].astype(int), rows[:, 2].astype(int), rows[:, 3]))
        self.placed = np.zeros(n_faces, dtype=bool)
        self.placed[list(depth)] = True
        self.axes = np.array([pattern.direction(c) for c in pattern.creases]).reshape(-1, 3)
        self.origins = np.array([[*v[c.start], 0.0] for c in pattern.creases]).reshape(-1, 3) / self.size
        # corners: (face, vertex) with the flat position; triangles index corners
        self.corner_face = np.array([f for f, face in enumerate(pattern.faces) for _ in face], dtype=int)
        self.corner_vertex = np.array([u for face in pattern.faces for u in face], dtype=int)
        # one number per flat point: the copies of a vertex doubled along a cut share it
        self.corner_point = np.unique(v, axis=0, return_inverse=True)[1].reshape(-1)[self.corner_vertex]
        self.flat = np.c_[v[self.corner_vertex] / self.size, np.zeros(len(self.corner_vertex))]
        starts = np.cumsum([0] + [len(f) for f in pattern.faces])
        tris = [tuple(starts[f] + t for t in tri) for f, face in enumerate(pattern.faces)
                for tri in triangulate(v[list(face)])]
        self.triangles = np.array(tris, dtype=int).reshape(-1, 3)
        self.tri_face = self.corner_face[self.triangles[:, 0]]
        self.corner_start = starts[:-1]
        self.tri_count = np.bincount(self.tri_face, minlength=n_faces)
        self.tri_start = np.cumsum(self.tri_count) - self.tri_count
        # face pairs tested: different faces that share no crease (and were both placed)
        self.allowed = np.ones((n_faces, n_faces), dtype=bool)
        np.fill_diagonal(self.allowed, False)
        for a, b in sides:
            self.allowed[a, b] = self.allowed[b, a] = False
        self.allowed &= self.placed[:, None] & self.placed[None, :]

    def poses(self, q: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Rotations (F, 3, 3) and translations (F, 3) (units of the pattern's size) of the faces at angles q."""
        q = np.asarray(q, dtype=float)
        n = len(self.pattern.faces)
        R = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
        p = np.zeros((n, 3))
        turn = rotation(self.axes, q)  # every hinge at once; a child on the right turns by -rho (the transpose)
        shift = self.origins - np.einsum("kij,kj->ki", turn, self.origins)  # rotation about the line through o
        for child, parent, crease, sign in self.levels:
            H, h = turn[crease], shift[crease]
            back = sign < 0
            H[back] = H[back].transpose(0, 2, 1)
            h[back] = -np.einsum("kij,kj->ki", H[back], h[back])
            R[child] = R[parent] @ H
            p[child] = p[parent] + np.einsum("kij,kj->ki", R[parent], h)
        return R, p

    def corners(self, q: ArrayLike) -> NDArray[np.float64]:
        """Each face's corners placed at angles q, (corners, 3), units of the pattern's size."""
        R, p = self.poses(q)
        return np.einsum("kij,kj->ki", R[self.corner_face], self.flat) + p[self.corner_face]

    def crossing(self, q: ArrayLike) -> NDArray[np.int_]:
        """Face index pairs (m, 2) (smaller first, sorted) whose triangles meet at angles q (rad)."""
        if not self.active or len(self.triangles) < 2:
            return np.zeros((0, 2), dtype=int)
        xyz = self.corners(q)
        # broad phase: faces' boxes, then the boxes of their triangles
        fi, fj = _box_pairs(np.minimum.reduceat(xyz, self.corner_start) - BOX_MARGIN,
                            np.maximum.reduceat(xyz, self.corner_start) + BOX_MARGIN)
        keep = self.allowed[fi, fj]
        fi, fj = fi[keep], fj[keep]
        ca, cb = self.tri_count[fi], self.tri_count[fj]
        per = ca * cb
        pair = np.repeat(np.arange(len(fi)), per)
        k = np.arange(per.sum()) - np.repeat(np.cumsum(per) - per, per)
        i = self.tri_start[fi][pair] + k // cb[pair]
        j = self.tri_start[fj][pair] + k % cb[pair]
        tri = xyz[self.triangles]
        lo, hi = tri.min(axis=1) - BOX_MARGIN, tri.max(axis=1) + BOX_MARGIN
        keep = np.all((lo[i] <= hi[j]) & (lo[j] <= hi[i]), axis=1)
        i, j, fi, fj = i[keep], j[keep], fi[pair[keep]], fj[pair[keep]]
        if not len(i):
            return np.zeros((0, 2), dtype=int)
        # faces whose triangles lie wholly on one side of the other's plane do not meet
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]  # a sliver (zero area) is never apart
        offset = np.sum(n * tri[:, 0], axis=1)
        apart = np.zeros(len(i), dtype=bool)
        for a, b in ((i, j), (j, i)):
            d = np.einsum("mki,mi->mk", tri[b], n[a]) - offset[a][:, None]
            apart |= np.all(d > BOX_MARGIN, axis=1) | np.all(d < -BOX_MARGIN, axis=1)
        i, j, fi, fj = i[~apart], j[~apart], fi[~apart], fj[~apart]
        A, B = tri[i], tri[j]
        # a vertex of the sheet that both triangles have: each is taken relative to its own copy of it, put first;
        # copies of a vertex along a cut are one where they coincide (the cut closed there)
        va, vb = self.corner_vertex[self.triangles[i]], self.corner_vertex[self.triangles[j]]
        pa, pb = self.corner_point[self.triangles[i]], self.corner_point[self.triangles[j]]
        same = va[:, :, None] == vb[:, None, :]
        twins = (pa[:, :, None] == pb[:, None, :]) & ~same
        if np.any(twins):
            gap = np.linalg.norm(A[:, :, None] - B[:, None, :], axis=-1)
            same |= twins & (gap <= CUT_CLOSED)
        shared = np.flatnonzero(same.any(axis=(1, 2)))
        first = same[shared]
        for T, k in ((A, np.argmax(first.any(axis=2), axis=1)), (B, np.argmax(first.any(axis=1), axis=1))):
            roll = (np.arange(3)[None, :] + k[:, None]) % 3
            T[shared] = np.take_along_axis(T[shared], roll[:, :, None], axis=1)
            T[shared] -= T[shared, :1]
        hit = triangles_meet(A, B) & (same.sum(axis=(1, 2)) <= 1)
        if not np.any(hit):
            return np.zeros((0, 2), dtype=int)
        return np.unique(np.sort(np.c_[fi[hit], fj[hit]], axis=1), axis=0)

    def __call__(self, q: ArrayLike) -> str | None:
        """None when no faces cross at q; else which do, and the crease that folds them together."""
        pairs = self.crossing(q)
        if not len(pairs):
            return None
        a, b = (int(f) for f in pairs[0])
        names = self.pattern.face_names
        k = self.folding_crease(a, b, q)
        crease = self.pattern.creases[k]
        more = f" (and {len(pairs) - 1} more pair(s))" if len(pairs) > 1 else ""
        return (f"faces {names[a]} and {names[b]} touch{more}; crease {crease.name} at {float(q[k]):.6g} rad, the "
                "most folded crease between them")

    def folding_crease(self, a: int, b: int, q: ArrayLike) -> int:
        """The most folded crease (largest |rho|) on a shortest path of creases from face a to face b."""
        step: dict[int, tuple[int, int]] = {a: (a, -1)}
        queue = deque([a])
        neighbours: dict[int, list[tuple[int, int]]] = {}
        for k, (f, g) in enumerate(self._crease_pairs):
            neighbours.setdefault(f, []).append((g, k))
            neighbours.setdefault(g, []).append((f, k))
        while queue and b not in step:
            f = queue.popleft()
            for g, k in neighbours.get(f, []):
                if g not in step:
                    step[g] = (f, k)
                    queue.append(g)
        creases = []
        f = b
        while f in step and step[f][1] >= 0:
            f, k = step[f]
            creases.append(k)
        q = np.asarray(q, dtype=float)
        return max(creases, key=lambda k: abs(q[k])) if creases else int(np.argmax(np.abs(q)))


def triangles_meet(A: NDArray[np.float64], B: NDArray[np.float64]) -> NDArray[np.bool_]:
    """
    Whether each pair of triangles A, B (m, 3, 3) meets along a segment longer than OVERLAP: the intervals in which
    each cuts the other's plane, on the planes' common line, overlap (Moller's interval test). Unlike an
    edge-through-interior test (`geometry.triangles_cross`) it also sees a crossing whose segment ends on both
    triangles' edges at once, as in mirror-symmetric folds. Corner 0 of B lies on B's plane exactly, so a vertex
    put at the origin in both is exactly on both planes.
    """
    nA = np.cross(A[:, 1] - A[:, 0], A[:, 2] - A[:, 0])
    nB = np.cross(B[:, 1] - B[:, 0], B[:, 2] - B[:, 0])
    line = np.cross(nA, nB)
    size = np.linalg.norm(line, axis=1)
    apart = size > COPLANAR * np.linalg.norm(nA, axis=1) * np.linalg.norm(nB, axis=1)
    line = line / np.where(apart, size, 1.0)[:, None]
    lo_a, hi_a = _interval(A, np.einsum("mki,mi->mk", A - B[:, :1], nB), line)
    lo_b, hi_b = _interval(B, np.einsum("mki,mi->mk", B - A[:, :1], nA), line)
    return apart & (np.minimum(hi_a, hi_b) - np.maximum(lo_a, lo_b) > OVERLAP)


def _interval(T: NDArray[np.float64], d: NDArray[np.float64], line: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
    """The interval (lo, hi) along `line` (m, 3) of where triangles T (m, 3, 3) with signed plane distances d (m, 3)
    of their corners cut the plane: edges whose ends lie on either side, and corners on it; (inf, -inf) if none."""
    p = np.einsum("mki,mi->mk", T, line)
    lo, hi = np.full(len(T), np.inf), np.full(len(T), -np.inf)
    for k in range(3):
        a, b = k, (k + 1) % 3
        cuts = d[:, a] * d[:, b] < 0
        with np.errstate(invalid="ignore", divide="ignore"):
            at = np.where(cuts, p[:, a] + (p[:, b] - p[:, a]) * d[:, a] / (d[:, a] - d[:, b]), np.nan)
        on = d[:, a] == 0
        at_corner = np.where(on, p[:, a], np.nan)
        lo = np.fmin(lo, np.fmin(at, at_corner))
        hi = np.fmax(hi, np.fmax(at, at_corner))
    return lo, hi


def _box_pairs(lo: NDArray[np.float64], hi: NDArray[np.float64]) -> tuple[NDArray[np.int_], NDArray[np.int_]]:
    """Index pairs (i, j), i != j, of boxes [lo, hi] (n, 3) that overlap: sweep and prune along the longest axis."""
    axis = int(np.argmax(hi.max(axis=0) - lo.min(axis=0)))
    order = np.argsort(lo[:, axis], kind="stable")
    start, stop = lo[order, axis], hi[order, axis]
    end = np.searchsorted(start, stop, side="right")  # boxes after k in the order start before k's end
    count = np.maximum(end - np.arange(len(order)) - 1, 0)
    first = np.repeat(np.arange(len(order)), count)
    offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    i, j = order[first], order[first + 1 + offset]
    overlap = np.all((lo[i] <= hi[j]) & (lo[j] <= hi[i]), axis=1)
    return i[overlap], j[overlap]
