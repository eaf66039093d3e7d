"""Degree-4 rigid-origami vertex = spherical 4R linkage (Peng 2018, ch. 2 and §3.2.1).

Conventions are those of `sim_origami.conventions`: sector alpha_i between creases i and i+1, fold angle rho_i = D-H
joint angle theta_i of the spherical linkage whose twists are the sector angles (Peng 2018, eqn 2-1; the mapping checked
here), rho > 0 a valley seen from +z.

Closed form (Peng 2018, eqn 2-5 solved for the next joint): with input crease 1,

    A cos rho_2 + B sin rho_2 = C,   rho_2 = atan2(B, A) +/- arccos(C / sqrt(A^2 + B^2)),

then rho_3, rho_4 from N = (Rz(rho_1) Rx(a12) Rz(rho_2) Rx(a23))^T Rx(-a41) = Rz(rho_3) Rx(a34) Rz(rho_4). The printed
matrix Q of (2-1) is the transpose of Rz Rx (found here: the printed product misses closure by 1.94 at a valid
configuration, the standard one by 1e-15); the standard D-H product is used here. Another input crease k is handled by
relabelling the creases cyclically.

Branches. The +/- labels swap when the input changes sign (found here), so each root is
named by its fold-sign pattern, which is constant along a branch between the flat state and the
lock: on each branch of a developable vertex exactly one crease folds opposite to the other three
("odd<k>"). A flat-foldable vertex (alpha_1 + alpha_3 = pi) names its branches by the thesis's modes:
S (rho_3 = -rho_1, rho_4 = rho_2) and C (rho_3 = rho_1, rho_4 = -rho_2). A vertex with a collinear
crease pair (alpha_i + alpha_(i+1) = pi) also folds about that straight line alone ("straight<i><j>").
All branches of a developable vertex meet at the flat state, a bifurcation point. A branch ends
where a crease folds flat (|rho| = pi, panels in contact: a lock) or where the input turns back.
"""

from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import Loop, LoopSystem
from ..errors import ParameterError
from ..geometry import rot_x, transform
from .base import Branch, Event, JointSpaceKinematics, as_inputs, domain_of

# Sum of sector angles and supplementary pairs are compared at this absolute tolerance (rad).
ANGLE_TOL = 1e-9
# A fold angle below this fraction of the largest fold counts as unfolded when naming a root by its
# sign pattern (the straight-fold root carries about 1e-16 rad there; real folds are not that small).
ZERO_FOLD = 1e-8
# ... and below this absolute fold (rad): near flat a straight fold's idle creases carry up to 1.5e-12 rad of rounding
# (sectors 89.999/90.001/90.001/89.999 deg at rho1 = 1e-5), which the relative test alone named mode C.
ZERO_FOLD_ABS = 1e-11
# A fold this close to +/- pi (rad, a few ulps) is folded flat; its sign is ambiguous.
FLAT_FOLD = 1e-14
# A flat-foldable vertex with every fold this close to +/- pi (rad) is in its fully folded state, which modes S and
# C share (rho3 = -rho1 and rho3 = rho1 agree mod 2 pi there). Its roots carry sqrt(eps) ~ 1e-8 rad of rounding, so
# their signs name a mode at random within ~1e-8 rad of the lock (thick-vertex4 with alpha2 = 46 deg refused inputs
# 1e-9 inside the domain it printed); 1e-7 is ten times that.
FOLDED_FLAT = 1e-7
# Inputs below this (rad) are evaluated on the tangent at the flat state, from +/- TANGENT_STEP.
TINY_INPUT = 1e-8
TANGENT_STEP = 1e-5
# Every branch name a degree-4 vertex can have (codes index this tuple).
NAMES = ("S", "C", "odd1", "odd2", "odd3", "odd4", "straight13", "straight24")


def developable_sectors(sectors: ArrayLike, names: tuple[str, ...]) -> NDArray[np.float64]:
    """
    Four sector angles (rad) named `names`, checked: each in (0, pi) and summing to 2 pi (a flat, developable
    vertex); ParameterError naming the value and the rule otherwise.
    """
    s = np.asarray(sectors, dtype=float)
    if s.shape != (len(names),):
        raise ParameterError(f"a degree-4 vertex needs {len(names)} sector angles, got {s.size} ({', '.join(names)})")
    for name, value in zip(names, s, strict=True):
        if not 0.0 < value < np.pi:
            raise ParameterError(f"sector angle {name} = {np.rad2deg(value):.6g} deg; each must lie in (0, 180) deg")
    total = float(np.sum(s))
    if abs(total - 2 * np.pi) > ANGLE_TOL:
        raise ParameterError(
            f"sector angles sum to {np.rad2deg(total):.12g} deg ({' + '.join(names)}, "
            f"{np.rad2deg(total - 2 * np.pi):+.3g} deg); "
            "a flat (developable) vertex needs 360"
        )
    return s


def fold_roots(alpha: ArrayLike, rho1: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """
    Both assembly modes of a spherical 4R driven by joint 1 (Peng 2018, eqn 2-5).

    Parameters
    ----------
    alpha : (4,) float
      Twists (sector angles) alpha_12, alpha_23, alpha_34, alpha_41 in radians.
    rho1 : (n,) float
      Input joint angle in radians.

    Returns
    -------
    rho : (2, n, 4) float
      Joint angles of the two roots, each smooth in rho1 (the roots are named by the caller).
    real : (n,) bool
      Where |C| <= sqrt(A^2 + B^2), i.e. where the linkage assembles.

    Notes
    -----
    Valid for developable twists only (sum 2 pi): the discriminant is factored at the flat state.
    """
    t1 = np.atleast_1d(np.asarray(rho1, dtype=float))
    terms, real = _root_terms(alpha, t1)
    out = np.empty((2, t1.size, 4))
    for k in (0, 1):
        out[k, :, 0] = t1
        out[k, :, 1], out[k, :, 2], out[k, :, 3] = _root(alpha, terms, k)
    return out, real


def fold_root(alpha: ArrayLike, rho1: ArrayLike, root: int) -> tuple[tuple[NDArray, ...], NDArray[np.bool_]]:
    """Root `root` (0 or 1) of `fold_roots` alone, as its four joint angles (n,) each, and `real` (n,): the same
    numbers for half the work."""
    t1 = np.atleast_1d(np.asarray(rho1, dtype=float))
    terms, real = _root_terms(alpha, t1)
    return (t1, *_root(alpha, terms, root)), real


def _root_terms(alpha: ArrayLike, t1: NDArray) -> tuple[tuple[NDArray, ...], NDArray[np.bool_]]:
    """cos(rho1), sin(rho1), atan2(B, A) and the spread arccos(C / |(A, B)|) of eqn 2-5 (n,) each, and `real`."""
    a12, a23, a34, a41 = np.asarray(alpha, dtype=float)
    c12, c23, c34, c41 = np.cos([a12, a23, a34, a41])
    s12, s23, s41 = np.sin([a12, a23, a41])
    P, Q = c41 * s12 * s23, c12 * s23 * s41
    R, K = c23 * s41 * s12, c34 - c12 * c23 * c41
    c1, s1 = np.cos(t1), np.sin(t1)
    A = P + Q * c1
    B = -s23 * s41 * s1
    C = -(R * c1 + K)
    # A^2 + B^2 - C^2 is a quadratic in cos(rho1) that vanishes at the flat state of a developable
    # vertex, so it factors as 2 sin^2(rho1/2) G with G linear in cos(rho1). Taking the root as
    # sqrt(2) sin(rho1/2) sqrt(G) keeps full precision at the double root, where arccos(C/|(A,B)|)
    # would lose half the digits (about 1e-8 rad), and makes each root smooth through rho1 = 0.
    a2 = Q**2 - (s23 * s41) ** 2 - R**2
    a1 = 2 * (P * Q - R * K)
    G = -(a2 * (1 + c1) + a1)
    real = G >= -1e-14
    root = np.sqrt(2.0) * np.sin(t1 / 2) * np.sqrt(np.maximum(G, 0.0))
    return (c1, s1, np.arctan2(B, A), np.arctan2(root, C)), real


def _root(alpha: NDArray, terms: tuple[NDArray, ...], k: int) -> tuple[NDArray, NDArray, NDArray]:
    """rho2, rho3, rho4 (n,) of root k: rho2 = atan2(B, A) + spread (k = 0) or - spread (k = 1)."""
    c1, s1, base, spread = terms
    t2 = base - spread if k else base + spread
    c2, s2 = np.cos(t2), np.sin(t2)
    return (np.arctan2(s2, c2), *_last_two(alpha, c1, s1, c2, s2))


def _last_two(alpha: NDArray, c1: NDArray, s1: NDArray, c2: NDArray, s2: NDArray) -> tuple[NDArray, NDArray]:
    """
    rho3 = atan2(N02, -N12), rho4 = atan2(N20, N21) with N = M^T Rx(-a41), M = Rz(t1) Rx(a12) Rz(t2) Rx(a23), from
    c1, s1 = cos, sin(t1) and c2, s2 = cos, sin(t2).

    The entries of M are written out (no (n, 3, 3) stacks): 5x faster than the matrix products.
    """
    a12, a23, _, a41 = alpha
    c12, s12, c23, s23, c41, s41 = (
        np.cos(a12),
        np.sin(a12),
        np.cos(a23),
        np.sin(a23),
        np.cos(a41),
        np.sin(a41),
    )
    # A = Rx(a12) Rz(t2) Rx(a23), rows 0..2 (entries used below)
    a00, a01, a02 = c2, -s2 * c23, s2 * s23
    a10, a11, a12_ = c12 * s2, c12 * c2 * c23 - s12 * s23, -c12 * c2 * s23 - s12 * c23
    a20, a21, a22 = s12 * s2, s12 * c2 * c23 + c12 * s23, -s12 * c2 * s23 + c12 * c23
    # M = Rz(t1) A
    m02 = c1 * a02 - s1 * a12_
    m10, m11, m12 = s1 * a00 + c1 * a10, s1 * a01 + c1 * a11, s1 * a02 + c1 * a12_
    n02 = m10 * s41 + a20 * c41
    n12 = m11 * s41 + a21 * c41
    n21 = m12 * c41 - a22 * s41
    return np.arctan2(n02, -n12), np.arctan2(m02, n21)


def flat_foldable_multipliers(alpha: ArrayLike) -> dict[str, NDArray[np.float64]]:
    """
    Tan-half multipliers m_ij = tan(rho_j/2) / tan(rho_i/2) of a flat-foldable vertex.

    Peng 2018, eqns 3-1, 3-3a (mode S) and 3-3b (mode C, reconstructed from 3-4a/3-5b).

    Returns
    -------
    {'S': (4,), 'C': (4,)} : m12, m23, m34, m41 of each mode.
    """
    a12, a23 = np.asarray(alpha, dtype=float)[:2]
    ratio_s = -np.sin((a23 - a12) / 2) / np.sin((a23 + a12) / 2)  # t1/t2 in mode S
    ratio_c = -np.cos((a23 - a12) / 2) / np.cos((a23 + a12) / 2)  # t1/t2 in mode C
    return {
        "S": np.array([1 / ratio_s, -ratio_s, -1 / ratio_s, ratio_s]),
        "C": np.array([1 / ratio_c, ratio_c, -1 / ratio_c, -ratio_c]),
    }


def flat_foldable_fold_angles(alpha: ArrayLike, rho1: ArrayLike, mode: str) -> NDArray[np.float64]:
    """Fold angles (n, 4) of a flat-foldable vertex on mode 'S' or 'C' from the multipliers."""
    m12, m23, m34, _ = flat_foldable_multipliers(alpha)[mode]
    t1 = np.tan(np.atleast_1d(np.asarray(rho1, dtype=float)) / 2)
    t = np.stack([t1, m12 * t1, m12 * m23 * t1, m12 * m23 * m34 * t1], -1)
    return 2 * np.arctan(t)


class Vertex4(JointSpaceKinematics):
    """
    A developable degree-4 vertex driven by the fold angle of one crease.

    Parameters
    ----------
    alpha : (4,) float
      Sector angles in radians, each in (0, pi), summing to 2 pi.
    input_crease : int
      Crease (1 to 4) whose fold angle is the input.
    """

    def __init__(self, alpha: ArrayLike, input_crease: int = 1):
        alpha = developable_sectors(alpha, ("alpha1", "alpha2", "alpha3", "alpha4"))
        if input_crease not in (1, 2, 3, 4):
            raise ParameterError(f"input crease {input_crease} does not exist; use 1 to 4")
        self.alpha = alpha
        self.input_crease = input_crease
        self.input_name = f"rho{input_crease}"
        self.joint_names = ("rho1", "rho2", "rho3", "rho4")
        self._shift = input_crease - 1

    @property
    def flat_foldable(self) -> bool:
        """Kawasaki: alpha_1 + alpha_3 = pi (then alpha_2 + alpha_4 = pi too)."""
        return abs(self.alpha[0] + self.alpha[2] - np.pi) < ANGLE_TOL

    @property
    def collinear_pairs(self) -> tuple[tuple[int, int], ...]:
        """Crease pairs (i, j), 1-based, that lie on one straight line in the flat sheet."""
        pairs = []
        for i in range(4):
            if abs(self.alpha[i] + self.alpha[(i + 1) % 4] - np.pi) < ANGLE_TOL:
                pairs.append(tuple(sorted((i + 1, (i + 2) % 4 + 1))))
        return tuple(sorted(set(pairs)))

    def _roots(self, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Both roots (2, n, 4) in crease order 1..4 for input values x."""
        rolled = np.roll(self.alpha, -self._shift)
        rho, real = fold_roots(rolled, x)
        return np.roll(rho, self._shift, axis=-1), real

    def _codes(self, rho: NDArray[np.float64]) -> NDArray[np.int8]:
        """
        Index into NAMES of each configuration's branch (..., 4) from its fold signs; -1 if none.

        A fold within FLAT_FOLD of +/- pi is folded flat and pi = -pi, so its sign may match either way
        (a domain end where the roots merge on a crease at pi, found by the property tests).
        """
        codes = self._sign_codes(rho)
        at_pi = np.abs(rho) > np.pi - FLAT_FOLD
        if np.any(at_pi):
            other = self._sign_codes(np.where(at_pi, -rho, rho))
            codes = np.where(codes == -1, other, codes)
        return codes

    def _sign_codes(self, rho: NDArray[np.float64]) -> NDArray[np.int8]:
        scale = np.max(np.abs(rho), axis=-1, keepdims=True)
        sign = np.where(np.abs(rho) <= np.maximum(ZERO_FOLD * scale, ZERO_FOLD_ABS), 0, np.sign(rho)).astype(np.int8)
        codes = np.full(rho.shape[:-1], -1, dtype=np.int8)
        zeros = np.sum(sign == 0, axis=-1)
        total = np.sum(sign, axis=-1)
        if self.flat_foldable:
            s1, s3 = sign[..., 0], sign[..., 2]
            codes[(zeros == 0) & (s3 == -s1)] = NAMES.index("S")
            codes[(zeros == 0) & (s3 == s1)] = NAMES.index("C")
        else:
            for k in range(4):
                odd = (zeros == 0) & (np.abs(total) == 2) & (sign[..., k] == -np.sign(total))
                codes[odd] = NAMES.index(f"odd{k + 1}")
        for i, j in self.collinear_pairs:
            others = [c for c in range(4) if c not in (i - 1, j - 1)]
            straight = (
                (zeros == 2)
                & (sign[..., others[0]] == 0)
                & (sign[..., others[1]] == 0)
                & (sign[..., i - 1] == sign[..., j - 1])
            )
            codes[straight] = NAMES.index(f"straight{i}{j}")
        return codes

    @cached_property
    def _branch_names(self) -> tuple[str, ...]:
        probe = np.array([1e-3, -1e-3])
        rho, real = self._roots(probe)
        codes = set(self._codes(rho)[:, real].ravel().tolist()) - {-1}
        return tuple(sorted(NAMES[c] for c in codes))

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        if branch not in self._branch_names:
            self.branch(branch)  # raises with the list of names
        x = as_inputs(x)
        return self.within_domain(branch, x, *self._evaluate_all(branch, x))

    def _evaluate_all(self, branch: str, x: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """The roots on `branch` wherever they are real, before the printed domain is applied (found from these)."""
        rho, real = self._roots(x)
        real &= np.abs(x) <= np.pi  # an input fold angle lives in [-pi, pi]
        codes = self._codes(rho)
        values = np.full((x.size, 4), np.nan)
        valid = np.zeros(x.size, dtype=bool)
        folded = (
            np.all(np.abs(rho) > np.pi - FOLDED_FLAT, axis=-1) if self.flat_foldable and branch in ("S", "C")
            else np.zeros(codes.shape, dtype=bool)
        )
        for k in (1, 0):
            hit = real & ((codes[k] == NAMES.index(branch)) | folded[k])
            values[hit] = rho[k, hit]
            valid |= hit
        # At rounding-level folds the sign pattern is noise: use the branch's tangent at flat
        # (central difference at +/- TANGENT_STEP; the neglected O(x^2) term is below 1e-16 rad).
        tiny = np.abs(x) < TINY_INPUT
        if np.any(tiny):
            ends, _ = self._evaluate_all(branch, np.array([-TANGENT_STEP, TANGENT_STEP]))
            values[tiny] = np.outer(x[tiny], (ends[1] - ends[0]) / (2 * TANGENT_STEP))
            valid |= tiny
        return values, valid

    def on_branch(self, name: str, rho: tuple[NDArray, ...]) -> NDArray[np.bool_]:
        """
        Whether finite configurations (rho1, ..., rho4) ((n,) each, crease order) lie on branch `name` by their fold
        signs: `_codes(rho) == name`, tested for that name alone, column by column (12x faster measured).
        """
        size = [np.abs(r) for r in rho]
        largest = np.maximum(np.maximum(size[0], size[1]), np.maximum(size[2], size[3]))
        cut = np.maximum(ZERO_FOLD * largest, ZERO_FOLD_ABS)
        folded = [s > cut for s in size]  # the nonzero signs of `_sign_codes`
        up = [r > 0 for r in rho]
        if name.startswith("straight"):  # creases i, j folded alike, the other two not
            i, j = int(name[-2]) - 1, int(name[-1]) - 1
            others = [~folded[k] for k in range(4) if k not in (i, j)]
            hit = np.logical_and.reduce([folded[i], folded[j], up[i] == up[j], *others])
            hit &= (i + 1, j + 1) in self.collinear_pairs
        else:  # every crease folded; S / C: rho3 against / with rho1; odd<k>: crease k against the other three
            if name in ("S", "C"):
                signs = [up[2] != up[0] if name == "S" else up[2] == up[0]]
            else:
                k = int(name[-1]) - 1
                signs = [up[j] != up[k] for j in range(4) if j != k]
            hit = np.logical_and.reduce(folded + signs)
            hit &= self.flat_foldable == (name in ("S", "C"))
        at_pi = ~hit & np.logical_or.reduce([s > np.pi - FLAT_FOLD for s in size])
        if np.any(at_pi):  # a fold at pi matches with either sign: `_codes` itself there
            hit[at_pi] = self._codes(np.stack([r[at_pi] for r in rho], -1)) == NAMES.index(name)
        return hit

    @cached_property
    def _branch_roots(self) -> dict[str, int | None]:
        """
        Per branch, the root of `fold_roots` (0 or 1) that `evaluate` takes at every input where it is valid on a
        4097-point grid over [-pi, pi] (inputs below TINY_INPUT left out), or None when it takes both.
        """
        x = np.linspace(-np.pi, np.pi, 4097)
        x = x[np.abs(x) >= TINY_INPUT]
        rho, real = self._roots(x)
        codes = self._codes(rho)
        out = {}
        for name in self._branch_names:
            first = real & (codes[0] == NAMES.index(name))
            second = real & (codes[1] == NAMES.index(name)) & ~first
            out[name] = 0 if not np.any(second) else 1 if not np.any(first) else None
        return out

    def branch_folds(self, branch: str, x: ArrayLike) -> tuple[list[NDArray[np.float64]], NDArray[np.bool_]]:
        """
        `evaluate` as four columns (n,) each (valid wherever the root is real, the printed domain not applied: the
        mesh applies its own), computing only the branch's root where it takes one (`_branch_roots`): inputs where
        that root is off the branch, or below TINY_INPUT, are handed to `_evaluate_all`. The same numbers
        (bit for bit on the vertices of the tests), 4x faster.
        """
        x = as_inputs(x)
        k = self._branch_roots.get(branch)
        if k is None:
            values, valid = self._evaluate_all(branch, x)
            return [values[:, j] for j in range(4)], valid
        rolled, real = fold_root(np.roll(self.alpha, -self._shift), x, k)
        rho = [rolled[(j - self._shift) % 4] for j in range(4)]
        valid = real & (np.abs(x) <= np.pi) & self.on_branch(branch, rho)
        redo = ~valid | (np.abs(x) < TINY_INPUT)
        rho = [np.where(valid, r, np.nan) for r in rho]
        if np.any(redo):
            values, valid[redo] = self._evaluate_all(branch, x[redo])
            for j in range(4):
                rho[j][redo] = values[:, j]
        return rho, valid

    def _valid(self, branch: str):
        return lambda x: self._evaluate_all(branch, as_inputs(x))[1]

    @cached_property
    def _branches(self) -> tuple[Branch, ...]:
        out = []
        for name in self._branch_names:
            domain = domain_of(self._valid(name), -np.pi, np.pi, 0.0)
            out.append(Branch(name, self._describe(name), domain))
        return tuple(out)

    def _describe(self, name: str) -> str:
        if name == "S":
            return "flat-foldable mode S: rho3 = -rho1, rho4 = rho2 (Peng 2018, eqn 3-3a)"
        if name == "C":
            return "flat-foldable mode C: rho3 = rho1, rho4 = -rho2 (Peng 2018, eqn 3-3b)"
        if name.startswith("straight"):
            return f"fold about the straight line of creases {name[-2]} and {name[-1]} only"
        return f"crease {name[-1]} folds opposite to the other three"

    def branches(self) -> tuple[Branch, ...]:
        return self._branches

    def events(self) -> tuple[Event, ...]:
        names = tuple(b.name for b in self._branches)
        events = [Event("bifurcation", 0.0, names, "flat state: every branch passes through it")]
        for b in self._branches:
            for end in b.domain:
                events.append(self._end_event(b.name, end))
        return tuple(events)

    def _end_event(self, name: str, end: float) -> Event:
        rho = self.evaluate(name, end)[0][0]
        k = int(np.argmax(np.abs(rho)))
        if abs(abs(rho[k]) - np.pi) < 1e-5:
            return Event("lock", end, (name,), f"crease {k + 1} folds flat (|rho{k + 1}| = pi)")
        return Event("turning_point", end, (name,), "|C| = sqrt(A^2 + B^2): the input turns back")

    def gruebler(self) -> int:
        """One spherical loop of 4 revolute joints: 4 - 3."""
        return 1

    def loop_system(self) -> LoopSystem:
        """Spherical D-H loop Rz(rho_1) Rx(alpha_1) ... Rz(rho_4) Rx(alpha_4) = I (Peng 2018, eqn 2-1)."""
        links = np.stack([transform(rot_x(a)) for a in self.alpha])
        return LoopSystem(4, (Loop((0, 1, 2, 3), links, (1, 1, 1, 1)),))

    def loop_input(self) -> tuple[int, float]:
        return self.input_crease - 1, 1.0
