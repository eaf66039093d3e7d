"""Generalized waterbomb tube: radial contraction for odd and even m (Feng, Ma and Chen 2020, §2; Feng 2018,
§6.1-6.3; "the sources" below).

Pattern (reconstructed here from the lengths the sources quote, as `waterbomb.unit_cell` is). One unit of row i
(the sources' row numbering, below) is centred on A_i with half-width a: top midpoint C_i at height L_m = a sin(beta) /
(sin(alpha) sin(alpha + beta)) above A_i, top corners B_i at (+-a, a cot(alpha)), bottom midpoint B_(i-1) at -L_m,
bottom corners C_(i-1) at (+-a, -a cot(alpha)); rows sit H = a cot(alpha) + L_m apart and are shifted by a. Flat
coordinates are integer slots p (x = p a): A_i and C_i at p = i mod 2 (mod 2), B_i at p = i + 1 (mod 2). A tube has n
units per row and m rows, rows i = -r0 .. m - 1 - r0 with r0 = (m - 1) // 2: for odd m row 0 is the equatorial row,
for even m it is the row just below the equator (Feng, Ma and Chen 2020, §2.2). Names count rows from the bottom,
r = i + r0, and units k = 0..n-1.

* Faces F<r>_<k>_<s>: s = 12, 23, 34, 45, 56, 61 is the pair of A-creases that bound it (23 and 56 are the big
  triangles), 6nm in all.
* Creases (9nm - 2n): A<r>_<k>_<j>, j = 1..6 the sources' numbering clockwise from the up midline A->C (1 up
  midline M, 2 upper-right diagonal V, 3 lower-right diagonal V, 4 down midline M, 5, 6 the left diagonals V);
  V<r>_<k> the vertical edge (M) between unit k and unit k+1, from the lower corner up; T<r>_<k>_r and
  T<r>_<k>_l the row-boundary edges (M) from C_i to the right and left top corner (rows below the top).

The flat layout is a strip (`pattern`, a CreasePattern): row i covers slots (i mod 2) - 1 .. (i mod 2) + 2n - 1.
The seam is a staircase: the vertical edge V<r>_<n-1> of every row and one row-boundary edge per inner row
boundary (2m - 1 creases) appear twice on the strip's boundary, 2n a apart; they are creases of the tube but
boundary edges of the strip (`seam`). `loop_system` closes every vertex of the tube (A's and the inner B's and
C's, seam vertices included) and adds one ring loop around row 0 across the seam, which makes the strip a tube.

Fold angles rho follow `sim_origami.creases` (0 flat, > 0 valley seen from the flat sheet's +z); +z ends up
outside the tube. The sources' dihedrals are phi = pi - s rho, with s = +1 on a valley, -1 on a mountain:
phi in [0, pi], phi = pi flat, phi = 0 folded; phi < 0 is a crease folded through its neighbour (penetration),
phi > pi a crease reversed through flat. The input is x = rho of A<r0>_0_1, the top midline of unit 0 of row 0
(the sources' theta = eta_01 = phi_0,1 = pi + x).

Analytic model (an independent coordinate model, derived here). Under the sources' symmetry every vertex lies in a
meridian half-plane: A_i and C_i at azimuth p pi / n with their slot p, B_i likewise, each at a signed radius r
(negative: through the axis) and height z. Every vertex meets two rigid edges to vertices already placed, one in its own
meridian and one in the meridian pi/n away, so it is the intersection of two circles in its meridian plane (`meet`; the
sources' '-' root, checked against the worked values of Feng, Ma and Chen 2020's equations at n6 m3 40/35, eta01 = 90
deg, tests/published/feng_ma_chen2020.py). Odd m starts from the equatorial row: r_A0 = a sin(theta/2 - pi/n) /
sin(pi/n), r_B0 = a sin(theta/2) / sin(pi/n), z_A0 = 0, z_B0 = a cot(alpha) (Feng, Ma and Chen 2020, eqn 11), then C_i,
A_(i+1), B_(i+1) row by row; the lower half is the mirror z -> -z (A_i <-> A_-i, B_i <-> C_(-i-1)). Even m starts from
the equatorial row boundary: r_B0 = r_C0 = rho = a sin(theta/2) / sin(pi/n), z_B0 = -z_C0 = sqrt(L_r^2 - 2 rho^2 (1 -
cos(pi/n))) / 2 (L_r = a / sin(alpha + beta)), then A_1, B_1, C_1, ...; the lower half is the half-turn z -> -z, azimuth
+ pi/n (A_i <-> A_(1-i), B_i <-> C_(-i)). This replaces the sources' vertex chain (Feng 2018, eqns 6-11...6-13, garbled
in print; Feng, Ma and Chen 2020, eqns 12a-g, with typos in 12d, 12g and 14) and Feng, Ma and Chen 2020's eqn 18, which
does not close the even tube (corrected here: r_A0 = 0.42500 a, not its 0.13198 a, at n6 alpha45 beta40, eta01 = 80
deg). Fold angles then follow from the 3-D vertices (`fold_angles`). `evaluate` measures only one crease per symmetry
class (`FoldPlan`: 15 of the 258 creases of the 6 x 5 tube), without cross products (`crease_folds`), on blocks of
inputs, and copies each to its class.

Domain: the first connected interval of theta above 0 on which every circle meets, no crease is reversed through
flat (a "strict" criterion added here: the sources only need the chain real) and the middle row is not through
the axis (r_A0 >= 0: theta >= 2 pi/n for odd m, Feng, Ma and Chen 2020, eqn 13). It ends at a fold of the top row
(eqn 14: the top crease flat, a turning point). Inside it, rows whose A's cross the axis (r_A < 0, vertical edges
folded through each other: eqn 15) are reported as lock events: the mechanism-structure-mechanism transition of
Feng 2018, §6.2.2. Events of kind "uniform_radius" mark the states with every row alike (Feng 2018, eqn 6-22),
regular points of this full tube.

Symmetry. The free tube has 4n - 6 DOF (counted here); `couplings` pin it to the contraction with joint couplings
between symmetry images (`loop_system`), as the scene does in MuJoCo. The twist (Feng 2018, §6.4) is not modelled;
its thresholds are: `alpha_limit` (eqn 38 / 6-47), `beta_max` (eqn 40 / 6-49, where the contraction ends in the
equal-diameter, fully folded cylinder) and `alpha_min` (eqn 6-33). scripts/waterbomb_tube_numbers.py prints the
sources' numbers against ours.
"""

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Coupling, Loop, LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import AssemblyError, ParameterError
from ..geometry import frame_along, invert, transform, wrap
from ..graph import spanning_edges
from .base import Branch, Event, JointSpaceKinematics, as_inputs, domain_of, input_blocks

BRANCH = "radial-contraction"
# A fold angle this far (rad) on the wrong side of flat counts as reversed.
REVERSAL_TOL = 1e-9
# Two creases are one symmetry class when their closed-form angles agree to this at generic inputs (rad): two for the
# couplings, five for `fold_plan`. Measured on the tubes and twists of the tests: <= 1.8e-15 within a class, >= 0.019
# between classes.
CLASS_TOL = 1e-9
# Where in a branch's domain (fractions of its width) `fold_plan` compares the fold angles.
PLAN_PROBES = np.array([0.5, 0.1, 0.3819660113, 0.6180339887, 0.9])
# Samples of theta in (0, pi) on which the domain's first interval is found, before its ends are bisected.
GRID = 4097

Key = tuple[str, int, int]  # (kind "A" / "B" / "C", row, slot p)


@dataclass(frozen=True)
class SeamCrease:
    """A tube crease on the strip's seam: its strip vertices (start, end) on the copy of each of its two faces."""

    name: str
    left_face: str
    right_face: str
    left_ends: tuple[int, int]
    right_ends: tuple[int, int]


@dataclass(frozen=True)
class Lengths:
    """Edge lengths (m) of the pattern: midline, diagonal, vertical edge, row boundary, and the height a cot(alpha)."""

    midline: float
    diagonal: float
    vertical: float
    boundary: float
    corner: float


def lengths(alpha: float, beta: float, a: float) -> Lengths:
    """Lengths (reconstructed here, consistent with Feng, Ma and Chen 2020): L_m = a sin(beta) / (sin(alpha)
    sin(alpha + beta)), L_d = a / sin(alpha), L_v = 2 a cot(alpha), L_r = a / sin(alpha + beta)."""
    corner = a / np.tan(alpha)
    return Lengths(
        a * np.sin(beta) / (np.sin(alpha) * np.sin(alpha + beta)),
        a / np.sin(alpha),
        2 * corner,
        a / np.sin(alpha + beta),
        corner,
    )


def row_range(m: int) -> tuple[int, int]:
    """Row indices (bottom, top) of the rows, the sources' numbering: r0 = (m - 1) // 2 rows below row 0."""
    r0 = (m - 1) // 2
    return -r0, m - 1 - r0


def _unit(i: int, p0: int) -> tuple[dict[str, tuple[Key, ...]], list[tuple[str, Key, Key, str]]]:
    """Faces (counter-clockwise) and creases (suffix, start, end, M/V) of the unit of row i centred at slot p0."""
    A, C, Bb = ("A", i, p0), ("C", i, p0), ("B", i - 1, p0)
    Bp, Bm, Cp, Cm = ("B", i, p0 + 1), ("B", i, p0 - 1), ("C", i - 1, p0 + 1), ("C", i - 1, p0 - 1)
    faces = {"12": (A, Bp, C), "61": (A, C, Bm), "56": (A, Bm, Cm), "45": (A, Cm, Bb), "34": (A, Bb, Cp),
             "23": (A, Cp, Bp)}
    creases = [("1", A, C, "M"), ("2", A, Bp, "V"), ("3", A, Cp, "V"), ("4", A, Bb, "M"), ("5", A, Cm, "V"),
               ("6", A, Bm, "V"), ("V", Cp, Bp, "M"), ("r", C, Bp, "M"), ("l", C, Bm, "M")]
    return faces, creases


@dataclass(frozen=True)
class TubeLayout:
    """
    The tube's topology and flat strip (module docstring for names).

    `keys` are the tube's vertices (kind, row, slot mod 2n) with flat positions `flat` (m); `creases` are the
    tube's creases as (name, start, end, M/V) over `keys`, strip creases first (in `pattern` order), then `seam`.
    `left` / `right` give each crease's face names and `third_left` / `third_right` the vertex of each face off the
    crease. `strip_keys` maps the strip's vertices to `keys`.
    """

    n: int
    m: int
    alpha: float
    beta: float
    a: float
    keys: tuple[Key, ...]
    flat: NDArray[np.float64]
    creases: tuple[tuple[str, int, int, str], ...]
    left: tuple[str, ...]
    right: tuple[str, ...]
    third_left: NDArray[np.int64]
    third_right: NDArray[np.int64]
    pattern: CreasePattern
    seam: tuple[SeamCrease, ...]
    strip_keys: NDArray[np.int64]

    @cached_property
    def names(self) -> tuple[str, ...]:
        return tuple(c[0] for c in self.creases)

    @cached_property
    def unit0(self) -> NDArray[np.int64]:
        """Creases of unit 0 of every row: the contraction folds every unit of a row alike, so these show them all."""
        return np.array([k for k, name in enumerate(self.names) if name.split("_")[1] == "0"])

    def _flat_vectors(self, ends: NDArray[np.int64]) -> NDArray[np.float64]:
        """Flat-sheet vectors (k, 2) in m from vertex ends[:, 0] to ends[:, 1] (indices into keys), across the seam
        where that is shorter (a face spans at most 2 a of the strip's width 2 n a)."""
        d = self.flat[ends[:, 1]] - self.flat[ends[:, 0]]
        width = 2 * self.n * self.a
        d[:, 0] -= width * np.round(d[:, 0] / width)
        return d

    @cached_property
    def crease_lengths(self) -> NDArray[np.float64]:
        """Length l (m) of every crease in `creases`; the rigid faces keep it in 3-D (within 1.6e-15 m measured on
        the tubes of the tests)."""
        d = self._flat_vectors(np.array([c[1:3] for c in self.creases]))
        return np.hypot(d[:, 0], d[:, 1])

    @cached_property
    def face_products(self) -> NDArray[np.float64]:
        """(d.v_l)(d.v_r) (m^4) of every crease in `creases`: d from its start to its end, v_l and v_r from its start
        to the third vertex of its left and right face. Each dot product stays within one rigid face, so it is the
        flat sheet's."""
        starts = np.array([c[1] for c in self.creases])
        d = self._flat_vectors(np.array([c[1:3] for c in self.creases]))
        left = self._flat_vectors(np.stack([starts, self.third_left], -1))
        right = self._flat_vectors(np.stack([starts, self.third_right], -1))
        return np.sum(d * left, axis=-1) * np.sum(d * right, axis=-1)

    def index(self, name: str) -> int:
        """Position of crease `name` in `creases`."""
        try:
            return self.names.index(name)
        except ValueError:
            raise ParameterError(f"unknown crease {name!r} of the {self.n} x {self.m} tube") from None


def _flat_y(kind: str, i: int, L: Lengths) -> float:
    return i * (L.corner + L.midline) + {"A": 0.0, "B": L.corner, "C": L.midline}[kind]


def tube_layout(n: int, m: int, alpha: float, beta: float, a: float) -> TubeLayout:
    """The tube of n units x m rows with design angles alpha, beta (rad) and half-width a (m)."""
    L = lengths(alpha, beta, a)
    bottom, top = row_range(m)
    faces: dict[str, tuple[Key, ...]] = {}
    raw: list[tuple[str, Key, Key, str]] = []
    for i in range(bottom, top + 1):
        for k in range(n):
            unit_faces, unit_creases = _unit(i, 2 * k + i % 2)
            r = i - bottom
            faces |= {f"F{r}_{k}_{s}": f for s, f in unit_faces.items()}
            for suffix, start, end, mv in unit_creases:
                if suffix in "rl" and i == top:
                    continue
                name = {"V": f"V{r}_{k}", "r": f"T{r}_{k}_r", "l": f"T{r}_{k}_l"}.get(suffix, f"A{r}_{k}_{suffix}")
                raw.append((name, start, end, mv))

    def tube_key(key: Key) -> Key:
        return (key[0], key[1], key[2] % (2 * n))

    strip = sorted({v for f in faces.values() for v in f}, key=lambda v: (v[1], "BAC".index(v[0]), v[2]))
    strip_index = {v: j for j, v in enumerate(strip)}
    keys = tuple(sorted({tube_key(v) for v in strip}, key=lambda v: (v[1], "BAC".index(v[0]), v[2])))
    key_index = {v: j for j, v in enumerate(keys)}
    # directed tube edge -> (face name, strip start, strip end) of the face that runs along it counter-clockwise
    along: dict[tuple[Key, Key], tuple[str, int, int]] = {}
    for name, f in faces.items():
        for u, v in zip(f, f[1:] + f[:1], strict=True):
            along[tube_key(u), tube_key(v)] = (name, strip_index[u], strip_index[v])
    inner, seam_list, seam = [], [], []
    for name, start, end, mv in raw:
        s, e = tube_key(start), tube_key(end)
        (fl, ls, le), (fr, re, rs) = along[s, e], along[e, s]
        if (ls, le) == (rs, re):
            inner.append((name, s, e, mv, fl, fr))
        else:
            seam_list.append((name, s, e, mv, fl, fr))
            seam.append(SeamCrease(name, fl, fr, (ls, le), (rs, re)))
    ordered = inner + seam_list

    def opposite(face: str, s: Key, e: Key) -> int:
        return key_index[next(tube_key(v) for v in faces[face] if tube_key(v) not in (s, e))]

    flat = np.array([(p * a, _flat_y(kind, i, L)) for kind, i, p in keys])
    xy = np.array([(p * a, _flat_y(kind, i, L)) for kind, i, p in strip])
    face_names = tuple(faces)
    pattern = CreasePattern(
        xy,
        tuple(tuple(strip_index[v] for v in faces[f]) for f in face_names),
        tuple(Crease(name, along[s, e][1], along[s, e][2], mv) for name, s, e, mv, _, _ in inner),
        face_names,
    )
    third_left = np.array([opposite(c[4], c[1], c[2]) for c in ordered])
    third_right = np.array([opposite(c[5], c[1], c[2]) for c in ordered])
    return TubeLayout(
        n, m, float(alpha), float(beta), float(a), keys, flat,
        tuple((name, key_index[s], key_index[e], mv) for name, s, e, mv, _, _ in ordered),
        tuple(c[4] for c in ordered), tuple(c[5] for c in ordered), third_left, third_right,
        pattern, tuple(seam), np.array([key_index[tube_key(v)] for v in strip]),
    )


def meet(p: tuple, d1: float, q: tuple, d2: float, n: int) -> tuple[NDArray, NDArray]:
    """
    The vertex (r, z) at distance d1 from p = (r, z) in its own meridian half-plane and d2 from q = (r, z) in the
    meridian pi/n away: two circles in the meridian plane, centred at p and at (r_q cos(pi/n), z_q) with radius
    sqrt(d2^2 - (r_q sin(pi/n))^2). Of their two intersections, the one clockwise of the line from the first centre
    to the second in the (r, z) plane (the sources' '-' root). NaN where the circles do not meet.
    """
    (pr, pz), (qr, qz) = p, q
    r2 = d2**2 - (qr * np.sin(np.pi / n)) ** 2
    dr, dz = qr * np.cos(np.pi / n) - pr, qz - pz
    dist2 = dr * dr + dz * dz
    dist = np.sqrt(dist2)
    along = (d1**2 - r2 + dist2) / (2 * dist)
    h2 = d1**2 - along**2
    h = np.sqrt(np.where((r2 >= 0) & (h2 >= 0), h2, np.nan))
    ur, uz = dr / dist, dz / dist
    return pr + along * ur + h * uz, pz + along * uz - h * ur


def row_coordinates(
    n: int, m: int, alpha: float, beta: float, a: float, theta: ArrayLike
) -> dict[tuple[str, int], tuple[NDArray, NDArray]]:
    """
    (r, z) in m of every vertex kind and row, {(kind, row): (r (N,), z (N,))}, at inputs theta = phi_0,1 (N,)
    (rad), on the contraction path (module docstring). NaN where the tube does not assemble.
    """
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    L = lengths(alpha, beta, a)
    s = np.sin(np.pi / n)
    bottom, top = row_range(m)
    rows: dict[tuple[str, int], tuple[NDArray, NDArray]] = {}
    rho = a * np.sin(theta / 2) / s
    if m % 2:
        rows["A", 0] = (a * np.sin(theta / 2 - np.pi / n) / s, np.zeros_like(theta))
        rows["B", 0] = (rho, np.full_like(theta, L.corner))
        rows["C", 0] = meet(rows["A", 0], L.midline, rows["B", 0], L.boundary, n)
    else:  # B_0 above the equator, C_0 below (the sources' assembly; the even-tube values in
        # tests/published/feng_ma_chen2020.py check it)
        zeta2 = L.boundary**2 - 2 * rho**2 * (1 - np.cos(np.pi / n))
        zeta = 0.5 * np.sqrt(np.where(zeta2 >= 0, zeta2, np.nan))
        rows["B", 0], rows["C", 0] = (rho, zeta), (rho, -zeta)
    for i in range(1, top + 1):
        rows["A", i] = meet(rows["B", i - 1], L.midline, rows["C", i - 1], L.diagonal, n)
        rows["B", i] = meet(rows["C", i - 1], L.vertical, rows["A", i], L.diagonal, n)
        rows["C", i] = meet(rows["A", i], L.midline, rows["B", i], L.boundary, n)
    # odd m: mirror, A_i <-> A_-i, B_i <-> C_(-i-1); even m: half-turn, A_i <-> A_(1-i), B_i <-> C_-i
    shift = 0 if m % 2 else 1
    for i in range(bottom, shift):
        r, z = rows["A", shift - i]
        rows["A", i] = (r, -z)
    for j in range(bottom - 1, 0):
        (rb, zb), (rc, zc) = rows["C", shift - j - 1], rows["B", shift - j - 1]
        rows["B", j], rows["C", j] = (rb, -zb), (rc, -zc)
    return rows


def vertices(layout: TubeLayout, theta: ArrayLike) -> NDArray[np.float64]:
    """3-D positions (N, len(keys), 3) in m of the tube's vertices at inputs theta (N,): tube axis +z, slot p at
    azimuth p pi / n, so that the flat sheet's +x runs counter-clockwise round the axis and its +z points out."""
    rows = row_coordinates(layout.n, layout.m, layout.alpha, layout.beta, layout.a, theta)
    r = np.stack([rows[kind, i][0] for kind, i, _ in layout.keys], -1)
    z = np.stack([rows[kind, i][1] for kind, i, _ in layout.keys], -1)
    psi = np.array([p for _, _, p in layout.keys]) * np.pi / layout.n
    return np.stack([r * np.cos(psi), r * np.sin(psi), z], -1)


def _cross(u: NDArray, v: NDArray) -> NDArray:
    """Cross products of (..., 3) arrays (componentwise: np.cross is slow on many small vectors)."""
    return np.stack([u[..., 1] * v[..., 2] - u[..., 2] * v[..., 1], u[..., 2] * v[..., 0] - u[..., 0] * v[..., 2],
                     u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]], -1)


def fold_angles(layout: TubeLayout, X: NDArray[np.float64], creases: ArrayLike | None = None) -> NDArray[np.float64]:
    """
    Fold angle rho (N, n) in (-pi, pi] of the tube's creases (all, or the indices `creases`) posed at vertices
    X (N, K, 3): the right-handed rotation about start -> end of the left face relative to the right face
    (`sim_origami.creases`).
    """
    pick = np.arange(len(layout.creases)) if creases is None else np.asarray(creases)
    ends = np.array([layout.creases[k][1:3] for k in pick])
    S, E = X[:, ends[:, 0]], X[:, ends[:, 1]]
    d = E - S
    n_left = _cross(d, X[:, layout.third_left[pick]] - S)  # the left face runs start -> end -> third
    n_right = _cross(S - E, X[:, layout.third_right[pick]] - E)  # the right face runs end -> start -> third
    sine = np.sum(_cross(n_right, n_left) * d, axis=-1) / np.sqrt(np.sum(d * d, axis=-1))
    return np.arctan2(sine, np.sum(n_right * n_left, axis=-1))


Position = Callable[[int], tuple[NDArray, NDArray, NDArray]]


def crease_folds(layout: TubeLayout, position: Position, creases: ArrayLike) -> list[NDArray[np.float64]]:
    """
    Fold angles rho (N,) of the creases with indices `creases`, each in (-pi, pi], from the positions (x, y, z) (m)
    that `position` gives for a vertex (its index in layout.keys): `fold_angles` without its three cross products.
    With d = end - start, l = |d| (`TubeLayout.crease_lengths`), v_l and v_r the third vertex of the left and right
    face less the start, the identities (d x a).(d x b) = (d.d)(a.b) - (d.a)(d.b) and (d x a) x (d x b) =
    det(d, a, b) d give rho = atan2(-l det(d, v_r, v_l), (d.v_l)(d.v_r) - l^2 v_r.v_l), where (d.v_l)(d.v_r) is
    constant (`TubeLayout.face_products`).
    """
    vectors: dict[tuple[int, int], tuple[NDArray, ...]] = {}

    def vector(start: int, end: int) -> tuple[NDArray, ...]:
        if (start, end) not in vectors:
            vectors[start, end] = tuple(e - s for s, e in zip(position(start), position(end), strict=True))
        return vectors[start, end]

    out = []
    for k in np.asarray(creases):
        _, start, end, _ = layout.creases[k]
        dx, dy, dz = vector(start, end)
        lx, ly, lz = vector(start, int(layout.third_left[k]))
        rx, ry, rz = vector(start, int(layout.third_right[k]))
        det = dx * (ry * lz - rz * ly) + dy * (rz * lx - rx * lz) + dz * (rx * ly - ry * lx)
        length = layout.crease_lengths[k]
        out.append(np.arctan2(-length * det, layout.face_products[k] - length**2 * (rx * lx + ry * ly + rz * lz)))
    return out


def tube_positions(layout: TubeLayout, rows: dict[tuple[str, int], tuple[NDArray, NDArray]]) -> Position:
    """The `Position` of the contraction's vertices (`vertices`, computed once each) at `rows` (`row_coordinates`)."""
    cache: dict[int, tuple[NDArray, NDArray, NDArray]] = {}

    def position(v: int) -> tuple[NDArray, NDArray, NDArray]:
        if v not in cache:
            kind, i, p = layout.keys[v]
            r, z = rows[kind, i]
            psi = p * np.pi / layout.n
            cache[v] = (r * np.cos(psi), r * np.sin(psi), z)
        return cache[v]

    return position


@dataclass(frozen=True)
class FoldPlan:
    """
    The distinct fold angles of one motion: the motion's symmetry (units of a row alike, mirror images) leaves few
    distinct angles, so only the representative creases `creases` (d,) are computed and every crease copies the
    column `take` (n_creases,) of them.
    """

    creases: NDArray[np.int64]
    take: NDArray[np.int64]

    def evaluate(
        self, x: NDArray[np.float64], valid: NDArray[np.bool_], distinct: Callable[[NDArray], list[NDArray]]
    ) -> NDArray[np.float64]:
        """
        Fold angles (N, n_creases) at inputs x (N,), NaN where not `valid` (N,): distinct(x_block), the
        representatives' angles (d arrays (n,)), on blocks of `base.BLOCK` inputs (their temporaries stay in the CPU
        cache), then one copy to every crease: whole rows of a (n_creases, N) array (contiguous copies; a column
        gather into (N, n_creases) took 0.48 s of 1.1 s at N = 1e6 on the 6 x 5 tube), returned transposed.
        """
        rows = np.empty((self.creases.size, x.size))
        for block in input_blocks(x.size):
            np.stack(distinct(x[block]), 0, out=rows[:, block])
        rows[:, ~valid] = np.nan
        return rows[self.take].T


def fold_plan(layout: TubeLayout, q: NDArray[np.float64]) -> FoldPlan:
    """
    The `FoldPlan` of a motion from its fold angles q (P, n_creases) (rad) at P generic inputs: creases of one M/V
    assignment whose angles agree to CLASS_TOL at every input share a representative (the first of them).
    """
    signs = assignment_signs(layout)
    creases: list[int] = []
    take = np.empty(q.shape[1], dtype=np.int64)
    for k in range(q.shape[1]):
        alike = np.all(np.abs(q[:, creases] - q[:, [k]]) <= CLASS_TOL, axis=0) & (signs[creases] == signs[k])
        take[k] = np.argmax(alike) if np.any(alike) else len(creases)
        if take[k] == len(creases):
            creases.append(k)
    return FoldPlan(np.array(creases), take)


def vertex_loops(layout: TubeLayout) -> tuple[Loop, ...]:
    """
    One spherical closure Rot(d_1, rho_1) ... Rot(d_6, rho_6) = I per vertex that faces surround in the tube (every
    A, the B's and C's between rows), creases counter-clockwise in the flat sheet, seam vertices included: a crease
    to the other side of the seam points along the flat difference taken modulo the strip's width 2 n a.
    """
    width = 2 * layout.n * layout.a
    bottom, top = row_range(layout.m)
    around: dict[int, list[tuple[float, int, NDArray]]] = {}
    for c, (_, s, e, _) in enumerate(layout.creases):
        d = layout.flat[e] - layout.flat[s]
        d[0] -= width * np.round(d[0] / width)
        for v, w in ((s, d), (e, -d)):
            around.setdefault(v, []).append((float(np.arctan2(w[1], w[0])), c, np.array([*w, 0.0])))
    loops = []
    for v, (kind, i, _) in enumerate(layout.keys):
        if kind != "A" and not bottom <= i < top:
            continue
        creases = sorted(around[v], key=lambda t: t[0])
        frames = [frame_along(d) for _, _, d in creases]
        links = np.stack([invert(frames[k]) @ frames[(k + 1) % len(frames)] for k in range(len(frames))])
        loops.append(Loop(tuple(c for _, c, _ in creases), links, (1,) * len(creases)))
    return tuple(loops)


def ring_loop(layout: TubeLayout, row: int = 0) -> Loop:
    """
    The closure round row `row`, across the seam: from face 56 of unit k across creases 6, 1, 2 of A to face 23
    and across the vertical edge to face 56 of unit k + 1, n times. Hinge frames are taken in the unrolled flat sheet,
    so the last link carries the strip's width: T = prod_k Rz(s_k rho_k) L_k with L_k = inv(F_k) F_(k+1) and
    L_last = inv(F_last) Shift(2 n a) F_0; s_k = +1 where the face entered is the crease's left face.
    """
    r = row - row_range(layout.m)[0]
    p0, width = row % 2, 2 * layout.n * layout.a
    names, faces = [], []
    for k in range(layout.n):
        names += [f"A{r}_{k}_6", f"A{r}_{k}_1", f"A{r}_{k}_2", f"V{r}_{k}"]
        faces += [f"F{r}_{k}_61", f"F{r}_{k}_12", f"F{r}_{k}_23", f"F{r}_{(k + 1) % layout.n}_56"]
    frames, signs = [], []
    for k, (name, entered) in enumerate(zip(names, faces, strict=True)):
        c = layout.index(name)
        _, s, e, _ = layout.creases[c]
        unit = k // 4
        start, end = layout.flat[s].copy(), layout.flat[e].copy()
        for point in (start, end):  # unroll: unit `unit` spans slots p0 + 2 unit -+ 1
            point[0] += width * np.round(((p0 + 2 * unit) * layout.a - point[0]) / width)
        frames.append(frame_along([*(end - start), 0.0], (*start, 0.0)))
        signs.append(1 if layout.left[c] == entered else -1)
    shift = transform(p=(width, 0.0, 0.0))
    links = [invert(frames[k]) @ frames[k + 1] for k in range(len(frames) - 1)]
    links.append(invert(frames[-1]) @ shift @ frames[0])
    return Loop(tuple(layout.index(nm) for nm in names), np.stack(links), tuple(signs))


def assignment_signs(layout: TubeLayout) -> NDArray[np.float64]:
    """+1 on valleys (the diagonals), -1 on mountains (midlines, vertical edges, row boundaries), per crease."""
    return np.array([1.0 if mv == "V" else -1.0 for _, _, _, mv in layout.creases])


def dihedrals(layout: TubeLayout, rho: ArrayLike, creases: ArrayLike | None = None) -> NDArray[np.float64]:
    """The sources' dihedral angles phi = pi - s rho (rad), wrapped to (-pi, pi] (module docstring), of all creases or
    of the indices `creases`."""
    signs = assignment_signs(layout)
    return wrap(np.pi - (signs if creases is None else signs[np.asarray(creases)]) * np.asarray(rho, dtype=float))


def _bisect(f, lo: float, hi: float, steps: int = 60) -> float:
    """A root of the scalar function f between lo and hi, where f changes sign (or turns NaN)."""
    f_lo = f(lo)
    for _ in range(steps):
        mid = 0.5 * (lo + hi)
        f_mid = f(mid)
        if np.isfinite(f_mid) and np.sign(f_mid) == np.sign(f_lo):
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def sign_changes(f, lo: float, hi: float, samples: int = 2001) -> list[float]:
    """Roots of the vectorised function f on [lo, hi]: sign changes on a grid, each refined by bisection."""
    grid = np.linspace(lo, hi, samples)
    values = f(grid)
    out = []
    for k in np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0):
        out.append(_bisect(lambda x: float(f(np.array([x]))[0]), grid[k], grid[k + 1]))
    return out


def reversed_creases(layout: TubeLayout, q: NDArray[np.float64], creases: ArrayLike | None = None) -> NDArray[np.bool_]:
    """
    Which creases (all, or the indices `creases`) are reversed through flat at fold angles q (..., n): the dihedral
    phi = pi - s rho, wrapped to (-pi, pi], lies in (-pi + REVERSAL_TOL, -pi/2), i.e. phi in (pi, 3 pi / 2). A crease
    folded through its neighbour (phi < 0, the sources' interference) is allowed down to -pi/2; beyond, it cannot be
    told from a reversed one by its angle alone and counts as reversed.
    """
    phi = dihedrals(layout, q, creases)
    return (phi > -np.pi + REVERSAL_TOL) & (phi < -np.pi / 2)


def folds_at(layout: TubeLayout, theta: ArrayLike, creases: ArrayLike | None = None) -> NDArray[np.float64]:
    """Fold angles (N, n) of all creases (or the indices `creases`) at inputs theta = phi_0,1 (N,) (rad), NaN where
    the tube does not assemble."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return fold_angles(layout, vertices(layout, theta), creases)


def valid_inputs(layout: TubeLayout, theta: ArrayLike, strict: bool = True) -> NDArray[np.bool_]:
    """
    Where the contraction is a rigid motion (N,) at theta (N,): theta in (0, pi), every vertex placed, the middle
    row's A's not through the axis (r_A0 >= 0), and (strict) no crease reversed through flat. `strict=False` is the
    sources' criterion (the chain real, Feng, Ma and Chen 2020, §2.1), which lets other creases pass through flat. Unit
    0 of each row stands for its row (`TubeLayout.unit0`).
    """
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    q = folds_at(layout, theta, layout.unit0)
    ok = np.all(np.isfinite(q), axis=-1) & (theta > 0) & (theta < np.pi)
    with np.errstate(invalid="ignore"):
        ok &= row_coordinates(layout.n, layout.m, layout.alpha, layout.beta, layout.a, theta)["A", 0][0] >= 0
        if strict:
            ok &= ~np.any(reversed_creases(layout, q, layout.unit0), axis=-1)
    return ok


def motion_range(layout: TubeLayout, strict: bool = True) -> tuple[float, float] | None:
    """
    The contraction's range of theta (rad): the first interval above 0 where `valid_inputs` holds, its ends
    bisected to about 1e-13 (`base.domain_of`); None where there is none (the tube cannot contract rigidly).
    """
    grid = np.linspace(0.0, np.pi, GRID)
    ok = valid_inputs(layout, grid, strict)
    if not ok.any():
        return None
    return domain_of(lambda t: valid_inputs(layout, t, strict), 0.0, np.pi, float(grid[np.argmax(ok)]), GRID)


def alpha_limit(n: int) -> float:
    """
    Largest alpha (rad) for the twist: tan(alpha) = 1 / cos(pi/n) (Feng, Ma and Chen 2020, eqn 38; Feng 2018, eqn 6-47).
    Above it the
    fully folded equatorial row pushes C_0 below the equator, into the lower small triangles.
    """
    return float(np.arctan(1.0 / np.cos(np.pi / n)))


def alpha_min(n: int) -> float:
    """
    Smallest alpha (rad) of a wave-shaped tube for alpha + beta = pi/2 (Feng 2018, eqn 6-33, theta_I = theta_II):
    (4 + 4 T^2 - T^4) c^4 - 2 T^2 c^2 - 1 = 0 with T = tan(pi/n), c = cos(alpha), a quadratic in c^2.
    """
    T2 = np.tan(np.pi / n) ** 2
    A = 4 + 4 * T2 - T2**2
    return float(np.arccos(np.sqrt((T2 + np.sqrt(T2**2 + A)) / A)))


def beta_max_residual(alpha: float, beta: ArrayLike, n: int) -> NDArray[np.float64]:
    """
    Left side of Feng, Ma and Chen 2020, eqn 40 (Feng 2018, eqn 6-49), zero where every row of the tube is fully
    folded at theta = 2 pi / n (the equal-diameter cylinder):
    c^4(a) s^2(a+b) T^4 + 2 c^2(a) [c(2b) - c^2(a+b)] T^2 + s^2(a+b) - 4 c^2(a) s^2(b), T = tan(pi/n).
    """
    b = np.asarray(beta, dtype=float)
    T2, ca2, sab2 = np.tan(np.pi / n) ** 2, np.cos(alpha) ** 2, np.sin(alpha + b) ** 2
    return (
        ca2**2 * sab2 * T2**2
        + 2 * ca2 * (np.cos(2 * b) - np.cos(alpha + b) ** 2) * T2
        + sab2
        - 4 * ca2 * np.sin(b) ** 2
    )


def beta_max(alpha: float, n: int) -> float:
    """
    Largest beta (rad) for the twist at this alpha (rad): the root of `beta_max_residual` in (0, pi/2) (Feng, Ma
    and Chen 2020, eqn 40). There every row's vertical edges fold flat together at theta = 2 pi / n, a bifurcation
    from which the twist may start in any row (Feng, Ma and Chen 2020, Fig. 16).

    Raises
    ------
    ParameterError
      If eqn 40 has no root for beta in (0, 90) deg.
    """
    roots = sign_changes(lambda b: beta_max_residual(alpha, b, n), 1e-6, np.pi / 2 - 1e-6)
    if not roots:
        raise ParameterError(f"eqn 40 has no root beta in (0, 90) deg for alpha = {np.rad2deg(alpha):.6g} deg, n = {n}")
    return roots[0]


class TubeLoops:
    """
    The tube's closure for a model with `layout`, `crease_names`, `input_crease` and symmetry `couplings`
    (pairs of crease names kept equal): every vertex loop, one ring round the middle row, and the couplings.
    """

    layout: TubeLayout
    pattern: CreasePattern
    crease_names: tuple[str, ...]
    input_crease: str
    couplings: tuple[tuple[str, str], ...]

    def gruebler(self) -> int:
        """Kutzbach: creases - 3 per vertex loop - 6 for the ring - 1 per coupling. Without couplings 4n - 6 (the
        free tube, counted here); with them negative, as the couplings are redundant on purpose."""
        return len(self.crease_names) - 3 * len(vertex_loops(self.layout)) - 6 - len(self.couplings)

    @property
    def tree_root(self) -> str:
        """The face on the input crease's right: root of `tree_creases`."""
        return self.layout.right[self.layout.index(self.input_crease)]

    def tree_creases(self) -> list[int]:
        """Indices of the creases of a shortest-path spanning tree of the tube's faces (seam creases included) from
        `tree_root`, the input crease in it. A shallow tree keeps a simulator's closure Jacobians short: MuJoCo
        steps the 10 x 5 tube 1.5x faster on it than on the strip's crease-order tree (depth 20 against 59)."""
        edges = list(zip(self.layout.right, self.layout.left, strict=True))
        return spanning_edges(self.pattern.face_names, edges, [self.layout.index(self.input_crease)], self.tree_root)

    def free_loop_system(self) -> LoopSystem:
        """The tube's closure without the symmetry couplings: every vertex and one ring round the middle row."""
        return LoopSystem(len(self.crease_names), (*vertex_loops(self.layout), ring_loop(self.layout)))

    def loop_system(self) -> LoopSystem:
        """The tube's closure with the symmetry couplings (`couplings`)."""
        return self._coupled(self.couplings)

    def _coupled(self, pairs: tuple[tuple[str, str], ...]) -> LoopSystem:
        """The free closure with couplings rho_a = rho_b for the crease-name pairs."""
        free = self.free_loop_system()
        index = {name: k for k, name in enumerate(self.crease_names)}
        return LoopSystem(free.n_joints, free.loops, tuple(Coupling(index[a], index[b]) for a, b in pairs))

    def symmetry_classes(self, q: NDArray[np.float64]) -> tuple[tuple[tuple[str, str], ...], int]:
        """
        Couplings from fold samples q (3, n_creases) (rad) of one motion: every spanning-tree crease whose folds at
        q[1] and q[2] match (to CLASS_TOL) an earlier one's is coupled to the first of its class. Returns the pairs
        and the coupled closure's mobility at q[0] (1 when the couplings leave exactly that motion).
        """
        key = np.round(q[1:] / CLASS_TOL).astype(np.int64)
        first: dict[tuple[int, int], int] = {}
        out = []
        for k in self.tree_creases():
            cls = (int(key[0, k]), int(key[1, k]))
            if cls in first:
                out.append((self.crease_names[k], self.crease_names[first[cls]]))
            else:
                first[cls] = k
        return tuple(out), self._coupled(tuple(out)).mobility(q[0])

    def loop_input(self) -> tuple[int, float]:
        return self.layout.index(self.input_crease), 1.0


class WaterbombTube(TubeLoops, JointSpaceKinematics):
    """
    The n x m waterbomb tube on its radial contraction, driven by x = rho of crease A<r0>_0_1 (module docstring
    for frames, signs and the model).

    Parameters
    ----------
    n : int
      Units round the tube, >= 3.
    m : int
      Rows, >= 1; odd m has an equatorial row (Feng, Ma and Chen 2020, §2.1), even m an equatorial row boundary
      (§2.2).
    alpha, beta : float
      Design angles (rad), each in (0, pi/2): the unit's big triangles have apex pi - 2 alpha, its small ones the
      angles alpha, beta, pi - alpha - beta.
    a : float
      Half-width of a unit (m), a in Feng, Ma and Chen 2020, t in Feng 2018.

    Raises
    ------
    ParameterError
      For a geometry out of range, or one that cannot contract rigidly (no configuration in (0, pi) of theta).
    """

    def __init__(self, n: int, m: int, alpha: float, beta: float, a: float = 1.0):
        for name, value, low in (("n", n, 3), ("m", m, 1)):
            if int(value) != value or value < low:
                raise ParameterError(f"{name} = {value:g}; the tube needs an integer {name} >= {low}")
        for name, value in (("alpha", alpha), ("beta", beta)):
            if not 0.0 < value < np.pi / 2:
                raise ParameterError(f"{name} = {np.rad2deg(value):.6g} deg; it must lie in (0, 90) deg")
        if not a > 0:
            raise ParameterError(f"half-width a = {a:g} m; it must be positive")
        self.n, self.m, self.alpha, self.beta, self.a = int(n), int(m), float(alpha), float(beta), float(a)
        self.layout = tube_layout(self.n, self.m, self.alpha, self.beta, self.a)
        self.pattern = self.layout.pattern
        self.crease_names = self.layout.names
        self.joint_names = tuple(f"rho_{c}" for c in self.crease_names)
        self.input_crease = f"A{-row_range(self.m)[0]}_0_1"
        self.input_name = f"rho_{self.input_crease}"
        self.domain = self._domain()

    # -- closed form -------------------------------------------------------------------------------------------
    def rows(self, x: ArrayLike) -> dict[tuple[str, int], tuple[NDArray, NDArray]]:
        """(r, z) in m of every vertex kind and row at inputs x (rad), `row_coordinates`."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return row_coordinates(self.n, self.m, self.alpha, self.beta, self.a, np.pi + np.asarray(x, dtype=float))

    def vertices(self, x: ArrayLike) -> NDArray[np.float64]:
        """3-D vertices (N, len(layout.keys), 3) in m at inputs x (N,) (`vertices`)."""
        with np.errstate(invalid="ignore", divide="ignore"):
            return vertices(self.layout, np.pi + as_inputs(x))

    def folds(self, x: ArrayLike) -> NDArray[np.float64]:
        """Fold angles (N, n_creases) at inputs x (N,), NaN where the tube does not assemble."""
        return folds_at(self.layout, np.pi + as_inputs(x))

    def _domain(self) -> tuple[float, float]:
        theta = motion_range(self.layout)
        if theta is None:
            raise ParameterError(
                f"the {self.n} x {self.m} tube with alpha = {np.rad2deg(self.alpha):.6g} deg, beta = "
                f"{np.rad2deg(self.beta):.6g} deg cannot contract rigidly: no theta in (0, 180) deg assembles without "
                "a crease reversed through flat (Feng, Ma and Chen 2020, §2.1)"
            )
        return theta[0] - np.pi, theta[1] - np.pi

    def radii(self, x: ArrayLike) -> NDArray[np.float64]:
        """Signed radius r_A (N, m) in m of each row's A vertices, rows bottom to top, at inputs x (N,)."""
        rows = self.rows(np.atleast_1d(x))
        bottom, top = row_range(self.m)
        return np.stack([rows["A", i][0] for i in range(bottom, top + 1)], -1)

    def length(self, x: ArrayLike, corners: bool = False) -> NDArray[np.float64]:
        """
        Axial length (N,) in m at inputs x (N,): from the bottom row's bottom midpoints to the top row's top
        midpoints (Feng, Ma and Chen 2020, Fig. 1d), or with `corners` between its corners (Feng 2018, eqn 6-18,
        L = 2 z_B,top).
        """
        rows = self.rows(np.atleast_1d(x))
        bottom, top = row_range(self.m)
        upper, lower = ("B", "C") if corners else ("C", "B")
        return rows[upper, top][1] - rows[lower, bottom - 1][1]

    # -- contract ----------------------------------------------------------------------------------------------
    def branches(self) -> tuple[Branch, ...]:
        symmetry = "mirror in the equatorial plane" if self.m % 2 else "half-turn about an equatorial radius"
        return (
            Branch(BRANCH, f"units plane-symmetric and alike round each row, {symmetry}: the tube contracts "
                   "radially (Feng, Ma and Chen 2020, §2)", self.domain),
        )

    @cached_property
    def plan(self) -> FoldPlan:
        """The contraction's distinct fold angles (`FoldPlan`), found from `folds` at five inputs inside the domain."""
        lo, hi = self.domain
        return fold_plan(self.layout, self.folds(lo + (hi - lo) * PLAN_PROBES))

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Fold angles of every crease: the `plan`'s representatives, measured as `folds` does, copied to the rest."""
        lo, hi = self.branch(branch).domain
        x = as_inputs(x)
        valid = (x >= lo) & (x <= hi)

        def distinct(block: NDArray) -> list[NDArray]:
            with np.errstate(invalid="ignore", divide="ignore"):
                return crease_folds(self.layout, tube_positions(self.layout, self.rows(block)), self.plan.creases)

        return self.plan.evaluate(np.where(valid, x, 0.5 * (lo + hi)), valid, distinct), valid

    def _end(self, inside: float, outside: float) -> Event:
        """What stops the motion between an end of the domain (`inside`) and a point just past it."""
        radii = self.radii(np.array([inside]))[0]
        if abs(radii[-row_range(self.m)[0]]) < 1e-9 * self.a:
            if self.m % 2:
                detail = ("the equatorial row's vertical edges fold flat (kappa_B0,4 = 0), its A's meet on the axis "
                          "(Feng, Ma and Chen 2020, eqn 13; Feng 2018, eqn 6-14): the twist of Feng 2018, §6.4 "
                          "branches off")
            else:
                detail = ("rows 0 and 1: vertical edges fold flat, r_A0 = r_A1 = 0 (Feng 2018, §6.2.3); even m has no "
                          "rigid twist")
            if np.max(np.abs(radii)) < 1e-9 * self.a:
                detail += ("; every row is fully folded, the equal-diameter cylinder of beta = beta_max (Feng, Ma "
                           "and Chen 2020, eqn 40): a bifurcation where the twist may start in any row "
                           "(Fig. 16)")
            return Event("lock", inside, (BRANCH,), detail)
        rows = self.rows(np.array([outside]))
        missing = next(((kind, i) for (kind, i), (r, _) in rows.items() if not np.isfinite(r[0])), None)
        if missing is not None:
            detail = (f"no assembly beyond: vertex {missing[0]}{missing[1]} loses its place (two circles part); "
                      "where it is the top C, the top row's up midlines are flat (Feng, Ma and Chen 2020, "
                      "eqn 14)")
            return Event("turning_point", inside, (BRANCH,), detail)
        if outside >= 0.0:
            return Event("lock", inside, (BRANCH,), "the input crease is flat (theta = 180 deg)")
        q = self.folds(np.array([outside]))[0]
        names = ", ".join(self.crease_names[k] for k in np.flatnonzero(reversed_creases(self.layout, q))[:4])
        return Event("lock", inside, (BRANCH,), f"creases {names} fold flat and would reverse (strict criterion)")

    def events(self) -> tuple[Event, ...]:
        lo, hi = self.domain
        out = [self._end(lo, lo - 1e-7), self._end(hi, hi + 1e-7)]
        bottom, top = row_range(self.m)
        crossings: dict[float, list[int]] = {}
        for i in range(bottom, top + 1):
            if i in (0, 1 - self.m % 2):
                continue  # the middle rows end the domain instead
            for x in sign_changes(lambda x, i=i: self.radii(x)[:, i - bottom], lo, hi):
                crossings.setdefault(round(x, 9), []).append(i)
        for x, rows in crossings.items():
            names = ", ".join(f"{i - bottom} (the sources' row {i})" for i in rows)
            detail = (f"rows {names}: r_A = 0, the vertical edges fold flat onto each other (kappa_Bi,4 = 0, Feng, Ma "
                      "and Chen 2020, eqn 15); where r_A < 0 the rigid tube penetrates itself: the "
                      "mechanism-structure-mechanism transition (Feng 2018, §6.2.2)")
            out.append(Event("lock", x, (BRANCH,), detail))
        first = 0 if self.m % 2 else 1
        if top > first:
            for x in sign_changes(
                lambda x: np.diff(self.radii(x)[:, first - bottom : first - bottom + 2])[:, 0], lo, hi
            ):
                r = self.radii(np.array([x]))[0]
                if np.ptp(r) < 1e-9 * self.a:
                    detail = (f"uniform radius r_A = {r[0]:.6g} m: every row alike (Feng 2018, eqn 6-22); the radius "
                              "profile changes sign here, and a truncated tube may switch motion (§6.3)")
                    out.append(Event("uniform_radius", x, (BRANCH,), detail))
        return tuple(sorted(out, key=lambda e: e.input))

    # -- symmetry couplings ------------------------------------------------------------------------------------
    @cached_property
    def couplings(self) -> tuple[tuple[str, str], ...]:
        """
        Couplings rho_a = rho_b that pin the free tube (4n - 6 DOF) to the contraction path: every spanning-tree
        crease coupled to the first tree crease of its symmetry class (creases whose closed-form angles agree at two
        generic inputs, to CLASS_TOL; they agree to 2e-15 all along the path). Far more than the 4n - 7 needed: a
        minimal set chosen for conditioning left 3.4x the MuJoCo path error (6 x 5 tube, 9.6e-7 against 2.8e-7 rad
        at 16x), as each soft coupling then carries more of the load.

        Raises
        ------
        AssemblyError
          If the couplings leave more than one degree of freedom (rank of the coupled closure at mid-range).
        """
        lo, hi = self.domain
        q = self.folds(lo + (hi - lo) * np.array([0.5, 0.3819660113, 0.6180339887]))
        out, dof = self.symmetry_classes(q)
        if dof != 1:
            theta = np.rad2deg(np.pi + lo + 0.5 * (hi - lo))
            raise AssemblyError(f"the symmetry couplings leave {dof} degrees of freedom at theta = {theta:.6g} deg; "
                                "the contraction needs 1")
        return tuple(out)
