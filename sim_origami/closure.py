"""Independent numeric loop closure: the second truth for every model.

A loop is a closed chain of revolute joints written in the seeds' Denavit-Hartenberg form

    T(q) = Rz(s_0 q[j_0]) L_0 Rz(s_1 q[j_1]) L_1 ... Rz(s_(n-1) q[j_(n-1)]) L_(n-1),

which closes when T(q) = I. `L_k` is the constant transform from joint k's frame to joint k+1's
frame at zero angle and `s_k = +/-1` is the direction in which the loop traverses joint k. The
residual of a loop is (rotation vector of T, translation of T): radians and the mechanism's length
unit. Nothing here knows a closed form; the solver is damped Newton (Levenberg-Marquardt, which
tolerates the rank-deficient Jacobians of overconstrained loops) with continuation in the input.
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import ConvergenceError
from .geometry import left_jacobian_inverse, rotation_vector, transform_z, wrap


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


def _levenberg_marquardt(residual, jacobian, u: NDArray[np.float64], tol: float, max_iter: int):
    """
    Damped Gauss-Newton (Levenberg-Marquardt, tolerant of rank-deficient Jacobians) on residual(u), from u; stops
    below `tol` (largest component), after `max_iter` steps, or when the damping needed exceeds 1e8.
    Returns (u, residual).
    """
    damping = 1e-6
    r = residual(u)
    for _ in range(max_iter):
        if np.max(np.abs(r)) < tol:
            break
        J = jacobian(u)
        JtJ = J.T @ J
        trial = u + np.linalg.solve(JtJ + damping * np.diag(np.diag(JtJ) + 1e-12), -J.T @ r)
        r_trial = residual(trial)
        if np.sum(r_trial**2) < np.sum(r**2):
            u, r = trial, r_trial
            damping = max(damping * 0.1, 1e-12)
        else:
            damping *= 10.0
            if damping > 1e8:
                break
    return u, r


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

    def residual(self, q: ArrayLike) -> NDArray[np.float64]:
        """
        Closure residual (..., 6 * n_loops + n_couplings): per loop, rotation vector then translation;
        then q[joint] - scale * q[other] (rad) per coupling.
        """
        q = np.asarray(q, dtype=float)
        parts = []
        for loop in self.loops:
            T = loop.product(q)
            parts += [rotation_vector(T[..., :3, :3]), T[..., :3, 3]]
        parts += [(q[..., c.joint] - c.scale * q[..., c.other])[..., None] for c in self.couplings]
        return np.concatenate(parts, axis=-1)

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

    def residual_norm(self, q: ArrayLike) -> NDArray[np.float64]:
        """Largest absolute closure residual component, (...)."""
        return np.max(np.abs(self.residual(q)), axis=-1)

    def jacobian(self, q: ArrayLike) -> NDArray[np.float64]:
        """
        Closure Jacobian (n_residuals, n_joints) at one configuration, exact.

        Turning joint k moves a loop's end by the joint's twist in the loop's base frame: axis w = s_k z_k
        through the joint's origin p_k. The end's translation t changes by w x (t - p_k) and its rotation
        vector phi by Jl^-1(phi) w (inverse left Jacobian of SO(3); the identity once the loop is closed).
        """
        q = np.asarray(q, dtype=float)
        J = np.zeros((6 * len(self.loops) + len(self.couplings), self.n_joints))
        for m, loop in enumerate(self.loops):
            T = np.eye(4)
            axes, points = np.zeros((len(loop.joints), 3)), np.zeros((len(loop.joints), 3))
            for k, (s, L) in enumerate(zip(loop.signs, loop.links, strict=True)):
                T = T @ transform_z(s * q[loop.joints[k]])
                axes[k], points[k] = s * T[:3, 2], T[:3, 3]
                T = T @ L
            rows = np.vstack([(left_jacobian_inverse(rotation_vector(T[:3, :3])) @ axes.T),
                              np.cross(axes, T[:3, 3] - points).T])  # fmt: skip
            np.add.at(J[6 * m : 6 * m + 6].T, list(loop.joints), rows.T)  # a joint may be in several loops
        for c, coupling in enumerate(self.couplings):
            J[6 * len(self.loops) + c, coupling.joint] += 1.0
            J[6 * len(self.loops) + c, coupling.other] -= coupling.scale
        return J

    def solve(
        self,
        q0: ArrayLike,
        fixed: ArrayLike,
        *,
        tol: float = 1e-14,
        max_iter: int = 60,
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

        u, r = _levenberg_marquardt(
            lambda u: w * self.residual(q_of(u)), lambda u: w[:, None] * self.jacobian(q_of(u))[:, free], q[free],
            tol, max_iter,
        )  # fmt: skip
        q = q_of(u)
        if np.max(np.abs(r)) < 100 * tol:
            return q
        raise ConvergenceError(
            f"loop closure did not converge: residual {np.max(np.abs(r)):.3g} > tolerance {tol:g} (radians, lengths "
            f"in units of the longest link, {self.length_scale:.4g})"
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
        u, r = _levenberg_marquardt(lambda u: self.residual(q_of(u)), jacobian, u0, tol, max_iter)
        return q_of(u), float(np.max(np.abs(r)))

    def follow(
        self, q_start: ArrayLike, input_joint: int, values: ArrayLike, *, tol: float = 1e-14
    ) -> NDArray[np.float64]:
        """
        Follow one branch by continuity: solve at each input value in turn.

        Each solve starts from a secant prediction through the two previous solutions, so the
        branch is kept through crossings. `q_start` must be closed (or nearly) at `values[0]`.

        Returns
        -------
        q : (len(values), n_joints) float
        """
        values = np.asarray(values, dtype=float)
        fixed = np.zeros(self.n_joints, dtype=bool)
        fixed[input_joint] = True
        out = np.empty((len(values), self.n_joints))
        q = np.array(q_start, dtype=float)
        for k, x in enumerate(values):
            guess = q.copy()
            if k >= 2 and values[k - 1] != values[k - 2]:
                rate = (out[k - 1] - out[k - 2]) / (values[k - 1] - values[k - 2])
                guess = out[k - 1] + rate * (x - values[k - 1])
            guess[input_joint] = x
            q = self.solve(guess, fixed, tol=tol)
            out[k] = q
        return out

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
        Instantaneous mobility: joints minus the numerical rank of the closure Jacobian.

        Singular values below rtol times the largest count as zero (the Jacobian is exact, so only rounding
        is below it; a regular pose keeps O(0.1) values).
        """
        s = np.linalg.svd(self.jacobian(q), compute_uv=False)
        return self.n_joints - int(np.sum(s > rtol * max(s.max(initial=0.0), 1.0)))
