"""Post-stabilisation of MuJoCo's soft closures: after each `mj_step`, project qpos (and optionally qvel) onto the
closure manifold with MuJoCo's own constraint rows.

MuJoCo's closures are soft: a step leaves them open by an amount set by the step and the closure time constant,
which is the whole of the path error on a driven sweep or a free run (the error is measured along the manifold,
`checks.paths.compare`). One Gauss-Newton step on the equality rows (efc_pos, efc_J after `mj_makeConstraint` at the
new qpos; the drive's row left out, so the input stays the dynamics' own) puts qpos back on the manifold to the
square of the gap; with `velocity` the velocity's component across the manifold is removed as well, so the next step
starts tangent to it. This changes the physics (energy is not conserved exactly by a projection), so it is a named
option of a preset (`stabilize` in `mjcf_templates/options/`), never applied to the plain-MuJoCo presets.

Modes: "none" (plain MuJoCo), "position" (qpos only), "position-velocity" (qpos, then qvel).
"""

from collections.abc import Callable

import mujoco
import numpy as np

from .errors import ParameterError
from .mjcf import preset_number

MODES = ("none", "position", "position-velocity")
# The custom numeric a preset states its mode with: 0 none, 1 position, 2 position-velocity.
PRESET_NUMERIC = "stabilize"

StepFunction = Callable[[mujoco.MjModel, mujoco.MjData], None]


def preset_mode(preset: str) -> str:
    """The stabilisation a preset states (its custom numeric `stabilize`: 0 none, 1 position, 2 position-velocity);
    "none" for a preset that states none (the plain-MuJoCo presets)."""
    try:
        code = preset_number(preset, PRESET_NUMERIC)
    except KeyError:
        return "none"
    if code not in (0, 1, 2):
        raise ParameterError(
            f"preset {preset}: stabilize {code!r} is not 0 (none), 1 (position), 2 (position-velocity)"
        )
    return MODES[int(code)]


def run_step(
    model: mujoco.MjModel, data: mujoco.MjData, preset: str, drive_joint: str | None = None, iterations: int = 1
) -> StepFunction:
    """
    The step function of a run with `preset`: `mujoco.mj_step` itself for a preset without stabilisation, else
    `step_function` (`iterations` projection steps) with the drive's equality row left out and its joint held
    (the input stays the drive's own).
    """
    return drive_step(model, data, preset_mode(preset), drive_joint, iterations)


def drive_step(
    model: mujoco.MjModel, data: mujoco.MjData, mode: str, drive_joint: str | None = None, iterations: int = 1
) -> StepFunction:
    """`step_function` for `mode` with `drive_joint`'s equality row (if any) left out and its dof held."""
    if mode == "none" or drive_joint is None:
        return step_function(model, data, mode, iterations=iterations)
    names = [model.equality(i).name for i in range(model.neq)]
    skip = tuple(i for i, name in enumerate(names) if name == f"drive_{drive_joint}")
    frozen = (int(model.jnt_dofadr[model.joint(drive_joint).id]),)
    return step_function(model, data, mode, skip=skip, frozen=frozen, iterations=iterations)


def closure_rows(model: mujoco.MjModel, data: mujoco.MjData, skip: tuple[int, ...] = ()) -> np.ndarray:
    """Indices of the equality rows of efc (closures and couplings) whose equality is not in `skip` (eq ids)."""
    _make_constraint(model, data)
    rows = np.flatnonzero(data.efc_type[: data.nefc] == mujoco.mjtConstraint.mjCNSTR_EQUALITY)
    return rows[~np.isin(data.efc_id[rows], skip)]


def _make_constraint(model: mujoco.MjModel, data: mujoco.MjData) -> None:
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
                  frozen: tuple[int, ...] = (), iterations: int = 1) -> StepFunction:  # fmt: skip
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
    rows = closure_rows(model, data, skip)
    nv, n_rows = model.nv, len(rows)
    # frozen dofs enter as extra rows that hold them: the projection is then over the other dofs alone
    J = np.zeros((n_rows + len(frozen), nv))
    J[n_rows + np.arange(len(frozen)), list(frozen)] = 1.0
    W, residual = np.empty_like(J), np.zeros(len(J))
    velocity = mode == "position-velocity"
    qpos, qvel = data.qpos, data.qvel
    jacobian = _sparse_jacobian if mujoco.mj_isSparse(model) else _dense_jacobian
    step, integrate, lstsq, solve_m = mujoco.mj_step, mujoco.mj_integratePos, np.linalg.lstsq, mujoco.mj_solveM

    def correction(m: mujoco.MjModel, d: mujoco.MjData, gap: np.ndarray) -> np.ndarray:
        """The least-kinetic-metric change dq with J dq = gap: M^-1 J^T (J M^-1 J^T)^+ gap (redundant rows)."""
        solve_m(m, d, W, J)  # rows of J M^-1, with M factorised at the current qpos
        return W.T @ lstsq(J @ W.T, gap, rcond=None)[0]

    def stabilized(m: mujoco.MjModel, d: mujoco.MjData) -> None:
        step(m, d)
        for k in range(iterations):
            (mujoco.mj_fwdPosition if k == 0 else _make_constraint)(m, d)  # M once per step: it moves O(gap)
            J[:n_rows] = jacobian(m, d)[rows]
            residual[:n_rows] = d.efc_pos[rows]
            integrate(m, qpos, correction(m, d, residual), -1.0)  # hinges add, balls turn their quaternion
        if velocity:
            _make_constraint(m, d)
            J[:n_rows] = jacobian(m, d)[rows]
            residual[:n_rows] = J[:n_rows] @ qvel
            qvel[:] -= correction(m, d, residual)

    return stabilized
