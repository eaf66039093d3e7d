"""Drive a scene in MuJoCo and return what happened as a `Trajectory`.

Dynamic runs drive the input quasi-statically along a minimum-jerk ramp (zero velocity and
acceleration at both ends)
from a closed start pose, with a joint-equality drive (kinematic tracking, feed-forward against
its 2 tau zeta qdot lag) or a force-limited servo (blockage). The kinematic projection mode closes
MuJoCo's own constraint residuals by Gauss-Newton at each input: the accuracy ceiling.

Joint angles come from the recorded qpos (the cut joints measured from the tree pose in numpy);
the closure residual is measured independently from the closure sites after `mj_kinematics`, so
poses are consistent with qpos when read (after `mj_step`, xpos lags one step). Any MuJoCo warning
aborts the run with `SimulationError`; warnings are captured so no MUJOCO_LOG.TXT is written, and outside a run
(a script's own stepping loop) they become Python RuntimeWarnings (`warn_in_python`, installed on import).
"""

import contextlib
import time
import warnings
from collections.abc import Callable
from dataclasses import dataclass, field

import mujoco
import numpy as np
import scipy.linalg
from numpy.typing import NDArray
from scipy import sparse as sp
from scipy.sparse.linalg import splu

from .errors import DomainError, ParameterError, SimulationError
from .mjcf import CompiledModel, ModelIds, ModelOptions, build_model, build_xml, with_keyframes
from .path import rank, rank_of
from .presets import ACCURATE, Preset
from .scenes.base import Scene
from .stabilize import StepFunction, make_constraint, run_step
from .sweep_rate import ramp, sweep_duration

# Closure residual is measured on at most this many samples of a run (after mj_kinematics each).
RESIDUAL_SAMPLES = 400
# Below this residual (m) a projection step that no longer lowers it ends the iteration (rounding floor).
STALL_TOL = 1e-13
# Projection stops when MuJoCo's equality residual falls below this times the scene's length scale (m), or at the
# rounding floor (STALL_TOL). With Newton steps 1e-14 left up to 1.8e-13 rad of angle error on ill-conditioned loops
# and 1e-15 at most 2.3e-14; the chord steps converge linearly, so they stop just under the bound: 1e-15 left 5.5e-14
# (corrugated sheet), 1e-16 (ending at the rounding floor) 4.3e-14, every scene's worst branch within 2x of Newton's.
PROJECTION_TOL = 1e-16
# A projection step keeps the last factorisation (chord method, across inputs) while each step divides the residual by
# at least 1 / CHORD_RATE; a slower step takes a fresh Jacobian (below STALL_TOL only once per input: there a slow
# fresh step is the rounding floor).
CHORD_RATE = 0.1
# The projection's normal equations are solved by Cholesky only while its factor's diagonal spans less than this
# (condition number of J below about 1e6); otherwise by the SVD.
CHOLESKY_SPAN = 1e6
# A quasi-static sweep moves no joint by this much (rad) in one step: a larger jump marks a divergence.
JUMP_RAD = 0.5


@dataclass(frozen=True)
class Trajectory:
    """
    One run. Angles in radians, lengths in metres, times in seconds.

    `q` holds every mechanism joint angle (n, n_joints); `closure_residual` is the largest
    distance between paired closure sites at the samples `residual_index`.
    """

    scene: str
    branch: str
    mode: str
    preset: Preset
    time: NDArray[np.float64]
    target: NDArray[np.float64]
    q: NDArray[np.float64]
    residual_index: NDArray[np.int64]
    closure_residual: NDArray[np.float64]
    cpu_time_s: float
    steps: int
    contacts: NDArray[np.int64] = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    drive_force: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))
    # The input's sweep time (s), hold excluded: `sweep_rate.sweep_duration` unless the caller chose it; 0 without one.
    sweep_time_s: float = 0.0


def warn_in_python(message: str) -> None:
    """MuJoCo's warnings outside a harness run (scripts' own loops, benches): a Python RuntimeWarning, instead of
    MuJoCo's default of printing and appending to MUJOCO_LOG.TXT in the working directory."""
    warnings.warn(f"MuJoCo: {message}", RuntimeWarning, stacklevel=2)


# Installed on import, so no code path that uses the harness writes MUJOCO_LOG.TXT; runs capture their own.
mujoco.set_mju_user_warning(warn_in_python)


@contextlib.contextmanager
def captured_warnings():
    """Collect MuJoCo warning texts instead of printing them and writing MUJOCO_LOG.TXT."""
    messages: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(messages.append)
    try:
        yield messages
    finally:
        mujoco.set_mju_user_warning(previous)


def scene_xml(scene: Scene, options: ModelOptions, keyframes: dict[str, NDArray[np.float64]] | None = None) -> str:
    """The MJCF text of a scene's mechanism and setup for these options (`mjcf.build_xml`), with keyframes if given."""
    xml = build_xml(scene.mechanism, scene.model_setup(), options)
    return with_keyframes(xml, scene.mechanism, keyframes) if keyframes else xml


def compile_model(scene: Scene, options: ModelOptions | None = None) -> CompiledModel:
    """
    The scene's model for these options (default `ModelOptions()`), built and compiled once (`mjcf.build_model`): the
    16 x 16 Miura FOLD sheet's text takes 0.42 s of CPU to build, 32 ms to compile. A validation makes one per kind
    of run and passes it to each function that steps or measures that model.
    """
    return build_model(scene.mechanism, scene.model_setup(), options or ModelOptions())


def _model(scene: Scene, model: CompiledModel | None, preset: Preset | None, **options) -> CompiledModel:
    """`model`, or, without one, the scene's compiled for `preset` (default the scene's) and `options`; a model and
    options for another are not taken together."""
    if model is None:
        return compile_model(scene, ModelOptions(preset=preset or scene.tuning.preset, **options))
    if preset is not None or options:
        raise ParameterError("give a compiled model or the options to compile one, not both")
    return model


class Bindings:
    """A compiled model's ids (`CompiledModel.ids`) as index arrays that map mechanism joints and closure sites."""

    def __init__(self, model: CompiledModel):
        joints = model.ids.joints
        # hinges map one qpos entry to one mechanism angle: moved in one indexed copy (per step of a log)
        self.hinge_joints = np.array([j.joints[0] for j, _ in joints if j.triad is None], dtype=int)
        self.hinge_qpos = np.array([adr for j, adr in joints if j.triad is None], dtype=int)
        self.balls = [(j, adr) for j, adr in joints if j.triad is not None]
        self.drives_qpos = np.array(model.ids.drive_qpos, dtype=int)
        self.drive_qpos = int(self.drives_qpos[0])
        self.site_pairs = np.array(model.ids.site_pairs, dtype=int).reshape(-1, 2)

    def set_pose(self, data: mujoco.MjData, q: NDArray[np.float64]) -> None:
        """Write mechanism angles (n_joints,) into qpos (the spanning tree's joints)."""
        data.qpos[self.hinge_qpos] = q[self.hinge_joints]
        for joint, adr in self.balls:
            data.qpos[adr : adr + joint.width] = joint.qpos(q)

    def angles(self, scene: Scene, qpos: NDArray[np.float64]) -> NDArray[np.float64]:
        """Mechanism angles (n, n_joints) from qpos rows (n, nq); cut joints measured."""
        q = np.zeros((len(qpos), len(scene.mechanism.joints)))
        q[:, self.hinge_joints] = qpos[:, self.hinge_qpos]
        for joint, adr in self.balls:
            q[:, list(joint.joints)] = joint.angles(qpos[:, adr : adr + joint.width])
        return scene.mechanism.complete(q)


def constraint_jacobian(model: mujoco.MjModel, data: mujoco.MjData) -> NDArray[np.float64]:
    """efc_J as a dense (nefc, nv) array, whether MuJoCo stored it dense or sparse (jacobian auto: nv >= 60)."""
    if not mujoco.mj_isSparse(model):
        return data.efc_J[: data.nefc * model.nv].reshape(data.nefc, model.nv)
    return sparse_constraint_jacobian(model, data).toarray()


def _check(data: mujoco.MjData, messages: list[str], context: str) -> None:
    """Raise SimulationError naming the run's configuration if MuJoCo warned or qpos is not finite."""
    bad = [mujoco.mjtWarning(i).name for i in range(len(data.warning)) if data.warning[i].number > 0]
    if bad or messages or not np.all(np.isfinite(data.qpos)):
        names = ", ".join(bad) or "non-finite qpos"
        detail = f": {messages[0].strip()}" if messages else ""
        raise SimulationError(f"{context}: MuJoCo warning {names}{detail}")


def _first_bad(qpos_log: NDArray, x: NDArray) -> str:
    """Where a run first went wrong: the first step whose qpos is not finite or jumps by more than JUMP_RAD from the
    step before (a divergence, or MuJoCo's reset after one), with its input (rad); '' when there is none."""
    finite = np.all(np.isfinite(qpos_log), axis=1)
    jump = np.r_[False, np.max(np.abs(np.diff(np.where(np.isfinite(qpos_log), qpos_log, 0.0), axis=0)), axis=1,
                               initial=0.0) > JUMP_RAD]
    bad = np.flatnonzero(~finite | jump)
    return f"; first went wrong at step {bad[0] + 1} of {len(x)} (input {x[bad[0]]:.6g} rad)" if len(bad) else ""


def _context(scene: Scene, branch: str, preset: Preset, how: str) -> str:
    """The configuration of a run, for error messages (radians, metres)."""
    params = ", ".join(f"{k}={v:.6g}" for k, v in scene.params.items())
    return f"scene {scene.name} ({params}), branch {branch}, preset {preset.name}, {how}"


def start_pose(scene: Scene, branch: str, start: float) -> NDArray[np.float64]:
    """Mechanism angles of the closed form on `branch` at input `start` (a closed pose)."""
    return scene.pose(branch, start)


def start_input(
    scene: Scene, branch: str, seed: str = "closed", bias: float = 1e-4, stop: float | None = None
) -> float:
    """
    The input (rad) a run on `branch` starts from: the start of its path (seed 'closed'), or a signed `bias`
    from the flat state towards `stop` (default the path's end) (seed 'flat': every branch meets there, so the
    engine is told the branch by a closed pose rather than left to choose).
    """
    start, end = scene.branch_path(branch)
    stop = end if stop is None else stop
    if seed == "flat":
        return float(np.copysign(bias, stop))
    if seed != "closed":
        raise DomainError(f"unknown seed {seed!r}; use 'closed' or 'flat'")
    return start


def _residuals(scene, model, data, binds, qpos_log):
    """Closure-site gaps (m) at up to RESIDUAL_SAMPLES recorded samples, after mj_kinematics each."""
    index = np.unique(np.linspace(0, len(qpos_log) - 1, min(RESIDUAL_SAMPLES, len(qpos_log))).astype(int))
    if not len(binds.site_pairs):
        return index, np.zeros(len(index))
    sites = binds.site_pairs.ravel()
    xpos = np.empty((len(index), len(sites), 3))
    for k, i in enumerate(index):
        data.qpos[:] = qpos_log[i]
        mujoco.mj_kinematics(model, data)
        xpos[k] = data.site_xpos[sites]
    gap = xpos[:, 0::2] - xpos[:, 1::2]
    return index, np.max(np.linalg.norm(gap, axis=-1), axis=-1)


def track(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    setpoint: NDArray,
    index: int,
    target: NDArray,
    qpos_log: NDArray,
    step: StepFunction = mujoco.mj_step,
) -> float:
    """
    The stepping loop: write target[k] into setpoint[index] (an eq_data row or ctrl), `step` (mj_step, or a preset's
    stabilised step: `stabilize.run_step`), log qpos into qpos_log[k]. Returns the CPU time (s) of the loop.
    Hoisted views and Python floats: the loop costs what a bare mj_step loop does (numpy scalar indexing per step
    added about 25 %, measured by `sim-origami bench`).
    """
    qpos = data.qpos
    cpu = time.thread_time()
    for value, row in zip(target.tolist(), qpos_log, strict=True):
        setpoint[index] = value
        step(model, data)
        row[:] = qpos
    return time.thread_time() - cpu


def drive_targets(
    scene: Scene, model: mujoco.MjModel, ids: ModelIds, start: float, stop: float, duration: float, n: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """
    The input x (n,) (rad) of a minimum-jerk sweep start -> stop over `duration` (s) in n steps of the model's
    timestep, and the setpoints the drive is given: drive_scale * x for the servo; for the joint-equality
    drive (`ids` name its equalities), x led by its lag 2 tau zeta xdot (tau clamped to refsafe's 2 h), so the joint
    tracks x. One drive: setpoints (n,); a scene with `drive_path`: (n, k), the path's joint values at the (led)
    input.
    """
    h = model.opt.timestep
    shape, rate = ramp(np.clip(h * np.arange(1, n + 1) / duration, 0.0, 1.0))
    x = start + (stop - start) * shape
    if scene.drive_path is not None:
        if ids.drive_equalities:
            eq = ids.drive_equalities[0]
            tau = max(model.eq_solref[eq, 0], 2 * h)
            return x, scene.drive_values(x + 2 * tau * model.eq_solref[eq, 1] * (stop - start) * rate / duration)
        return x, scene.drive_values(x)
    if not ids.drive_equalities:
        return x, scene.drive_scale * x
    eq = ids.drive_equalities[0]
    tau = max(model.eq_solref[eq, 0], 2 * h)
    return x, scene.drive_scale * (x + 2 * tau * model.eq_solref[eq, 1] * (stop - start) * rate / duration)


def track_path(
    model: mujoco.MjModel,
    data: mujoco.MjData,
    rows: NDArray,
    targets: NDArray,
    qpos_log: NDArray,
    step: StepFunction = mujoco.mj_step,
) -> float:
    """`track` for several joint-equality drives (eq ids `rows`): targets (n, k) written each step."""
    qpos, eq_data = data.qpos, model.eq_data
    cpu = time.thread_time()
    for value, row in zip(targets, qpos_log, strict=True):
        eq_data[rows, 0] = value
        step(model, data)
        row[:] = qpos
    return time.thread_time() - cpu


def simulate(
    scene: Scene,
    branch: str,
    *,
    preset: Preset | None = None,
    start: float | None = None,
    stop: float | None = None,
    seed: str = "closed",
    bias: float = 1e-4,
    drive: str | None = None,
    contact: bool | None = None,
    duration: float | None = None,
    hold: float = 0.0,
    initial: NDArray[np.float64] | None = None,
    model: CompiledModel | None = None,
) -> Trajectory:
    """
    Drive the scene's input from `start` to `stop` (radians) along a minimum-jerk ramp.

    Parameters
    ----------
    branch : str
      Analytic branch to start on (seed 'closed') or to bias towards (seed 'flat').
    preset : Preset
      Integrator, step, constraint stiffness and sweep duration (mjcf_templates/options/); default the scene's.
    drive : 'equality' (default) or 'servo'
      Kinematic tracking, or a force-limited position servo (blockage runs).
    contact : bool
      Enable the scene's contact pairs (thick panels); default off.
    duration, hold : float
      Sweep time (default: `sweep_rate.sweep_duration`, from the path's joint rates) and extra time holding the
      final target.
    initial : (n_joints,) float, optional
      Mechanism angles to start from instead of the closed form's pose on `branch` at `start` (e.g. a
      pose of another model, to see which branch this mechanism takes from it); the drive starts at
      its angle there.
    model : CompiledModel, optional
      The model to step (`compile_model`; its options give the preset, drive and contact), instead of one compiled
      from `preset`, `drive` and `contact` for this run.
    """
    given = {k: v for k, v in (("drive", drive), ("contact", contact)) if v is not None}
    if given.get("drive", "equality") not in ("equality", "servo"):
        raise DomainError(f"unknown drive {drive!r}; use 'equality' or 'servo'")
    stop = scene.branch_path(branch)[1] if stop is None else stop
    if seed != "closed" or start is None:
        start = start_input(scene, branch, seed, bias, stop)
    compiled = _model(scene, model, preset, **given)
    preset, drive, ids = compiled.preset, compiled.options.drive, compiled.ids
    if drive not in ("equality", "servo"):
        raise DomainError(f"a run needs a driven model (drive 'equality' or 'servo'), not drive {drive!r}")
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    if initial is not None:
        start = float(initial[scene.mechanism.joint_index(scene.drive_joint)]) / scene.drive_scale
    binds.set_pose(data, start_pose(scene, branch, start) if initial is None else np.asarray(initial, dtype=float))
    mujoco.mj_forward(model, data)

    h = model.opt.timestep
    # The path's sweep time, rounded up to whole steps so that the ramp's last sample is its end
    T = duration or h * np.ceil(sweep_duration(scene, branch, preset, start, stop) / h - 1e-9)
    n = round((T + hold) / h)
    if n < 2:
        raise DomainError(f"a sweep of {T + hold:g} s is shorter than two time steps of {h:g} s")
    t = h * np.arange(1, n + 1)
    x, setpoints = drive_targets(scene, model, ids, start, stop, T, n)
    qpos_log = np.empty((n, model.nq))
    contacts = np.zeros(n if drive == "servo" else 0, dtype=np.int64)
    force = np.zeros(n if drive == "servo" else 0)
    step = run_step(model, data, compiled)
    with captured_warnings() as messages:
        if drive == "equality" and scene.drive_path is not None:
            cpu = track_path(model, data, np.array(ids.drive_equalities), setpoints, qpos_log, step)
        elif drive == "equality":
            cpu = track(model, data, model.eq_data[ids.drive_equalities[0]], 0, setpoints, qpos_log, step)
        else:
            act, acts = ids.drive_actuators[0], np.array(ids.drive_actuators)
            cpu = time.thread_time()
            for k in range(n):
                data.ctrl[acts if scene.drive_path is not None else act] = setpoints[k]
                step(model, data)
                qpos_log[k] = data.qpos
                contacts[k] = data.ncon
                force[k] = data.actuator_force[act]
            cpu = time.thread_time() - cpu
        how = f"{drive} drive {start:.6g} -> {stop:.6g} rad in {T:g} s"
        _check(data, messages, _context(scene, branch, preset, how) + _first_bad(qpos_log, x))
    index, residual = _residuals(scene, model, data, binds, qpos_log)
    return Trajectory(
        scene=scene.name, branch=branch, mode=f"dynamic/{drive}", preset=preset, time=t, target=x,
        q=binds.angles(scene, qpos_log), residual_index=index, closure_residual=residual,
        cpu_time_s=cpu, steps=n, contacts=contacts, drive_force=force, sweep_time_s=T,
    )


def sparse_constraint_jacobian(model: mujoco.MjModel, data: mujoco.MjData) -> sp.csr_matrix:
    """efc_J as a sparse (nefc, nv) matrix, read from MuJoCo's own sparse rows (a model with jacobian sparse)."""
    n = data.nefc
    nnz, adr = data.efc_J_rownnz[:n], data.efc_J_rowadr[:n]
    starts = np.concatenate([[0], np.cumsum(nnz)])
    index = np.repeat(adr - starts[:-1], nnz) + np.arange(starts[-1])
    return sp.csr_matrix((data.efc_J[index], data.efc_J_colind[index], starts), shape=(n, model.nv))


def _least_squares(J) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """
    r -> the least-squares solution x of J x = r. Normal equations by Cholesky where J has well-conditioned full
    column rank (its factor's diagonal spans under CHOLESKY_SPAN); else the pseudo-inverse of J's thin SVD without
    the singular values lstsq would drop (rcond = eps max(J.shape)): idle spins, bifurcations. A sparse J (a large
    model) factors its sparse normal matrix (`_sparse_normal`) and falls back to the dense SVD.
    """
    if sp.issparse(J):
        solve = _sparse_normal(J)
        if solve is not None:
            return solve
        J = J.toarray()
    try:  # J comes from a finite pose (project stops at a non-finite residual): no finiteness scans per solve
        factor = scipy.linalg.cho_factor(J.T @ J, check_finite=False)
        diagonal = np.abs(np.diag(factor[0]))
        if diagonal.min(initial=np.inf) > diagonal.max(initial=0.0) / CHOLESKY_SPAN:
            return lambda r: scipy.linalg.cho_solve(factor, J.T @ r, check_finite=False)
    except np.linalg.LinAlgError:
        pass
    U, s, Vt = np.linalg.svd(J, full_matrices=False)
    keep = s > np.finfo(float).eps * max(J.shape) * s.max(initial=0.0)
    U, s_inv, Vt = U[:, keep], 1.0 / s[keep], Vt[keep]
    return lambda r: Vt.T @ (s_inv * (U.T @ r))


def _sparse_normal(J: sp.csr_matrix) -> Callable[[NDArray[np.float64]], NDArray[np.float64]] | None:
    """
    r -> x solving J^T J x = J^T r by a sparse symmetric LU of the normal matrix (SuperLU, no pivoting off the
    diagonal: its pivots are the squares of a Cholesky factor's diagonal), or None where those pivots span
    CHOLESKY_SPAN^2 or more (ill-conditioned, as the dense test). Forming J^T J densely cost 26 ms a factorisation on a
    20 x 20 Miura sheet (2100 rows, 399 hinges: 30 of its 108 s), its rows a few dozen entries each.
    """
    try:
        lu = splu((J.T @ J).tocsc(), permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0, options={"SymmetricMode": True})
    except RuntimeError:  # exactly singular
        return None
    pivots = np.abs(lu.U.diagonal())
    if not pivots.min(initial=np.inf) > pivots.max(initial=0.0) / CHOLESKY_SPAN**2:
        return None
    transposed = J.T.tocsr()
    return lambda r: lu.solve(transposed @ r)


def project(
    scene: Scene, branch: str, inputs: NDArray[np.float64], *, preset: Preset | None = None,
    model: CompiledModel | None = None,
) -> Trajectory:
    """
    Kinematic projection: at each input, Gauss-Newton on MuJoCo's equality residuals (efc_pos,
    efc_J rows of the closures) over the free hinges, from a secant prediction along the path; each input keeps the
    iterate with the smallest residual. The least-squares step reuses the last factorisation, of this input or an
    earlier one (chord method), while the residual falls by 1 / CHORD_RATE a step or is below STALL_TOL, by Cholesky
    where J is well conditioned (`_least_squares`): the 16 x 16 Miura FOLD sheet (1350 rows, 255 hinges) took 418
    factorisations and 4.6 s of CPU for 200 inputs with a fresh one per input and per slow step, 201 and 2.5 s now.
    On `model` (an equality-driven `compile_model`) when given, else on one compiled for `preset` (the scene's).
    """
    compiled = _model(scene, model, preset)
    preset = compiled.preset
    model, data, free = closure_model(compiled)
    binds = Bindings(compiled)
    inputs = np.asarray(inputs, dtype=float)
    binds.set_pose(data, scene.pose(branch, float(inputs[0])))
    qpos_log, step, rate = np.empty((len(inputs), model.nq)), np.zeros(model.nv), np.zeros(model.nv)
    solve, rows, nefc = None, None, -1
    sparse = bool(mujoco.mj_isSparse(model))
    cpu = time.thread_time()
    with captured_warnings() as messages:
        for k, value in enumerate(inputs):
            # secant predictor along the path (in MuJoCo's tangent space, so balls stay unit quaternions); repeated
            # inputs (a one-point domain) have no secant: its rate would divide by zero
            if k >= 2 and inputs[k - 1] != inputs[k - 2]:
                mujoco.mj_differentiatePos(model, rate, inputs[k - 1] - inputs[k - 2], qpos_log[k - 2], qpos_log[k - 1])
                mujoco.mj_integratePos(model, data.qpos, rate, value - inputs[k - 1])
            if scene.drive_path is None:
                data.qpos[binds.drive_qpos] = scene.drive_scale * value
            else:
                data.qpos[binds.drives_qpos] = scene.drive_values(value)[0]
            previous, best, best_qpos, fresh = np.inf, np.inf, data.qpos.copy(), False
            for _ in range(20):
                make_constraint(model, data)  # the rows only (no inertia, no collision): 0.24 ms, not 0.32
                if data.nefc != nefc:  # reading efc_type costs 1.1 ms on the 16 x 16 Miura sheet: only when it changes
                    rows, nefc, solve = data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY, data.nefc, None
                r = data.efc_pos[rows]
                size = np.max(np.abs(r), initial=0.0)
                if not np.isfinite(size):  # a Gauss-Newton step diverged: a failed run, named where it happened
                    raise SimulationError(f"{_context(scene, branch, preset, 'projection')}: non-finite closure "
                                          f"residual at input {value:.6g} rad (sample {k + 1} of {len(inputs)})")
                if size < best:
                    best, best_qpos[:] = size, data.qpos
                if size < PROJECTION_TOL * scene.length_scale or (size < STALL_TOL and size >= previous and fresh):
                    break  # converged, or at the rounding floor of a large model (for this input's own Jacobian)
                # the last factorisation, of this input or an earlier one, while it contracts fast enough; a slow step
                # takes a fresh Jacobian, once per input below STALL_TOL (there a slow fresh step is the floor)
                if solve is None or (size > CHORD_RATE * previous and (size >= STALL_TOL or not fresh)):
                    J = sparse_constraint_jacobian(model, data) if sparse else constraint_jacobian(model, data)
                    solve, fresh = _least_squares(J[rows][:, free]), True
                previous = size
                step[free] = -solve(r)
                mujoco.mj_integratePos(model, data.qpos, step, 1.0)  # hinges add, balls turn their quaternion
            data.qpos[:] = best_qpos  # the iterate closest to closing (at the floor the residual wanders)
            qpos_log[k] = data.qpos
        _check(data, messages, _context(scene, branch, preset, "projection"))
    cpu = time.thread_time() - cpu
    index, residual = _residuals(scene, model, data, binds, qpos_log)
    return Trajectory(
        scene=scene.name, branch=branch, mode="projection", preset=preset, time=np.arange(len(inputs), dtype=float),
        target=inputs, q=binds.angles(scene, qpos_log), residual_index=index, closure_residual=residual,
        cpu_time_s=cpu, steps=len(inputs),
    )


def contact_distance(
    scene: Scene, branch: str, inputs: NDArray[np.float64], model: CompiledModel | None = None
) -> NDArray[np.float64]:
    """
    Smallest signed distance (m) between the collision solids of `Scene.colliding_pairs`, posed by the closed form,
    on `model` (a `compile_model` with contact) or one compiled for it.

    A kinematic sweep (no dynamics): negative means the solids overlap at that input.
    """
    return _contact_probe(scene, branch, model)(np.asarray(inputs, dtype=float))


def _contact_probe(
    scene: Scene, branch: str, model: CompiledModel | None = None
) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """contact_distance on one compiled model: a function of the inputs (rad) for repeated calls."""
    if not scene.colliding_pairs:
        raise ParameterError(f"scene {scene.name!r} has no collision solids (no contact pairs, no self contact)")
    compiled = model or compile_model(scene, ModelOptions(contact=True))
    if not compiled.ids.collision:
        raise ParameterError(f"scene {scene.name!r}: the model given has no collision solids (compiled without "
                             "contact)")
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    pairs = [(compiled.ids.collision[a], compiled.ids.collision[b]) for a, b in scene.colliding_pairs]
    fromto = np.zeros(6)

    def distance(inputs: NDArray[np.float64]) -> NDArray[np.float64]:
        out = np.empty(len(inputs))
        for k, value in enumerate(inputs):
            binds.set_pose(data, scene.pose(branch, float(value)))
            mujoco.mj_kinematics(model, data)
            out[k] = min(mujoco.mj_geomDistance(model, data, g1, g2, 1.0, fromto) for g1, g2 in pairs)
        return out

    return distance


def contact_input(
    scene: Scene, branch: str, start: float, stop: float, samples: int = 400, model: CompiledModel | None = None
) -> float:
    """
    First input between start and stop at which the contact pairs touch, or nan if none (on `model`, as
    `contact_distance`).

    A sweep first (the distance is not monotonic: solids can pass through and separate again),
    then bisection inside the first bracket, to about 1e-12 rad.
    """
    distance = _contact_probe(scene, branch, model)
    grid = np.linspace(start, stop, samples)
    dist = distance(grid)
    hits = np.flatnonzero(dist <= 0.0)
    if not len(hits):
        return float("nan")
    if hits[0] == 0:
        return float(grid[0])
    lo, hi = grid[hits[0] - 1], grid[hits[0]]
    for _ in range(45):
        mid = 0.5 * (lo + hi)
        if distance(np.array([mid]))[0] <= 0.0:
            hi = mid
        else:
            lo = mid
    return float(hi)


def mujoco_mobility(scene: Scene, q: NDArray[np.float64], model: CompiledModel | None = None) -> int:
    """
    Instantaneous mobility in MuJoCo at mechanism angles q: hinges minus the numerical rank of
    the closure rows of efc_J (the drive disabled), on `model` (an equality-driven `compile_model`; its options do not
    change the rows) or one compiled for the fast preset. Redundant connect rows only lower the rank.
    """
    compiled = model or compile_model(scene)
    mj, data, _ = closure_model(compiled)
    return mj.nv - rank(_closure_rows(mj, data, Bindings(compiled), q))


def _closure_rows(model: mujoco.MjModel, data: mujoco.MjData, binds: Bindings, q: NDArray[np.float64]) -> NDArray:
    """efc_J's closure rows (dense, every dof) at mechanism angles q, the drives off (`closure_model`)."""
    binds.set_pose(data, q)
    make_constraint(model, data)
    return constraint_jacobian(model, data)[data.efc_type == mujoco.mjtConstraint.mjCNSTR_EQUALITY]


def projection_conditions(
    scene: Scene, q: NDArray[np.float64], model: CompiledModel | None = None
) -> NDArray[np.float64]:
    """
    How much the rounding of MuJoCo's closure residuals can move the free hinges at mechanism angles q (k, n_joints)
    (rad), per pose (k,): the sites' largest distance from the world origin (m) over the smallest singular value of
    efc_J's closure rows over the free hinges (m per rad; the smallest the rank keeps, `path.rank_of`, as
    `mujoco_mobility` counts). Site positions round to eps times their coordinates, and a least-squares step turns a
    residual r into angles of up to |r| / s_min: a thin-panelled sheet (6 x 6 Miura of 25:1 panels, 6 units long,
    s_min 8.5e-4) reads 7000 where the loop closure's own condition number is 207. On `model` as `mujoco_mobility`.
    """
    compiled = model or compile_model(scene)
    model, data, free = closure_model(compiled)
    binds = Bindings(compiled)
    q = np.atleast_2d(q)
    out = np.ones(len(q))
    for k, pose in enumerate(q):
        sv = np.linalg.svd(_closure_rows(model, data, binds, pose)[:, free], compute_uv=False)
        r = rank_of(sv)
        if r:
            out[k] = float(np.max(np.linalg.norm(data.site_xpos, axis=1), initial=1.0)) / sv[r - 1]
    return out


def closure_model(compiled: CompiledModel) -> tuple[mujoco.MjModel, mujoco.MjData, NDArray[np.int64]]:
    """A copy of the compiled model with its drive equalities off, and the dof addresses of the hinges it leaves free
    (every one but the driven): what the kinematic projection, the mobility count and the projection's conditioning
    work on."""
    model, data = compiled.fresh()
    data.eq_active[list(compiled.ids.drive_equalities)] = 0
    held = set(compiled.ids.drive_dofs)
    return model, data, np.array([a for a in range(model.nv) if a not in held], dtype=int)


@dataclass(frozen=True)
class FreeRun:
    """Free motion under gravity: joint angles, total energy (J) at each logged state and CPU time (s) of the
    stepping. `q` and `energy[1:]` are the states after each step, `energy[0]` the release."""

    time: NDArray[np.float64]
    q: NDArray[np.float64]
    energy: NDArray[np.float64]
    closure_residual: NDArray[np.float64]
    cpu_time_s: float
    steps: int


def state_energy(model: mujoco.MjModel, qpos: NDArray[np.float64], qvel: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    Total (potential + kinetic) energy (J) at each state (qpos (n, nq), qvel (n, nv)), on a data of its own.

    Not `data.energy` after `mj_step`: MuJoCo fills it inside the step's forward pass, and RK4's last forward pass
    is an internal stage of the step (its fourth evaluation), not the state the step ends at; read there, A04's
    drift under fast was 3.7x, under fast-projected 8x, under accurate 4.4x what its states hold (docs/performance.md).
    """
    data = mujoco.MjData(model)
    out = np.empty(len(qpos))
    for k, (p, v) in enumerate(zip(qpos, qvel, strict=True)):
        data.qpos[:], data.qvel[:] = p, v
        mujoco.mj_kinematics(model, data)  # the bodies' centres of mass: gravity's potential
        mujoco.mj_comPos(model, data)
        mujoco.mj_makeM(model, data)  # the mass matrix at this state: kinetic energy 1/2 qvel' M qvel
        mujoco.mj_energyPos(model, data)
        mujoco.mj_energyVel(model, data)
        out[k] = data.energy[0] + data.energy[1]
    return out


def simulate_free(
    scene: Scene, branch: str, start: float, duration: float, *, preset: Preset | None = None,
    model: CompiledModel | None = None,
) -> FreeRun:
    """
    Release the scene at rest from the closed pose on `branch` at input `start`, under its gravity,
    with no drive, and record joint angles and total (kinetic + potential) energy at the trajectory's states
    (`state_energy`, after the stepping: its CPU is not the run's). On `model` (`compile_model` with drive "none" and
    gravity) when given, else on one compiled for `preset` (default accurate).
    """
    if model is not None and preset is not None:
        raise ParameterError("give a compiled model or the options to compile one, not both")
    compiled = model or compile_model(scene, ModelOptions(preset=preset or ACCURATE, drive="none", gravity=True))
    preset = compiled.preset
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    binds.set_pose(data, start_pose(scene, branch, start))
    mujoco.mj_forward(model, data)
    n = round(duration / model.opt.timestep)
    qpos_log, qvel_log = np.empty((n + 1, model.nq)), np.empty((n + 1, model.nv))
    qpos_log[0], qvel_log[0] = data.qpos, data.qvel
    step = run_step(model, data, compiled)
    with captured_warnings() as messages:
        qpos, qvel = data.qpos, data.qvel
        cpu = time.thread_time()
        for k in range(1, n + 1):
            step(model, data)
            qpos_log[k] = qpos
            qvel_log[k] = qvel
        cpu = time.thread_time() - cpu
        _check(data, messages, _context(scene, branch, preset, f"free run of {duration:g} s from {start:.6g} rad"))
    energy = state_energy(model, qpos_log, qvel_log)
    _, residual = _residuals(scene, model, data, binds, qpos_log[1:])
    t = model.opt.timestep * np.arange(1, n + 1)
    return FreeRun(t, binds.angles(scene, qpos_log[1:]), energy, residual, cpu, n)
