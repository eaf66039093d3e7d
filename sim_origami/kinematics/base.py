"""The contract every closed-form kinematics model meets (numpy only).

A model maps one input angle to named output joints on named branches. Each model also exposes
its loop as a `closure.LoopSystem` over "loop joints" (the revolute joints of the linkage), so the
numeric solver and MuJoCo can be compared with the closed form through the same `observe` map.

Writing your own (a closed form in your own module, made a scene with `scenes.custom_scene`; docs/extending.md):

* `input_name` (str) and `joint_names` (tuple of str): what `describe` prints and reference CSVs name.
* `branches()`: every motion branch, named by geometry, each with a closed, finite input domain (rad).
* `evaluate(branch, x)`: vectorised over x (rad); values (n, len(joint_names)) and a validity mask (n,);
  NaN exactly where invalid; never raises for an input outside the domain. Keep each branch continuous
  along its domain (no 2 pi jumps): the numeric solve follows it by continuity and is compared without wrapping.
* `loop_system()`: the linkage as closed chains of revolute joints (`closure.Loop`, `dh.dh_loop` for a D-H
  loop); this is the independent truth, so build it from the geometry, never from the closed form.
* `loop_input()`: (loop joint index, scale): that loop joint equals scale * input; the scene drives it.
* `loop_angles(values)` and `observe(q_loop)`: outputs to loop joint angles and back; each inverts the other.
  `JointSpaceKinematics` (outputs = loop joints) and `dh.DHKinematics` (one D-H loop) provide them.
* `events()`: bifurcations, locks and turning points (may be empty); `gruebler()`: the Kutzbach count.
"""

from abc import ABC, abstractmethod
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..errors import DomainError, ParameterError


@dataclass(frozen=True)
class Branch:
    """A motion branch, named by geometry, valid for inputs in `domain` (radians, closed)."""

    name: str
    description: str
    domain: tuple[float, float]


@dataclass(frozen=True)
class Event:
    """A special input value: a bifurcation, a lock (self-contact) or a turning point."""

    kind: str
    input: float
    branches: tuple[str, ...]
    detail: str


class Kinematics(ABC):
    """
    Closed-form kinematics of one mechanism; all angles in radians. Subclass it and define the abstract
    members below (the module docstring lists the rules); `scenes.custom.check_kinematics` checks them.
    """

    input_name: str
    joint_names: tuple[str, ...]

    @abstractmethod
    def branches(self) -> tuple[Branch, ...]:
        """Every motion branch with its input domain."""

    @abstractmethod
    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """
        Output joints on one branch, without raising.

        Returns
        -------
        values : (n, len(joint_names)) float
          NaN exactly where `valid` is False.
        valid : (n,) bool
          Whether each input lies in the branch's domain.
        """

    @abstractmethod
    def events(self) -> tuple[Event, ...]:
        """Bifurcations, locks and turning points of the motion."""

    @abstractmethod
    def gruebler(self) -> int:
        """Grubler-Kutzbach mobility count: n - 6 per spatial loop, n - 3 per spherical loop."""

    @abstractmethod
    def loop_system(self) -> LoopSystem:
        """The linkage as closed chains of revolute joints (the numeric truth)."""

    @abstractmethod
    def loop_input(self) -> tuple[int, float]:
        """(loop joint index, scale): that loop joint equals scale * input."""

    def loop_inputs(self, x: ArrayLike) -> tuple[tuple[int, ...], NDArray[np.float64]]:
        """(loop joints, their values (n, k)) that inputs x (n,) hold: `loop_input`'s one joint by default."""
        joint, scale = self.loop_input()
        return (joint,), scale * as_inputs(x)[:, None]

    def evaluate_held(
        self, branch: str, x: ArrayLike, held: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """
        `evaluate` with the input loop joints (`loop_inputs`' joints) at `held` (n, k) (rad) instead of their values
        at x: for several inputs, the reference where a simulation's driven joints are, which may lie off the
        inputs' path. One input: `evaluate` at x (the held joint is scale * x there).
        """
        return self.evaluate(branch, x)

    @abstractmethod
    def observe(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        """Output joints (n, k) measured from loop joint angles (n, n_loop_joints)."""

    @abstractmethod
    def loop_angles(self, values: ArrayLike) -> NDArray[np.float64]:
        """Loop joint angles (n, n_loop_joints) of closed-form outputs (n, k)."""

    def points(self, branch: str, x: ArrayLike) -> NDArray[np.float64] | None:
        """
        Named points (n, V, 3) of the closed form in units of the model's length scale, for models whose
        truth is a shape (the vertices of a polyhedron); None for the others.
        """
        return None

    def observe_points(self, q_loop: ArrayLike) -> NDArray[np.float64] | None:
        """The same points measured from loop joint angles (n, n_loop_joints); None where `points` is None."""
        return None

    def in_domain(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """Inputs x as a 1-D float array (rad) and whether each lies in the branch's closed domain."""
        lo, hi = self.branch(branch).domain
        x = as_inputs(x)
        return x, (x >= lo) & (x <= hi)

    def within_domain(
        self, branch: str, x: NDArray[np.float64], values: NDArray[np.float64], valid: NDArray[np.bool_]
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """
        `evaluate`'s result made valid only on the branch's printed domain: a domain found by bisection
        (`domain_of`) ends EDGE_MARGIN inside where the model's own test flips, and inputs between must be null too.
        """
        lo, hi = self.branch(branch).domain
        outside = valid & ((x < lo) | (x > hi))
        if np.any(outside):
            values = values.copy()
            values[outside] = np.nan
        return values, valid & ~outside

    def branch(self, name: str) -> Branch:
        """The branch called `name`; ParameterError listing the names otherwise."""
        for b in self.branches():
            if b.name == name:
                return b
        names = ", ".join(b.name for b in self.branches())
        raise ParameterError(f"unknown branch {name!r}; this model has: {names}")

    def joint_angles(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        """
        Output joints on one branch (n, k) in radians.

        Raises
        ------
        DomainError
          When any input lies outside the branch's domain; names the first such value.
        """
        x = as_inputs(x)
        values, valid = self.evaluate(branch, x)
        if not np.all(valid):
            bad = float(x[~valid][0])
            lo, hi = self.branch(branch).domain
            raise DomainError(
                f"{self.input_name} = {bad:.6g} rad is outside branch {branch!r}, "
                f"whose domain is [{lo:.6g}, {hi:.6g}] rad"
            )
        return values

    def at(self, branch: str, x: float) -> dict[str, float]:
        """Output joints at one input value, by name; DomainError unless x is one number."""
        if as_inputs(x).size != 1:
            raise DomainError(f"at takes one input; {np.size(x)} given (joint_angles takes several)")
        return dict(zip(self.joint_names, self.joint_angles(branch, x)[0].tolist(), strict=True))


# Bisected domain ends are pulled inward by this much (rad): at the exact edge, validity can flip
# with the last ulp of numpy's vectorised sin/cos, which depends on the array's length.
EDGE_MARGIN = 1e-13


class JointSpaceKinematics(Kinematics):
    """A model whose output joints are its loop joints (the hinge angles), in the same order."""

    def observe(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(q_loop, dtype=float).reshape(-1, len(self.joint_names))

    def loop_angles(self, values: ArrayLike) -> NDArray[np.float64]:
        return np.asarray(values, dtype=float).reshape(-1, len(self.joint_names))


def domain_of(valid_at, lo: float, hi: float, anchor: float, samples: int = 4097) -> tuple[float, float]:
    """
    The closed interval around `anchor` on which the vectorised predicate `valid_at` holds.

    Dense sampling of [lo, hi] finds the connected run through `anchor`; bisection refines both
    ends to about 1e-13 rad, then pulls them EDGE_MARGIN inside.
    """
    grid = np.linspace(lo, hi, samples)
    ok = valid_at(grid)
    k = int(np.argmin(np.abs(grid - anchor)))
    if not ok[k]:
        raise ParameterError(f"no valid configuration at input {anchor:.6g} rad")
    left, right = k, k
    while left > 0 and ok[left - 1]:
        left -= 1
    while right < samples - 1 and ok[right + 1]:
        right += 1

    def refine(inside: float, outside: float) -> float:
        a = np.array([inside])
        b = np.array([outside])
        for _ in range(60):
            mid = 0.5 * (a + b)
            good = valid_at(mid)
            a = np.where(good, mid, a)
            b = np.where(good, b, mid)
        return float(a[0])

    start = grid[left] if left == 0 else refine(grid[left], grid[left - 1]) + EDGE_MARGIN
    stop = grid[right] if right == samples - 1 else refine(grid[right], grid[right + 1]) - EDGE_MARGIN
    return float(start), float(stop)


# Inputs per block of a vectorised evaluation: a block's temporaries stay in the CPU cache. 1e6 inputs: Kokotsakis
# Example 1 0.43 s of CPU (one block 0.75 s, 4096: 0.48 s, 16384: 0.63 s); 6 x 5 tube 1.10 s (one block 1.76 s,
# 4096: 1.17 s, 16384: 1.43 s).
BLOCK = 8192


def input_blocks(n: int, size: int = BLOCK) -> Iterator[slice]:
    """Consecutive slices of at most `size` of n inputs, for evaluations done block by block."""
    for start in range(0, n, size):
        yield slice(start, min(start + size, n))


def as_inputs(x: ArrayLike) -> NDArray[np.float64]:
    """Inputs (rad) as a 1-D float array: one number or a 1-D sequence of them; DomainError naming what was given
    otherwise (a 2-D array, a string)."""
    try:
        x = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        raise DomainError(f"inputs {str(x)[:40]!r} are not numbers (rad)") from None
    if x.ndim > 1:
        raise DomainError(f"inputs of shape {x.shape}: give one input or a 1-D array of them (rad)")
    return np.atleast_1d(x)


def transformation_inputs(x: ArrayLike, domain: tuple[float, float], name: str, what: str) -> NDArray[np.float64]:
    """
    Inputs `name` (rad) of a transformation `what` as a 1-D array; DomainError naming the first one not finite or
    outside `domain` (1e-12 rad slack).
    """
    x = as_inputs(x)
    lo, hi = domain
    bad = x[~((x >= lo - 1e-12) & (x <= hi + 1e-12))]
    if bad.size:
        raise DomainError(
            f"{name} = {np.rad2deg(bad[0]):.6g} deg is outside the transformation, whose domain is "
            f"[{np.rad2deg(lo):.6g}, {np.rad2deg(hi):.6g}] deg ({what})"
        )
    return x
