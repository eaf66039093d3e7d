"""Flat crease patterns and their per-vertex loop closure (numpy only).

Frames. The flat sheet lies in the world XY plane, normal +z, lengths in metres. Faces are
counter-clockwise vertex loops seen from +z. A crease joins two faces along the edge from vertex
`start` to vertex `end`; its hinge is the line through (x_start, y_start, height) along that edge
(height != 0 for thick panels whose hinges sit on a panel surface, seed 003 ch. 4).

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
from .geometry import frame_along, invert
from .graph import spanning_edges

ASSIGNMENTS = ("M", "V", "U", "F")


@dataclass(frozen=True)
class Crease:
    """A hinge between two faces; `assignment` M (mountain), V (valley) or U (unassigned)."""

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
                                         f"both run along edge {a}->{b}: overlapping or clockwise faces")  # fmt: skip
                out[a, b] = f
        return out

    def crease(self, name: str) -> Crease:
        """The crease called `name`; ParameterError listing the names otherwise."""
        for crease in self.creases:
            if crease.name == name:
                return crease
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
        known = {frozenset((c.start, c.end)): c.height for c in self.creases}
        known |= {frozenset((a, b)): h for a, b, h in self.border_heights}
        loop = self.faces[face]
        return np.array([known.get(frozenset(e), np.nan) for e in zip(loop, loop[1:] + loop[:1], strict=True)])

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
        out = []
        for v in range(len(self.vertices)):
            out_edges = {b for (a, b) in self._edge_face if a == v}
            in_edges = {a for (a, b) in self._edge_face if b == v}
            if out_edges and out_edges == in_edges:
                out.append(v)
        return tuple(out)

    def vertex_creases(self, v: int) -> list[tuple[int, NDArray[np.float64]]]:
        """(crease index, outward unit direction) of the creases at interior vertex v, counter-clockwise."""
        by_edge = {frozenset((c.start, c.end)): k for k, c in enumerate(self.creases)}
        out = []
        for (a, b), _ in self._edge_face.items():
            if a != v:
                continue
            k = by_edge.get(frozenset((a, b)))
            if k is None:
                raise ParameterError(f"edge {a}-{b} at interior vertex {v} joins two faces but is not a crease")
            d = self.vertices[b] - self.vertices[a]
            out.append((k, np.array([*d, 0.0]) / np.linalg.norm(d)))
        return sorted(out, key=lambda kd: np.arctan2(kd[1][1], kd[1][0]))

    def loop_system(self, couplings: tuple[Coupling, ...] = ()) -> LoopSystem:
        """One PoE closure per interior vertex over the crease angles (in `creases` order)."""
        loops = []
        for v in self.interior_vertices():
            around = self.vertex_creases(v)
            frames = [frame_along(d, (*self.vertices[v], self.creases[k].height)) for k, d in around]
            n = len(frames)
            links = np.stack([invert(frames[i]) @ frames[(i + 1) % n] for i in range(n)])
            loops.append(Loop(tuple(k for k, _ in around), links, (1,) * n))
        return LoopSystem(len(self.creases), tuple(loops), couplings)
