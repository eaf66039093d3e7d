"""Path error: simulated outputs against the closed form at the simulated input."""

from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from ..geometry import wrap
from ..path import condition
from ..scenes.base import Scene


@dataclass(frozen=True)
class PathComparison:
    """Simulated and analytic outputs (n, k) at the simulated inputs (n,), radians."""

    input: NDArray[np.float64]
    simulated: NDArray[np.float64]
    analytic: NDArray[np.float64]

    @cached_property
    def error(self) -> NDArray[np.float64]:
        """|simulated - analytic| (n, k), modulo 2 pi; NaN where the input left the branch's domain."""
        return np.abs(wrap(self.simulated - self.analytic))

    def max_error(self) -> float:
        """Largest error over samples and joints (inf if the input ever left the domain)."""
        err = self.error
        return float(np.max(err)) if np.all(np.isfinite(err)) else float("inf")


def compare(scene: Scene, branch: str, q: NDArray[np.float64]) -> PathComparison:
    """
    Outputs measured from mechanism angles q (n, n_joints) against `branch`. With several driven joints, the
    reference holds them where q has them: their dynamic lags differ, so they leave the drive path a little, and
    the reference at the path's nearest point would count that tracking gap, geared up by the mechanism, as error
    (docs/fold_motion.md, the waterbomb cell driven by five creases).
    """
    x = scene.input_of(q)
    if scene.drive_path is None:
        analytic, _ = scene.kinematics.evaluate(branch, x)
    else:
        joints, _ = scene.kinematics.loop_inputs(x[:1])
        analytic, _ = scene.kinematics.evaluate_held(branch, x, scene.mechanism_to_loop(q)[:, list(joints)])
    return PathComparison(x, scene.outputs(q), analytic)


def closure_conditions(scene: Scene, x: NDArray[np.float64], values: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    Condition numbers (n,) of the loop-closure Jacobian with the inputs held, at the closed form's outputs `values`
    (n, k) at inputs x (n,) (rad): how much the rounding of a closure residual moves the joint angles. Singular values
    below RANK_RTOL of the largest (idle spins, redundant freedoms) are left out, as the mobility counts them.
    """
    kin = scene.kinematics
    loops = kin.loop_system()  # built once: registered scenes build theirs on every call (25 ms for the tube)
    free = np.ones(loops.n_joints, dtype=bool)
    free[list(kin.loop_inputs(np.asarray(x)[:1])[0])] = False
    out = np.ones(len(x))
    for k, q in enumerate(kin.loop_angles(np.atleast_2d(values))):
        out[k] = condition((loops.jacobian_sparse(q) if loops.sparse else loops.jacobian(q))[:, free])
    return out


def floor_verdict_values(
    scene: Scene, path: PathComparison, base: float, factor: float,
    other_condition: Callable[[NDArray[np.int64]], NDArray[np.float64]] | None = None,
) -> tuple[float, float, str]:
    """
    (error, tolerance, where) of a comparison held to a rounding floor: every sample's error against
    max(base, factor eps cond), cond the closure Jacobian's condition number there (`closure_conditions`, computed
    only at samples whose error exceeds `base`); the sample with the largest error over tolerance is reported.
    `other_condition` (sample indices -> condition numbers) is the other side's, asked only where a sample exceeds
    the closure's tolerance, and the larger one holds there (MuJoCo's projection: `simulate.projection_conditions`).
    """
    err = np.max(path.error, axis=1)
    if not np.all(np.isfinite(err)):
        return float("inf"), base, "the input left the branch's domain"
    above = np.flatnonzero(err > base)
    if not len(above):
        return float(np.max(err, initial=0.0)), base, "every sample within the base tolerance"
    eps = np.finfo(float).eps
    cond = closure_conditions(scene, path.input[above], path.analytic[above])
    what = np.full(len(above), "the closure Jacobian's condition number", dtype=object)
    over = np.flatnonzero(err[above] > factor * eps * cond)
    if other_condition is not None and len(over):
        other = other_condition(above[over])
        larger = over[other > cond[over]]
        cond[larger] = other[other > cond[over]]
        what[larger] = "MuJoCo's closure rows' extent over smallest singular value"
    tol = np.maximum(base, factor * eps * cond)
    worst = int(np.argmax(err[above] / tol))
    k = above[worst]
    return (float(err[k]), float(tol[worst]), f"worst against its tolerance at input {path.input[k]:.6g} rad, where "
            f"{what[worst]} is {cond[worst]:.3g} ({len(above)} samples above {base:g})")
