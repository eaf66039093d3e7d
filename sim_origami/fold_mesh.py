"""Mesh steps behind the FOLD reader (`sim_origami.fold`): the sheet's plane, faces from a planar edge graph,
consistent face orientation, cuts and joins, the nearest rigid folded form (scipy's sparse least squares), unfolding
a folded form, and dihedral fold angles.

Every tolerance is relative to the sheet's size (the diagonal of its bounding box), so a 1 mm sheet and a
1000-unit sheet are read alike. Faces are vertex loops; a face's normal follows its loop counter-clockwise
(the FOLD 1.2 specification's orientation), and a fold angle rho > 0 folds the two normals towards each other
(a valley, `sim_origami.creases`).
"""

from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass
from itertools import chain, combinations
from typing import Protocol

import numpy as np
from numpy.typing import NDArray
from scipy import sparse as sp
from scipy.optimize import linprog
from scipy.sparse.linalg import splu

from .errors import ParameterError
from .geometry import minimal_rotation, rotation

# A sheet is flat when no vertex is further than this from its fitted plane, relative to its size.
PLANE_RTOL = 1e-6
# Unfolding: a vertex placed by two faces may differ by this, relative to the sheet's size. A folded form is first
# projected onto the nearest developable one (`nearest_developable`), whose placements agree to rounding.
DEVELOP_RTOL = 1e-9
# The projection: at most this many Gauss-Newton steps; a form whose conditions hold to RIGID_RTOL of its size is
# exact (to rounding) and kept as it is. One that moves is closed further, to CLOSED_RTOL of its size or until a step
# no longer halves the residual (its rounding floor): unfolding a 50 x 50 Miura sheet printed to 6 decimals placed
# vertices twice 1.1e-9 of its size apart from a form closed to 1e-14, 3.3e-10 from 2e-16.
RIGID_STEPS = 30
RIGID_RTOL = 1e-13
CLOSED_RTOL = 1e-15
# A measured fold angle this close to +-pi takes its sign from the crease's M/V letter (rad).
FLAT_FOLD_TOL = 1e-6

Face = tuple[int, ...]


def sides(face: Face) -> Iterator[tuple[int, int]]:
    """The directed sides (a, b) of a face loop."""
    return zip(face, face[1:] + face[:1], strict=True)


def key(a: int, b: int) -> tuple[int, int]:
    """An undirected edge's key: its two vertices, smaller first."""
    return (a, b) if a < b else (b, a)


def size(xyz: NDArray[np.float64]) -> float:
    """The diagonal of the bounding box of points (n, d)."""
    return float(np.linalg.norm(np.ptp(xyz, axis=0))) if len(xyz) else 0.0


def corners(faces: list[Face]) -> tuple[NDArray[np.int_], NDArray[np.int_], NDArray[np.int_], NDArray[np.int_]]:
    """Every face corner as flat arrays: (face, vertex, next vertex, previous vertex) round its loop."""
    lengths = np.fromiter(map(len, faces), dtype=int, count=len(faces))
    v = np.fromiter(chain.from_iterable(faces), dtype=int, count=int(lengths.sum()))
    group = np.repeat(np.arange(len(faces)), lengths)
    starts = np.cumsum(lengths) - lengths
    pos = np.arange(len(v)) - starts[group]
    nxt = starts[group] + (pos + 1) % lengths[group]
    prv = starts[group] + (pos - 1) % lengths[group]
    return group, v, v[nxt], v[prv]


def signed_areas(xy: NDArray[np.float64], faces: list[Face]) -> NDArray[np.float64]:
    """Signed areas (n_faces,) of face loops in the plane (> 0 counter-clockwise)."""
    f_of, v, nxt, _ = corners(faces)
    cross = xy[v, 0] * xy[nxt, 1] - xy[nxt, 0] * xy[v, 1]
    return 0.5 * np.bincount(f_of, weights=cross, minlength=len(faces))


def corner_angles(xy: NDArray[np.float64], faces: list[Face]) -> tuple[NDArray[np.int_], NDArray[np.float64]]:
    """(vertex, interior angle rad in [0, 2 pi)) of every corner of counter-clockwise face loops."""
    _, v, nxt, prv = corners(faces)
    to_next, to_prev = xy[nxt] - xy[v], xy[prv] - xy[v]
    cross = to_next[:, 0] * to_prev[:, 1] - to_next[:, 1] * to_prev[:, 0]
    return v, np.mod(np.arctan2(cross, np.sum(to_next * to_prev, axis=-1)), 2 * np.pi)


def plane_fit(xyz: NDArray[np.float64]) -> tuple[NDArray[np.float64], float, float]:
    """
    The points' best plane by SVD: (rotation (3, 3) carrying its normal to +z, largest and rms distance off it).
    The normal is taken with z > 0 (else y > 0, else x > 0) and the rotation is the smallest one, so a sheet
    near the XY plane keeps its x and y.
    """
    centred = xyz - xyz.mean(axis=0)
    _, _, vt = np.linalg.svd(centred, full_matrices=False)
    normal = vt[-1] if len(vt) == 3 else np.array([0.0, 0.0, 1.0])
    for axis in (2, 1, 0):
        if abs(normal[axis]) > 1e-9:
            normal = normal * np.sign(normal[axis])
            break
    off = centred @ normal
    rotation = minimal_rotation(normal, np.array([0.0, 0.0, 1.0])) if normal[2] > -1.0 + 1e-12 else -np.eye(3)
    return rotation, float(np.max(np.abs(off))), float(np.sqrt(np.mean(off**2)))


def planar_faces(xy: NDArray[np.float64], edges: list[tuple[int, int]]) -> list[Face]:
    """
    The bounded faces of a planar straight-line graph, counter-clockwise: edges sorted by angle round each vertex,
    each face traced by turning to the next edge clockwise from the one it came in on; each component's outer
    face (clockwise) is dropped.
    """
    if not edges:
        raise ParameterError("edges_vertices is empty; faces cannot be built without edges")
    ends = np.asarray(edges, dtype=int)
    src = np.concatenate([ends[:, 0], ends[:, 1]])  # half-edge h < m runs a -> b, h + m runs b -> a
    dst = np.concatenate([ends[:, 1], ends[:, 0]])
    m = len(edges)
    d = xy[dst] - xy[src]
    order = np.lexsort((np.arctan2(d[:, 1], d[:, 0]), src))  # half-edges grouped by source, by angle
    first = np.searchsorted(src[order], src[order], side="left")
    count = np.bincount(src, minlength=len(xy))[src[order]]
    rank = np.empty(2 * m, dtype=int)
    rank[order] = np.arange(2 * m)
    twin = np.concatenate([np.arange(m, 2 * m), np.arange(m)])
    # next(u -> v) = v -> w, w the neighbour of v just clockwise of u
    t = rank[twin]
    pos = t - first[t]
    nxt = order[first[t] + (pos - 1) % count[t]]
    seen = np.zeros(2 * m, dtype=bool)
    loops = []
    nxt_list, src_list = nxt.tolist(), src.tolist()
    for h0 in range(2 * m):
        if seen[h0]:
            continue
        loop, h = [], h0
        while not seen[h]:
            seen[h] = True
            loop.append(src_list[h])
            h = nxt_list[h]
        loops.append(tuple(loop))
    faces = []
    for face, area in zip(loops, signed_areas(xy, loops), strict=True):
        if area <= 0.0:
            continue  # an outer face (or a dangling edge's sliver)
        if len(set(face)) != len(face):
            v = next(v for v in face if face.count(v) > 1)
            raise ParameterError(
                f"building faces from edges_vertices: the face round vertex {v} passes it twice (a dangling edge or "
                "an edge that crosses another without a vertex); give faces_vertices or fix the edge graph"
            )
        faces.append(face)
    if not faces:
        raise ParameterError("edges_vertices encloses no face; a crease pattern needs at least one face")
    return faces


def faces_from_edges(faces_edges: list[tuple[int, ...]], edges: list[tuple[int, int]]) -> list[Face]:
    """faces_vertices from FOLD faces_edges (edge i of a face runs from its vertex i to vertex i + 1)."""
    out = []
    for f, loop in enumerate(faces_edges):
        if len(loop) < 3:
            raise ParameterError(f"faces_edges[{f}] = {list(loop)}; a face has 3 or more edges")
        face = []
        for i, k in enumerate(loop):
            shared = set(edges[loop[i - 1]]) & set(edges[k])
            if len(shared) != 1:
                raise ParameterError(
                    f"faces_edges[{f}]: edges {loop[i - 1]} and {k} share {len(shared)} vertices; consecutive "
                    "edges of a face share one"
                )
            face.append(shared.pop())
        out.append(tuple(face))
    return out


def side_faces(faces: list[Face]) -> dict[tuple[int, int], list[tuple[int, tuple[int, int]]]]:
    """Undirected face side -> [(face, directed side)], for every face."""
    out: dict[tuple[int, int], list[tuple[int, tuple[int, int]]]] = {}
    for f, face in enumerate(faces):
        for a, b in sides(face):
            out.setdefault(key(a, b), []).append((f, (a, b)))
    return out


def orient(faces: list[Face], by_side: dict | None = None) -> list[Face]:
    """
    Faces reversed where needed so that each shared side runs opposite ways in its two faces (one normal for the
    whole sheet); each connected piece keeps its first face's loop. ParameterError for a side in three faces or
    a sheet that cannot be oriented.
    """
    by_side = side_faces(faces) if by_side is None else by_side
    for (a, b), users in by_side.items():
        if len(users) > 2:
            raise ParameterError(f"faces {[f for f, _ in users]} all have side {a}-{b}; a side borders 1 or 2 faces")
    flip = [None] * len(faces)
    for start in range(len(faces)):
        if flip[start] is not None:
            continue
        flip[start] = False
        queue = deque([start])
        while queue:
            f = queue.popleft()
            for a, b in sides(faces[f]):
                for g, (c, _) in by_side[key(a, b)]:
                    if g == f:
                        continue
                    # g keeps its loop when it runs this side b -> a while f (as oriented) runs it a -> b
                    want = (c == a) != flip[f]
                    if flip[g] is None:
                        flip[g] = want
                        queue.append(g)
                    elif flip[g] != want:
                        raise ParameterError(
                            f"faces {f} and {g} cannot be given one normal (the sheet is not orientable round side "
                            f"{a}-{b}); FOLD faces must form an orientable surface"
                        )
    return [reverse(face) if flipped else face for face, flipped in zip(faces, flip, strict=True)]


def reverse(face: Face) -> Face:
    """The loop run the other way, keeping its first vertex."""
    return (face[0], *face[:0:-1])


def split_cuts(
    n_vertices: int, faces: list[Face], cuts: set[tuple[int, int]]
) -> tuple[list[Face], NDArray[np.int_], dict[tuple[int, int], int]]:
    """
    Cuts split the paper: at each vertex the faces round it are grouped by the uncut sides they share, and each
    group after the first gets its own copy of the vertex. Returns the faces on the new vertices, the file vertex
    of each new vertex, and the map (face, file vertex) -> new vertex.
    """
    parent: dict[tuple[int, int], tuple[int, int]] = {}

    def find(x: tuple[int, int]) -> tuple[int, int]:
        while parent.setdefault(x, x) != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for edge, users in side_faces(faces).items():
        if len(users) == 2 and edge not in cuts:
            (f, _), (g, _) = users
            for v in edge:
                parent[find((f, v))] = find((g, v))
    new_of: dict[tuple[int, int], int] = {}
    source = list(range(n_vertices))
    root_id: dict[tuple[int, int], int] = {}
    used: set[int] = set()
    for f, face in enumerate(faces):
        for v in face:
            root = find((f, v))
            if root not in root_id:
                if v in used:
                    root_id[root] = len(source)
                    source.append(v)
                else:
                    root_id[root] = v
                    used.add(v)
            new_of[f, v] = root_id[root]
    out = [tuple(new_of[f, v] for v in face) for f, face in enumerate(faces)]
    return out, np.asarray(source, dtype=int), new_of


def merge_joins(faces: list[Face], joins: list[tuple[int, tuple[int, int]]]) -> list[Face]:
    """Joined faces become one polygon: the loops of the two faces on a join edge (k, (a, b)) spliced along it."""
    alive = dict(enumerate(faces))
    owner = {side: f for f, face in alive.items() for side in sides(face)}
    for k, (a, b) in joins:
        f, g = owner.get((a, b)), owner.get((b, a))
        if f is None or g is None:
            raise ParameterError(f"join edge {k} ({a}-{b}) does not have a face on each side; a join merges two faces")
        if f == g:
            raise ParameterError(f"join edge {k} ({a}-{b}) has the same merged face on both sides; joins must not "
                                 "close round a loop or end inside a face")
        lf, lg = alive[f], alive[g]
        i, j = lf.index(b), lg.index(a)
        merged = lf[i:] + lf[:i] + (lg[j:] + lg[:j])[1:-1]  # b ... a, then a's successors in g up to before b
        if len(set(merged)) != len(merged):
            raise ParameterError(f"joining along edge {k} ({a}-{b}) makes a face that passes a vertex twice; "
                                 "joins must leave simple polygons")
        del alive[g]
        alive[f] = merged
        for side in sides(merged):
            owner[side] = f
    return [alive[f] for f in sorted(alive)]


def face_normals(xyz: NDArray[np.float64], faces: list[Face]) -> NDArray[np.float64]:
    """Newell normals (n_faces, 3) of face loops in 3-D, not normalised (length = twice the area)."""
    f_of, a, b, _ = corners(faces)
    centre = np.stack([np.bincount(f_of, weights=xyz[a, i], minlength=len(faces)) for i in range(3)], axis=1)
    centre /= np.bincount(f_of, minlength=len(faces))[:, None]
    cross = np.cross(xyz[a] - centre[f_of], xyz[b] - centre[f_of])
    return np.stack([np.bincount(f_of, weights=cross[:, i], minlength=len(faces)) for i in range(3)], axis=1)


def dihedral_angles(
    xyz: NDArray[np.float64],
    faces: list[Face],
    hinges: list[tuple[int, int, int, int]],
    signs: NDArray[np.float64],
    what: str,
) -> NDArray[np.float64]:
    """
    Fold angles (n,) rad of hinges (start, end, left face, right face) in 3-D coordinates `xyz`: the rotation
    about start -> end of the left face's normal from the right face's; faces are loops whose normals are the
    sheet's +z. Angles within FLAT_FOLD_TOL of +-pi take the sign of `signs` (+1 valley, -1 mountain, 0 free).
    """
    if not hinges:
        return np.zeros(0)
    normals = face_normals(xyz, faces)
    scale = size(xyz) ** 2
    length = np.linalg.norm(normals, axis=1)
    flat = np.flatnonzero(length <= 1e-12 * scale)
    if flat.size:
        raise ParameterError(f"{what}: face {flat[0]} has no area in 3-D, so it has no normal to measure folds by")
    n = normals / length[:, None]
    h = np.asarray(hinges, dtype=int)
    axis = xyz[h[:, 1]] - xyz[h[:, 0]]
    length = np.linalg.norm(axis, axis=1)
    short = np.flatnonzero(length <= 1e-12 * np.sqrt(scale))
    if short.size:
        raise ParameterError(f"{what}: crease {h[short[0], 0]}-{h[short[0], 1]} has no length in 3-D, so no axis")
    axis /= length[:, None]
    left, right = n[h[:, 2]], n[h[:, 3]]
    rho = np.arctan2(np.einsum("ij,ij->i", np.cross(right, left), axis), np.einsum("ij,ij->i", right, left))
    near = np.pi - np.abs(rho) <= FLAT_FOLD_TOL
    return np.where(near & (signs != 0), np.pi * np.sign(signs), rho)


def unfold(xyz: NDArray[np.float64], faces: list[Face]) -> tuple[NDArray[np.float64], list[str]]:
    """
    The flat sheet (n, 2) of a folded form: faces (oriented) placed breadth-first across shared sides, each by its
    own edge lengths and angles, counter-clockwise; separate pieces are laid side by side. ParameterError when a
    vertex placed by two faces lands at two points more than DEVELOP_RTOL of the size apart (not developable: project
    the form with `nearest_developable` first).
    """
    scale = size(xyz)
    tol = DEVELOP_RTOL * scale
    xy = np.full((len(xyz), 2), np.nan)
    by_side = {side: f for f, face in enumerate(faces) for side in sides(face)}
    normals = face_normals(xyz, faces)
    done = np.zeros(len(faces), dtype=bool)
    worst, notes, pieces = 0.0, [], 0
    for start in range(len(faces)):
        if done[start]:
            continue
        pieces += 1
        a, b = faces[start][0], faces[start][1]
        offset = 0.0 if pieces == 1 else float(np.nanmax(xy[:, 0])) + 0.1 * scale
        base = np.array([offset, 0.0])
        anchor = (a, b, base, base + np.array([np.linalg.norm(xyz[b] - xyz[a]), 0.0]))
        queue = deque([(start, anchor)])
        done[start] = True
        while queue:
            f, (a, b, pa, pb) = queue.popleft()
            n = normals[f]
            if np.linalg.norm(n) <= 1e-12 * scale**2:
                raise ParameterError(f"vertices_coords: face {f} has no area in 3-D; faces must not be degenerate")
            e1 = xyz[b] - xyz[a]
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(n / np.linalg.norm(n), e1)
            u = (pb - pa) / np.linalg.norm(pb - pa)
            v = np.array([-u[1], u[0]])
            for w in faces[f]:
                local = xyz[w] - xyz[a]
                p = pa + (local @ e1) * u + (local @ e2) * v
                if np.isnan(xy[w, 0]):
                    xy[w] = p
                else:
                    gap = float(np.linalg.norm(p - xy[w]))
                    if gap > tol:
                        raise ParameterError(
                            f"folded form not developable: unfolding places vertex {w} twice, {gap:.3g} apart "
                            f"({gap / scale:.3g} of the sheet's size, more than {tol / scale:.3g}); the faces' edge "
                            "lengths and angles do not fit one flat sheet (panels bent or stretched)"
                        )
                    worst = max(worst, gap)
            for c, d in sides(faces[f]):
                g = by_side.get((d, c))
                if g is not None and not done[g]:
                    done[g] = True
                    queue.append((g, (d, c, xy[d].copy(), xy[c].copy())))
    notes.append(
        f"unfolded the 3-D folded form into the plane across {len(faces)} faces ({pieces} piece(s)); vertices "
        f"placed twice agree to {worst / scale:.2g} of the sheet's size (allowed {DEVELOP_RTOL:.2g})"
    )
    return xy, notes


# -- the nearest rigid folded form -------------------------------------------------------------------------------

# Projections with at most this many coordinates solve each Gauss-Newton step densely (least norm by SVD); larger
# ones by the sparse normal equations, damped by this fraction of their mean diagonal (a 10 x 10 Miura sheet's motion
# fit, 1815 coordinates: 21 s by SVD).
DENSE_COORDS = 600
NORMAL_DAMPING = 1e-12
NORMAL_REFINE = 4
# The least largest move is sought where the least-norm point moves a value by more than its precision and at most
# this many times it: far beyond, the verdict is the same and the tangent's programme is only rounding.
REFINE_UP_TO = 10.0


@dataclass(frozen=True)
class Fit:
    """
    A folded form (`given`, (n, 3) file units) and the nearest rigid one (`xyz`): planar faces, and sector angles
    closing to 2 pi round every interior vertex, or faces congruent to a crease pattern's (`RigidConditions`).
    `precision` (n, 3) is each coordinate's, the projection's unit; `residual` the conditions' largest residual left
    (file units); `conditions` says what was imposed, in words.
    """

    given: NDArray[np.float64]
    xyz: NDArray[np.float64]
    precision: NDArray[np.float64]
    residual: float
    conditions: str

    @property
    def moved(self) -> NDArray[np.float64]:
        """Each coordinate's move (n, 3), file units."""
        return self.xyz - self.given

    @property
    def ratio(self) -> float:
        """The largest move of a coordinate over its precision (<= 1: the form is rigid within its printing)."""
        return float(np.max(np.abs(self.moved) / self.precision, initial=0.0))

    @property
    def distance(self) -> float:
        """The largest distance (file units) a vertex moved."""
        return float(np.max(np.linalg.norm(self.moved, axis=1), initial=0.0))

    @property
    def vertex(self) -> int:
        """The vertex (row of `given`) that moved the most."""
        return int(np.argmax(np.linalg.norm(self.moved, axis=1)))


class Conditions(Protocol):
    """Exact conditions on values x: zero residuals where they hold, their sparse Jacobian, and what they are."""

    def residual(self, x: NDArray[np.float64]) -> NDArray[np.float64]: ...

    def jacobian(self, x: NDArray[np.float64]) -> sp.csr_matrix: ...

    def describe(self) -> str: ...


class RigidConditions:
    """
    Conditions (in file units) on a folded form's coordinates (n, 3) that hold exactly when it is a rigid folded
    state: each face planar (the distance of its vertices from the plane of its widest corner triangle), and either
    the sector angles round each interior vertex summing to 2 pi (developable; the defect times the vertex's mean
    edge length) or, given `bars` with their `rest` lengths, those lengths kept (faces congruent to a crease
    pattern's). With `flat_foldable`, each interior vertex of four corners also keeps two opposite sector angles
    summing to pi (Kawasaki's condition, the defect times the mean edge length). `residual` and the sparse
    `jacobian` (m, 3n).
    """

    def __init__(
        self,
        xyz: NDArray[np.float64],
        faces: list[Face],
        bars: NDArray[np.int_] | None = None,
        rest: NDArray[np.float64] | None = None,
        flat_foldable: bool = False,
    ):
        self.n = len(xyz)
        count: dict[tuple[int, int], int] = {}
        for face in faces:
            for a, b in sides(face):
                count[key(a, b)] = count.get(key(a, b), 0) + 1
        border = {v for (a, b), k in count.items() if k == 1 for v in (a, b)}
        _, v, nxt, prv = corners(faces)
        self.interior = np.array(sorted(set(v.tolist()) - border), dtype=int) if bars is None else np.zeros(0, int)
        at = np.full(self.n, -1)
        at[self.interior] = np.arange(len(self.interior))
        keep = at[v] >= 0
        self.corner = (v[keep], nxt[keep], prv[keep])
        # sector rows: row k sums the angles of corners `sector_corner` (entries of row `sector_row`) to `total[k]`
        self.sector_row, self.sector_corner = at[v[keep]], np.arange(int(np.sum(keep)))
        self.total = np.full(len(self.interior), 2 * np.pi)
        if flat_foldable:
            rows, picked = _kawasaki_rows(*self.corner, self.sector_row, len(self.interior))
            self.sector_row = np.concatenate([self.sector_row, rows + len(self.interior)])
            self.sector_corner = np.concatenate([self.sector_corner, picked])
            self.total = np.concatenate([self.total, np.full(int(rows.max(initial=-1)) + 1, np.pi)])
        self.n_sectors = len(self.total)
        lengths = np.linalg.norm(xyz[nxt[keep]] - xyz[v[keep]], axis=1)[self.sector_corner]
        self.edge = np.bincount(self.sector_row, weights=lengths, minlength=self.n_sectors).astype(float)
        self.edge /= np.maximum(np.bincount(self.sector_row, minlength=self.n_sectors), 1)
        planes, areas = [np.zeros((0, 4), dtype=int)], [np.zeros(0)]
        for k in sorted({len(face) for face in faces} - {3}):  # faces of each size at once (a 50 x 50 sheet: 2500)
            loops = np.array([face for face in faces if len(face) == k], dtype=int)
            triples = np.array(list(combinations(range(k), 3)))
            p = xyz[loops]
            spans = p[:, triples[:, 1]] - p[:, triples[:, 0]], p[:, triples[:, 2]] - p[:, triples[:, 0]]
            area = np.linalg.norm(np.cross(*spans), axis=-1)
            best = np.argmax(area, axis=1)
            for d in range(k):  # each other vertex against the plane of its face's widest corner triangle
                other = np.all(triples[best] != d, axis=1)
                ijk = loops[np.arange(len(loops))[:, None], triples[best]][other]
                planes.append(np.column_stack([ijk, loops[other, d]]))
                areas.append(area[np.arange(len(loops)), best][other])
        self.planes, self.plane_area = np.concatenate(planes), np.concatenate(areas)
        self.bars = np.zeros((0, 2), dtype=int) if bars is None else np.asarray(bars, dtype=int)
        self.rest = np.zeros(0) if rest is None else np.asarray(rest, dtype=float)

    @property
    def size(self) -> int:
        """How many conditions."""
        return self.n_sectors + len(self.planes) + len(self.bars)

    def describe(self) -> str:
        """What is imposed, counted."""
        parts = [f"{len(self.interior)} vertex angle sums"] if len(self.interior) else []
        kawasaki = self.n_sectors - len(self.interior)
        parts += [f"{kawasaki} opposite-sector sums (flat-foldable vertices)"] if kawasaki else []
        parts += [f"{len(self.planes)} face planarities"] if len(self.planes) else []
        parts += [f"{len(self.bars)} face lengths"] if len(self.bars) else []
        return ", ".join(parts) or "none"

    def _corner_angles(self, x: NDArray[np.float64]) -> tuple[NDArray, ...]:
        v, nxt, prv = self.corner
        u, w = x[nxt] - x[v], x[prv] - x[v]
        lu, lw = np.linalg.norm(u, axis=1), np.linalg.norm(w, axis=1)
        uh, wh = u / lu[:, None], w / lw[:, None]
        c, s = np.einsum("ij,ij->i", uh, wh), np.linalg.norm(np.cross(uh, wh), axis=1)
        return np.arctan2(s, c), uh, wh, lu, lw, c, s

    def _plane(self, x: NDArray[np.float64]) -> tuple[NDArray, ...]:
        a, b, c, d = self.planes.T
        e1, e2, e3 = x[b] - x[a], x[c] - x[a], x[d] - x[a]
        return e1, e2, e3

    def residual(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """The conditions' residuals (m,) at coordinates x (n, 3), file units."""
        theta = self._corner_angles(x)[0][self.sector_corner]
        defect = self.total - np.bincount(self.sector_row, weights=theta, minlength=self.n_sectors)
        e1, e2, e3 = self._plane(x)
        planar = np.einsum("ij,ij->i", np.cross(e1, e2), e3) / self.plane_area
        stretch = np.linalg.norm(x[self.bars[:, 0]] - x[self.bars[:, 1]], axis=1) - self.rest
        return np.concatenate([defect * self.edge, planar, stretch])

    def jacobian(self, x: NDArray[np.float64]) -> sp.csr_matrix:
        """The residuals' derivatives (m, 3n) with respect to the coordinates, flattened vertex by vertex."""
        rows, cols, vals = [], [], []

        def add(row: NDArray, vertex: NDArray, grad: NDArray) -> None:
            rows.append(np.repeat(row, 3))
            cols.append((3 * vertex[:, None] + np.arange(3)).ravel())
            vals.append(grad.ravel())

        _, uh, wh, lu, lw, c, s = (part[self.sector_corner] for part in self._corner_angles(x))
        v, nxt, prv = (part[self.sector_corner] for part in self.corner)
        scale = self.edge[self.sector_row][:, None] / s[:, None]
        d_u = (c[:, None] * uh - wh) / lu[:, None] * scale  # d theta / d u times the row's scale
        d_w = (c[:, None] * wh - uh) / lw[:, None] * scale
        add(self.sector_row, nxt, -d_u)
        add(self.sector_row, prv, -d_w)
        add(self.sector_row, v, d_u + d_w)
        e1, e2, e3 = self._plane(x)
        row = self.n_sectors + np.arange(len(self.planes))
        a, b, cc, d = self.planes.T
        g1, g2, g3 = (np.cross(e2, e3), np.cross(e3, e1), np.cross(e1, e2))
        area = self.plane_area[:, None]
        for vertex, grad in ((b, g1), (cc, g2), (d, g3), (a, -(g1 + g2 + g3))):
            add(row, vertex, grad / area)
        row = self.n_sectors + len(self.planes) + np.arange(len(self.bars))
        along = x[self.bars[:, 0]] - x[self.bars[:, 1]]
        along /= np.linalg.norm(along, axis=1)[:, None]
        add(row, self.bars[:, 0], along)
        add(row, self.bars[:, 1], -along)
        shape = (self.size, 3 * self.n)
        if not rows:
            return sp.csr_matrix(shape)
        return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=shape)


def _kawasaki_rows(v: NDArray[np.int_], nxt: NDArray[np.int_], prv: NDArray[np.int_], row: NDArray[np.int_],
                   n_rows: int) -> tuple[NDArray[np.int_], NDArray[np.int_]]:
    """For each vertex row with four corners (entries of `v`, `nxt`, `prv` by `row`), a Kawasaki row: (row, corner)
    entries of its first corner and the one opposite it (sharing no edge with it), rows numbered from 0."""
    order = np.argsort(row, kind="stable")
    counts = np.bincount(row, minlength=n_rows)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    four = starts[counts == 4]
    quad = order[four[:, None] + np.arange(4)]  # (m, 4) corners of each four-corner vertex
    first = quad[:, 0]
    disjoint = np.column_stack([(nxt[quad[:, j]] != nxt[first]) & (nxt[quad[:, j]] != prv[first])
                                & (prv[quad[:, j]] != nxt[first]) & (prv[quad[:, j]] != prv[first])
                                for j in (1, 2, 3)])
    ok = disjoint.sum(axis=1) == 1
    opposite = quad[ok][np.arange(int(ok.sum())), 1 + np.argmax(disjoint[ok], axis=1)]
    rows = np.repeat(np.arange(int(ok.sum())), 2)
    return rows, np.column_stack([first[ok], opposite]).ravel()


def nearest_rigid(
    xyz: NDArray[np.float64], precision: NDArray[np.float64], conditions: Conditions, bounded: int | None = None,
    tol: float | None = None,
) -> Fit:
    """
    The rigid folded form nearest `xyz` (n, 3), or any values (n,), in units of each one's `precision` (same shape
    and unit): least-norm Gauss-Newton in z = (x - xyz) / precision (`precision.nearest_exact`, with the conditions'
    analytic sparse Jacobian), from the values as given, until the conditions hold to `tol` (default RIGID_RTOL of
    the size). Where that point moves one of the first `bounded` rows (default all) by more than its precision, the
    point of the conditions with the least largest such move is taken (`_least_largest`): the values lie within their
    precision of an exact state when it is within it. The best iterate (smallest residual) is returned; the caller
    judges a residual left.
    """
    scale = size(xyz.reshape(len(xyz), -1))
    tol = RIGID_RTOL * scale if tol is None else tol
    closed, last = CLOSED_RTOL * scale, np.inf
    x0, w = xyz.ravel(), precision.ravel()
    limit = np.zeros(len(x0), dtype=bool)
    limit[: (len(x0) if bounded is None else bounded * int(np.prod(xyz.shape[1:])))] = True
    z = np.zeros_like(x0)
    best_x, best_r, refined = xyz, np.inf, False
    for _ in range(RIGID_STEPS):
        x = (x0 + z * w).reshape(xyz.shape)
        r = conditions.residual(x)
        worst = float(np.max(np.abs(r), initial=0.0))
        if not np.isfinite(worst):  # a face or crease collapsed on the way: the best so far stands
            break
        if worst < best_r:
            best_x, best_r = x, worst
        # kept when exact as given; once moved, closed to CLOSED_RTOL or to its rounding floor within `tol`
        done = worst <= tol if not np.any(z) else worst <= closed or (worst <= tol and worst > 0.5 * last)
        last = worst
        largest = np.max(np.abs(z[limit]), initial=0.0)
        if done and (refined or not 1.0 < largest <= REFINE_UP_TO):
            break
        J = conditions.jacobian(x) @ sp.diags(w)
        if done:  # the least-norm point moves a value beyond its precision: the least largest move, closed again
            z, refined, best_r, last = _least_largest(J, z, limit), True, np.inf, np.inf
        else:
            z = z + _least_norm(J, -r) if refined else _least_norm(J, J @ z - r)
    return Fit(xyz, best_x, precision, best_r, conditions.describe())


def _least_norm(J: sp.csr_matrix, rhs: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    The least-norm solution of J z = rhs (J (m, k)): by SVD up to DENSE_COORDS columns; beyond, from the sparse
    normal equations J J^T y = rhs, z = J^T y, regularised by NORMAL_DAMPING of their mean diagonal (dependent
    conditions, as a root face fixed by all its vertices, make them singular) and refined NORMAL_REFINE times on the
    residual left, which the damping alone left too large for a 10 x 10 Miura sheet's motion fit to converge.
    """
    if J.shape[1] <= DENSE_COORDS:
        return np.linalg.lstsq(J.toarray(), rhs, rcond=None)[0]
    normal = (J @ J.T).tocsc()
    damping = NORMAL_DAMPING * normal.diagonal().mean()
    solve = splu(normal + damping * sp.identity(normal.shape[0], format="csc")).solve
    z = np.zeros(J.shape[1])
    for _ in range(NORMAL_REFINE):
        z = z + J.T @ solve(rhs - J @ z)
    return z


def _least_largest(J: sp.csr_matrix, z: NDArray[np.float64], limit: NDArray[np.bool_]) -> NDArray[np.float64]:
    """
    The point on the conditions' tangent at z (J (m, k)) whose largest |entry| among `limit` is least: a linear
    programme, minimise t with |entry| <= t there. The least-norm point need not be it: a degree-4 vertex's four
    angles printed to 2 decimals moved one by 1.03 of its precision, and a 16 x 16 Miura sheet printed to 4 decimals,
    held flat-foldable, by 1.15, where the states they round are within it. Up to DENSE_COORDS in the tangent's null
    space (z + N y, N by SVD: robust where the columns' scales differ by 1e6, as a motion fit's free states make
    them); beyond, in z' itself with J z' = J z as sparse equalities.
    """
    if J.shape[1] <= DENSE_COORDS:
        _, sigma, vt = np.linalg.svd(J.toarray())
        rank = int(np.sum(sigma > sigma[0] * 1e-10)) if len(sigma) else 0
        basis = vt[rank:].T
        if not basis.shape[1]:
            return z
        y = _minimax(sp.csr_matrix(basis[limit]), z[limit], None, None)
        return z if y is None else z + basis @ y
    rows = np.flatnonzero(limit)
    pick = sp.csr_matrix((np.ones(len(rows)), (np.arange(len(rows)), rows)), shape=(len(rows), J.shape[1]))
    found = _minimax(pick, np.zeros(len(rows)), J, J @ z)
    return z if found is None else found


def _minimax(A: sp.csr_matrix, c: NDArray[np.float64], a_eq: sp.csr_matrix | None,
             b_eq: NDArray[np.float64] | None) -> NDArray[np.float64] | None:
    """argmin over y of max |c + A y| (with a_eq y = b_eq, if given) by HiGHS; None when it finds none."""
    k = A.shape[1]
    minus = -np.ones((A.shape[0], 1))
    a_ub = sp.vstack([sp.hstack([A, minus]), sp.hstack([-A, minus])]).tocsr()
    eq = None if a_eq is None else sp.hstack([a_eq, sp.csr_matrix((a_eq.shape[0], 1))]).tocsr()
    cost = np.zeros(k + 1)
    cost[-1] = 1.0
    found = linprog(cost, A_ub=a_ub, b_ub=np.concatenate([-c, c]), A_eq=eq, b_eq=b_eq,
                    bounds=[(None, None)] * k + [(0, None)], method="highs")
    return found.x[:k] if found.success else None


def nearest_developable(xyz: NDArray[np.float64], faces: list[Face], precision: NDArray[np.float64]) -> Fit:
    """The developable folded form nearest `xyz` (planar faces, 2 pi round every interior vertex): `nearest_rigid`."""
    return nearest_rigid(xyz, precision, RigidConditions(xyz, faces))


def face_bars(faces: list[Face]) -> NDArray[np.int_]:
    """Vertex pairs (b, 2) whose lengths fix every face's shape with its planarity: its sides and the diagonals
    from its first vertex (shared sides once)."""
    pairs = {key(a, b) for face in faces for a, b in sides(face)}
    pairs |= {key(face[0], face[j]) for face in faces for j in range(2, len(face) - 1)}
    return np.array(sorted(pairs), dtype=int).reshape(-1, 2)


class MotionConditions:
    """
    The conditions for a folded form X0 (n, 3) to lie on a rigid motion of its own crease pattern, for patterns
    whose loops leave them no freedom unless their geometry is special (a Miura or square-twist sheet: as many
    closure conditions as creases). X0 developable (`RigidConditions`), and K more folded states X1..XK of the same
    faces: each face congruent to X0's (its sides and fan diagonals as long, and planar), the `gauge` vertices (one
    face's) where X0's are (the rigid placement fixed) and the distance between two vertices across a crease held
    (where the state lies along the motion). Coordinates stacked ((K + 1) n, 3); `residual`, `jacobian` as
    `RigidConditions`.
    """

    def __init__(
        self,
        xyz: NDArray[np.float64],
        faces: list[Face],
        states: list[NDArray[np.float64]],
        gauge: Face,
        marker: tuple[int, int],
    ):
        self.n, self.k = len(xyz), len(states)
        self.base = RigidConditions(xyz, faces)
        self.shape = RigidConditions(xyz, faces, np.zeros((0, 2), dtype=int), np.zeros(0))  # planarity only
        self.bars = face_bars(faces)
        self.gauge = np.array(gauge, dtype=int)
        self.marker = np.array(marker, dtype=int)
        self.reach = np.array([np.linalg.norm(x[marker[0]] - x[marker[1]]) for x in states])

    @property
    def per_state(self) -> int:
        """Conditions on each further state."""
        return self.shape.size + len(self.bars) + 3 * len(self.gauge) + 1

    @property
    def size(self) -> int:
        """How many conditions."""
        return self.base.size + self.k * self.per_state

    def describe(self) -> str:
        """What is imposed, counted."""
        return (f"{self.base.describe()}, and {self.k} further states of the same faces along one rigid motion "
                f"({len(self.bars)} face lengths and {self.shape.size} face planarities each)")

    def residual(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """The residuals (m,) at stacked coordinates x ((K + 1) n, 3), file units."""
        x0, out = x[: self.n], [self.base.residual(x[: self.n])]
        length0 = np.linalg.norm(x0[self.bars[:, 0]] - x0[self.bars[:, 1]], axis=1)
        for k in range(self.k):
            xk = x[(k + 1) * self.n : (k + 2) * self.n]
            lengths = np.linalg.norm(xk[self.bars[:, 0]] - xk[self.bars[:, 1]], axis=1)
            out += [self.shape.residual(xk), lengths - length0, (xk[self.gauge] - x0[self.gauge]).ravel(),
                    [np.linalg.norm(xk[self.marker[0]] - xk[self.marker[1]]) - self.reach[k]]]
        return np.concatenate(out)

    def jacobian(self, x: NDArray[np.float64]) -> sp.csr_matrix:
        """The residuals' derivatives (m, 3 (K + 1) n), coordinates flattened vertex by vertex, state by state."""
        n3, x0 = 3 * self.n, x[: self.n]
        m = 3 * len(self.gauge)
        pick = sp.csr_matrix((np.ones(m), (np.arange(m), (3 * self.gauge[:, None] + np.arange(3)).ravel())),
                             shape=(m, n3))
        blocks = [[self.base.jacobian(x0)] + [None] * self.k]
        for k in range(self.k):
            xk = x[(k + 1) * self.n : (k + 2) * self.n]
            row: list = [None] * (self.k + 1)
            bars_k, bars_0 = _bar_jacobian(xk, self.bars, self.n), _bar_jacobian(x0, self.bars, self.n)
            mark = _bar_jacobian(xk, self.marker[None], self.n)
            row[0] = sp.vstack([sp.csr_matrix((self.shape.size, n3)), -bars_0, -pick, sp.csr_matrix((1, n3))])
            row[k + 1] = sp.vstack([self.shape.jacobian(xk), bars_k, pick, mark])
            blocks.append(row)
        return sp.bmat(blocks, format="csr")


def _bar_jacobian(x: NDArray[np.float64], bars: NDArray[np.int_], n: int) -> sp.csr_matrix:
    """Derivatives (b, 3n) of the bars' lengths |x_a - x_b| with respect to the coordinates x (n, 3)."""
    along = x[bars[:, 0]] - x[bars[:, 1]]
    along /= np.linalg.norm(along, axis=1)[:, None]
    rows = np.repeat(np.arange(len(bars)), 6)
    cols = np.concatenate([3 * bars[:, :1] + np.arange(3), 3 * bars[:, 1:] + np.arange(3)], axis=1).ravel()
    return sp.csr_matrix((np.concatenate([along, -along], axis=1).ravel(), (rows, cols)), shape=(len(bars), 3 * n))


def place(
    xy: NDArray[np.float64], faces: list[Face], hinges: list[tuple[int, int, int, int]], rho: NDArray[np.float64],
    root: int,
) -> NDArray[np.float64]:
    """
    The sheet `xy` (n, 2) folded by fold angles `rho` (per hinge (start, end, left face, right face), rad, as
    `dihedral_angles` measures them), its faces placed breadth-first from `root` (left in the plane): (n, 3), each
    vertex where the first face placed puts it (where the angles do not close the loops, other faces disagree).
    """
    pose = {root: (np.eye(3), np.zeros(3))}
    flat = np.column_stack([xy, np.zeros(len(xy))])
    by_face: dict[int, list[tuple[int, int, float]]] = {}
    for (a, b, left, right), angle in zip(hinges, rho, strict=True):
        by_face.setdefault(right, []).append((left, a, b, angle))
        by_face.setdefault(left, []).append((right, b, a, angle))
    queue = deque([root])
    while queue:
        f = queue.popleft()
        R, t = pose[f]
        for g, a, b, angle in by_face.get(f, []):
            if g in pose:
                continue
            turn = rotation((flat[b] - flat[a]) / np.linalg.norm(flat[b] - flat[a]), angle)
            R_g = R @ turn
            pose[g] = (R_g, R @ flat[a] + t - R_g @ flat[a])
            queue.append(g)
    out = np.full((len(xy), 3), np.nan)
    for f in pose:
        R, t = pose[f]
        for v in faces[f]:
            if np.isnan(out[v, 0]):
                out[v] = R @ flat[v] + t
    return out


def superpose(a: NDArray[np.float64], b: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The proper rotation R (3, 3) and shift t (3,) that carry points a (k, 3) nearest b (k, 3): R a + t (Kabsch)."""
    ca, cb = a.mean(axis=0), b.mean(axis=0)
    u, _, vt = np.linalg.svd((a - ca).T @ (b - cb))
    d = np.sign(np.linalg.det(vt.T @ u.T))
    rotation = vt.T @ np.diag([1.0, 1.0, d]) @ u.T
    return rotation, cb - rotation @ ca
