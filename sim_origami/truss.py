"""The truss method (Yang 2017, ch. 2-3): a linkage as a pin-jointed truss, its mobility, states of self-stress and
redundant bars, and its path, followed by the path engine (`path.follow_arc`) with bifurcation handling.

Construction (Yang 2017, Sec. 2.2, Figs. 2-1 to 2-3). Every revolute joint gives two nodes on its axis, shared by its
two bodies: its frame origin P (the D-H foot, or the crease's start vertex) and P' = P + l z with l the joint's largest
|anchor|, so z points from P to P' (Yang 2017's "A, A'", Fig. 2-2). A spherical joint gives one node at its frame
origin. Points of one body that coincide are one node (Myard: joints 3 and 4 meet, link 34 becomes the triangle C C'
C''); points of different bodies are never merged, even where they coincide at some pose (the Bricard bundle). A body
whose nodes are collinear gets an auxiliary node (unless it is a plain bar between two spherical joints, whose idle spin
Yang 2017 does not count), and one with four or more coplanar nodes gets one off its plane, AUX_OFFSET times its size
from its centroid. Each body is then braced minimally: the bars already present between its nodes (a joint bar is
counted once for both its bodies) and further bars, in node order, while they raise the rank, up to 3k - 6 for k nodes.
So each body is isostatic and b - r counts only the loops' overconstraint.

Matrices (Yang 2017, Eqs. 1-11 to 1-16, 2-1 to 2-6). The compatibility matrix C (b x 3j) maps nodal displacements d to
bar elongations; its rows hold unit bar directions (Yang 2017, Eq. 1-15, divided by each bar's length, same rank and
null spaces, dimensionless singular values); the equilibrium matrix is H = C^T. A joint coupling q_a = c q_b of the
mechanism adds one row l_char (w_a - c w_b) with w the joint rate (rad per unit displacement) of the least-squares rigid
motion of each body's nodes.

Counts (Yang 2017, Sec. 2.3, Eqs. 2-3, 2-7; Sec. 3.2): r = numerical rank of [C; K], m = 3j - 6 - r mechanisms (DOF,
rigid motions removed), s = b + c - r states of self-stress (redundant constraints), Maxwell's 3j - 6 - b - c = m - s.

Units: lengths in the mechanism's unit, angles in radians; positions in the mechanism's world frame (the root body's
frame), where the root body's nodes stay fixed while a path is followed.
"""

from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import sparse as sp
from scipy.sparse.linalg import LinearOperator, eigsh, splu

from .errors import AssemblyError, ParameterError
from .geometry import invert, wrap
from .graph import DisjointSets
from .mechanism import Mechanism
from .path import ArcSystem, follow_arc, least_outside, padded_svd, singular_values

if TYPE_CHECKING:
    from .scenes.base import Scene

# Relative rank threshold: singular values below RANK_RTOL x the largest count as zero (a threshold for
# exact coordinates, chosen here). Measured on every registered scene at its start pose and its
# bifurcation points: kept values >= 1.5e-4 of the largest (triangle-twist-6r), dropped ones <= 1e-15.
RANK_RTOL = 1e-9
# Points of one body closer than this x the mechanism's size are one node.
MERGE_RTOL = 1e-9
# A node's positions from its bodies' poses may differ by this x the size (an unclosed q is refused).
CLOSURE_RTOL = 1e-8
# Auxiliary nodes sit this far (x the body's size) off the line or plane of a degenerate body's nodes.
AUX_OFFSET = 0.3
# Counts only, of trusses over GRAM_FROM coordinates: the rank from the Gram matrix M^T M of [C; K] (`_gram_counts`).
# Its GRAM_LOW smallest eigenvectors must reach singular values above GRAM_CUT x the largest (else the full SVD):
# they then span every singular vector below, each mixed with those above by at most 1e-16 / GRAM_CUT^2, so M on
# their span gives the small singular values to 1e-16 / GRAM_CUT of the largest, far below RANK_RTOL (16 x 16 Miura
# sheet, 1800 x 1611: zeros at 5e-15 instead of 4e-16 from the SVD, the others the same to 1e-12, in 0.4 s for 1.3).
GRAM_FROM = 256
GRAM_LOW = 64
GRAM_CUT = 1e-5
# A bar takes part in a state of self-stress when its entry in the orthonormal self-stress basis exceeds this.
STRESS_TOL = 1e-6


@dataclass(frozen=True)
class Hinge:
    """A mechanism joint in the truss: `nodes` = (P, P') for a revolute joint, (centre,) for a spherical one."""

    name: str
    parent: str
    child: str
    nodes: tuple[int, ...]
    frame_parent: NDArray[np.float64]
    frame_child: NDArray[np.float64]

    @property
    def revolute(self) -> bool:
        return len(self.nodes) == 2


@dataclass(frozen=True)
class Truss:
    """
    Nodes and bars of a linkage at one configuration.

    Attributes
    ----------
    node_names : joint name (P), joint name + "'" (P'), body + "*" (auxiliary); merged points take the first name.
    nodes : (j, 3) positions in the world frame.
    bars : (b, 2) node indices; `lengths` (b,) their rest lengths, from the bodies' own geometry.
    joint_bar : (b,) True for the bar P P' of a revolute joint.
    bar_body : (b,) the body that braces each bar ("" for a joint bar, which belongs to both its bodies).
    body_nodes, body_local : each body's node indices and their coordinates in the body frame.
    hinges : the mechanism's joints; `couplings` (hinge a, hinge b, c): q_a = c q_b.
    angles0 : (len(hinges),) joint angles at the configuration the truss was built at (rad).
    ground : the body fixed while a path is followed.
    scale : characteristic length (largest joint-node spacing l).
    """

    node_names: tuple[str, ...]
    nodes: NDArray[np.float64]
    bars: NDArray[np.int64]
    lengths: NDArray[np.float64]
    joint_bar: NDArray[np.bool_]
    bar_body: tuple[str, ...]
    body_nodes: dict[str, NDArray[np.int64]]
    body_local: dict[str, NDArray[np.float64]]
    hinges: tuple[Hinge, ...]
    couplings: tuple[tuple[int, int, float], ...]
    angles0: NDArray[np.float64]
    ground: str
    scale: float

    def bar_names(self) -> tuple[str, ...]:
        """'P-Q' for every bar."""
        return tuple(f"{self.node_names[p]}-{self.node_names[q]}" for p, q in self.bars)

    def without(self, bars: Sequence[int]) -> "Truss":
        """The same truss with bars `bars` removed (Yang 2017, ch. 3: redundant-bar removal)."""
        bad = [k for k in bars if not 0 <= k < len(self.bars)]
        if bad:
            raise ParameterError(f"bars {bad} do not exist; this truss has bars 0 .. {len(self.bars) - 1}")
        keep = np.ones(len(self.bars), dtype=bool)
        keep[list(bars)] = False
        names = tuple(n for n, k in zip(self.bar_body, keep, strict=True) if k)
        return replace(self, bars=self.bars[keep], lengths=self.lengths[keep], joint_bar=self.joint_bar[keep],
                       bar_body=names)


# -- construction ----------------------------------------------------------------------------------------------


def _joint_points(mechanism: Mechanism, spherical: set[str]) -> tuple[list[tuple[str, str, NDArray]], float]:
    """Candidate points (label, body, local xyz): P and P' per revolute joint, the centre per spherical one."""
    points, spans = [], []
    for j in mechanism.joints:
        span = max((abs(a) for a in j.anchors), default=0.0)
        if j.name not in spherical and not span > 0:
            raise ParameterError(f"joint {j.name!r} has anchors {j.anchors}; a revolute joint needs one off its origin")
        spans.append(span)
        for body, frame in ((j.parent, j.frame_parent), (j.child, j.frame_child)):
            points.append((j.name, body, frame[:3, 3].copy()))
            if j.name not in spherical:
                points.append((j.name + "'", body, frame[:3, 3] + span * frame[:3, 2]))
    return points, max(spans, default=1.0) or 1.0


def _merge(points: list[tuple[str, str, NDArray]], tol: float) -> tuple[list[str], dict[tuple[str, str], int]]:
    """Union of the labels whose points coincide in a common body; returns node names and (label, body) -> node."""
    labels = list(dict.fromkeys(p[0] for p in points))
    index = {lab: k for k, lab in enumerate(labels)}
    sets = DisjointSets(range(len(labels)))
    by_body: dict[str, list[int]] = {}
    for a, (_, body, _) in enumerate(points):
        by_body.setdefault(body, []).append(a)
    close = []  # coinciding pairs (a < b) of one body, distances body by body (1920 points: 0.17 s pair by pair)
    for members in by_body.values():
        x = np.array([points[a][2] for a in members])
        i, j = np.nonzero(np.triu(np.linalg.norm(x[:, None] - x[None], axis=-1) < tol, 1))
        close += zip(np.array(members)[i].tolist(), np.array(members)[j].tolist(), strict=True)
    for a, b in sorted(close):  # the pair-by-pair order: the same unions, so the same node names
        sets.union(index[points[a][0]], index[points[b][0]])
    roots = sorted({sets.find(k) for k in range(len(labels))})
    node_of_root = {r: n for n, r in enumerate(roots)}
    names = [labels[r] for r in roots]
    node = {(lab, body): node_of_root[sets.find(index[lab])] for lab, body, _ in points}
    return names, node


def _span(local: NDArray, tol: float) -> tuple[int, NDArray, NDArray]:
    """(dimension of the affine hull, centroid, principal directions) of points (k, 3)."""
    centre = local.mean(axis=0)
    if len(local) < 2:
        return 0, centre, np.eye(3)
    _, s, vt = np.linalg.svd(local - centre)
    return int(np.sum(s > tol)), centre, vt


def _auxiliary(local: NDArray, plain_bar: bool, tol: float) -> list[NDArray]:
    """Auxiliary points (body frame) that make a degenerate body rigid: off its line, then off its plane."""
    extra: list[NDArray] = []
    dim, centre, vt = _span(local, tol)
    size = max(float(np.max(np.linalg.norm(local - centre, axis=1))), tol)
    if dim == 1 and not plain_bar:
        extra.append(centre + AUX_OFFSET * size * vt[1])
        dim = 2
    if dim == 2 and len(local) + len(extra) >= 4:
        _, centre, vt = _span(np.vstack([local, *extra]), tol)
        extra.append(centre + AUX_OFFSET * size * vt[2])
    return extra


def _bar_row(local: NDArray, p: int, q: int) -> NDArray:
    """Row of a body's own rigidity matrix (3k,) for the bar p-q, unit direction."""
    row = np.zeros(local.size)
    u = (local[p] - local[q]) / np.linalg.norm(local[p] - local[q])
    row[3 * p : 3 * p + 3], row[3 * q : 3 * q + 3] = u, -u
    return row


def _brace(local: NDArray, existing: list[tuple[int, int]]) -> list[tuple[int, int]]:
    """Extra bars (local indices) raising a body's rigidity rank to 3k - 6 (1 for two nodes), in node order."""
    k = len(local)
    target = 1 if k == 2 else max(3 * k - 6, 0)
    basis: list[NDArray] = []

    def independent(row: NDArray) -> bool:
        for b in basis:
            row = row - (row @ b) * b
        if np.linalg.norm(row) > 1e-9:
            basis.append(row / np.linalg.norm(row))
            return True
        return False

    for p, q in existing:
        independent(_bar_row(local, p, q))
    added = []
    for p in range(k):
        for q in range(p + 1, k):
            if len(basis) >= target:
                return added
            if (p, q) not in existing and independent(_bar_row(local, p, q)):
                added.append((p, q))
    if len(basis) < target:
        raise AssemblyError(f"a body with {k} nodes reached rigidity rank {len(basis)} < {target}")
    return added


def _body_nodes(
    mechanism: Mechanism, points: list, node: dict, names: list[str], tol: float
) -> tuple[dict[str, NDArray], dict[str, NDArray]]:
    """Per body: node indices and local coordinates, with auxiliary nodes appended to `names`."""
    revolute_bodies = {b for lab, b, _ in points if lab.endswith("'")}
    body_nodes, body_local = {}, {}
    for body in (b.name for b in mechanism.bodies):
        seen: dict[int, NDArray] = {}
        for lab, b, x in points:
            if b == body:
                seen.setdefault(node[(lab, b)], x)
        idx, local = list(seen), [seen[i] for i in seen]
        for x in _auxiliary(np.array(local).reshape(-1, 3), body not in revolute_bodies and len(idx) == 2, tol):
            names.append(f"{body}*" if f"{body}*" not in names else f"{body}*{len(idx)}")
            idx.append(len(names) - 1)
            local.append(x)
        body_nodes[body], body_local[body] = np.array(idx, dtype=int), np.array(local).reshape(-1, 3)
    return body_nodes, body_local


def _bars(
    body_nodes: dict[str, NDArray], body_local: dict[str, NDArray], joint_pairs: list[tuple[int, ...]], tol: float
) -> tuple[NDArray, NDArray, NDArray, tuple[str, ...]]:
    """Joint bars, then each body's minimal bracing: (bars (b, 2), rest lengths, joint-bar flags, owners)."""
    owner = {(min(p, q), max(p, q)): "" for p, q in joint_pairs}
    length: dict[tuple[int, int], float] = {}
    for body, idx in body_nodes.items():
        local, pos = body_local[body], {n: k for k, n in enumerate(idx)}
        existing = sorted((pos[p], pos[q]) if pos[p] < pos[q] else (pos[q], pos[p])
                          for p, q in owner if p in pos and q in pos)
        for p, q in existing + _brace(local, existing):
            key = (min(idx[p], idx[q]), max(idx[p], idx[q]))
            owner.setdefault(key, body)
            length[key] = float(np.linalg.norm(local[p] - local[q]))
    if min(length.values(), default=1.0) < tol or len(length) != len(owner):
        raise AssemblyError("a bar joins two coincident nodes, or a joint bar lies in no body")
    pairs = np.array(list(owner), dtype=int).reshape(-1, 2)
    joint = np.array([owner[key] == "" for key in owner], dtype=bool)
    return pairs, np.array([length[key] for key in owner]), joint, tuple(owner.values())


def _positions(
    poses: dict[str, NDArray],
    body_nodes: dict[str, NDArray],
    body_local: dict[str, NDArray],
    n_nodes: int,
    tol: float,
) -> NDArray:
    """World node positions from body poses: mean over the node's bodies; AssemblyError if they disagree."""
    seen: list[list[NDArray]] = [[] for _ in range(n_nodes)]
    for body, idx in body_nodes.items():
        world = body_local[body] @ poses[body][:3, :3].T + poses[body][:3, 3]
        for n, x in zip(idx, world, strict=True):
            seen[n].append(x)
    nodes = np.array([np.mean(xs, axis=0) for xs in seen])
    gap = max(float(np.max(np.linalg.norm(np.array(xs) - x, axis=1))) for xs, x in zip(seen, nodes, strict=True))
    if gap > tol:
        raise AssemblyError(f"the loops are not closed at q: a shared node differs by {gap:.3g} between its bodies "
                            f"(limit {tol:.3g}, CLOSURE_RTOL x the truss size)")
    return nodes


def truss_of(mechanism: Mechanism, q: ArrayLike, spherical: Sequence[str] = ()) -> Truss:
    """
    The equivalent truss of `mechanism` at joint angles q (rad, (n_joints,), every loop closed).

    Joints named in `spherical` become spherical joints (one node at the frame origin): e.g. joints 3
    and 4 of the Bennett linkage give its RSSR form (Yang 2017, Sec. 3.3). Their angles are then undefined.
    """
    q = np.asarray(q, dtype=float)
    if q.shape != (len(mechanism.joints),) or not np.all(np.isfinite(q)):
        raise ParameterError(f"q has shape {q.shape} with finite={bool(np.all(np.isfinite(q)))}; "
                             f"it must hold {len(mechanism.joints)} finite joint angles (rad)")
    balls = set(spherical)
    for name in balls:
        mechanism.joint_index(name)
    poses = mechanism.body_poses(q)
    if mechanism.balls:  # its spherical joints' hinge triples become single S joints between their end bodies
        balls |= set(mechanism.balls)
        full, mechanism = mechanism, mechanism.reduced()
        q = np.array([0.0 if j.name in balls else q[full.joint_index(j.name)] for j in mechanism.joints])
    points, scale = _joint_points(mechanism, balls)
    names, node = _merge(points, MERGE_RTOL * scale)
    body_nodes, body_local = _body_nodes(mechanism, points, node, names, MERGE_RTOL * scale)
    hinges, pairs = [], []
    for j in mechanism.joints:
        ids = (node[(j.name, j.parent)],) + (() if j.name in balls else (node[(j.name + "'", j.parent)],))
        if len(set(ids)) < len(ids):
            raise ParameterError(f"joint {j.name!r}: its two axis nodes coincide (anchor {j.anchors} too short)")
        hinges.append(Hinge(j.name, j.parent, j.child, ids, j.frame_parent, j.frame_child))
        if len(ids) == 2:
            pairs.append(ids)
    bars, lengths, joint_bar, owner = _bars(body_nodes, body_local, pairs, MERGE_RTOL * scale)
    nodes = _positions(poses, body_nodes, body_local, len(names), CLOSURE_RTOL * scale)
    index = {h.name: i for i, h in enumerate(hinges)}
    couplings = []
    for a, b, c in mechanism.couplings:
        if a in balls or b in balls:
            raise ParameterError(f"coupling {a} = {c:g} x {b} names a spherical joint; couplings need revolute joints")
        couplings.append((index[a], index[b], float(c)))
    return Truss(tuple(names), nodes, bars, lengths, joint_bar, owner, body_nodes, body_local, tuple(hinges),
                 tuple(couplings), q.copy(), mechanism.root, scale)


# -- matrices and counts ---------------------------------------------------------------------------------------


def compatibility(truss: Truss, x: ArrayLike | None = None) -> NDArray[np.float64]:
    """Compatibility matrix C (b, 3j) at node positions x (default: the truss's): unit bar directions."""
    x = truss.nodes if x is None else np.asarray(x, dtype=float)
    if x.shape != truss.nodes.shape or not np.all(np.isfinite(x)):
        raise ParameterError(f"node positions of shape {x.shape} (finite: {bool(np.all(np.isfinite(x)))}); "
                             f"they must be {truss.nodes.shape} and finite")
    p, q = truss.bars[:, 0], truss.bars[:, 1]
    u = x[p] - x[q]
    length = np.linalg.norm(u, axis=1, keepdims=True)
    if np.any(length == 0):
        raise ParameterError(f"bar {truss.bar_names()[int(np.argmin(length))]} has zero length at these positions")
    u = u / length
    C = np.zeros((len(truss.bars), 3 * len(x)))
    rows = np.arange(len(truss.bars))
    for k in range(3):
        C[rows, 3 * p + k] = u[:, k]
        C[rows, 3 * q + k] = -u[:, k]
    return C


def _body_rates(truss: Truss, body: str, x: NDArray) -> NDArray[np.float64]:
    """(3, 3j): angular velocity of `body` (least-squares rigid motion of its nodes) from nodal velocities."""
    idx = truss.body_nodes[body]
    r = x[idx] - x[idx].mean(axis=0)
    A = np.zeros((3 * len(idx), 6))
    for k, v in enumerate(r):
        A[3 * k : 3 * k + 3, :3] = np.eye(3)
        A[3 * k : 3 * k + 3, 3:] = [[0, v[2], -v[1]], [-v[2], 0, v[0]], [v[1], -v[0], 0]]  # w x r = -[r]x w
    W = np.zeros((3, 3 * len(x)))
    cols = (3 * idx[:, None] + np.arange(3)).ravel()
    W[:, cols] = np.linalg.pinv(A)[3:]
    return W


def joint_rates(truss: Truss, x: ArrayLike | None = None) -> NDArray[np.float64]:
    """(n_revolute, 3j): each revolute joint's rate (rad per unit displacement) from nodal velocities."""
    x = truss.nodes if x is None else np.asarray(x, dtype=float)
    rows = []
    for h in truss.hinges:
        if h.revolute:
            z = x[h.nodes[1]] - x[h.nodes[0]]
            rows.append(z / np.linalg.norm(z) @ (_body_rates(truss, h.child, x) - _body_rates(truss, h.parent, x)))
    return np.array(rows).reshape(-1, 3 * len(x))


def coupling_rows(truss: Truss, x: ArrayLike | None = None) -> NDArray[np.float64]:
    """(n_couplings, 3j): scale x (rate of q_a - c q_b), dimensionless like the rows of C."""
    x = truss.nodes if x is None else np.asarray(x, dtype=float)
    if not truss.couplings:
        return np.zeros((0, 3 * len(x)))
    revolute = [i for i, h in enumerate(truss.hinges) if h.revolute]
    R = joint_rates(truss, x)
    at = {i: k for k, i in enumerate(revolute)}
    return np.array([truss.scale * (R[at[a]] - c * R[at[b]]) for a, b, c in truss.couplings])


def constraints(truss: Truss, x: ArrayLike | None = None) -> NDArray[np.float64]:
    """[C; K]: bar rows then coupling rows, (b + c, 3j)."""
    return np.vstack([compatibility(truss, x), coupling_rows(truss, x)])


@dataclass(frozen=True)
class Counts:
    """
    Truss counts at one configuration (Yang 2017, Sec. 2.3).

    nodes j, bars b, couplings c, rank r of [C; K], mobility m = 3j - 6 - r, self_stress s = b + c - r,
    maxwell = 3j - 6 - b - c (= m - s), redundant: names of the bars that carry a state of self-stress
    (each one can be removed without changing r; None when not asked for), kept / dropped: the smallest singular
    value counted in the rank and the largest one counted as zero, both relative to the largest.
    """

    nodes: int
    bars: int
    couplings: int
    rank: int
    mobility: int
    self_stress: int
    maxwell: int
    redundant: tuple[str, ...] | None
    kept: float
    dropped: float


def analyse(truss: Truss, x: ArrayLike | None = None, rtol: float = RANK_RTOL, stresses: bool = True) -> Counts:
    """
    Mobility, self-stress and redundant bars of `truss` at positions x (default: its own).

    With stresses False only the counts (`redundant` is None), from the singular values alone, or for trusses over
    GRAM_FROM coordinates from the Gram matrix and M on its near-null eigenvectors (`_gram_counts`): the 16 x 16
    Miura sheet's [C; K] (1800 x 1611) in 0.4 s instead of 1.3 s (the SVD values) or 2.2 s (the full SVD). (The Gram
    matrix's eigenvalues alone leave zero singular values at 1e-8 relative, above RANK_RTOL.)
    """
    M = constraints(truss, x)
    j, b, c = len(truss.nodes), len(truss.bars), len(truss.couplings)
    gram = None if stresses or M.shape[1] <= GRAM_FROM else _gram_counts(M, rtol)
    if gram is not None:
        r, kept, dropped = gram
        return Counts(j, b, c, r, 3 * j - 6 - r, b + c - r, 3 * j - 6 - b - c, None, kept, dropped)
    if stresses:
        U, s, _ = padded_svd(M)
    else:
        s = singular_values(M)
    rel = s / s.max()
    r = int(np.sum(rel > rtol))
    redundant = None
    if stresses:
        stress = U[:b, r:]
        redundant = tuple(n for n, w in zip(truss.bar_names(), stress, strict=True) if np.linalg.norm(w) > STRESS_TOL)
    kept = float(rel[r - 1]) if r else 0.0
    dropped = float(rel[r]) if r < len(rel) else 0.0
    return Counts(j, b, c, r, 3 * j - 6 - r, b + c - r, 3 * j - 6 - b - c, redundant, kept, dropped)


def _gram_counts(M: NDArray[np.float64], rtol: float) -> tuple[int, float, float] | None:
    """
    (rank, kept, dropped) of a large [C; K] as `analyse` counts them, from its Gram matrix (see GRAM_CUT): the
    largest eigenvalue by Lanczos, the GRAM_LOW smallest eigenpairs, the singular values of M on those eigenvectors.
    None when the GRAM_LOW-th eigenvalue is below GRAM_CUT^2 x the largest (too many small singular values).
    """
    A = sp.csr_matrix(M)
    G = (A.T @ A).tocsr()
    top = float(eigsh(G, k=1, which="LA", v0=np.ones(G.shape[0]), return_eigenvectors=False)[0])
    # the smallest by Lanczos on (G + c I)^-1 (c = GRAM_CUT^2 x the largest), factored once by sparse LU, and one more
    # inverse iteration on them, which takes their near-null part to rounding (M on them 1.4e-12 of the largest
    # without it, 1e-15 from the dense eigh): a dense eigh of G costs n^3 (28.5 s of a 28 x 28 Miura sheet's 171 s)
    n, shift = G.shape[0], GRAM_CUT**2 * top
    lu = splu((G + shift * sp.identity(n, format="csc")).tocsc())
    inverse = LinearOperator((n, n), matvec=lu.solve, matmat=lu.solve, dtype=float)
    w, V = eigsh(G, k=GRAM_LOW, sigma=-shift, which="LM", OPinv=inverse, v0=np.ones(n))
    V = np.linalg.qr(lu.solve(V[:, np.argsort(w)]))[0]
    w = np.sum(V * (G @ V), axis=0)
    if not top > 0 or w.max() < GRAM_CUT**2 * top or least_outside(G, lu.solve, V) <= rtol**2 * top:
        return None
    s = np.linalg.svd(A @ V, compute_uv=False)
    rel = np.r_[s, np.zeros(GRAM_LOW - len(s))] / np.sqrt(top)  # the GRAM_LOW smallest; the largest is counted
    small = int(np.sum(rel <= rtol))
    return M.shape[1] - small, float(rel[rel > rtol].min()), float(rel[rel <= rtol].max(initial=0.0))


def removable_bars(truss: Truss) -> tuple[int, ...]:
    """
    Yang 2017, Secs. 3.3-3.4: s body bars of ONE body whose removal keeps the rank (joint bars stay), giving a
    non-overconstrained truss with the same mobility (Bennett -> RSSR, Myard -> RRSRR / RSRRR).

    Bodies are tried in order. A body's bars are projected off the row space of all other rows and kept
    greedily, in order, while they raise the rank; the rest are removable when there are exactly s of them.
    AssemblyError when no single body carries all s redundancies (removing bars of several links changes
    the topology).
    """
    M = constraints(truss)
    floor = RANK_RTOL * np.linalg.svd(M, compute_uv=False).max()
    s = analyse(truss).self_stress
    if s == 0:
        return ()
    for body in truss.body_nodes:
        mine = [k for k, owner in enumerate(truss.bar_body) if owner == body]
        _, sv, vt = np.linalg.svd(np.delete(M, mine, axis=0), full_matrices=False)
        basis = vt[sv > floor]
        left = M[mine] - (M[mine] @ basis.T) @ basis
        kept: list[int] = []
        for i in range(len(mine)):
            if np.linalg.matrix_rank(left[[*kept, i]], tol=floor) > len(kept):
                kept.append(i)
        if len(mine) - len(kept) == s:
            return tuple(k for i, k in enumerate(mine) if i not in kept)
    raise AssemblyError(f"no single body carries all {s} redundant bars; removing bars of several links changes "
                        "the topology (Yang 2017, ch. 3)")


# -- poses and joint angles from node positions ----------------------------------------------------------------


def body_poses(truss: Truss, x: ArrayLike | None = None) -> dict[str, NDArray[np.float64]]:
    """World pose (4, 4) of every body with 3+ non-collinear nodes: least-squares rigid fit (Kabsch)."""
    x = truss.nodes if x is None else np.asarray(x, dtype=float)
    out = {}
    for body, idx in truss.body_nodes.items():
        local = truss.body_local[body]
        if _span(local, MERGE_RTOL * truss.scale)[0] < 2:
            continue
        a, w = local - local.mean(0), x[idx] - x[idx].mean(0)
        U, _, Vt = np.linalg.svd(w.T @ a)
        D = np.diag([1.0, 1.0, np.sign(np.linalg.det(U @ Vt))])
        T = np.eye(4)
        T[:3, :3] = U @ D @ Vt
        T[:3, 3] = x[idx].mean(0) - T[:3, :3] @ local.mean(0)
        out[body] = T
    return out


def joint_angles(truss: Truss, x: ArrayLike | None = None) -> NDArray[np.float64]:
    """
    Angles (rad, in (-pi, pi]) of the revolute joints, in `hinges` order, from node positions; the
    mechanism's convention: child relative to parent about the joint's z. Spherical joints are skipped.
    """
    poses = body_poses(truss, x)
    out = []
    for h in truss.hinges:
        if h.revolute:
            M = invert(h.frame_parent) @ invert(poses[h.parent]) @ poses[h.child] @ h.frame_child
            out.append(np.arctan2(M[1, 0], M[0, 0]))
    return np.array(out)


def revolute_names(truss: Truss) -> tuple[str, ...]:
    """Names of the revolute joints: the order of `joint_angles`."""
    return tuple(h.name for h in truss.hinges if h.revolute)


# -- predictor-corrector path following (Yang 2017, Sec. 2.4, eqns 2-12 to 2-18), by `path.follow_arc` ---------------

# Newton corrector: bring every bar-length error below CORRECTOR_TOL x scale.
CORRECTOR_TOL = 1e-13


@dataclass(frozen=True)
class Bifurcation:
    """
    A point where the mobility jumps: its index in the path, the drive input there (rad), sigma_2 relative to
    sigma_max, the mobility there, the number of real branch directions found at second order, the choice made.
    """

    index: int
    input: float
    sigma2: float
    mobility: int
    directions: int
    choice: str


@dataclass(frozen=True)
class TrussPath:
    """
    A followed path: nodes (n, j, 3); revolute joint angles (n, k) unwrapped along the path (rad, in the order
    of `joints`); drive input (n,) (rad); sigma2 (n,), the second-smallest singular value of the grounded
    [C; K] relative to its largest; the bifurcations met; whether the input reached `stop` (the last point
    then lies on it to 1e-14 rad).
    """

    nodes: NDArray[np.float64]
    angles: NDArray[np.float64]
    joints: tuple[str, ...]
    input: NDArray[np.float64]
    sigma2: NDArray[np.float64]
    bifurcations: tuple[Bifurcation, ...]
    reached: bool


class _Follower(ArcSystem):
    """The grounded truss equations over the free node coordinates: residual (bar length errors, scaled coupling
    errors), Jacobian [C; K], and the revolute joint angles as the chart."""

    def __init__(self, truss: Truss, rtol: float):
        self.truss = truss
        grounded = np.zeros(len(truss.nodes), dtype=bool)
        grounded[truss.body_nodes[truss.ground]] = True
        self.free = np.repeat(~grounded, 3)
        self.rows = np.concatenate([~(grounded[truss.bars[:, 0]] & grounded[truss.bars[:, 1]]),
                                    np.ones(len(truss.couplings), dtype=bool)])
        self.revolute = [i for i, h in enumerate(truss.hinges) if h.revolute]
        super().__init__(int(self.free.sum()), int(self.rows.sum()), truss.scale, CORRECTOR_TOL * truss.scale, rtol)

    def chart(self, x: NDArray, ref: NDArray) -> NDArray:
        """Revolute joint angles unwrapped next to `ref`."""
        return ref + wrap(joint_angles(self.truss, x) - ref)

    def chart_rate(self, x: NDArray, k: int) -> NDArray:
        return joint_rates(self.truss, x)[:, self.free][k]

    def residual(self, x: NDArray, ref: NDArray) -> NDArray:
        """Bar length errors, then scale x (q_a - c q_b) per coupling, on the rows not fixed by the ground."""
        t = self.truss
        p, q = t.bars[:, 0], t.bars[:, 1]
        out = [np.linalg.norm(x[p] - x[q], axis=1) - t.lengths]
        if t.couplings:
            a = dict(zip(self.revolute, self.chart(x, ref), strict=True))
            out.append(np.array([t.scale * (a[i] - c * a[k]) for i, k, c in t.couplings]))
        return np.concatenate(out)[self.rows]

    def jacobian(self, x: NDArray) -> NDArray:
        return constraints(self.truss, x)[self.rows][:, self.free]

    def move(self, x: NDArray, d: NDArray) -> NDArray:
        """Nodes x displaced by d over the free coordinates."""
        y = x.copy().ravel()
        y[self.free] += d
        return y.reshape(x.shape)


def follow(
    truss: Truss,
    drive: str,
    stop: float,
    *,
    drive_scale: float = 1.0,
    step: float | None = None,
    choice: str = "keep",
    max_points: int = 20000,
    rtol: float = RANK_RTOL,
) -> TrussPath:
    """
    Follow the 1-DOF motion of `truss` from its configuration until the input q_drive / drive_scale reaches
    `stop` (rad), with `path.follow_arc`: predictor along the mechanism mode (the null vector of the grounded
    [C; K]), corrector by the rank-truncated pseudo-inverse, step control on the arc length in node space
    (`step`: first step, length units, default `path.FIRST_STEP` x scale). The root body stays fixed.

    At a dip of sigma_2 its minimum is located on the path; where the mobility jumps there (a bifurcation)
    the branch directions are found at second order and `choice` picks one: 'keep' (closest to the incoming
    tangent: straight through a transversal crossing) or 'switch' (the other branch). The path ends early,
    with reached = False, after `max_points` points.
    """
    if not (np.isfinite(stop) and np.isfinite(drive_scale) and drive_scale != 0):
        raise ParameterError(f"stop = {stop!r} rad, drive_scale = {drive_scale!r}: both must be finite, scale nonzero")
    names = revolute_names(truss)
    if drive not in names:
        raise ParameterError(f"drive joint {drive!r} is not a revolute joint of the truss; they are {list(names)}")
    f, k = _Follower(truss, rtol), names.index(drive)
    run = follow_arc(f, truss.nodes, truss.angles0[f.revolute], k, stop * drive_scale, step=step, choice=choice,
                     max_points=max_points, unit=drive_scale)
    angles = np.array([p.chart for p in run.points])
    events = tuple(Bifurcation(e.index, float(e.point.chart[k] / drive_scale), e.point.sigma2, e.mobility,
                               e.directions, choice) for e in run.events)
    return TrussPath(np.array([p.x for p in run.points]), angles, names, angles[:, k] / drive_scale,
                     np.array([p.sigma2 for p in run.points]), events, run.reached)


# -- scenes ----------------------------------------------------------------------------------------------------


def truss_mobility(scene: "Scene", q: ArrayLike, rtol: float = RANK_RTOL, stresses: bool = True) -> Counts:
    """Truss counts of `scene`'s mechanism (a `scenes.Scene`) at mechanism joint angles q (rad); `analyse`."""
    return analyse(truss_of(scene.mechanism, q), rtol=rtol, stresses=stresses)


@dataclass(frozen=True)
class ScenePath:
    """A truss path of a scene: input (n,) (rad), mechanism joint angles q (n, n_joints) (rad), the truss path."""

    input: NDArray[np.float64]
    q: NDArray[np.float64]
    path: TrussPath


def follow_scene(scene: "Scene", branch: str, start: float, stop: float, *, choice: str = "keep",
                 step: float | None = None) -> ScenePath:
    """Follow `scene` with the truss method from its closed-form pose on `branch` at input `start` to `stop` (rad)."""
    truss = truss_of(scene.mechanism, scene.pose(branch, start))
    path = follow(truss, scene.drive_joint, stop, drive_scale=scene.drive_scale, step=step, choice=choice)
    order = [path.joints.index(j.name) for j in scene.mechanism.joints]
    return ScenePath(path.input, path.angles[:, order], path)
