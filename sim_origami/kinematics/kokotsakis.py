"""Kokotsakis 3x3 meshes of four degree-4 vertices (Peng 2018, §2.3-2.5).

Mesh. A central quadrilateral with corners A, B, C, D in clockwise order seen from +z, one developable
degree-4 vertex (a spherical 4R linkage) at each corner, 9 panels (central, four sides, four corners), 4
inner creases (AB, BC, CD, DA) and 8 outer creases. Each vertex carries Peng 2018's crease numbering 1..4
(sector alpha_k between creases k and k+1); `MeshVertex.previous` is the crease pointing to the previous
corner (A's previous is D) and a mirrored vertex (a mirror image placement, Peng 2018, §2.3) numbers its creases
clockwise. Outer creases are named by vertex and thesis number (``a3``, ``b4``, ...). Layout (reconstructed
here): A = (0, 0), crease A->D along +x, |AB| and |BC| given, D where the line from C meets the x axis;
side panels are quadrilaterals and corner panels triangles bounded by outer creases of length `outer`.

Signs (`sim_origami.creases`): rho is the crease's own fold angle, 0 flat, > 0 a valley seen from +z. It is
the D-H angle theta of Peng 2018 at every vertex whose numbering runs counter-clockwise (checked here); a
mirror image keeps every valley a valley, so a mirrored vertex has the same rho on corresponding creases
(the thesis's "reflection negates the D-H angles" is the clockwise numbering).

Cases (`example`), each driven by the inner crease AB:

1. Rotation case, identical generic vertices (eqn 2-34, Figs 2-11/2-12): alpha = (90, 70, 60, 140) deg at
   every vertex; A, B, C, D carry the same (rho_1..rho_4) on the same branch (Path4, eqn 2-23).
2. Variant rotation case (eqns 2-35...2-38, Fig 2-13): alpha_a = alpha_c = (80, 70, 100, 110) deg,
   alpha_b = alpha_d = (100, 110, 80, 70) deg, all the same flat-foldable vertex; it closes with all four
   vertices in mode S or all in mode C. Mixed modes do not close: each vertex multiplies tan(rho/2) by a
   constant (eqns 3-1, 3-3), so the loop gain m12(A) m23(B) m34(C) m41(D) of a mixed loop is not 1 (it is
   42.66, -0.0234, -1, 1819.7, 5.5e-4, 0.0234 or -42.66) and only the flat and the fully folded states close.
3. Two-fold case (Path1, eqns 2-15...2-17; reconstructed here): B and D are mirror images of A and C, the shared
   creases are a2-b2, b1-c1, c2-d2, d1-a1, so every central corner is alpha_12. The central panel is
   planar only for alpha_12 = 90 deg: a rectangle, built with the vertex of Example 1 (which has
   alpha_12 = 90 deg) and |AB| = |BC| = 1. Derived here: it closes on six combinations, not only with every vertex
   alike: a mirror pair on one branch carries equal folds, so the crease it shares with the rest of the loop
   matches whenever A, B and C, D (pairs sharing crease 2) or B, C and D, A (sharing crease 1) are pairwise
   on one branch. The mixed ones are named per vertex (``odd2-odd2-odd3-odd3`` = A, B on odd2, C, D on odd3).
4. Plane-symmetric case (Path3, eqn 2-19; reconstructed here): D and C are mirror images of A and B, the shared creases
   are a2-b2, b3-c3, c2-d2, d1-a1, so the central corners are alpha_12, alpha_23, alpha_23, alpha_12 and a
   planar central panel needs alpha_12 + alpha_23 = 180 deg: an isosceles trapezoid, mirror-symmetric about
   the plane through the midpoints of DA and BC. The thesis's figure vertex (Fig 2-6, its
   caption's second alpha34 read as alpha41) is not developable (sectors sum to 33 pi/18), so
   the mesh keeps its alpha_12 = 40 and alpha_41 = 100 deg and takes alpha_23 = 140, alpha_34 = 80 deg.
   Creases 1 and 3 of every vertex are then collinear: a3-DA-d3 and b1-BC-c1 are straight lines across the
   sheet, which the thesis excludes (§2.5: "more than 1 DOF"). Derived here: both hold: the mesh moves on one 1-DOF
   branch with every vertex alike (odd1, A = B = C = D in rho, which is A = B, C = D = -A in the thesis's D-H
   angles), and on a 2-DOF family that folds the two straight lines alone (rho_AB = 0 on it, mobility 2
   everywhere on it); the two meet at the flat state (`straight_lines`).

Closed form. From the input x = rho_AB each vertex is solved in turn with `vertex4` (its input the crease
it shares with the previous vertex): A and B from AB, C from BC, D from CD. Crease DA then comes out twice,
from A and from D; their difference is the loop mismatch, zero on a mesh branch. The branches are the
combinations of vertex branches whose mismatch vanishes at every probe input (named by the common vertex
branch, e.g. ``S``, or per vertex when mixed). All pass through the flat state, a bifurcation where the
closure's rank drops from 11 to 8 (4 loops of rank 2 in the sheet's plane: mobility 4), and end where a
crease folds flat (a lock; every case here) or where the input turns back. `evaluate` solves each vertex on
the one root of eqn 2-5 its branch takes (`Vertex4.branch_folds`), on blocks of inputs.
"""

import itertools
from dataclasses import dataclass
from functools import cache, cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import AssemblyError, ParameterError
from ..geometry import wrap
from .base import Branch, Event, JointSpaceKinematics, as_inputs, domain_of, input_blocks
from .vertex4 import ANGLE_TOL, Vertex4

CORNERS = ("A", "B", "C", "D")
INNER = ("AB", "BC", "CD", "DA")
INPUT = "AB"
FACES = ("central", "side_AB", "side_BC", "side_CD", "side_DA", "corner_A", "corner_B", "corner_C", "corner_D")
DEG = np.pi / 180
# Loop mismatch (rad) below which a combination of vertex branches closes: the largest over PROBES measured
# <= 3.6e-15 on every closing combination; >= 0.057 on every other one (Example 2, S-S-C-S).
CLOSE_TOL = 1e-12
# Inputs (rad) at which each combination of vertex branches is tried; those outside its domain are skipped.
PROBES = (-0.6, -0.3, -0.1, 0.1, 0.3, 0.6)
# A domain end whose largest fold is this close to pi (rad) is a crease folded flat (a lock).
LOCK_TOL = 1e-5


@dataclass(frozen=True)
class MeshVertex:
    """
    One degree-4 vertex of the mesh.

    Attributes
    ----------
    alpha : (4,) float
      Sector angles (rad) in the thesis's numbering: alpha[k - 1] lies between creases k and k + 1.
    previous : int
      Thesis number (1-4) of the crease pointing to the previous corner (A -> D, B -> A, C -> B, D -> C).
    mirrored : bool
      True when the thesis numbering runs clockwise in the flat sheet (a mirror-image placement).
    """

    alpha: tuple[float, float, float, float]
    previous: int
    mirrored: bool = False

    @property
    def next(self) -> int:
        """Thesis number of the crease pointing to the next corner (A -> B, ...)."""
        return (self.previous - 2) % 4 + 1 if self.mirrored else self.previous % 4 + 1

    @property
    def outer(self) -> tuple[int, int]:
        """Thesis numbers of the two outer creases, counter-clockwise from the crease to the next corner."""
        step = -1 if self.mirrored else 1
        return ((self.next - 1 + step) % 4 + 1, (self.next - 1 + 2 * step) % 4 + 1)

    @property
    def central_angle(self) -> float:
        """The central panel's corner angle (rad): the sector between `previous` and `next`."""
        return self.alpha[(self.next if self.mirrored else self.previous) - 1]

    def directions(self, toward_previous: float) -> NDArray[np.float64]:
        """
        Flat-sheet angles (4,) of creases 1..4 (rad from +x) given that of crease `previous`, found by
        walking counter-clockwise: k -> k + 1 across sector alpha_k, or k -> k - 1 across alpha_(k-1) if mirrored.
        """
        out = np.empty(4)
        angle, k = toward_previous, self.previous
        for _ in range(4):
            out[k - 1] = angle
            if self.mirrored:
                k = (k - 2) % 4 + 1
                angle += self.alpha[k - 1]
            else:
                angle += self.alpha[k - 1]
                k = k % 4 + 1
        return out


def example(case: int) -> tuple[MeshVertex, MeshVertex, MeshVertex, MeshVertex]:
    """The four vertices A, B, C, D of case 1, 2 or 3 (module docstring)."""
    generic = tuple(np.array([90.0, 70.0, 60.0, 140.0]) * DEG)  # eqn 2-34
    if case == 1:
        return tuple(MeshVertex(generic, k) for k in (1, 2, 3, 4))
    if case == 2:
        ac = tuple(np.array([4, 3.5, 5, 5.5]) * np.pi / 9)  # (4 pi/9, 7 pi/18, 5 pi/9, 11 pi/18), eqn 2-38
        bd = tuple(np.array([5, 5.5, 4, 3.5]) * np.pi / 9)
        return (MeshVertex(ac, 1), MeshVertex(bd, 2), MeshVertex(ac, 3), MeshVertex(bd, 4))
    if case == 3:
        return (MeshVertex(generic, 1), MeshVertex(generic, 2, True), MeshVertex(generic, 1),
                MeshVertex(generic, 2, True))
    if case == 4:
        plane = tuple(np.array([2, 7, 4, 5]) * np.pi / 9)  # (40, 140, 80, 100) deg: alpha_12 + alpha_23 = 180 deg
        return (MeshVertex(plane, 1), MeshVertex(plane, 2), MeshVertex(plane, 3, True), MeshVertex(plane, 2, True))
    raise ParameterError(
        f"case = {case!r}; the Kokotsakis cases are 1 (Example 1), 2 (Example 2), 3 (two-fold), 4 (plane-symmetric)"
    )


def check_vertices(vertices: tuple[MeshVertex, ...]) -> None:
    """ParameterError unless every vertex is developable with sectors in (0, pi) and the central panel planar."""
    if len(vertices) != 4:
        raise ParameterError(f"a Kokotsakis mesh has 4 vertices, got {len(vertices)}")
    for name, v in zip(CORNERS, vertices, strict=True):
        alpha = np.asarray(v.alpha, dtype=float)
        if alpha.shape != (4,) or v.previous not in (1, 2, 3, 4):
            raise ParameterError(f"vertex {name}: needs 4 sector angles and a crease 1-4 toward the previous corner")
        for k, a in enumerate(alpha, start=1):
            if not 0.0 < a < np.pi:
                raise ParameterError(f"vertex {name}: alpha{k} = {a / DEG:.6g} deg; each must lie in (0, 180) deg")
        total = float(np.sum(alpha))
        if abs(total - 2 * np.pi) > ANGLE_TOL:
            raise ParameterError(
                f"vertex {name}: sector angles sum to {total / DEG:.12g} deg; a developable vertex needs 360 (eqn 2-33)"
            )
    central = sum(v.central_angle for v in vertices)
    if abs(central - 2 * np.pi) > ANGLE_TOL:
        corners = ", ".join(f"{n} {v.central_angle / DEG:.6g}" for n, v in zip(CORNERS, vertices, strict=True))
        raise ParameterError(
            f"central panel corners ({corners} deg) sum to {central / DEG:.12g} deg; a planar panel needs 360 "
            "(eqn 2-32)"
        )


def corners(vertices: tuple[MeshVertex, ...], ab: float, bc: float) -> NDArray[np.float64]:
    """
    Corners A, B, C, D (4, 2) in metres: A at the origin, A -> D along +x, the given |AB| and |BC|.

    Raises
    ------
    ParameterError
      When the line from C at the corner angle of C misses the positive x axis (no convex quadrilateral).
    """
    if not (ab > 0 and bc > 0):
        raise ParameterError(f"side lengths |AB| = {ab:g} m, |BC| = {bc:g} m; both must be positive")
    at_a, at_b, at_c, _ = (v.central_angle for v in vertices)
    to_b = at_a  # direction of A -> B (rad from +x)
    to_c = to_b + np.pi + at_b
    to_d = to_c + np.pi + at_c
    B = ab * np.array([np.cos(to_b), np.sin(to_b)])
    C = B + bc * np.array([np.cos(to_c), np.sin(to_c)])
    t = -C[1] / np.sin(to_d)
    x = C[0] + t * np.cos(to_d)
    if not (t > 0 and x > 0):
        raise ParameterError(f"|AB| = {ab:g} m and |BC| = {bc:g} m give no convex central quadrilateral")
    return np.array([[0.0, 0.0], B, C, [x, 0.0]])


def _convex(points: NDArray[np.float64]) -> bool:
    """True when the polygon (n, 2) turns left at every corner (strictly convex, counter-clockwise)."""
    edges = np.roll(points, -1, axis=0) - points
    turns = edges[:, 0] * np.roll(edges, -1, axis=0)[:, 1] - edges[:, 1] * np.roll(edges, -1, axis=0)[:, 0]
    return bool(np.all(turns > 0))


def crease_pattern(
    vertices: tuple[MeshVertex, ...], *, ab: float = 1.0, bc: float = 1.0, outer: float = 0.5
) -> CreasePattern:
    """
    The mesh as a flat crease pattern (module docstring for the layout and names); lengths in metres.

    Raises
    ------
    ParameterError
      For a non-developable vertex, a non-planar central panel, or an outer length that makes a panel
      non-convex (its outer creases would cross).
    """
    check_vertices(vertices)
    if not outer > 0:
        raise ParameterError(f"outer crease length {outer:g} m; it must be positive")
    points = corners(vertices, ab, bc)
    xy = [tuple(p) for p in points]
    ends: dict[tuple[int, int], int] = {}  # (vertex index, thesis crease number) -> pattern vertex of the outer end
    outer_creases = []
    for i, (name, v) in enumerate(zip(CORNERS, vertices, strict=True)):
        d = points[(i - 1) % 4] - points[i]
        phi = v.directions(np.arctan2(d[1], d[0]))
        for k in v.outer:
            ends[i, k] = len(xy)
            xy.append((points[i, 0] + outer * np.cos(phi[k - 1]), points[i, 1] + outer * np.sin(phi[k - 1])))
            outer_creases.append(Crease(f"{name.lower()}{k}", i, ends[i, k]))
    faces = [(0, 3, 2, 1)]
    for i in range(4):
        j = (i + 1) % 4
        faces.append((i, j, ends[j, vertices[j].outer[1]], ends[i, vertices[i].outer[0]]))
    for i, v in enumerate(vertices):
        faces.append((i, ends[i, v.outer[0]], ends[i, v.outer[1]]))
    xy = np.array(xy)
    for name, face in zip(FACES, faces, strict=True):
        if not _convex(xy[list(face)]):
            raise ParameterError(f"outer crease length {outer:g} m makes panel {name!r} non-convex: its creases cross")
    inner = tuple(Crease(n, CORNERS.index(n[0]), CORNERS.index(n[1])) for n in INNER)
    return CreasePattern(xy, tuple(faces), inner + tuple(outer_creases), FACES)


def straight_lines(pattern: CreasePattern) -> tuple[tuple[str, str, str], ...]:
    """
    Crease lines straight across the mesh: (outer, inner, outer) crease names where an inner crease continues
    into an outer crease at both ends (directions within ANGLE_TOL rad in the flat sheet). Each folds alone,
    every other crease flat, as a simple hinge: a family of rigid motions with one DOF per line.
    """
    xy = pattern.vertices
    out = []
    for inner in pattern.creases[: len(INNER)]:
        ends = []
        for at, away in ((inner.start, inner.end), (inner.end, inner.start)):
            u = xy[at] - xy[away]
            for c in pattern.creases[len(INNER) :]:
                v = xy[c.end] - xy[c.start]
                cross = u[0] * v[1] - u[1] * v[0]
                if c.start == at and abs(np.arctan2(cross, u @ v)) < ANGLE_TOL:
                    ends.append(c.name)
        if len(ends) == 2:
            out.append((ends[0], inner.name, ends[1]))
    return tuple(out)


def crease_names(vertices: tuple[MeshVertex, ...]) -> tuple[str, ...]:
    """Crease names in pattern order: the inner creases, then each vertex's outer creases."""
    return INNER + tuple(f"{n.lower()}{k}" for n, v in zip(CORNERS, vertices, strict=True) for k in v.outer)


@cache
def _solver(alpha: tuple[float, float, float, float], crease: int) -> Vertex4:
    """The closed-form vertex of sectors `alpha` (rad) driven by crease `crease`, built once (its branch domains
    are traced at construction) and shared by every mesh that uses it."""
    return Vertex4(np.asarray(alpha, dtype=float), crease)


def _solvers(vertices: tuple[MeshVertex, ...]) -> tuple[Vertex4, ...]:
    """One closed-form vertex per corner, driven by the crease it shares with the previous vertex (A: AB)."""
    first = _solver(tuple(vertices[0].alpha), vertices[0].next)
    return (first, *(_solver(tuple(v.alpha), v.previous) for v in vertices[1:]))


def _chain(
    solvers: tuple[Vertex4, ...], vertices: tuple[MeshVertex, ...], branches: tuple[str, ...], x: NDArray
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Vertex fold angles (4, n, 4), thesis numbering, solved in turn from x = rho_AB; valid (n,)."""
    rho = np.full((4, x.size, 4), np.nan)
    valid = np.ones(x.size, dtype=bool)
    value = x
    for i, (solver, v, b) in enumerate(zip(solvers, vertices, branches, strict=True)):
        inputs = x if i < 2 else value
        ok = valid & np.isfinite(inputs)
        out, good = solver.evaluate(b, np.where(ok, inputs, 0.0))
        valid = ok & good
        rho[i, valid] = out[valid]
        value = rho[i, :, v.next - 1]
    return rho, valid


def _mismatch(rho: NDArray[np.float64], valid: NDArray[np.bool_], vertices: tuple[MeshVertex, ...]) -> NDArray:
    """rho_DA from D minus rho_DA from A (n,), wrapped; NaN where the chain is invalid."""
    out = wrap(rho[3, :, vertices[3].next - 1] - rho[0, :, vertices[0].previous - 1])
    return np.where(valid, out, np.nan)


def loop_mismatch(vertices: tuple[MeshVertex, ...], branches: tuple[str, ...], x: ArrayLike) -> NDArray[np.float64]:
    """
    rho_DA from vertex D minus rho_DA from vertex A (rad, wrapped), with every vertex on its branch in
    `branches` and x = rho_AB (n,); NaN where a vertex leaves its branch's domain. Zero on a mesh motion.
    """
    check_vertices(vertices)
    x = as_inputs(x)
    return _mismatch(*_chain(_solvers(vertices), vertices, tuple(branches), x), vertices)


def combination_name(combo: tuple[str, ...]) -> str:
    """A mesh branch's name from its vertex branches (A, B, C, D): the common one, or all four joined by '-'."""
    return combo[0] if len(set(combo)) == 1 else "-".join(combo)


def branch_mismatches(vertices: tuple[MeshVertex, ...]) -> dict[tuple[str, ...], float]:
    """
    Largest |loop mismatch| (rad) at PROBES of every combination of vertex branches (A, B, C, D), inf where no
    probe lies in the combination's domain. A combination closes the mesh where it is <= CLOSE_TOL; the side and
    outer crease lengths do not enter.
    """
    check_vertices(vertices)
    solvers = _solvers(vertices)
    out = {}
    for combo in itertools.product(*([b.name for b in s.branches()] for s in solvers)):
        m = np.abs(_mismatch(*_chain(solvers, vertices, combo, np.array(PROBES)), vertices))
        out[combo] = float(np.nanmax(m)) if np.any(np.isfinite(m)) else np.inf
    return out


class Kokotsakis(JointSpaceKinematics):
    """
    A Kokotsakis mesh driven by x = rho_AB (module docstring for frames, signs and branches).

    Parameters
    ----------
    vertices : 4 MeshVertex
      Vertices A, B, C, D (`example` gives the thesis's cases).
    ab, bc, outer : float
      Central side lengths |AB|, |BC| and the outer crease length (m).

    Raises
    ------
    ParameterError
      For a bad geometry (`crease_pattern`).
    AssemblyError
      When no combination of vertex branches closes the loop: the mesh is rigid.
    """

    input_name = f"rho{INPUT}"

    def __init__(self, vertices: tuple[MeshVertex, ...], *, ab: float = 1.0, bc: float = 1.0, outer: float = 0.5):
        self.vertices = tuple(vertices)
        self.pattern = crease_pattern(self.vertices, ab=ab, bc=bc, outer=outer)
        self.creases = crease_names(self.vertices)
        self.joint_names = tuple(f"rho{c}" for c in self.creases)
        self._solvers = _solvers(self.vertices)
        # each crease's (vertex index, thesis number) it is read from; DA from A (the loop's end is D)
        first, second, third = self.vertices[:3]
        inner = ((0, first.next), (1, second.next), (2, third.next), (0, first.previous))
        self._source = inner + tuple((i, k) for i, v in enumerate(self.vertices) for k in v.outer)
        if not self._combinations:
            raise AssemblyError(
                f"no combination of vertex branches closes the mesh: smallest loop mismatch {self._smallest:.3g} rad "
                f"at inputs {PROBES} rad"
            )

    @cached_property
    def _tried(self) -> dict[tuple[str, ...], float]:
        return branch_mismatches(self.vertices)

    @property
    def _smallest(self) -> float:
        return min(self._tried.values())

    @cached_property
    def _combinations(self) -> dict[str, tuple[str, ...]]:
        """Mesh branch name -> the vertex branches of A, B, C, D, for every closing combination."""
        out = {}
        for combo, m in self._tried.items():
            if m <= CLOSE_TOL:
                out[combination_name(combo)] = combo
        return out

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """`_chain` on blocks of `base.BLOCK` inputs, each vertex on its own root only (`Vertex4.branch_folds`)."""
        if branch not in self._combinations:
            self.branch(branch)  # raises with the list of names
        x = as_inputs(x)
        return self.within_domain(branch, x, *self._evaluate_all(branch, x))

    def _evaluate_all(self, branch: str, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """The model's own values and validity, before the printed domain is applied (it is found from these)."""
        values, valid = np.empty((x.size, len(self.creases))), np.empty(x.size, dtype=bool)
        for block in input_blocks(x.size):
            valid[block] = self._evaluate(self._combinations[branch], x[block], values[block])
        return values, valid

    def _evaluate(self, combo: tuple[str, ...], x: NDArray[np.float64], out: NDArray[np.float64]) -> NDArray[np.bool_]:
        """Crease folds (n, 12) into `out` at inputs x (n,) with the vertices on the branches `combo`; valid (n,)."""
        rho, valid, value = [], np.ones(x.size, dtype=bool), x
        for solver, v, b in zip(self._solvers, self.vertices, combo, strict=True):
            ok = valid & np.isfinite(value)
            folds, good = solver.branch_folds(b, np.where(ok, value, 0.0))
            valid = ok & good
            rho.append(folds)
            value = x if len(rho) == 1 else folds[v.next - 1]
        valid &= np.abs(x) <= np.pi
        np.stack([rho[i][k - 1] for i, k in self._source], axis=-1, out=out)
        out[~valid] = np.nan
        return valid

    def vertex_folds(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """
        Fold angles (n, 4, 4) of vertices A, B, C, D (axis 1) in their thesis numbering (axis 2), rad.

        Raises
        ------
        DomainError
          When any input lies outside the branch's domain.
        """
        x = as_inputs(x)
        self.joint_angles(branch, x)
        rho, _ = _chain(self._solvers, self.vertices, self._combinations[branch], x)
        return np.swapaxes(rho, 0, 1)

    @cached_property
    def _branches(self) -> tuple[Branch, ...]:
        out = []
        for name, combo in self._combinations.items():
            domain = domain_of(lambda x, n=name: self._evaluate_all(n, x)[1], -np.pi, np.pi, 0.0)
            out.append(Branch(name, self._describe(combo), domain))
        return tuple(sorted(out, key=lambda b: b.name))

    def _describe(self, combo: tuple[str, ...]) -> str:
        if len(set(combo)) == 1:
            return f"every vertex on its branch {combo[0]!r} ({self._solvers[0].branch(combo[0]).description})"
        parts = zip(CORNERS, self._solvers, combo, strict=True)
        return "; ".join(f"{n} on {b!r} ({s.branch(b).description})" for n, s, b in parts)

    def branches(self) -> tuple[Branch, ...]:
        return self._branches

    def events(self) -> tuple[Event, ...]:
        names = tuple(b.name for b in self._branches)
        detail = "flat state: every mesh branch passes through it"
        lines = straight_lines(self.pattern)
        if lines:
            detail += (f"; so does the {len(lines)}-DOF family folding the straight crease lines "
                       f"{', '.join('-'.join(line) for line in lines)} alone (rho_{INPUT} = 0 on it)")
        out = [Event("bifurcation", 0.0, names, detail)]
        for b in self._branches:
            for end in b.domain:
                out.append(self._end_event(b.name, end))
        return tuple(out)

    def _end_event(self, name: str, end: float) -> Event:
        rho = self.evaluate(name, end)[0][0]
        flat = [c for c, r in zip(self.creases, rho, strict=True) if abs(abs(r) - np.pi) < LOCK_TOL]
        if flat:
            return Event("lock", end, (name,), f"folded flat (|rho| = pi) at crease(s) {', '.join(flat)}")
        return Event("turning_point", end, (name,), "a vertex's input turns back: the mesh cannot go on")

    def gruebler(self) -> int:
        """Kutzbach: 12 creases - 3 per spherical vertex loop = 0 (the mesh moves by its special geometry)."""
        return len(self.creases) - 3 * 4

    def loop_system(self) -> LoopSystem:
        """The crease pattern's per-vertex closure: 4 spherical loops over the 12 creases."""
        return self.pattern.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return self.creases.index(INPUT), 1.0
