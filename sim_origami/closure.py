"""Independent numeric loop closure: the second truth for every model.

A loop is a closed chain of revolute joints written in the Denavit-Hartenberg form of the sources (Yang 2017,
Eq. 1-2; Peng 2018, Eqs. 1-1, 1-2)

    T(q) = Rz(s_0 q[j_0]) L_0 Rz(s_1 q[j_1]) L_1 ... Rz(s_(n-1) q[j_(n-1)]) L_(n-1),

which closes when T(q) = I. `L_k` is the constant transform from joint k's frame to joint k+1's
frame at zero angle and `s_k = +/-1` is the direction in which the loop traverses joint k. The
residual of a loop is (rotation vector of T, translation of T): radians and the mechanism's length
unit. Nothing here knows a closed form; the solver is damped Newton (Levenberg-Marquardt, which
tolerates the rank-deficient Jacobians of overconstrained loops) with continuation in the input; both
are the path engine's (`path.levenberg_marquardt`, `path.sweep`).
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import sparse as sp

from .errors import ConvergenceError
from .geometry import left_jacobian_inverse, rotation_vector, transform_z, wrap
from .path import levenberg_marquardt, rank, sweep

# `follow`'s first Levenberg-Marquardt damping. From the path engine's 1e-6 its steps near a solution converged only
# linearly (the 16 x 16 Miura sheet's continuation: 6.8e-5, 2.3e-8, 7.8e-12, 4.5e-16, three Jacobians a solve), from
# 1e-9 quadratically (6.8e-5, 1.5e-9, 3.9e-16, two). Other solves keep 1e-6: with 1e-9 everywhere the Myard RSRRR
# file's bifurcation was located 8e-5 rad off (the trace's corrector alone at 1e-9: 2.3e-8, against 1e-9) and the
# bird base's trace from flat took another branch.
FOLLOW_DAMPING = 1e-9


@dataclass(frozen=True)
class Loop:
    """One closed chain; see the module docstring for the product it stands for."""

    joints: tuple[int, ...]
    links: NDArray[np.float64]  # (n, 4, 4)
    signs: tuple[int, ...]

    def product(self, q: ArrayLike) -> NDArray[np.float64]:
        """Loop transforms T(q), (..., 4, 4), for joint vectors q of shape (..., n_joints)."""
        q = np.asarray(q, dtype=float)
        T = np.broadcast_to(np.eye(4), (*q.shape[:-1], 4, 4))
        for j, s, L in zip(self.joints, self.signs, self.links, strict=True):
            T = T @ transform_z(s * q[..., j]) @ L
        return T


def _scale_rows(J, w: NDArray[np.float64]):
    """Rows of a dense or sparse (CSC) Jacobian times weights w (n_rows,); a sparse one keeps its pattern, explicit
    zeros too (the corrector's band layout is kept per pattern, `path.BandedNormal`)."""
    if not sp.issparse(J):
        return w[:, None] * J
    return sp.csc_matrix((J.data * w[J.indices], J.indices, J.indptr), shape=J.shape)


@dataclass(frozen=True)
class Coupling:
    """A linear joint coupling q[joint] = scale * q[other] (an imposed symmetry or a periodic copy)."""

    joint: int
    other: int
    scale: float = 1.0


@dataclass(frozen=True)
class LoopSystem:
    """All independent loops of a mechanism over one vector of `n_joints` joint angles, plus couplings."""

    n_joints: int
    loops: tuple[Loop, ...]
    couplings: tuple[Coupling, ...] = ()
    # Solve with sparse normal equations (patterns of hundreds of creases; same results to the tolerance).
    sparse: bool = False

    @cached_property
    def _batches(self) -> tuple[tuple[NDArray, NDArray, NDArray, NDArray], ...]:
        """
        The loops grouped by length, so products run over a group at once (a Python step per joint of the
        loop, not per loop): (loop indices (G,), joints (G, n), signs (G, n), links (G, n, 4, 4)) per group.
        """
        groups: dict[int, list[int]] = {}
        for m, loop in enumerate(self.loops):
            groups.setdefault(len(loop.joints), []).append(m)
        return tuple(
            (np.array(ms), np.array([self.loops[m].joints for m in ms]),
             np.array([self.loops[m].signs for m in ms], dtype=float), np.stack([self.loops[m].links for m in ms]))
            for ms in groups.values()
        )

    @property
    def n_residuals(self) -> int:
        """Rows of the residual: 6 per loop, one per coupling."""
        return 6 * len(self.loops) + len(self.couplings)

    def residual(self, q: ArrayLike) -> NDArray[np.float64]:
        """
        Closure residual (..., 6 * n_loops + n_couplings): per loop, rotation vector then translation;
        then q[joint] - scale * q[other] (rad) per coupling. Empty (..., 0) for an open chain.
        """
        q = np.asarray(q, dtype=float)
        out = np.empty((*q.shape[:-1], self.n_residuals))
        per_loop = out[..., : 6 * len(self.loops)].reshape(*q.shape[:-1], len(self.loops), 6)
        for ms, joints, signs, links in self._batches:
            angles = signs * q[..., joints]
            T = transform_z(angles[..., 0]) @ links[:, 0]  # = I Rz L: the identity's product is exact
            for k in range(1, joints.shape[1]):
                T = T @ transform_z(angles[..., k]) @ links[:, k]
            per_loop[..., ms, :3] = rotation_vector(T[..., :3, :3])
            per_loop[..., ms, 3:] = T[..., :3, 3]
        for c, coupling in enumerate(self.couplings):
            out[..., 6 * len(self.loops) + c] = q[..., coupling.joint] - coupling.scale * q[..., coupling.other]
        return out

    @cached_property
    def length_scale(self) -> float:
        """
        The loops' longest link (largest translation of any L_k, length units), at least 1: translations are held to
        the solve's tolerance in units of it on large models and in length units on small and spherical ones (whose
        links carry only rounding, 1e-16).
        """
        lengths = [float(np.linalg.norm(L[:3, 3])) for loop in self.loops for L in loop.links]
        return max([1.0, *lengths])

    @cached_property
    def _weights(self) -> NDArray[np.float64]:
        """Residual weights that make every component dimensionless: translations in units of `length_scale`."""
        loop = np.r_[np.ones(3), np.full(3, 1.0 / self.length_scale)]
        return np.r_[np.tile(loop, len(self.loops)), np.ones(len(self.couplings))]

    def residual_size(self, r: ArrayLike) -> NDArray[np.float64]:
        """Largest component of residuals r (..., n_residuals) as `solve` weighs them (translations in units of
        `length_scale`), (...); 0 for an open chain."""
        return np.max(np.abs(np.asarray(r) * self._weights), axis=-1, initial=0.0)

    def residual_norm(self, q: ArrayLike) -> NDArray[np.float64]:
        """Largest absolute closure residual component, (...); 0 for an open chain."""
        return np.max(np.abs(self.residual(q)), axis=-1, initial=0.0)

    def jacobian(self, q: ArrayLike) -> NDArray[np.float64]:
        """
        Closure Jacobian (n_residuals, n_joints) at one configuration, exact.

        Turning joint k moves a loop's end by the joint's twist in the loop's base frame: axis w = s_k z_k
        through the joint's origin p_k. The end's translation t changes by w x (t - p_k) and its rotation
        vector phi by Jl^-1(phi) w (inverse left Jacobian of SO(3); the identity once the loop is closed).
        """
        J = np.zeros((self.n_residuals, self.n_joints))
        rows, cols, values = self.jacobian_entries(q)
        np.add.at(J, (rows, cols), values)  # a joint may appear in several loops, and twice in one
        return J

    def jacobian_sparse(self, q: ArrayLike) -> sp.csc_matrix:
        """`jacobian` as a sparse matrix (a loop touches only its own joints): for patterns of many creases."""
        position, indices, indptr = self._sparse_layout
        data = np.bincount(position, weights=self.jacobian_entries(q)[2], minlength=len(indices))
        return sp.csc_matrix((data, indices, indptr), shape=(self.n_residuals, self.n_joints))

    @cached_property
    def _sparse_layout(self) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.int64]]:
        """Where `jacobian_entries` land in CSC storage, the same at every q: (slot of each entry, row indices,
        column pointers); repeated positions share a slot and are summed."""
        rows, cols, _ = self.jacobian_entries(np.zeros(self.n_joints))
        slots, position = np.unique(cols * self.n_residuals + rows, return_inverse=True)
        indptr = np.searchsorted(slots // self.n_residuals, np.arange(self.n_joints + 1))
        return position, slots % self.n_residuals, indptr

    def jacobian_entries(self, q: ArrayLike) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64]]:
        """The Jacobian's entries as (rows, columns, values), repeated positions to be summed."""
        q = np.asarray(q, dtype=float)
        rows_out, cols_out, vals_out = [], [], []
        for ms, joints, signs, links in self._batches:
            g, n = joints.shape
            axes, points = np.zeros((g, n, 3)), np.zeros((g, n, 3))
            angles = signs * q[joints]
            T = transform_z(angles[:, 0])  # the product starts at the first rotation (I Rz = Rz exactly)
            for k in range(n):
                if k:
                    T = T @ transform_z(angles[:, k])
                axes[:, k], points[:, k] = signs[:, k, None] * T[:, :3, 2], T[:, :3, 3]
                T = T @ links[:, k]
            rot = left_jacobian_inverse(rotation_vector(T[:, :3, :3])) @ np.swapaxes(axes, 1, 2)  # (g, 3, n)
            d = T[:, None, :3, 3] - points
            # axes x d written out (as np.cross computes it, the same values in a third of the time)
            move = np.stack([axes[..., 1] * d[..., 2] - axes[..., 2] * d[..., 1],
                             axes[..., 2] * d[..., 0] - axes[..., 0] * d[..., 2],
                             axes[..., 0] * d[..., 1] - axes[..., 1] * d[..., 0]], axis=1)
            rows = 6 * ms[:, None, None] + np.arange(6)[None, :, None]
            rows_out.append(np.broadcast_to(rows, (g, 6, n)).ravel())
            cols_out.append(np.broadcast_to(joints[:, None, :], (g, 6, n)).ravel())
            vals_out.append(np.concatenate([rot, move], axis=1).ravel())
        base = 6 * len(self.loops)
        for c, coupling in enumerate(self.couplings):
            rows_out.append(np.array([base + c, base + c]))
            cols_out.append(np.array([coupling.joint, coupling.other]))
            vals_out.append(np.array([1.0, -coupling.scale]))
        if not rows_out:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64), np.zeros(0)
        return np.concatenate(rows_out), np.concatenate(cols_out), np.concatenate(vals_out)

    def solve(
        self,
        q0: ArrayLike,
        fixed: ArrayLike,
        *,
        tol: float = 1e-14,
        max_iter: int = 60,
        damping: float = 1e-6,
    ) -> NDArray[np.float64]:
        """
        Close the loops by moving the joints not in `fixed`, starting from `q0`.

        Parameters
        ----------
        q0 : (n_joints,) float
          Start configuration; fixed joints keep their value.
        fixed : (n_joints,) bool
          Joints held at their `q0` value (the input).
        tol : float
          Stop when the largest residual component is below this: radians, and translations in units of the
          loops' `length_scale` (a Bricard linkage with 10 km links closes to the same relative precision as one
          with 1 m links; an absolute 1e-14 m was below the rounding of its 1e4 m products).
        damping : float
          Levenberg-Marquardt's first damping (`path.levenberg_marquardt`).

        Raises
        ------
        ConvergenceError
          When the residual stays above `tol` (within a factor 100) after `max_iter` iterations.
        """
        q = np.array(q0, dtype=float)
        free = ~np.asarray(fixed, dtype=bool)
        w = self._weights

        def q_of(u: NDArray[np.float64]) -> NDArray[np.float64]:
            out = q.copy()
            out[free] = u
            return out

        jacobian = self.jacobian_sparse if self.sparse else self.jacobian
        u, r = levenberg_marquardt(
            lambda u: w * self.residual(q_of(u)), lambda u: _scale_rows(jacobian(q_of(u))[:, free], w), q[free], tol,
            max_iter, damping=damping,
        )
        q = q_of(u)
        worst = float(np.max(np.abs(r), initial=0.0))
        if worst < 100 * tol:
            return q
        raise ConvergenceError(
            f"loop closure did not converge: residual {worst:.3g} > tolerance {tol:g} (radians, lengths in units of "
            f"the longest link, {self.length_scale:.4g})"
        )

    def solve_signed(
        self, signs: ArrayLike, input_joint: int, x: float, *, tol: float = 1e-14, max_iter: int = 200
    ) -> tuple[NDArray[np.float64], float]:
        """
        Close the loops at q[input_joint] = x with every other joint held to the sign of `signs` (+1, -1),
        as mountain/valley joint ranges would: q = signs pi sigmoid(u), strictly inside (0, pi) or (-pi, 0).

        Levenberg-Marquardt in u from q = signs |x|; stops below `tol` or when no step lowers the residual.
        Returns (q, largest |residual|): the residual stalls above zero when no configuration with these
        signs closes (a rigid-foldability verdict, not a convergence failure, so nothing is raised).
        """
        s = np.asarray(signs, dtype=float)
        free = np.arange(self.n_joints) != input_joint

        def q_of(u: NDArray[np.float64]) -> NDArray[np.float64]:
            q = np.full(self.n_joints, float(x))
            q[free] = s[free] * np.pi / (1.0 + np.exp(-np.clip(u, -700.0, 700.0)))
            return q

        def jacobian(u: NDArray[np.float64]) -> NDArray[np.float64]:
            q = q_of(u)
            rate = q[free] * (1.0 - q[free] / (s[free] * np.pi))  # dq/du
            return self.jacobian(q)[:, free] * rate

        u0 = np.full(int(np.sum(free)), np.log(abs(x) / (np.pi - abs(x))))
        u, r = levenberg_marquardt(lambda u: self.residual(q_of(u)), jacobian, u0, tol, max_iter)
        return q_of(u), float(np.max(np.abs(r), initial=0.0))

    def follow(
        self, q_start: ArrayLike, input_joint: int | tuple[int, ...], values: ArrayLike, *, tol: float = 1e-14
    ) -> NDArray[np.float64]:
        """
        Follow one branch by continuity: solve at each input value in turn (`path.sweep`).

        Each solve starts from a secant prediction through the two previous solutions, so the
        branch is kept through crossings. `q_start` must be closed (or nearly) at `values[0]`. Several
        input joints (a tuple) take rows of `values` (n, k); the secant's parameter is then the arc length of
        the inputs' path.

        Returns
        -------
        q : (len(values), n_joints) float
        """
        values = np.asarray(values, dtype=float)
        inputs = np.atleast_1d(input_joint)
        fixed = np.zeros(self.n_joints, dtype=bool)
        fixed[inputs] = True
        s = values if values.ndim == 1 else np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(values, axis=0), axis=1))]

        def close(guess: NDArray[np.float64], k: int) -> NDArray[np.float64]:
            guess[inputs] = values[k]
            return self.solve(guess, fixed, tol=tol, damping=FOLLOW_DAMPING)

        return sweep(close, q_start, s)

    def assemblies(
        self,
        input_joint: int,
        value: float,
        *,
        starts: int = 64,
        seed: int = 0,
        tol: float = 1e-13,
    ) -> NDArray[np.float64]:
        """
        All distinct closed configurations found from random starts at one input value.

        Returns
        -------
        q : (k, n_joints) float
          Distinct solutions (angles wrapped to (-pi, pi]), k >= 0.
        """
        rng = np.random.default_rng(seed)
        fixed = np.zeros(self.n_joints, dtype=bool)
        fixed[input_joint] = True
        found: list[NDArray[np.float64]] = []
        for _ in range(starts):
            q0 = rng.uniform(-np.pi, np.pi, self.n_joints)
            q0[input_joint] = value
            try:
                q = self.solve(q0, fixed, tol=tol)
            except ConvergenceError:
                continue
            q = wrap(q)
            if not any(np.max(np.abs(wrap(q - f))) < 1e-6 for f in found):
                found.append(q)
        return np.array(found).reshape(-1, self.n_joints)

    def mobility(self, q: ArrayLike, rtol: float = 1e-6) -> int:
        """
        Instantaneous mobility: joints minus the numerical rank of the closure Jacobian (`path.rank`).

        Singular values below rtol times the largest count as zero (the Jacobian is exact, so only rounding
        is below it; a regular pose keeps O(0.1) values).
        """
        return self.n_joints - rank(self.jacobian_sparse(q) if self.sparse else self.jacobian(q), rtol)
