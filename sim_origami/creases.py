"""Flat crease patterns and their per-vertex loop closure (numpy only).

Frames. The flat sheet lies in the world XY plane, normal +z, lengths in metres. Faces are
counter-clockwise vertex loops seen from +z. A crease joins two faces along the edge from vertex
`start` to vertex `end`; its hinge is the line through (x_start, y_start, height) along that edge
(height != 0 for thick panels whose hinges sit on a panel surface, Peng 2018, ch. 4).

Signs (`sim_origami.conventions`). The crease angle rho is the right-handed rotation about
start -> end of the face on its left (counter-clockwise side) relative to the face on its right;
flat is 0, rho > 0 is a valley seen from +z. Reversing start and end swaps the two faces and the
axis together, so rho belongs to the crease, not to its orientation: around every vertex it is the
vertex convention's fold angle with d pointing away from the vertex. M/V assignments are recorded
for the reader; the closure does not use them.

Loops. Every interior vertex (faces closing all the way round it) gives one closure,
Rot(line_1, rho_1) ... Rot(line_n, rho_n) = I over its creases in counter-clockwise order; for a
disc-like pattern these generate every loop of the face graph.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from .closure import Coupling, Loop, LoopSystem
from .errors import ParameterError
from .fold_mesh import signed_areas
from .geometry import frame_along, frames_along, invert
from .graph import spanning_edges

# A border cycle walked with the paper on its left whose area is at most this times the pattern's extent squared
# is a hole's (clockwise, or none for an inner slit); a piece's outer border has the piece's area.
HOLE_AREA_RTOL = 1e-12

# M mountain, V valley, U unassigned (free), F flat (a crease present but meant to stay unfolded).
ASSIGNMENTS = ("M", "V", "U", "F")


@dataclass(frozen=True)
class Crease:
    """A hinge between two faces; `assignment` M (mountain), V (valley), U (unassigned) or F (stays flat)."""

    name: str
    start: int
    end: int
    assignment: str = "U"
    height: float = 0.0


@dataclass(frozen=True)
class CreasePattern:
    """
    Vertices (n, 2) m, counter-clockwise faces (vertex indices), creases and face names; `border_heights`
    (start, end, height m) are hinge heights on border edges that are creases of a neighbouring cell (a
    periodic cell's thick panels take their shape from them; they are not joints here).
    """

    vertices: NDArray[np.float64]
    faces: tuple[tuple[int, ...], ...]
    creases: tuple[Crease, ...]
    face_names: tuple[str, ...]
    border_heights: tuple[tuple[int, int, float], ...] = ()

    def __post_init__(self):
        if len(self.face_names) != len(self.faces):
            raise ParameterError(f"{len(self.face_names)} face names for {len(self.faces)} faces")
        for crease in self.creases:
            if crease.assignment not in ASSIGNMENTS:
                raise ParameterError(f"crease {crease.name!r} has assignment {crease.assignment!r}; use M, V, U or F")
            self.crease_faces(crease)

    @cached_property
    def _edge_face(self) -> dict[tuple[int, int], int]:
        """Directed edge (a, b) -> the face that has it in counter-clockwise order (the face on its left)."""
        out = {}
        for f, face in enumerate(self.faces):
            for a, b in zip(face, face[1:] + face[:1], strict=True):
                if (a, b) in out:
                    raise ParameterError(f"faces {self.face_names[out[a, b]]!r} and {self.face_names[f]!r} "
                                         f"both run along edge {a}->{b}: overlapping or clockwise faces")
                out[a, b] = f
        return out

    @cached_property
    def _by_name(self) -> dict[str, Crease]:
        return {c.name: c for c in reversed(self.creases)}

    @cached_property
    def _crease_of_edge(self) -> dict[tuple[int, int], int]:
        """(smaller, larger vertex) -> index of the crease along that edge."""
        return {(min(c.start, c.end), max(c.start, c.end)): k for k, c in enumerate(self.creases)}

    @cached_property
    def _out_edges(self) -> dict[int, list[int]]:
        """Vertex a -> the vertices b of the directed face sides a -> b (each face side indexed once)."""
        out: dict[int, list[int]] = {}
        for a, b in self._edge_face:
            out.setdefault(a, []).append(b)
        return out

    @cached_property
    def _interior(self) -> tuple[int, ...]:
        into: dict[int, set[int]] = {}
        for a, b in self._edge_face:
            into.setdefault(b, set()).add(a)
        return tuple(v for v in range(len(self.vertices))
                     if v in self._out_edges and set(self._out_edges[v]) == into.get(v))

    def crease(self, name: str) -> Crease:
        """The crease called `name`; ParameterError listing the names otherwise."""
        if name in self._by_name:
            return self._by_name[name]
        raise ParameterError(f"unknown crease {name!r}; creases are {[c.name for c in self.creases]}")

    def crease_faces(self, crease: Crease) -> tuple[str, str]:
        """(right face, left face) of a crease: the joint's parent and child."""
        left = self._edge_face.get((crease.start, crease.end))
        right = self._edge_face.get((crease.end, crease.start))
        if left is None or right is None:
            raise ParameterError(
                f"crease {crease.name!r} ({crease.start}->{crease.end}) must join two faces; it borders "
                f"{sum(x is not None for x in (left, right))}"
            )
        return self.face_names[right], self.face_names[left]

    def direction(self, crease: Crease) -> NDArray[np.float64]:
        """Unit direction (3,) of a crease from its start to its end."""
        d = self.vertices[crease.end] - self.vertices[crease.start]
        return np.array([*d, 0.0]) / np.linalg.norm(d)

    def length(self, crease: Crease) -> float:
        """Crease length (m)."""
        return float(np.linalg.norm(self.vertices[crease.end] - self.vertices[crease.start]))

    def hinge_frame(self, crease: Crease) -> NDArray[np.float64]:
        """Frame (4, 4) on the hinge line: origin above `start` at `height`, z along start -> end."""
        x, y = self.vertices[crease.start]
        return frame_along(self.direction(crease), (x, y, crease.height))

    def edge_heights(self, face: int) -> NDArray[np.float64]:
        """Hinge height (m) on each edge of face `face` (edge i from its vertex i to i+1); NaN on a free border."""
        loop = self.faces[face]
        return np.array([self._heights.get(frozenset(e), np.nan) for e in zip(loop, loop[1:] + loop[:1], strict=True)])

    @cached_property
    def _heights(self) -> dict[frozenset, float]:
        known = {frozenset((c.start, c.end)): c.height for c in self.creases}
        return known | {frozenset((a, b)): h for a, b, h in self.border_heights}

    def touching_faces(self) -> tuple[tuple[str, str], ...]:
        """Pairs of faces that share a vertex (so touch in every pose), sorted by face order."""
        at: dict[int, set[int]] = {}
        for f, face in enumerate(self.faces):
            for v in face:
                at.setdefault(v, set()).add(f)
        pairs = {(a, b) for group in at.values() for a in group for b in group if a < b}
        return tuple((self.face_names[a], self.face_names[b]) for a, b in sorted(pairs))

    def spanning_creases(self, prefer: tuple[str, ...] = ()) -> tuple[int, ...]:
        """Indices of creases joining the faces in a spanning tree, Kruskal in crease order with the creases
        named in `prefer` first (as `mechanism.Mechanism.tree` picks a pattern mechanism's hinges)."""
        edges = [self.crease_faces(c) for c in self.creases]
        first = [k for k, c in enumerate(self.creases) if c.name in prefer]
        return tuple(spanning_edges(self.face_names, edges, first))

    def interior_vertices(self) -> tuple[int, ...]:
        """Vertices that faces surround completely; each is a loop of the creases meeting there."""
        return self._interior

    def vertex_creases(self, v: int) -> list[tuple[int, NDArray[np.float64]]]:
        """(crease index, outward unit direction) of the creases at interior vertex v, counter-clockwise."""
        ks, d, _ = self._around((v,))
        return list(zip(ks.tolist(), d, strict=True))

    def _around(self, vertices: tuple[int, ...]) -> tuple[NDArray[np.int_], NDArray[np.float64], NDArray[np.int_]]:
        """
        The creases round each of `vertices`, counter-clockwise, listed vertex after vertex: crease indices,
        outward unit directions (n, 3) and how many round each vertex.
        """
        counts = np.array([len(self._out_edges.get(v, ())) for v in vertices], dtype=int)
        at = np.repeat(np.asarray(vertices, dtype=int), counts)
        ends = np.fromiter((b for v in vertices for b in self._out_edges.get(v, ())), dtype=int, count=len(at))
        ks = [self._crease_of_edge.get((min(a, b), max(a, b))) for a, b in zip(at.tolist(), ends.tolist(), strict=True)]
        if None in ks:
            a, b = at[ks.index(None)], ends[ks.index(None)]
            raise ParameterError(f"edge {a}-{b} at interior vertex {a} joins two faces but is not a crease")
        d = np.zeros((len(at), 3))
        d[:, :2] = self.vertices[ends] - self.vertices[at]
        d /= np.sqrt(d[:, None, :] @ d[:, :, None])[:, 0]  # rounded as np.linalg.norm of each row
        order = np.lexsort((np.arctan2(d[:, 1], d[:, 0]), np.repeat(np.arange(len(vertices)), counts)))
        return np.asarray(ks, dtype=int)[order], d[order], counts

    def hole_loops(self) -> tuple[tuple[tuple[int, ...], NDArray[np.float64], NDArray[np.float64]], ...]:
        """
        The loop of creases round each hole (crease indices, outward unit directions (n, 3) from the hole's
        vertices, those vertices (n, 2)), in the order a walk round the hole through the paper crosses them. A hole
        is a boundary cycle other than a piece's outer one: walked with the paper on its left it turns clockwise
        (area <= 0; an inner slit's cycle has none). Round each of its vertices v the paper spans counter-clockwise
        from the side to the next vertex to the side to the previous one, so the walk goes round the cycle backwards
        and crosses v's creases in that order, from the right of each outward direction to its left, as a vertex's
        loop does.
        """
        nxt: dict[int, list[int]] = {}
        for a, b in self._edge_face:
            if (b, a) not in self._edge_face:
                nxt.setdefault(a, []).append(b)
        if any(len(out) > 1 for out in nxt.values()):
            return ()  # a vertex where the border touches itself: its cycles are not unique (none found so far)
        v = self.vertices
        scale = float(np.max(np.ptp(v, axis=0))) ** 2
        loops, seen = [], set()
        for start in nxt:
            if start in seen:
                continue
            cycle = [start]
            while nxt[cycle[-1]][0] != start:
                if nxt[cycle[-1]][0] not in nxt or len(cycle) > len(nxt):
                    return ()  # a border that does not close (faces not one oriented sheet): no hole to tell
                cycle.append(nxt[cycle[-1]][0])
            seen.update(cycle)
            if float(signed_areas(v, [tuple(cycle)])[0]) > HOLE_AREA_RTOL * scale:
                continue  # a piece's outer border
            ks, dirs, at_v = [], [], []
            for i in range(len(cycle) - 1, -1, -1):
                at, after, before = cycle[i], cycle[(i + 1) % len(cycle)], cycle[i - 1]
                start_angle = self._angle(at, after)
                span = (self._angle(at, before) - start_angle) % (2 * np.pi)
                round_v = []
                for b in self._out_edges.get(at, []):
                    k = self._crease_of_edge.get((min(at, b), max(at, b)))
                    turn = (self._angle(at, b) - start_angle) % (2 * np.pi)
                    if k is not None and 0.0 < turn < span:
                        round_v.append((turn, k, b))
                for _, k, b in sorted(round_v):
                    d = v[b] - v[at]
                    ks.append(k)
                    dirs.append([*(d / np.linalg.norm(d)), 0.0])
                    at_v.append(at)
            if ks:
                loops.append((tuple(ks), np.array(dirs), v[at_v]))
        return tuple(loops)

    def loop_system(self, couplings: tuple[Coupling, ...] = ()) -> LoopSystem:
        """One PoE closure per interior vertex over the crease angles (in `creases` order), then one round each
        hole (`hole_loops`): the ring of paper round a hole closes on itself as the paper round a vertex does."""
        interior = self.interior_vertices()
        holes = self.hole_loops()
        if not interior:
            return LoopSystem(len(self.creases), self._hole_closures(holes), couplings)
        # every hinge frame and link at once (the same numbers as vertex by vertex). A vertex's hinges all pass over
        # it, so its frames are placed relative to it: the links are the same, without the rounding of coordinates far
        # from the origin (a sheet near (700, -300) with 0.067-wide panels closed only to 1.1e-13 from its frames at
        # the vertices' own coordinates; to 1e-16 from there)
        ks, d, lengths = self._around(interior)
        heights = np.array([c.height for c in self.creases])[ks]
        frames = frames_along(d, np.column_stack([np.zeros((len(ks), 2)), heights]))
        group = np.repeat(np.arange(len(interior)), lengths)
        starts = np.cumsum(lengths) - lengths
        nxt = starts[group] + (np.arange(len(ks)) - starts[group] + 1) % lengths[group]
        links = invert(frames) @ frames[nxt]
        ks_list = ks.tolist()
        loops = tuple(
            Loop(tuple(ks_list[s : s + n]), links[s : s + n], (1,) * n) for s, n in zip(starts, lengths, strict=True)
        )
        return LoopSystem(len(self.creases), loops + self._hole_closures(holes), couplings)

    def _angle(self, a: int, b: int) -> float:
        """Direction (rad) of the side from vertex a to vertex b."""
        d = self.vertices[b] - self.vertices[a]
        return float(np.arctan2(d[1], d[0]))

    def _hole_closures(self, holes: tuple) -> tuple[Loop, ...]:
        """The PoE closure of each of `hole_loops`: hinge frames along its creases from the hole's vertices, at
        their heights, linked as a vertex loop's are."""
        out = []
        for ks, d, at in holes:
            heights = np.array([self.creases[k].height for k in ks])
            frames = frames_along(d, np.column_stack([at - at[0], heights]))  # relative to one of its vertices
            links = invert(frames) @ frames[np.r_[1 : len(ks), 0]]
            out.append(Loop(tuple(ks), links, (1,) * len(ks)))
        return tuple(out)
