"""Census of Kokotsakis meshes built from variants of one base vertex (Peng 2018, §2.4, §2.5, Tables A2-A4).

    python scripts/kokotsakis_variants.py [n_random]      (n_random extra random bases, default 2; 9 s of CPU)

What it does. For a base degree-4 vertex (sectors alpha_12 .. alpha_41) every sector set of Peng 2018's twist
variants (Table 2-1) that is an origami vertex is listed (`variants`: each sector alpha or pi - alpha, sum 2 pi). For
each transmission type (two-fold = Path1, plane-symmetric = Path3, rotation = Path4, laid out as `kokotsakis.example`
cases 3, 4 and 1 lay them out) every choice of variant at A, B, C, D is built, kept when `check_vertices` passes
(developable, sectors in (0, pi), planar central panel), and tried on every combination of vertex branches
(`kokotsakis.branch_mismatches` at the module's PROBES): a combination closes when the largest |mismatch| is <=
CLOSE_TOL (what `Kokotsakis` does; it raises AssemblyError when none closes). A closing mesh is labelled by its
flat-sheet angles up to rotation and mirror image (`signature`): congruent to a known construction with a variant of
the base ('case 1/3/4 type': four identical vertices laid out as that case; 'example 2': congruent to eqn 2-38;
'example 2 type': Example 2's layout A = C = v, B = D = all-supplement variant of v), else 'mirror-symmetric' (the
crease pattern has a reflection symmetry, which makes the loop close on its own: each vertex's mirror image repeats its
folds), else 'new'. 'ff' marks meshes whose four vertices are flat-foldable (Kawasaki).

Measured (CLOSE_TOL = 1e-12 rad). Every closing combination closes to <= 2.3e-14 rad at every probe; every other
combination of a planar mesh misses by >= 0.036 rad at its worst probe (>= 0.308 rad for the generic vertex).

    base (deg)                     type       meshes planar closing  labels of the closing meshes
    generic 2-34 (90,70,60,140)    two-fold     16     16      8     2 case 3 type, 4 mirror-symmetric, 2 new
                                   plane-sym    16      8      8     8 new (4 classes)
                                   rotation     16      4      4     2 case 1 type, 2 new
    example 2 (80,70,100,110)      two-fold    256     96     36     16 mirror-symmetric, 20 new (3 classes)
                                   plane-sym   256     64     24     24 new (12 classes)
                                   rotation    256     64     24     4 case 1 type, 4 example 2 (1 class), 16 new
    collinear 1-3 (40,140,80,100)  rotation    256     64     16     4 case 1 type, 12 new
    collinear 2-4 (100,40,140,80)  rotation    256     64     16     4 case 1 type, 12 new; 48 more close only
                                                                     through a straight crease line (excluded, §2.5)
    random 1, 2 (generic)          two-fold     16      6      6     4 mirror-symmetric, 2 new (1 class)
                                   plane-sym    16      4      4     4 new (2 classes)
                                   rotation     16      2      2     2 case 1 type (aaaa and pppp)

Findings.
1. Example 2 is found: rotation type, A = C = base, B = D = all supplements (and its 3 relabellings), closing on
   modes S and C only.
2. The thesis's claim that Example 2 is the only new rigid-origami pattern from Tables A2-A4 does not hold. Closing
   meshes that are neither congruent to cases 1-4 / Example 2 nor mirror-symmetric: for the generic vertex 2
   (two-fold), 8 (plane-symmetric) and 2 (rotation), 7 congruence classes; for the flat-foldable base 60 (all
   flat-foldable like Example 2: 19 classes). For every generic base the two-fold type closes with A = C = base,
   B = D = the (mirrored) all-supplement variant pppp: a parallelogram, 6 branches; the plane-symmetric type with
   A = B = base, C = D = pppp (mirrored), 4 branches, and its relabellings. The rotation type closes only with
   identical vertices, as the thesis says, except for its own vertex (eqn 2-34): alpha_12 = 90 deg makes
   pi - alpha_12 = alpha_12 and adds A = base, B = C = D = pppp (and the reverse). They are rigid origami with one
   DOF per branch: `validate` passed on generic-vertex examples of all three types (closed-form residual <= 2.1e-14,
   closed form vs numeric <= 3.6e-14 rad, MuJoCo fast path error 2.1e-9 to 4.5e-8 rad, numeric = MuJoCo = truss
   mobility 1 folded and 4 at flat); the plane-symmetric one is in the tests.
3. Every vertex of these meshes lies on the same four crease lines as the base (Example 1 too): the reading of
   Table A1 derived here (a pure variant is the same linkage with reversed axes) seen in the flat sheet.
4. Table A4's legible conditions are the developability conditions of the variants beyond aaaa / pppp
   (`variant_conditions`): alpha12 + alpha23 = pi, alpha12 + alpha34 = pi (flat-foldable), alpha12 + alpha41 = pi.
   Each admits closing non-identical rotation meshes (12, 20, 12 here). Row R3R16 with 'Sigma = 2 pi' alone is no
   origami mesh for a generic base: its A = appa (eqn 2-30b) sums to 2 pi + 2 (alpha12 + alpha41 - pi), 460 deg for
   2-34, so it needs alpha12 + alpha41 = pi like R3R15R5.

Limits. The collinear bases break Peng 2018's rule (§2.5: no collinear non-adjacent creases) at every vertex; they are
here only because A4's conditions name them. Branches are probed at rho_AB in PROBES (|x| = 0.1 to 0.6 rad): a branch
that exists only below 0.1 rad, or a family with rho_AB = 0 (the straight crease lines of case 4), is not seen. Sectors
in (0, pi) admit only alpha and pi - alpha per sector, so the census covers every origami mesh that the 256 twist
variants give with these three layouts.
"""

import itertools
import sys
from dataclasses import dataclass

import numpy as np

from sim_origami.errors import ParameterError
from sim_origami.kinematics.kokotsakis import (
    CLOSE_TOL,
    MeshVertex,
    branch_mismatches,
    check_vertices,
    combination_name,
    example,
)
from sim_origami.kinematics.vertex4 import ANGLE_TOL

DEG = np.pi / 180
Sectors = tuple[float, float, float, float]
# Transmission type -> (previous, mirrored) of A, B, C, D, as the module's examples lay them out.
LAYOUTS = {
    "two-fold": tuple((v.previous, v.mirrored) for v in example(3)),  # Path1, eqn 2-15
    "plane-sym": tuple((v.previous, v.mirrored) for v in example(4)),  # Path3, eqn 2-19
    "rotation": tuple((v.previous, v.mirrored) for v in example(1)),  # Path4, eqn 2-23
}
# Base vertices (deg, Peng 2018's numbering alpha_12 .. alpha_41).
BASES = {
    "generic 2-34": (90.0, 70.0, 60.0, 140.0),
    "example 2": (80.0, 70.0, 100.0, 110.0),  # flat-foldable (eqn 2-38)
    "collinear 1-3": (40.0, 140.0, 80.0, 100.0),  # case 4's vertex: alpha_12 + alpha_23 = 180
    "collinear 2-4": (100.0, 40.0, 140.0, 80.0),  # alpha_12 + alpha_41 = 180
}
# Sector angles are rounded to this many decimals (deg) when meshes are compared for congruence.
DECIMALS = 6
# Peng 2018, Table A1 (regenerated here over the 256 variants): the class Ri of each all-sector variant code on the
# pair (theta_1, theta_2).
R_CLASS = {"aaaa": "R1", "paap": "R2", "appa": "R3", "pppp": "R4", "ppaa": "R5", "apap": "R6", "papa": "R7",
           "aapp": "R8"}
# Legible rotation-case rows of Peng 2018, Table A4: transmission -> printed condition on the base.
A4_ROWS = {
    "R2R5, R4R12, R3R13R12": "alpha12 + alpha23 = alpha34 + alpha41 = pi",
    "R3R16": "Sigma = 2 pi",
    "R2R6R5, R4R11R5": "alpha12 + alpha34 = alpha23 + alpha41 = pi",
    "R3R15R5": "alpha12 + alpha41 = alpha23 + alpha34 = pi",
}


def random_bases(count: int, seed: int = 3) -> dict[str, tuple[float, ...]]:
    """
    `count` random generic bases (deg): Dirichlet sectors summing to 360, each in [15, 165] deg, no pair of
    sectors within 5 deg of summing to 180 and none within 5 deg of 90 (so only the variants aaaa and pppp exist).
    """
    rng = np.random.default_rng(seed)
    out: dict[str, tuple[float, ...]] = {}
    while len(out) < count:
        alpha = np.round(rng.dirichlet(np.full(4, 4.0)) * 360.0, 3)
        alpha[3] = 360.0 - alpha[:3].sum()
        pairs = np.abs(alpha[:, None] + alpha[None, :] - 180.0)[np.triu_indices(4, 1)]
        if np.all((alpha >= 15) & (alpha <= 165) & (np.abs(alpha - 90) > 5)) and np.all(pairs > 5):
            out[f"random {len(out) + 1}"] = tuple(float(a) for a in alpha)
    return out


def variants(base_deg: tuple[float, ...]) -> tuple[tuple[str, Sectors], ...]:
    """
    Every developable sector set (rad) reachable from the base by Peng 2018's twist variants (Table 2-1), with
    its code ('a' = alpha, 'p' = pi - alpha per sector, the thesis's order alpha_12 .. alpha_41), distinct sets only; a
    set reached by several codes keeps the one with an even number of 'p' (a pure variant, Table A1), then fewest 'p'.

    As origami sectors lie in (0, pi), so of alpha, pi - alpha, -pi + alpha, -alpha only alpha and pi - alpha are
    sectors (-alpha and -pi + alpha are the same sectors with the link's x axis reversed). Supplementing
    sector k changes the sum by pi - 2 alpha_k: two supplements keep 2 pi iff the pair sums to pi, all four always,
    one or three only when a sector is pi/2 (then the set equals an even one).
    """
    alpha = np.asarray(base_deg, dtype=float) * DEG
    out: dict[Sectors, str] = {}
    for flips in sorted(itertools.product((0, 1), repeat=4), key=lambda f: (sum(f) % 2, sum(f), f)):
        sectors = np.where(np.array(flips) == 1, np.pi - alpha, alpha)
        if abs(sectors.sum() - 2 * np.pi) < ANGLE_TOL:
            out.setdefault(tuple(float(s) for s in sectors), "".join("ap"[f] for f in flips))
    return tuple((code, sectors) for sectors, code in out.items())


def mesh(sectors: tuple[Sectors, ...], layout: tuple[tuple[int, bool], ...]) -> tuple[MeshVertex, ...]:
    """Vertices A, B, C, D with the given sector sets laid out as `layout` (previous, mirrored)."""
    return tuple(MeshVertex(s, p, m) for s, (p, m) in zip(sectors, layout, strict=True))


def planar(vertices: tuple[MeshVertex, ...]) -> bool:
    """`check_vertices` passes: developable vertices, sectors in (0, pi), planar central panel (eqns 2-32, 2-33)."""
    try:
        check_vertices(vertices)
    except ParameterError:
        return False
    return True


def closing(tried: dict[tuple[str, ...], float], straight: bool = False) -> tuple[str, ...]:
    """
    Names of the closing combinations (mismatch <= CLOSE_TOL), as `Kokotsakis` names its branches: those with no
    vertex on a straight-line branch (`vertex4` 'straight<i><j>'), or with one if `straight`. A straight-line branch
    folds a crease line running straight across the mesh, a family of its own that Peng 2018, §2.5, excludes ("more
    than 1 DOF"; `kokotsakis.straight_lines`).
    """
    names = (combination_name(c) for c, m in tried.items() if m <= CLOSE_TOL)
    return tuple(sorted(n for n in names if ("straight" in n) == straight))


def ccw_sectors(vertex: MeshVertex) -> tuple[float, ...]:
    """Sectors (rad) counter-clockwise in the flat sheet seen from +z, starting with the central panel's corner."""
    phi = vertex.directions(0.0) % (2 * np.pi)
    return tuple(np.diff(np.append(np.sort(phi), 2 * np.pi)).tolist())


def _corners_deg(vertices: tuple[MeshVertex, ...], decimals: int) -> list[tuple[float, ...]]:
    """Each corner's `ccw_sectors` in deg, rounded to `decimals`."""
    return [tuple(np.round(np.array(ccw_sectors(v)) / DEG, decimals).tolist()) for v in vertices]


def _images(vertices: tuple[MeshVertex, ...]) -> tuple[list, list]:
    """The corners' `ccw_sectors` (deg, rounded; corners clockwise around the central panel) and its mirror image,
    which reverses the corner order and each corner's sectors after the central one."""
    corners = _corners_deg(vertices, DECIMALS)
    return corners, [(c[0], *c[:0:-1]) for c in corners[::-1]]


def signature(vertices: tuple[MeshVertex, ...]) -> tuple:
    """
    The mesh's flat-sheet angles up to congruence: `_images`, minimised over the 4 cyclic relabellings and the
    mirror image. Side lengths are left out: they do not enter the closure.
    """
    return min(tuple(seq[k:] + seq[:k]) for seq in _images(vertices) for k in range(4))


def mirror_symmetric(vertices: tuple[MeshVertex, ...]) -> bool:
    """
    True when the flat crease pattern's angles are those of its mirror image (some relabelling): a reflection
    through two opposite corners or through the midpoints of two opposite inner creases. Each vertex's mirror image
    then carries the same folds, so the loop closes by symmetry (a plane-symmetric Kokotsakis mesh, Peng 2018, §2.3,
    Path3).
    """
    corners, mirror = _images(vertices)
    return any(mirror[k:] + mirror[:k] == corners for k in range(4))


def flat_foldable(vertices: tuple[MeshVertex, ...]) -> bool:
    """Every vertex satisfies Kawasaki (alpha_12 + alpha_34 = pi)."""
    return all(abs(v.alpha[0] + v.alpha[2] - np.pi) < ANGLE_TOL for v in vertices)


def known(base_deg: tuple[float, ...]) -> dict[tuple, str]:
    """
    Signatures of the known constructions with any variant v of the base, numbered from any of its sectors:
    four identical vertices laid out as case 1 (rotation), case 3 (two-fold) or case 4 (plane-symmetric), and
    Example 2's layout (rotation, A = C = v, B = D = all-supplement variant of v), where planar; and eqn 2-38.
    """
    out = {signature(example(2)): "example 2"}
    for _, sectors in variants(base_deg):
        for k in range(4):
            v = sectors[k:] + sectors[:k]
            for case in (1, 3, 4):
                candidate = mesh((v,) * 4, tuple((u.previous, u.mirrored) for u in example(case)))
                if planar(candidate):
                    out.setdefault(signature(candidate), f"case {case} type")
            supplement = tuple(np.pi - s for s in v)
            candidate = mesh((v, supplement, v, supplement), LAYOUTS["rotation"])
            if planar(candidate):
                out.setdefault(signature(candidate), "example 2 type")
    return out


@dataclass(frozen=True)
class Row:
    """One variant mesh of a census."""

    transmission: str
    base: str
    codes: tuple[str, ...]  # variant code of A, B, C, D ('a' / 'p' per sector, thesis order)
    planar: bool  # `check_vertices` passes
    closing: tuple[str, ...]  # closing branch combinations, no vertex on a straight-line branch
    straight: tuple[str, ...]  # closing combinations with a vertex on a straight-line branch
    best_open: float  # smallest mismatch (rad) of a non-closing combination (inf if none was tried)
    worst_closed: float  # largest mismatch (rad) of a closing combination (0 if none)
    corners: tuple[tuple[float, ...], ...]  # each corner's `ccw_sectors` (deg, 3 decimals), central corner first
    signature: tuple
    label: str  # known construction, "mirror-symmetric", "new", "straight only", "rigid" or "" (not planar)
    flat_foldable: bool


def census(base_name: str, base_deg: tuple[float, ...], transmission: str) -> list[Row]:
    """Every mesh of one transmission type whose four vertices are variants of the base (a `Row` per mesh)."""
    table = dict(variants(base_deg))
    labels = known(base_deg)
    rows = []
    for codes in itertools.product(table, repeat=4):
        vertices = mesh(tuple(table[c] for c in codes), LAYOUTS[transmission])
        sig = signature(vertices)
        corners = tuple(_corners_deg(vertices, 3))
        ff = flat_foldable(vertices)
        if not planar(vertices):
            rows.append(Row(transmission, base_name, codes, False, (), (), np.inf, 0.0, corners, sig, "", ff))
            continue
        tried = branch_mismatches(vertices)
        closes, straight = closing(tried), closing(tried, straight=True)
        best_open = min((m for m in tried.values() if m > CLOSE_TOL), default=np.inf)
        worst_closed = max((m for m in tried.values() if m <= CLOSE_TOL), default=0.0)
        if not closes:
            label = "straight only" if straight else "rigid"
        else:
            label = labels.get(sig) or ("mirror-symmetric" if mirror_symmetric(vertices) else "new")
        rows.append(Row(transmission, base_name, codes, True, closes, straight, best_open, worst_closed, corners, sig,
                        label, ff))
    return rows


def summary(rows: list[Row]) -> dict[str, float]:
    """Counts of meshes, planar ones, closing ones (no straight-line branch) and closing ones per label (and their
    congruence classes); the largest closing mismatch and the smallest mismatch of any non-closing combination
    (rad)."""
    good = [r for r in rows if r.planar]
    shut = [r for r in good if r.closing or r.straight]
    out: dict[str, float] = {"meshes": len(rows), "planar": len(good), "closing": sum(bool(r.closing) for r in good)}
    for label in sorted({r.label for r in shut}):
        out[label] = sum(r.label == label for r in shut)
        out[f"{label} classes"] = len({r.signature for r in shut if r.label == label})
    out["worst closed"] = max((r.worst_closed for r in good), default=0.0)
    out["best open"] = min((r.best_open for r in good), default=np.inf)
    return out


def variant_conditions(base_deg: tuple[float, ...]) -> dict[str, bool]:
    """
    Which sector pairs of the base sum to pi (rad, to ANGLE_TOL): the conditions for variants beyond aaaa and pppp
    (`variants`): alpha12 + alpha23 = pi (creases 1, 3 collinear) gives ppaa / aapp (R5 / R8), alpha12 + alpha34 = pi
    (flat-foldable) papa / apap (R7 / R6), alpha12 + alpha41 = pi (creases 2, 4 collinear) paap / appa (R2 / R3).
    These are the three legible conditions of Table A4 (`A4_ROWS`).
    """
    a = np.asarray(base_deg, dtype=float) * DEG
    return {
        f"alpha12 + alpha{k} = pi": bool(abs(a[0] + a[i] - np.pi) < ANGLE_TOL) for i, k in ((1, 23), (2, 34), (3, 41))
    }


def describe(r: Row) -> str:
    """One table line: type, variant codes (and Table A1 classes), label, flat-foldable, closing combinations and
    the corners' counter-clockwise sectors (deg, central corner first)."""
    classes = "-".join(R_CLASS.get(c, "odd") for c in r.codes)
    closes = f"closes {len(r.closing)}: {','.join(r.closing) or '-'}"
    if r.straight:
        closes += f" (+{len(r.straight)} through a straight line)"
    corners = "  ".join("/".join(f"{s:g}" for s in c) for c in r.corners)
    head = f"  {r.transmission:9s} {'-'.join(r.codes)} ({classes}) {r.label:16s}{' ff' * r.flat_foldable:3s}"
    return f"{head} {closes}  [{corners}]"


def main() -> None:
    bases = BASES | random_bases(int(sys.argv[1]) if len(sys.argv) > 1 else 2)
    totals = []
    for name, base in bases.items():
        table = ", ".join(f"{c} ({'/'.join(f'{s / DEG:g}' for s in v)})" for c, v in variants(base))
        print(f"base {name} {base} deg: variants {table}; pairs summing to 180 deg: {variant_conditions(base)}")
        for transmission in LAYOUTS:
            rows = census(name, base, transmission)
            print("\n".join(describe(r) for r in rows if r.planar))
            totals.append((name, transmission, summary(rows), {r.signature for r in rows if r.label == "new"}))
    print("\nsummary (closing = no vertex on a straight-line branch; 'classes' = congruence classes)")
    for name, transmission, counts, _ in totals:
        print(f"  {name:14s} {transmission:9s} {counts}")
    for name in bases:
        new = set().union(*(s for n, _, _, s in totals if n == name))
        print(f"  {name}: {len(new)} congruence classes of new closing meshes over the three types")
    print("Peng 2018, Table A4, legible rows:", A4_ROWS)


if __name__ == "__main__":
    main()
