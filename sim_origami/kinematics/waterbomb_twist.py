"""Generalized waterbomb tube, twist of the fully folded middle row (Feng, Ma and Chen 2020, §3,
eqns 24-41; Feng 2018, §6.4; "the sources" below).

The tube, its names, flat strip, seam, vertex loops, ring loop and fold-angle measurement are those of
`waterbomb_tube` (imported, not copied); m must be odd. Fold angles rho: `sim_origami.creases` (0 flat, > 0 valley
seen from the flat sheet's +z, which ends up outside the tube); the sources' dihedrals are phi = pi - s rho (s = +1
valley, -1 mountain). Every fold angle is reported in (s pi/2 - pi, s pi/2 + pi] (`unwrapped`): the middle row's
vertical edges sit at rho = -pi all along the twist, and a fully folded crease must not flip between -pi and +pi.

Input. x = rho of A<r0>_0_2, the upper-right diagonal of unit 0 of the middle row (row 0): the sources' input eta02
= pi - x (Feng, Ma and Chen 2020, §3, Table 1). The tube axis is +z, slot p at azimuth p pi / n as in `waterbomb_tube`.

Model (an explicit construction of the twist of Feng 2018, §6.4, derived here; checked against the worked twist states
and limits of Feng, Ma and Chen 2020, §3, in tests/published/feng_ma_chen2020.py). At the end of the contraction (eta01
= 2 pi / n) every A_0 is on the axis and the middle row's vertical edges are folded flat (kappa_B0,4 = 0); they stay so
during the twist. Put every A_0 at the origin; the vertical edge of slot p (odd) has its midpoint E at radius a, azimuth
p pi / n, height 0, and turns about the radius through E: its direction is u = cos(zeta) e_psi + sin(zeta) e_z (zeta =
pi/2 untwisted), so B_0 = E + a cot(alpha) u and C_-1 = E - a cot(alpha) u. B_0 then sits at radius a sqrt(1 +
cot^2(alpha) cos^2(zeta)), height a cot(alpha) sin(zeta), azimuth p pi / n + delta with delta = atan(cot(alpha)
cos(zeta)). The upper half (the B_0 and C_0 rings and every row above) is plane-symmetric about the meridians at p pi /
n + delta, like the contraction: C_0 meets A_0 (the origin) and the B_0's (`waterbomb_tube.meet`), then A_i, B_i, C_i
row by row with the contraction's chain. The lower half is the image of the upper under the half-turn about the
horizontal radius at azimuth 0 (through unit 0's A_0 midline): A_i <-> A_-i, B_i <-> C_(-i-1), slot p <-> -p, so its
vertices sit at azimuth p pi / n - delta, height -z. The relative end-ring twist (top end ring against the bottom one,
about +z, from the untwisted state) is 2 delta; positive is counter-clockwise seen from +z. zeta < pi/2 turns the upper
half counter-clockwise and folds eta02 to 0 (the sources' counter-clockwise twist, Feng, Ma and Chen 2020, Fig 13a);
zeta > pi/2 clockwise, to eta03 = eta06 = 0 (Fig 13b). The sources' quartic (34) is not needed: zeta(x) inverts the
monotone map x(zeta) (checked at build) by a table, one Newton and one secant step (`WaterbombTwist.tilt`). `evaluate`
measures one crease per symmetry class (`waterbomb_tube.FoldPlan`) and copies it to the rest of its class.

Symmetry of the twist (which creases are equal along it). The tube keeps the dihedral group D_n: the n-fold turn about
the axis (units of a row alike) and the half-turns about the horizontal radii through each A_0 midline and each row-0
vertical edge (row i <-> -i; A creases 1 <-> 4, 2 <-> 5, 3 <-> 6; vertical edges of rows i <-> -i; the row
boundaries above row i <-> those below row -i). On top, each half is plane-symmetric about its meridians: in every row
but the middle one, creases 2 = 6 and 3 = 5 of A and the two row boundaries of a unit are equal, as are the two row
boundaries on each side of the middle row (kappa_B0,2 = kappa_B0,6). The middle row's A is line- but not
plane-symmetric: eta01 = eta04, eta02 = eta05, eta03 = eta06 (Feng, Ma and Chen 2020, eqn 24). `couplings` couples every
spanning-tree crease to the first tree crease of its class (classes found from the closed form, as the contraction model
does). The radial contraction has all of these symmetries too, so it satisfies the couplings: the coupled closure
carries both paths, crossing at the bifurcation (mobility 2 there, 1 elsewhere on either).

Branches (input x): "twist-ccw" (x from the start to the counter-clockwise end), "twist-cw" (from the clockwise end to
the start) and the contraction seen from this input ("radial-contraction", `WaterbombTube` at eta01 = 2 atan(tan(eta02 /
2) / cos(alpha)), Feng, Ma and Chen 2020, eqn 9, from its upper end to the start), which crosses the twist at the start
x_b = pi - 2 atan(cos(alpha) tan(pi/n)) (eqn 39a).

Domain of the twist: the interval of zeta around pi/2 on which every vertex is placed, the middle row's diagonals are
not folded through (eta02 >= 0 and eta03 >= 0: limits (a), (b), the big and small triangles of the middle units
coincide) and no crease is reversed through flat (`waterbomb_tube.reversed_creases`, the strict criterion;
`tilt_range(strict=False)` is the sources' "chain real"); the top row deploying (eqn 14, limit (c)) shows as a vertex
losing its place. Rows whose A's cross the axis (r_A = 0, kappa_Bi,4 = 0: limit (d), eqn 15) are lock events inside the
domain, as in `waterbomb_tube` (interference; the twist ranges of Feng, Ma and Chen 2020, Fig 14c, as reproduced here,
keep it too): with beta > beta_max (eqn 40) rows +-1 already start through the axis.

Other rows (Feng, Ma and Chen 2020, §3 and Fig 16 paths I and III). At beta = beta_max the contraction ends in the fully
folded equal-diameter cylinder (configuration iii: every row's A's on the axis), from which any row may twist (`row` =
row k: +1 top, path I; -1 bottom, path III; 0 the middle, path II). The construction above builds each side of the
twisting row outward by the chain, so a row's place does not depend on the rows farther out (as for the contraction,
Feng, Ma and Chen 2020, Fig 7): the twist of row k in the m-row tube is the middle-row twist of the m + 2 |k| row tube,
its rows i - k kept as rows i (`twist_rows`; slots shift by k, which turns the whole tube by k pi / n and leaves
every fold angle as it is). Checked, not assumed: every vertex loop and the ring closes to 5.4e-15 along both senses,
and the start equals the contraction's end at theta = 2 pi / n (configuration iii) to 8.9e-16 rad (n6 m3 alpha 40, rows
-1, 0, 1; tests/test_waterbomb_twist_rows.py). The input is then the twisting row's A<k + r0>_0_2; the limits (a), (b)
apply to its diagonals, (c), (d) to the other rows, which touch the axis at the start (r_A = c (zeta - pi/2)^2, not a
crossing). For beta != beta_max the row k is not fully folded where the contraction ends (r_A = -1.615 a (beta -
beta_max) for rows +-1 of n6 alpha 40), so its twist would start from a state off the contraction: refused unless |r_A|
<= FOLDED_TOL a there. The half-turn about the horizontal radius through the middle row at azimuth (k mod 2) pi / n maps
the twist of row k onto that of row -k at the same input and end-ring twist: on the flat strip the point reflection A_i
<-> A_-i, B_i <-> C_(-i-1), slot p <-> 2 (k mod 2) - p (the input A<k + r0>_0_2 <-> A<r0 - k>_0_5, equal to A<r0 -
k>_0_2 by the twisting row's line symmetry; checked in the tests). Only the twist is modelled for row != 0: its
couplings (found from the closed form as for row 0; 91 on the 6 x 3 tube) make the twisting row's A line-symmetric
(eta01 = eta04), which the radial contraction breaks in rows +-1 (its coupled residual 0.80), so "radial-contraction" is
not a branch of that model (the contraction is the row-0 model's).
"""

from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import AssemblyError, ParameterError
from ..geometry import wrap
from .base import Branch, Event, JointSpaceKinematics, as_inputs, domain_of
from .waterbomb_tube import BRANCH as CONTRACTION
from .waterbomb_tube import (
    GRID,
    PLAN_PROBES,
    FoldPlan,
    Position,
    TubeLayout,
    TubeLoops,
    WaterbombTube,
    alpha_limit,
    assignment_signs,
    beta_max,
    crease_folds,
    fold_angles,
    fold_plan,
    lengths,
    meet,
    reversed_creases,
    row_range,
    sign_changes,
    tube_positions,
)

CCW = "twist-ccw"
CW = "twist-cw"
# The domain's ends are told apart by evaluating this far (rad of zeta) beyond them.
BEYOND = 1e-7
# A row is fully folded (its A's on the axis) where |r_A| <= FOLDED_TOL a, the threshold `waterbomb_tube` reports the
# equal-diameter cylinder with. A row other than the middle one twists from the contraction's end only if it is fully
# folded there, i.e. beta = beta_max: r_A(+-1) = -1.615 a (beta - beta_max) (rad) at the end (n6 m3 alpha 40,
# measured), so |beta - beta_max| <= 6.2e-10 rad (3.5e-8 deg); the twist's start then differs from the contraction's
# end by <= 6.93 |beta - beta_max| = 4.3e-9 rad of fold angle (measured), below MuJoCo's fast target 1e-7 rad.
FOLDED_TOL = 1e-9


def start_input(n: int, alpha: float) -> float:
    """The twist's start x_b (rad): eta02 = 2 atan(cos(alpha) tan(pi/n)) on the fully folded middle row (eqn 39a)."""
    return float(np.pi - 2 * np.arctan(np.cos(alpha) * np.tan(np.pi / n)))


def ring_twist(alpha: float, zeta: ArrayLike) -> NDArray[np.float64]:
    """Relative end-ring twist 2 delta (rad, counter-clockwise about +z positive) at side-edge tilts zeta (rad)."""
    return 2 * np.arctan(np.cos(np.asarray(zeta, dtype=float)) / np.tan(alpha))


def middle_row(
    n: int, alpha: float, beta: float, a: float, zeta: ArrayLike
) -> tuple[dict[tuple[str, int], tuple[NDArray, NDArray]], NDArray[np.float64]]:
    """(r, z) in m of A_0, B_0 and C_0, {(kind, 0): (r (N,), z (N,))}, and the upper half's azimuth offset delta (N,)
    (rad) at side-edge tilts zeta (N,) (rad) (module docstring)."""
    zeta = np.atleast_1d(np.asarray(zeta, dtype=float))
    w, b0, c0 = middle_points(n, alpha, beta, a, zeta)
    return {("A", 0): (np.zeros_like(zeta), np.zeros_like(zeta)), ("B", 0): b0, ("C", 0): c0}, np.arctan2(w, a)


def middle_points(
    n: int, alpha: float, beta: float, a: float, zeta: NDArray[np.float64]
) -> tuple[NDArray[np.float64], tuple[NDArray, NDArray], tuple[NDArray, NDArray]]:
    """w = a cot(alpha) cos(zeta) (N,) (m) and (r, z) in m of B_0 and C_0 at side-edge tilts zeta (N,) (rad): B_0 at
    (hypot(a, w), a cot(alpha) sin(zeta)), C_0 where it meets A_0 (the origin) and B_0 (module docstring)."""
    L = lengths(alpha, beta, a)
    w = L.corner * np.cos(zeta)
    b0 = (np.hypot(a, w), L.corner * np.sin(zeta))
    return w, b0, meet((0.0, 0.0), L.midline, b0, L.boundary, n)


def twist_rows(
    n: int, m: int, alpha: float, beta: float, a: float, zeta: ArrayLike, row: int = 0
) -> tuple[dict[tuple[str, int], tuple[NDArray, NDArray]], NDArray[np.float64]]:
    """
    (r, z) in m of every vertex kind and row, {(kind, row): (r (N,), z (N,))}, and the upper half's azimuth
    offset delta (N,) (rad), at side-edge tilts zeta (N,) (rad), row `row` twisting; NaN where a vertex cannot
    be placed. Row `row` != 0: the middle-row twist of the m + 2 |row| row tube, its rows i - row kept as rows
    i (module docstring, "Other rows").
    """
    if row:
        rows, delta = twist_rows(n, m + 2 * abs(row), alpha, beta, a, zeta)
        bottom, top = row_range(m)
        kept = {(kind, i): rz for (kind, i), rz in rows.items() if bottom - (kind != "A") <= i + row <= top}
        return {(kind, i + row): rz for (kind, i), rz in kept.items()}, delta
    L = lengths(alpha, beta, a)
    bottom, top = row_range(m)
    rows, delta = middle_row(n, alpha, beta, a, zeta)
    for i in range(1, top + 1):  # the contraction's chain (waterbomb_tube.row_coordinates)
        rows["A", i] = meet(rows["B", i - 1], L.midline, rows["C", i - 1], L.diagonal, n)
        rows["B", i] = meet(rows["C", i - 1], L.vertical, rows["A", i], L.diagonal, n)
        rows["C", i] = meet(rows["A", i], L.midline, rows["B", i], L.boundary, n)
    for i in range(bottom, 0):  # half-turn: A_i <-> A_-i, B_j <-> C_(-j-1), z -> -z
        r, z = rows["A", -i]
        rows["A", i] = (r, -z)
    for j in range(bottom - 1, 0):
        (rb, zb), (rc, zc) = rows["C", -j - 1], rows["B", -j - 1]
        rows["B", j], rows["C", j] = (rb, -zb), (rc, -zc)
    return rows, delta


def middle_input(n: int, alpha: float, beta: float, a: float, zeta: ArrayLike) -> NDArray[np.float64]:
    """
    The input x (N,) = rho of A<r0>_0_2 (rad, in (-pi/2, 3 pi/2]) at side-edge tilts zeta (N,) (rad), from A_0 (the
    origin), B_0 (slot 1), C_0 (slot 0) and C_-1 (slot 1) alone: the rotation about A_0 -> B_0 of the small face
    (A_0, B_0, C_0) (left) relative to the big face (A_0, C_-1, B_0) (right), as `waterbomb_tube.fold_angles`.
    """
    rows, delta = middle_row(n, alpha, beta, a, zeta)
    (rb, zb), (rc, zc) = rows["B", 0], rows["C", 0]

    def point(r: NDArray, psi: NDArray, z: NDArray) -> NDArray:
        return np.stack([r * np.cos(psi), r * np.sin(psi), z], -1)

    B = point(rb, np.pi / n + delta, zb)
    left = np.cross(B, point(rc, delta, zc))
    right = -np.cross(B, point(rb, np.pi / n - delta, -zb))
    sine = np.sum(np.cross(right, left) * B, axis=-1) / np.linalg.norm(B, axis=-1)
    return np.pi / 2 + wrap(np.arctan2(sine, np.sum(right * left, axis=-1)) - np.pi / 2)


def expanded_middle_input(n: int, alpha: float, beta: float, a: float, zeta: ArrayLike) -> NDArray[np.float64]:
    """
    `middle_input` with its cross products multiplied out, which `WaterbombTwist.tilt` inverts (3x faster; the two
    agree within 8.9e-16 rad on the twists of the tests). In the frame turned by -delta about the axis C_0 lies at
    azimuth 0, B_0 at pi/n and C_-1 at pi/n - 2 delta, with cos(delta) = a / r_B, sin(delta) = w / r_B; with left =
    B x C_0 and right = C_-1 x B, (right x left).B / |B| = |B| det(C_-1, B, C_0) and right.left = (C_-1.B)(B.C_0) -
    (C_-1.C_0)(B.B).
    """
    w, (rb, zb), (rc, zc) = middle_points(n, alpha, beta, a, np.atleast_1d(np.asarray(zeta, dtype=float)))
    cn, sn = np.cos(np.pi / n), np.sin(np.pi / n)
    bx, by = rb * cn, rb * sn
    mx, my = (cn * (a * a - w * w) + sn * 2 * a * w) / rb, (sn * (a * a - w * w) - cn * 2 * a * w) / rb
    det = mx * by * zc + my * (zb * rc - bx * zc) + zb * by * rc
    b_b = rb * rb + zb * zb
    cosine = (mx * bx + my * by - zb * zb) * (bx * rc + zb * zc) - (mx * rc - zb * zc) * b_b
    return unwrapped_fold(np.arctan2(np.sqrt(b_b) * det, cosine), 1.0)


def upper_half(layout: TubeLayout, row: int = 0) -> NDArray[np.bool_]:
    """Per vertex key: in the upper half of the twist of row `row` (B_i, C_i with i >= row, A_i with i >= row +
    1; the A_row are on the axis)."""
    return np.array([i >= row + (1 if kind == "A" else 0) for kind, i, _ in layout.keys])


def twist_vertices(layout: TubeLayout, zeta: ArrayLike, row: int = 0) -> NDArray[np.float64]:
    """3-D vertices (N, len(layout.keys), 3) in m at side-edge tilts zeta (N,) (rad) of the twist of row `row`,
    axis +z (module docstring)."""
    rows, delta = twist_rows(layout.n, layout.m, layout.alpha, layout.beta, layout.a, zeta, row)
    names = list(rows)
    pick = np.array([names.index((kind, i)) for kind, i, _ in layout.keys])
    r = np.stack([rows[key][0] for key in names], -1)[:, pick]
    z = np.stack([rows[key][1] for key in names], -1)[:, pick]
    side = np.where(upper_half(layout, row), 1.0, -1.0)
    psi = np.array([p for _, _, p in layout.keys]) * np.pi / layout.n + side * delta[:, None]
    return np.stack([r * np.cos(psi), r * np.sin(psi), z], -1)


def twist_positions(
    layout: TubeLayout, rows: dict[tuple[str, int], tuple[NDArray, NDArray]], delta: NDArray, upper: NDArray[np.bool_]
) -> Position:
    """
    The `Position` (`waterbomb_tube.crease_folds`) of the twist's vertices at `rows` and offset delta (`twist_rows`),
    turned by -delta about the axis (which leaves every fold angle as it is): the upper half (`upper`, per vertex key)
    at azimuth p pi / n, the lower half at p pi / n - 2 delta. Each vertex is computed once.
    """
    c2, s2 = np.cos(2 * delta), np.sin(2 * delta)
    cache: dict[int, tuple[NDArray, NDArray, NDArray]] = {}
    turned: dict[int, tuple[NDArray, NDArray]] = {}

    def position(v: int) -> tuple[NDArray, NDArray, NDArray]:
        if v not in cache:
            kind, i, p = layout.keys[v]
            r, z = rows[kind, i]
            cp, sp = np.cos(p * np.pi / layout.n), np.sin(p * np.pi / layout.n)
            if upper[v]:
                cache[v] = (r * cp, r * sp, z)
            else:
                if p not in turned:
                    turned[p] = (cp * c2 + sp * s2, sp * c2 - cp * s2)
                cos, sin = turned[p]
                cache[v] = (r * cos, r * sin, z)
        return cache[v]

    return position


def unwrapped_fold(q: NDArray[np.float64], sign: float) -> NDArray[np.float64]:
    """`unwrapped` for fold angles q in [-pi, pi] (arctan2's range) of creases with M/V sign `sign` (+1 valley, -1
    mountain): q moved to (sign pi/2 - pi, sign pi/2 + pi], i.e. a valley's q <= -pi/2 and a mountain's q > pi/2
    turned by 2 pi."""
    if sign > 0:
        return np.where(q <= -np.pi / 2, q + 2 * np.pi, q)
    return np.where(q > np.pi / 2, q - 2 * np.pi, q)


def unwrapped(layout: TubeLayout, q: ArrayLike, creases: ArrayLike | None = None) -> NDArray[np.float64]:
    """Fold angles (..., n) of all creases (or the indices `creases`) moved to (s pi/2 - pi, s pi/2 + pi] (rad), s =
    +1 valley, -1 mountain: a fully folded crease reads s pi, never -s pi."""
    s = assignment_signs(layout)
    s = s if creases is None else s[np.asarray(creases)]
    return s * np.pi / 2 + wrap(np.asarray(q, dtype=float) - s * np.pi / 2)


def twist_folds(
    layout: TubeLayout, zeta: ArrayLike, creases: ArrayLike | None = None, row: int = 0
) -> NDArray[np.float64]:
    """Fold angles (N, n) of all creases (or the indices `creases`) at side-edge tilts zeta (N,) (rad) of the twist
    of row `row`, `unwrapped`; NaN where the tube does not assemble."""
    with np.errstate(invalid="ignore", divide="ignore"):
        q = fold_angles(layout, twist_vertices(layout, zeta, row), creases)
    return unwrapped(layout, q, creases)


def middle_diagonals(layout: TubeLayout, row: int = 0) -> tuple[int, int]:
    """Indices of A<r>_0_2 (the input, eta02) and A<r>_0_3 (eta03 = eta06) of row `row` (named r = row + r0)
    in layout.creases."""
    r = row - row_range(layout.m)[0]
    return layout.index(f"A{r}_0_2"), layout.index(f"A{r}_0_3")


def twist_checks(layout: TubeLayout, zeta: ArrayLike, row: int = 0) -> dict[str, NDArray[np.bool_]]:
    """
    The domain's conditions (N,) at side-edge tilts zeta (N,) of the twist of row `row` (module docstring):
    'placed' (every vertex), 'diagonals' (the twisting row's eta02, eta03 >= 0), 'unreversed' (no crease reversed
    through flat). Unit 0 of each row stands for its row.
    """
    zeta = np.atleast_1d(np.asarray(zeta, dtype=float))
    picks = np.concatenate([layout.unit0, middle_diagonals(layout, row)])
    q = twist_folds(layout, zeta, picks, row)
    with np.errstate(invalid="ignore"):
        return {
            "placed": np.all(np.isfinite(q), axis=-1),
            "diagonals": np.all(q[:, -2:] <= np.pi, axis=-1),
            "unreversed": ~np.any(reversed_creases(layout, q, picks), axis=-1),
        }


def valid_tilts(layout: TubeLayout, zeta: ArrayLike, strict: bool = True, row: int = 0) -> NDArray[np.bool_]:
    """Where the twist of row `row` is a rigid motion (N,) at side-edge tilts zeta (N,) (rad): every
    `twist_checks` holds; `strict=False` drops 'unreversed', the sources' criterion (the chain real, Feng, Ma and
    Chen 2020, §3)."""
    checks = twist_checks(layout, zeta, row)
    if not strict:
        del checks["unreversed"]
    return np.logical_and.reduce(list(checks.values()))


def tilt_range(layout: TubeLayout, strict: bool = True, row: int = 0) -> tuple[float, float] | None:
    """The range of side-edge tilts zeta (rad) of the twist of row `row`: the interval around pi/2 where
    `valid_tilts` holds, its ends bisected to about 1e-13 (`base.domain_of`); None where the start is not valid."""
    try:
        return domain_of(lambda z: valid_tilts(layout, z, strict, row), 1e-9, np.pi - 1e-9, np.pi / 2, GRID)
    except ParameterError:
        return None


def twisting_row(m: int, row: float) -> int:
    """The row `row` of an m-row tube as an int; ParameterError unless it is one of the tube's rows."""
    bottom, top = row_range(m)
    if row != int(row) or not bottom <= row <= top:
        rows = ", ".join(str(i) for i in range(bottom, top + 1))
        raise ParameterError(
            f"row = {row:g}; the {m}-row tube twists in one of its rows {rows} (0 the middle row, {top} the top)"
        )
    return int(row)


class WaterbombTwist(TubeLoops, JointSpaceKinematics):
    """
    The n x m waterbomb tube (m odd) twisting from its fully folded middle row, and its radial contraction, driven
    by x = rho of crease A<r0>_0_2 (eta02 = pi - x); module docstring for frames, signs and the model.

    Parameters
    ----------
    n : int
      Units round the tube, >= 3.
    m : int
      Rows, odd (the twist needs a middle row, Feng, Ma and Chen 2020, §3).
    alpha, beta : float
      Design angles (rad): alpha in (0, `alpha_limit`(n)) (eqn 38), beta in (0, pi/2); above `beta_max`(alpha, n)
      (eqn 40) rows +-1 start through the axis (lock events where they leave it).
    a : float
      Half-width of a unit (m).
    row : int
      Row that twists (0 the middle row, +1 the one above it, ...; module docstring, "Other rows"); a row other
      than 0 only at beta = beta_max (|r_A| <= FOLDED_TOL a where the contraction ends), without the contraction
      branch. The input is that row's A<row + r0>_0_2.

    Raises
    ------
    ParameterError
      For a geometry out of range, one whose middle row cannot fully fold or twist rigidly, a row that is not one of
      the tube's rows, or a row other than 0 that is not fully folded where the contraction ends.
    """

    def __init__(self, n: int, m: int, alpha: float, beta: float, a: float = 1.0, row: int = 0):
        if int(m) == m and m % 2 == 0:
            raise ParameterError(f"m = {m:g} rows; the rigid twist needs an odd m, a middle row to fold "
                                  "(Feng, Ma and Chen 2020, §3)")
        if int(n) == n and n >= 3 and alpha >= alpha_limit(int(n)):
            raise ParameterError(
                f"alpha = {np.rad2deg(alpha):.6g} deg is not below the twist's limit "
                f"{np.rad2deg(alpha_limit(int(n))):.6g} deg for n = {n:g} (tan(alpha) = 1/cos(pi/n), "
                "Feng, Ma and Chen 2020, eqn 38)"
            )
        self.tube = WaterbombTube(n, m, alpha, beta, a)  # checks n, m, alpha, beta, a and the contraction
        tube = self.tube
        self.n, self.m, self.alpha, self.beta, self.a = tube.n, tube.m, tube.alpha, tube.beta, tube.a
        self.layout = self.tube.layout
        self.pattern = self.layout.pattern
        self.crease_names = self.layout.names
        self.joint_names = tuple(f"rho_{c}" for c in self.crease_names)
        self.row = twisting_row(self.m, row)
        self.input_crease = self.crease_names[middle_diagonals(self.layout, self.row)[0]]
        self.input_name = f"rho_{self.input_crease}"
        self.start = start_input(self.n, self.alpha)
        if abs(self.tube.domain[0] - (2 * np.pi / self.n - np.pi)) > 1e-9:  # bisected ends sit 1e-13 inside
            raise ParameterError(
                f"the {self.n} x {self.m} tube (alpha = {np.rad2deg(alpha):.6g}, beta = {np.rad2deg(beta):.6g} deg) "
                f"cannot contract to its fully folded middle row: its contraction starts at eta01 = "
                f"{np.rad2deg(np.pi + self.tube.domain[0]):.6g} deg, not 360/n (Feng, Ma and Chen 2020, eqn 13)"
            )
        if self.row:
            self._check_folded_row()
        self.tilts = self._tilts()
        self.domain = (float(self.input_of(self.tilts[1])[0]), float(self.input_of(self.tilts[0])[0]))

    def _check_folded_row(self) -> None:
        """ParameterError unless the twisting row is fully folded where the contraction ends (theta = 2 pi / n):
        |r_A| <= FOLDED_TOL a there, i.e. beta = beta_max (eqn 40) to about 6e-10 rad (FOLDED_TOL)."""
        bottom = row_range(self.m)[0]
        radius = float(self.tube.radii(np.array([2 * np.pi / self.n - np.pi]))[0, self.row - bottom])
        if abs(radius) > FOLDED_TOL * self.a:
            raise ParameterError(
                f"beta = {np.rad2deg(self.beta):.10g} deg is not beta_max = "
                f"{np.rad2deg(beta_max(self.alpha, self.n)):.10g} deg (Feng, Ma and Chen 2020, eqn 40): "
                f"row {self.row} "
                f"has r_A = {radius / self.a:.3g} a where the contraction ends (theta = 360/n), not fully folded "
                f"(|r_A| <= {FOLDED_TOL:g} a), so its twist does not start from the contraction; only the middle row "
                "(row 0) twists from there unless beta = beta_max (Fig 16)"
            )

    # -- closed form -------------------------------------------------------------------------------------------
    def _tilts(self) -> tuple[float, float]:
        """The twist's range of zeta (rad) (`tilt_range`); x(zeta) checked strictly decreasing on it."""
        tilts = tilt_range(self.layout, row=self.row)
        if tilts is None:
            raise ParameterError(
                f"the {self.n} x {self.m} tube (alpha = {np.rad2deg(self.alpha):.6g}, beta = "
                f"{np.rad2deg(self.beta):.6g} deg) has no rigid state at the twist's start (Feng, Ma and Chen 2020, §3)"
            )
        x = self.input_of(np.linspace(*tilts, GRID))
        if not np.all(np.diff(x) < 0):
            raise AssemblyError(f"eta02 is not monotone in the side-edge tilt on [{tilts[0]:.6g}, {tilts[1]:.6g}] rad")
        return tilts

    def input_of(self, zeta: ArrayLike) -> NDArray[np.float64]:
        """The input x (N,) = rho of A<r0>_0_2 (rad) at side-edge tilts zeta (N,) (rad)."""
        return middle_input(self.n, self.alpha, self.beta, self.a, zeta)

    @cached_property
    def _tilt_table(self) -> tuple[float, float, NDArray[np.float64], NDArray[np.float64]]:
        """zeta(x) at GRID inputs x_0 + k h over the twist's domain, interpolated in `input_of` on 16 GRID tilts:
        (x_0, h, zeta (GRID,), its differences (GRID - 1,))."""
        zeta = np.linspace(*self.tilts, 16 * GRID)[::-1]
        lo, hi = self.domain
        table = np.interp(np.linspace(lo, hi, GRID), self.input_of(zeta), zeta)
        return lo, (hi - lo) / (GRID - 1), table, np.diff(table)

    def tilt(self, x: ArrayLike) -> NDArray[np.float64]:
        """
        Side-edge tilt zeta (N,) (rad) at inputs x (N,) inside the twist's domain (x falls with zeta): `_tilt_table`
        interpolated, one Newton step with the table's slope and one secant step on `expanded_middle_input`, which
        leave it within 5.5e-8, 7.7e-12 and 2.1e-15 rad of the root (measured on the twists of the tests); NaN at NaN.
        """
        x = as_inputs(x)
        x0, h, table, steps = self._tilt_table
        u = np.clip((x - x0) / h, 0.0, GRID - 1)
        k = np.where(u < GRID - 1, u, GRID - 2).astype(np.intp)  # NaN to GRID - 2, then NaN through u - k
        z0 = table[k] + (u - k) * steps[k]
        f0 = expanded_middle_input(self.n, self.alpha, self.beta, self.a, z0) - x
        z1 = np.clip(z0 - f0 * steps[k] / h, *self.tilts)
        f1 = expanded_middle_input(self.n, self.alpha, self.beta, self.a, z1) - x
        moved = f1 != f0
        return np.clip(z1 - np.where(moved, f1 * (z1 - z0) / np.where(moved, f1 - f0, 1.0), 0.0), *self.tilts)

    def contraction_theta(self, x: ArrayLike) -> NDArray[np.float64]:
        """The contraction's eta01 (rad) at inputs x: tan(eta02 / 2) = cos(alpha) tan(eta01 / 2) (Feng, Ma and
        Chen 2020, eqn 9)."""
        eta02 = np.pi - np.asarray(x, dtype=float)
        return 2 * np.arctan(np.tan(eta02 / 2) / np.cos(self.alpha))

    def contraction_input(self, theta: ArrayLike) -> NDArray[np.float64]:
        """The input x (rad) at the contraction's eta01 = theta (rad), eqn 9."""
        return np.pi - 2 * np.arctan(np.cos(self.alpha) * np.tan(np.asarray(theta, dtype=float) / 2))

    def _twist(self, branch: str) -> bool:
        """Whether `branch` is a twist (not the contraction); ParameterError for an unknown name."""
        return self.branch(branch).name != CONTRACTION

    def vertices(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """3-D vertices (N, len(layout.keys), 3) in m at inputs x (N,) on `branch` (no domain check)."""
        x = as_inputs(x)
        if not self._twist(branch):
            return self.tube.vertices(self.contraction_theta(x) - np.pi)
        return twist_vertices(self.layout, self.tilt(x), self.row)

    def folds(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """Fold angles (N, n_creases) (rad, `unwrapped`) at inputs x (N,) on `branch` (no domain check)."""
        x = as_inputs(x)
        if not self._twist(branch):
            return unwrapped(self.layout, self.tube.folds(self.contraction_theta(x) - np.pi))
        return twist_folds(self.layout, self.tilt(x), row=self.row)

    def end_twist(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """Relative end-ring twist (N,) (rad, counter-clockwise about +z positive) at inputs x (N,); 0 on the
        contraction."""
        x = as_inputs(x)
        return ring_twist(self.alpha, self.tilt(x)) if self._twist(branch) else np.zeros_like(x)

    def radii(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """Signed radius r_A (N, m) in m of each row's A vertices, rows bottom to top, at inputs x (N,)."""
        x = as_inputs(x)
        if not self._twist(branch):
            return self.tube.radii(self.contraction_theta(x) - np.pi)
        return self._tilt_radii(self.tilt(x))

    # -- contract ----------------------------------------------------------------------------------------------
    def branches(self) -> tuple[Branch, ...]:
        lo, hi = self.domain
        if self.row:
            which = "top" if self.row > 0 else "bottom"
            return (
                Branch(CCW, f"row {self.row} ({which} side) twists from the equal-diameter cylinder (Feng, Ma "
                       "and Chen 2020, Fig 16), the rows above it turn counter-clockwise about +z against those "
                       "below: x rises, its eta02 falls to 0 or the domain's end", (self.start, hi)),
                Branch(CW, f"row {self.row} twists, the rows above it turn clockwise: x falls, its eta02 rises "
                       "and eta03 = eta06 falls to 0 or the domain's end", (lo, self.start)),
            )
        c_lo = float(self.contraction_input(np.pi + self.tube.domain[1]))
        return (
            Branch(CCW, "middle row twists, upper half turns counter-clockwise about +z against the lower half "
                   "(Feng, Ma and Chen 2020, Fig 13a): x rises, eta02 falls to 0 or the domain's end",
                   (self.start, hi)),
            Branch(CW, "middle row twists, upper half turns clockwise (Fig 13b): x falls, eta02 rises and eta03 "
                   "= eta06 falls to 0 or the domain's end", (lo, self.start)),
            Branch(CONTRACTION, "the radial contraction (waterbomb_tube) seen from eta02, from its upper end down to "
                   "the fully folded middle row, where it meets the twist", (c_lo, self.start)),
        )

    @cached_property
    def plans(self) -> dict[str, FoldPlan]:
        """Each branch's distinct fold angles (`waterbomb_tube.FoldPlan`), from `folds` at five inputs inside it."""
        out = {}
        for b in self.branches():
            lo, hi = b.domain
            out[b.name] = fold_plan(self.layout, self.folds(b.name, lo + (hi - lo) * PLAN_PROBES))
        return out

    @cached_property
    def _upper(self) -> NDArray[np.bool_]:
        return upper_half(self.layout, self.row)

    @cached_property
    def _signs(self) -> NDArray[np.float64]:
        return assignment_signs(self.layout)

    def _distinct(self, branch: str, x: NDArray[np.float64]) -> list[NDArray[np.float64]]:
        """The `plans`' representative fold angles (rad, `unwrapped`) at inputs x (N,) on `branch`."""
        creases = self.plans[branch].creases
        with np.errstate(invalid="ignore", divide="ignore"):
            if self._twist(branch):
                rows, delta = twist_rows(self.n, self.m, self.alpha, self.beta, self.a, self.tilt(x), self.row)
                position = twist_positions(self.layout, rows, delta, self._upper)
            else:
                position = tube_positions(self.layout, self.tube.rows(self.contraction_theta(x) - np.pi))
            raw = crease_folds(self.layout, position, creases)
        return [unwrapped_fold(q, sign) for q, sign in zip(raw, self._signs[creases], strict=True)]

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Fold angles of every crease: the `plans`' representatives, measured as `folds` does, copied to the rest."""
        x, valid = self.in_domain(branch, x)
        lo, hi = self.branch(branch).domain
        xs = np.where(valid, x, 0.5 * (lo + hi))
        return self.plans[branch].evaluate(xs, valid, lambda block: self._distinct(branch, block)), valid

    def _twist_end(self, branch: str, tilt: float, beyond: float) -> Event:
        """What ends the twist between the tilt `tilt` at a domain end and `beyond` just past it."""
        checks = {k: bool(v[0]) for k, v in twist_checks(self.layout, np.array([beyond]), self.row).items()}
        x = float(self.input_of(np.array([tilt]))[0])
        twist = np.rad2deg(ring_twist(self.alpha, tilt))
        where = f"zeta = {np.rad2deg(tilt):.6g} deg, end-ring twist {twist:.6g} deg"
        if not checks["placed"]:
            outer = "top row's up" if not self.row else "outermost row's outer"
            detail = (f"no assembly beyond ({where}): a vertex loses its place, the {outer} midlines flat "
                      "(Feng, Ma and Chen 2020, eqn 14, limit (c))")
            return Event("turning_point", x, (branch,), detail)
        if not checks["diagonals"]:
            crease = "eta02" if branch == CCW else "eta03 = eta06"
            units = "middle units" if not self.row else f"units of row {self.row}"
            detail = (f"{crease} = 0 ({where}): the big and small triangles of the {units} coincide (Feng, Ma "
                      "and Chen 2020, Fig 13, limits (a)/(b); the double root of eqn 41 with W5 corrected here: the "
                      "c(2 pi/n) coefficient of W5 gains 2 sin^2(alpha), and the printed W5 puts the limit at "
                      "64.975 deg, not 100.800 deg, for n6 alpha40)")
        else:
            detail = f"a crease folds flat and would reverse ({where}; strict criterion)"
        return Event("lock", x, (branch,), detail)

    def _tilt_radii(self, zeta: ArrayLike) -> NDArray[np.float64]:
        """Signed radius r_A (N, m) in m of each row's A vertices, rows bottom to top, at side-edge tilts zeta (N,)."""
        rows, _ = twist_rows(self.n, self.m, self.alpha, self.beta, self.a, zeta, self.row)
        bottom, top = row_range(self.m)
        return np.stack([rows["A", i][0] for i in range(bottom, top + 1)], -1)

    def _row_radius(self, zeta: NDArray[np.float64], row: int, touching: bool) -> NDArray[np.float64]:
        """r_A (N,) in m of row `row` at tilts zeta (N,); for a row `touching` the axis at the start (beta =
        beta_max) |r_A| <= FOLDED_TOL a reads 0: there r_A = c (zeta - pi/2)^2 (c = 0.93, 1.73 m for the rows next
        to and two from the twisting one, n6 alpha 40, measured) touches 0 with round-off of either sign (6.7e-16 m)
        and is no crossing."""
        r = self._tilt_radii(zeta)[:, row - row_range(self.m)[0]]
        return np.where(np.abs(r) <= FOLDED_TOL * self.a, 0.0, r) if touching else r

    def _crossings(self) -> list[Event]:
        """Lock events where rows' A's cross the axis during the twist (r_A = 0, their vertical edges folded flat
        onto each other: Feng, Ma and Chen 2020, limit (d), eqn 15); where r_A < 0 the rigid tube penetrates itself
        (interference, which the paper's ranges of Fig 14c keep, as reproduced here). Rows i and -i cross together
        (the half-turn)."""
        lo, hi = self.tilts
        bottom, top = row_range(self.m)
        touching = np.abs(self._tilt_radii(np.array([np.pi / 2]))[0]) <= FOLDED_TOL * self.a
        crossings: dict[float, list[int]] = {}
        for i in range(bottom, top + 1):
            if i != self.row:
                for zeta in sign_changes(lambda z, i=i: self._row_radius(z, i, touching[i - bottom]), lo, hi):
                    crossings.setdefault(round(zeta, 9), []).append(i)
        out = []
        for zeta, rows in crossings.items():
            names = ", ".join(f"{i - bottom} (row {i})" for i in rows)
            detail = (f"rows {names}: r_A = 0, the vertical edges fold flat onto each other (kappa_Bi,4 = 0, Feng, Ma "
                      "and Chen 2020, limit (d), eqn 15); where r_A < 0 the rigid tube penetrates itself")
            x = float(self.input_of(np.array([zeta]))[0])
            out.append(Event("lock", x, (CCW if zeta < np.pi / 2 else CW,), detail))
        return out

    def events(self) -> tuple[Event, ...]:
        lo, hi = self.tilts
        meet_detail = ("the fully folded middle row (eta01 = 2 pi/n, kappa_B0,4 = 0, every A_0 on the axis, Feng, Ma "
                       "and Chen 2020, eqn 13): the radial contraction ends and the twist branches off (eqn 39a); the "
                       "coupled closure's mobility is 2 here")
        if self.row:
            return self._row_events()
        through = np.flatnonzero(self._tilt_radii(np.array([np.pi / 2]))[0] < 0)
        if len(through):
            meet_detail += (f"; rows {', '.join(str(r) for r in through)} are through the axis here (beta > beta_max "
                            f"= {np.rad2deg(beta_max(self.alpha, self.n)):.6g} deg, eqn 40: interference)")
        out = [
            Event("bifurcation", self.start, (CW, CONTRACTION), meet_detail + "; the clockwise twist and the "
                  "contraction leave it on the same side of the input"),
            Event("bifurcation", self.start, (CCW,), meet_detail + "; the counter-clockwise twist leaves it on the "
                  "other side, where the contraction would fold the middle row through itself"),
            self._twist_end(CCW, lo, lo - BEYOND),
            self._twist_end(CW, hi, hi + BEYOND),
            *self._crossings(),
        ]
        for e in self.tube.events():
            if e.input > self.tube.domain[0] + 1e-9:  # the contraction's lower end is the bifurcation above
                out.append(Event(e.kind, float(self.contraction_input(np.pi + e.input)), (CONTRACTION,), e.detail))
        return tuple(sorted(out, key=lambda e: e.input))

    def _row_events(self) -> tuple[Event, ...]:
        """`events` of the twist of a row other than the middle one (module docstring, "Other rows")."""
        lo, hi = self.tilts
        meet_detail = (f"the fully folded equal-diameter cylinder (configuration iii, beta = beta_max, eqn 40): every "
                       f"row's A's on the axis; row {self.row}'s twist (Fig 16 path "
                       f"{'I' if self.row > 0 else 'III'}) branches off where the radial contraction and the other "
                       "rows' twists end or start; the coupled closure's mobility is 2 here")
        out = [
            Event("bifurcation", self.start, (CW,), meet_detail + "; the clockwise twist leaves it to smaller x"),
            Event("bifurcation", self.start, (CCW,), meet_detail + "; the counter-clockwise twist to larger x"),
            self._twist_end(CCW, lo, lo - BEYOND),
            self._twist_end(CW, hi, hi + BEYOND),
            *self._crossings(),
        ]
        return tuple(sorted(out, key=lambda e: e.input))

    @cached_property
    def couplings(self) -> tuple[tuple[str, str], ...]:
        """
        Couplings rho_a = rho_b imposing the twist's symmetry (module docstring): every spanning-tree crease coupled
        to the first tree crease of its class, the creases whose closed-form angles agree at two generic tilts (one
        each way) to CLASS_TOL.

        Raises
        ------
        AssemblyError
          If the coupled closure's mobility at a third tilt is not 1.
        """
        lo, hi = self.tilts
        q = twist_folds(self.layout, lo + (hi - lo) * np.array([0.3, 0.2, 0.7]), row=self.row)
        out, dof = self.symmetry_classes(q)
        if dof != 1:
            raise AssemblyError(f"the twist's couplings leave {dof} degrees of freedom at zeta = "
                                f"{np.rad2deg(lo + 0.3 * (hi - lo)):.6g} deg; the twist needs 1")
        return tuple(out)
