"""Post-stabilisation of MuJoCo's soft closures: after each `mj_step`, project qpos (and optionally qvel) onto the
closure manifold with MuJoCo's own constraint rows.

MuJoCo's closures are soft: a step leaves them open by an amount set by the step and the closure time constant,
which is the whole of the path error on a driven sweep or a free run (the error is measured along the manifold,
`checks.paths.compare`). One Gauss-Newton step on the equality rows (efc_pos, efc_J after `mj_makeConstraint` at the
new qpos; the drive's row left out, so the input stays the dynamics' own) puts qpos back on the manifold to the
square of the gap; with `velocity` the velocity's component across the manifold is removed as well, so the next step
starts tangent to it. This changes the physics (energy is not conserved exactly by a projection), so it is a named
option of a preset (`stabilize` in `mjcf_templates/options/`, `Preset.stabilize`), never applied to the plain-MuJoCo
presets.

Modes: "none" (plain MuJoCo), "position" (qpos only), "position-velocity" (qpos, then qvel).
"""

import contextlib
from collections.abc import Callable, Iterator

import mujoco
import numpy as np

from .errors import ParameterError
from .mjcf import CompiledModel, ModelIds
from .presets import STABILIZE_MODES

MODES = STABILIZE_MODES  # "none", "position", "position-velocity": what a preset states (`Preset.stabilize`)

# Weight of the kinetic metric against the rows in `step_function`'s solve: small enough that the step is the
# least-metric solution (a larger weight leaves the rows that part open), large enough to keep the solve regular
# along the closures' free motion.
METRIC_WEIGHT = 1e-10

StepFunction = Callable[[mujoco.MjModel, mujoco.MjData], None]

# Open `before_projection` blocks, innermost last: each stabilised step appends its qpos before projecting to the last.
_BEFORE: list[list[np.ndarray]] = []


@contextlib.contextmanager
def before_projection() -> Iterator[list[np.ndarray]]:
    """
    Inside the block every stabilised step (`step_function`, "position" modes) appends a copy of qpos as MuJoCo's own
    step left it, before its projection: what MuJoCo's dynamics alone did from the last projected state, which
    `validation.run_branch` scores as the dynamic check of a projected preset (after the projection the path is
    on the closures by construction, a repeat of the kinematic projection's check).
    """
    log: list[np.ndarray] = []
    _BEFORE.append(log)
    try:
        yield log
    finally:
        _BEFORE.remove(log)


def run_step(model: mujoco.MjModel, data: mujoco.MjData, compiled: CompiledModel, iterations: int = 1) -> StepFunction:
    """
    The step function of a run on `model` (a copy of `compiled.model`) with its preset: `mujoco.mj_step` itself for a
    preset without stabilisation, else `step_function` (`iterations` projection steps) with the drives' equality rows
    left out and their joints held (the inputs stay the drives' own; an undriven model holds none).
    """
    return drive_step(model, data, compiled.preset.stabilize, compiled.ids, iterations)


def drive_step(
    model: mujoco.MjModel, data: mujoco.MjData, mode: str, ids: ModelIds | None = None, iterations: int = 1
) -> StepFunction:
    """`step_function` for `mode` with the drives' equality rows (`ids`, if any) left out and their dofs held."""
    if mode == "none" or ids is None or not ids.held:
        return step_function(model, data, mode, iterations=iterations)
    return step_function(model, data, mode, skip=ids.drive_equalities, frozen=ids.held, iterations=iterations)


def make_constraint(model: mujoco.MjModel, data: mujoco.MjData) -> None:
    """efc_J and efc_pos at the current qpos: the part of mj_fwdPosition the rows need (no inertia, no collision)."""
    mujoco.mj_kinematics(model, data)
    mujoco.mj_comPos(model, data)
    mujoco.mj_makeConstraint(model, data)


def _dense_jacobian(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """efc_J as a fresh (nefc, nv) view (the arena moves with nefc), stored dense (jacobian auto: nv < 60)."""
    return data.efc_J[: data.nefc * model.nv].reshape(data.nefc, model.nv)


def _sparse_jacobian(model: mujoco.MjModel, data: mujoco.MjData) -> np.ndarray:
    """efc_J of a sparse model (nv >= 60) made dense."""
    dense = np.zeros((data.nefc, model.nv))
    mujoco.mju_sparse2dense(dense, data.efc_J, data.efc_J_rownnz, data.efc_J_rowadr, data.efc_J_colind)
    return dense


def step_function(model: mujoco.MjModel, data: mujoco.MjData, mode: str, skip: tuple[int, ...] = (),
                  frozen: tuple[int, ...] = (), iterations: int = 1) -> StepFunction:
    """
    A replacement for `mujoco.mj_step` on this model: mj_step, then `iterations` Gauss-Newton steps of qpos onto the
    equality rows (all but the equalities `skip`) over every dof not in `frozen` (e.g. the driven joint), then for
    "position-velocity" the removal of J qvel, both in the kinetic metric M (the constraint impulse's direction: a
    Euclidean least-squares step instead pushed A04's free run 4 J off its energy in 10 s).
    """
    if mode not in MODES:
        raise ParameterError(f"unknown stabilize mode {mode!r}; modes are {', '.join(MODES)}")
    if mode == "none":
        return mujoco.mj_step
    held = list(frozen)
    skipped = np.zeros(model.neq, dtype=bool)
    skipped[list(skip)] = True
    M, A, b, dq = np.zeros((model.nv, model.nv)), np.zeros((model.nv, model.nv)), np.zeros(model.nv), np.zeros(model.nv)
    velocity = mode == "position-velocity"
    qpos, qvel = data.qpos, data.qvel
    jacobian = _sparse_jacobian if mujoco.mj_isSparse(model) else _dense_jacobian
    step, integrate, full_m = mujoco.mj_step, mujoco.mj_integratePos, mujoco.mj_fullM

    def rows(m: mujoco.MjModel, d: mujoco.MjData) -> tuple[np.ndarray, np.ndarray | slice]:
        """The closure rows' Jacobian (k, nv) and their place in efc, taken afresh: MuJoCo leaves a connect out of
        efc at poses where it is degenerate (the 4 x 4 Miura sheet lost one after its first step). Equality rows
        come first in efc, d.ne of them."""
        equality = slice(0, d.ne)
        if not skip:
            return jacobian(m, d)[equality], equality
        index = np.flatnonzero(~skipped[d.efc_id[equality]])
        return jacobian(m, d)[index], index

    def correction(J: np.ndarray, gap: np.ndarray) -> np.ndarray:
        """
        The change dq (held dofs 0) of least kinetic metric with J dq = gap (rows may be redundant), as the limit of
        (J^T J + mu M) dq = J^T gap for small mu: an nv x nv solve, whatever the number of rows (the waterbomb tube
        has 639 for nv 179). mu is METRIC_WEIGHT of J^T J's scale over M's. MuJoCo's own single-threaded products
        and Cholesky: numpy's BLAS threads the larger ones, which on a busy machine took 0.24 s for one 107 x 107
        solve (and hid their CPU from the stepping thread's clock).
        """
        mujoco.mju_mulMatTMat(A, J, J)
        mujoco.mju_mulMatTVec(b, J, gap)
        A[:] += METRIC_WEIGHT * np.trace(A) / np.trace(M) * M
        if held:  # the held dofs' rows and columns become identity: they stay, the rest solve exactly as without them
            A[held, :], A[:, held], b[held] = 0.0, 0.0, 0.0
            A[held, held] = 1.0
        mujoco.mju_cholFactor(A, 0.0)
        mujoco.mju_cholSolve(dq, A, b)
        return dq

    def stabilized(m: mujoco.MjModel, d: mujoco.MjData) -> None:
        step(m, d)
        if _BEFORE:
            _BEFORE[-1].append(qpos.copy())
        for k in range(iterations):
            if k == 0:
                mujoco.mj_fwdPosition(m, d)
                full_m(m, d, M)  # once per step: it moves O(gap)
            else:
                make_constraint(m, d)
            J, index = rows(m, d)
            integrate(
                m, qpos, correction(J, np.ascontiguousarray(d.efc_pos[index])), -1.0
            )  # hinges add, balls turn their quaternion
        if velocity:
            make_constraint(m, d)
            J, _ = rows(m, d)
            qvel[:] -= correction(J, J @ qvel)  # J (k, nv) times a vector: below BLAS's threading sizes

    return stabilized
