"""MuJoCo (the harness's presets) and Exudyn side by side on the same mechanism, scored as what each run is.

Cases. The Bennett sweep (theta1 0.6 -> 2.4 rad along the harness's minimum-jerk ramp, the fast preset's sweep
time): one freedom driven, so the motion is the closed form at the simulated input and the score is the path error
(`checks.paths.compare`, max |angle - closed form| at the simulated input, rad). IFToMM A04 (10 s free under gravity
from rest): a dynamic run, scored against a converged reference trajectory, not against the manifold:

- trajectory error: max over 10 s (states every 40 ms) and joints of |angle - reference angle| (rad);
- period error: |period - reference period| (s), the period from the input's turning points over 10 s;
- energy drift: max |E - E0| (J) at the trajectory's states (`simulate.state_energy`, the same mass model for both
  tools: MuJoCo's bodies and inertias, which Exudyn is given);
- manifold distance (a separate column): the path error above, which a projection zeroes whatever the motion.

The reference is MuJoCo `accurate` (RK4, closures 4 h) at 0.05 ms, checked converged by its own halving (0.1 ms ->
0.05 ms) and against the best Exudyn run (another formulation and integrator); both differences are printed.

Exudyn 1.13 (`pip install -e '.[peers]'`) is built from the project's own mechanism (`sim_origami.studies.peer_model`:
the same bodies, MuJoCo's masses and inertias, the same hinges), two ways:

- `body`: redundant coordinates (rigid bodies with Euler parameters, tree hinges revolute joints, each cut hinge a
  generic joint with five constrained axes, the driven hinge one with six and the ramp as its offset);
- `tree`: minimal coordinates (ObjectKinematicTree over the mechanism's spanning tree, one coordinate a hinge), the
  cut hinges as generic joints between MarkerKinematicTreeRigid markers, couplings (q_a = c q_b) and the drive as
  coordinate constraints (ObjectConnectorCoordinate; the drive's ramp a symbolic offset user function).

Both: generalized-alpha (index 3, spectral radius rho), modified Newton, dense solver ignoring the redundant closure
rows' singular Jacobian, one thread; Newton tolerances Exudyn's defaults (relative 1e-8, absolute 1e-10) or tight
(relative 1e-12, absolute 1e-14). Every setting is stated in its row. CPU is the stepping thread's time (MuJoCo: the
stepping loop; Exudyn: SolveDynamic), best of `--rounds` rounds that run every setting once in turn (as
`pareto.measure_all`), stated as a ratio to the fast preset's in the same run.

`--scaling` runs each scale case (Bennett, miura-sheet, corrugated-sheet, a 16 x 16 Miura FOLD sheet, the waterbomb
tube) driven along its default sweep with MuJoCo fast and fast-projected and Exudyn's tree (and body model where it
takes the scene) at MuJoCo's step with tight and default tolerances, interleaved.

    .venv/bin/python scripts/peer_exudyn.py [--rounds 3] [--scaling | --long]
"""

import argparse
import dataclasses
import importlib.util
import sys
import tempfile
import time
from collections.abc import Callable
from pathlib import Path

import sim_origami  # noqa: F401  (before numpy: one OpenBLAS thread unless set)

# isort: split
import mujoco
import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import ACCURATE, FAST, FAST_PROJECTED, Preset
from sim_origami.scenes.base import Scene
from sim_origami.simulate import (
    Bindings,
    captured_warnings,
    compile_model,
    drive_targets,
    start_pose,
    state_energy,
    track,
    track_path,
)
from sim_origami.stabilize import run_step
from sim_origami.studies.peer_model import (
    body_poses,
    kinetic_energy,
    potential_energy,
    rigid_model,
    tree_model,
)
from sim_origami.sweep_rate import sweep_duration

FREE_S = 10.0  # the A04 benchmark's free run
SAMPLE_S = 0.04  # free runs are compared at multiples of this (every step tried divides it)
REFERENCE_H = 5e-5  # the reference's step (s), `accurate` otherwise
FOLD_STEPS = 10  # steps of the 16 x 16 FOLD sheet in the scaling table
TIGHT = (1e-12, 1e-14)  # Newton relative and absolute tolerances, tight
DEFAULT = (1e-8, 1e-10)  # Exudyn's defaults


@dataclasses.dataclass(frozen=True)
class Case:
    """A scene on one branch: a driven sweep start -> stop (rad) in `duration` s, or (free) released at rest."""

    label: str
    scene: Scene
    branch: str
    start: float
    stop: float
    duration: float
    free: bool
    end: float | None = None  # simulated time (s) when only the start of the sweep is run (per-step cost)

    @property
    def simulated(self) -> float:
        return self.duration if self.end is None else self.end


@dataclasses.dataclass
class Run:
    """One run: mechanism angles at the states (n + 1, n_joints) from t = 0 every h s, energy there (J) or None."""

    q: np.ndarray
    h: float
    cpu: float
    energy: np.ndarray | None = None


@dataclasses.dataclass
class Result:
    """A setting's scores (nan where they do not apply) and best CPU (s)."""

    tool: str
    label: str
    path: float = np.nan  # max |angle - closed form at the simulated input| (rad): the manifold distance
    trajectory: float = np.nan  # max |angle - reference| (rad), free runs
    period: float = np.nan  # |period - reference period| (s), free runs
    drift: float = np.nan  # max |E - E0| at the states (J), free runs
    cpu: float = np.inf
    steps: int = 0
    failed: str = ""


def mujoco_run(case: Case, preset: Preset, h: float | None = None, iterations: int = 1) -> Callable[[], Run]:
    """
    One MuJoCo setting: the harness's own stepping (`simulate.track` / the free run's loop, the preset's step
    function) on `preset`, with the timestep set to `h` (closure time constants scaled with it) and `iterations`
    projection steps a step (fast-projected).
    """
    scene = case.scene
    compiled = compile_model(scene, ModelOptions(preset=preset, drive="none" if case.free else "equality",
                                                 gravity=case.free))
    model, data = compiled.fresh()
    if h is not None:
        model.eq_solref[:, 0] *= h / model.opt.timestep
        model.opt.timestep = h
    binds, ids = Bindings(compiled), compiled.ids
    pose = start_pose(scene, case.branch, case.start)
    n = round(case.simulated / model.opt.timestep)

    def run() -> Run:
        mujoco.mj_resetData(model, data)
        binds.set_pose(data, pose)
        mujoco.mj_forward(model, data)
        qpos_log, qvel_log = np.empty((n + 1, model.nq)), np.empty((n + 1, model.nv))
        qpos_log[0], qvel_log[0] = data.qpos, data.qvel
        with captured_warnings() as messages:
            if case.free:
                step = run_step(model, data, compiled, iterations=iterations)
                qpos, qvel = data.qpos, data.qvel
                cpu = time.thread_time()
                for k in range(1, n + 1):
                    step(model, data)
                    qpos_log[k] = qpos
                    qvel_log[k] = qvel
                cpu = time.thread_time() - cpu
            else:
                step = run_step(model, data, compiled, iterations=iterations)
                _, setpoints = drive_targets(scene, model, ids, case.start, case.stop, case.duration, n)
                if scene.drive_path is not None:
                    cpu = track_path(model, data, np.array(ids.drive_equalities), setpoints, qpos_log[1:], step)
                else:
                    cpu = track(model, data, model.eq_data[ids.drive_equalities[0]], 0, setpoints, qpos_log[1:], step)
        if messages or not np.all(np.isfinite(qpos_log)):
            raise RuntimeError(f"MuJoCo warned: {messages[0] if messages else 'non-finite qpos'}")
        energy = state_energy(model, qpos_log, qvel_log) if case.free else None
        return Run(binds.angles(scene, qpos_log), model.opt.timestep, cpu, energy)

    return run


def _settings(h: float, duration: float, rho: float, tolerances: tuple[float, float]):
    """Exudyn's simulation settings: generalized-alpha index 3, modified Newton, dense solver, one thread."""
    import exudyn as exu

    settings = exu.SimulationSettings()
    ti = settings.timeIntegration
    ti.numberOfSteps, ti.endTime, ti.verboseMode = round(duration / h), duration, 0
    ti.generalizedAlpha.spectralRadius = rho
    ti.generalizedAlpha.useIndex2Constraints = False
    ti.generalizedAlpha.useNewmark = False
    ti.newton.useModifiedNewton = True
    ti.newton.relativeTolerance, ti.newton.absoluteTolerance = tolerances
    settings.linearSolver.solverType = exu.LinearSolverType.EigenDense
    settings.linearSolver.ignoreSingularJacobian = True
    settings.parallel.numberOfThreads = 1
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = 0.999999 * duration / round(duration / h)  # every step, rounding aside
    settings.show.statistics = False
    settings.show.computationTime = False
    return settings


def _solve(mbs, settings, n: int) -> float:
    """SolveDynamic's CPU (s); a run that stops early (Newton failed) raises."""
    cpu = time.thread_time()
    ok = mbs.SolveDynamic(settings)
    cpu = time.thread_time() - cpu
    if ok is False:
        raise RuntimeError("Exudyn's SolveDynamic did not finish (Newton did not converge)")
    return cpu


def _ramp(case: Case, scale: float) -> Callable:
    """The harness's minimum-jerk ramp (`sweep_rate.ramp`, t <= duration) times `scale` as an offset function of
    time; Exudyn compiles it to a symbolic user function (a Python callback a Newton iteration doubled its CPU)."""
    span, duration = scale * (case.stop - case.start), case.duration

    def offset(mbs, t, itemNumber, lOffset):
        p = t / duration
        return span * p * p * p * (10 - 15 * p + 6 * p * p)

    return offset


def exudyn_body_run(case: Case, h: float, rho: float, tolerances: tuple[float, float]) -> Callable[[], Run]:
    """Exudyn with rigid bodies (redundant coordinates) at step h, spectral radius rho, Newton tolerances."""
    import exudyn as exu
    from exudyn.advancedUtilities import CreateSymbolicUserFunction
    from exudyn.itemInterface import SensorBody
    from exudyn.rigidBodyUtilities import RigidBodyInertia

    scene = case.scene
    rigid = rigid_model(scene, start_pose(scene, case.branch, case.start))
    n = round(case.simulated / h)
    ramp = _ramp(case, 1.0)

    def offset(mbs, t, itemNumber, offsetUserFunctionParameters):
        return [0, 0, 0, 0, 0, ramp(mbs, t, itemNumber, 0)]

    def run() -> Run:
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        items = {rigid.root: mbs.CreateGround()}
        sensors = {}
        for b in rigid.bodies:
            items[b.name] = mbs.CreateRigidBody(
                inertia=RigidBodyInertia(b.mass, np.diag(b.inertia)), referencePosition=b.pose[:3, 3],
                referenceRotationMatrix=b.pose[:3, :3], gravity=rigid.gravity,
                nodeType=exu.NodeType.RotationEulerParameters,
            )
            kinds = ["Position", "RotationMatrix"] + (["Velocity", "AngularVelocityLocal"] if case.free else [])
            sensors[b.name] = {
                kind: mbs.AddSensor(SensorBody(bodyNumber=items[b.name], storeInternal=True,
                                               outputVariableType=getattr(exu.OutputVariableType, kind)))
                for kind in kinds
            }
        for j in rigid.hinges:
            pair, point, axes = [items[j.parent], items[j.child]], j.frame[:3, 3], j.frame[:3, :3]
            if j.driven and not case.free:
                drive = CreateSymbolicUserFunction(mbs, offset, "offsetUserFunction", itemTypeName="ObjectJointGeneric")
                mbs.CreateGenericJoint(itemNumbers=pair, position=point, rotationMatrixAxes=axes,
                                       constrainedAxes=[1] * 6, offsetUserFunction=drive, show=False)
            elif j.cut:
                mbs.CreateGenericJoint(itemNumbers=pair, position=point, rotationMatrixAxes=axes,
                                       constrainedAxes=[1, 1, 1, 1, 1, 0], show=False)
            else:
                mbs.CreateRevoluteJoint(itemNumbers=pair, position=point, axis=axes[:, 2], show=False)
        mbs.Assemble()
        cpu = _solve(mbs, _settings(h, case.simulated, rho, tolerances), n)
        data = {b: {kind: mbs.GetSensorStoredData(s)[:, 1:] for kind, s in of_body.items()}
                for b, of_body in sensors.items()}
        stored = len(next(iter(data.values()))["Position"])
        if stored != n + 1:
            raise RuntimeError(f"Exudyn stored {stored} samples, not {n + 1}")
        principal = {}
        for b, d in data.items():
            T = np.zeros((n + 1, 4, 4))
            T[:, :3, :3], T[:, :3, 3], T[:, 3, 3] = d["RotationMatrix"].reshape(-1, 3, 3), d["Position"], 1.0
            principal[b] = T
        q = scene.mechanism.angles_from_poses(body_poses(rigid, principal))
        energy = None
        if case.free:
            energy = kinetic_energy(rigid, {b: d["Velocity"] for b, d in data.items()},
                                    {b: d["AngularVelocityLocal"] for b, d in data.items()}) + potential_energy(
                rigid, {b: d["Position"] for b, d in data.items()})
        return Run(q, h, cpu, energy)

    return run


def exudyn_tree_run(case: Case, h: float, rho: float, tolerances: tuple[float, float]) -> Callable[[], Run]:
    """Exudyn in minimal coordinates (ObjectKinematicTree, loops closed by generic joints between tree markers,
    couplings and the drive by coordinate constraints) at step h, spectral radius rho, Newton tolerances."""
    import exudyn as exu
    from exudyn.advancedUtilities import CreateSymbolicUserFunction
    from exudyn.itemInterface import (
        MarkerBodyRigid,
        MarkerKinematicTreeRigid,
        MarkerNodeCoordinate,
        NodeGenericODE2,
        NodePointGround,
        ObjectConnectorCoordinate,
        ObjectGround,
        ObjectJointGeneric,
        ObjectKinematicTree,
        SensorNode,
    )

    scene = case.scene
    mech = scene.mechanism
    tree = tree_model(scene, start_pose(scene, case.branch, case.start))
    n = round(case.simulated / h)
    bodies = {b.name: b for b in tree.rigid.bodies}
    link_of_joint = {link.joint: k for k, link in enumerate(tree.links)}
    implied = set(mech.implied)
    drives = () if case.free else scene.drives
    if scene.drive_path is not None and drives:
        raise RuntimeError("the peer's drive takes one input joint (this scene drives a path of several)")
    compiled = compile_model(scene, ModelOptions(drive="none", gravity=case.free))
    model, binds = compiled.model, Bindings(compiled)

    def run() -> Run:
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        m = len(tree.links)
        node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0] * m, initialCoordinates=[0.0] * m,
                                           initialCoordinates_t=[0.0] * m, numberOfODE2Coordinates=m))
        inertias, coms = [], []
        for link in tree.links:
            R = link.com_frame[:3, :3]
            inertias.append(R @ np.diag(bodies[link.body].inertia) @ R.T)
            coms.append(link.com_frame[:3, 3])
        kt = mbs.AddObject(ObjectKinematicTree(
            nodeNumber=node, jointTypes=[exu.JointType.RevoluteZ] * m, linkParents=[lk.parent for lk in tree.links],
            jointTransformations=exu.Matrix3DList([lk.transform[:3, :3] for lk in tree.links]),
            jointOffsets=exu.Vector3DList([lk.transform[:3, 3] for lk in tree.links]),
            linkInertiasCOM=exu.Matrix3DList(inertias), linkCOMs=exu.Vector3DList(coms),
            linkMasses=[bodies[lk.body].mass for lk in tree.links], baseOffset=[0.0, 0.0, 0.0],
            gravity=list(tree.rigid.gravity) if case.free else [0.0, 0.0, 0.0]))
        ground = mbs.AddObject(ObjectGround())
        for hinge in tree.rigid.hinges:
            if not hinge.cut or hinge.name in implied:  # implied: closed by the couplings and other loops, as MJCF
                continue
            markers = []
            for body in (hinge.parent, hinge.child):
                if body == tree.rigid.root:
                    markers.append(mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=hinge.frame)))
                else:
                    k = tree.link_of_body[body]
                    local = np.linalg.inv(tree.frames[k]) @ hinge.frame
                    markers.append(mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=kt, linkNumber=k,
                                                                          localHT=local)))
            mbs.AddObject(ObjectJointGeneric(markerNumbers=markers, constrainedAxes=[1, 1, 1, 1, 1, 0]))
        coordinate = [mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=k)) for k in range(m)]
        for a, b, c in mech.couplings:  # q_a = c q_b; a link's coordinate is sign (q - q0); constraint f c_b - c_a
            ka, kb = link_of_joint[mech.joint_index(a)], link_of_joint[mech.joint_index(b)]
            sa, sb = tree.links[ka].sign, tree.links[kb].sign
            qa0, qb0 = tree.q0[mech.joint_index(a)], tree.q0[mech.joint_index(b)]
            mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[coordinate[ka], coordinate[kb]],
                                                    factor1=c * sa * sb, offset=sa * (qa0 - c * qb0)))
        if drives:
            k = link_of_joint[mech.joint_index(scene.drive_joint)]
            fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
            connector = mbs.AddObject(ObjectConnectorCoordinate(markerNumbers=[fixed, coordinate[k]]))
            ramp = CreateSymbolicUserFunction(mbs, _ramp(case, scene.drive_scale * tree.links[k].sign),
                                              "offsetUserFunction", itemTypeName="ObjectConnectorCoordinate")
            mbs.SetObjectParameter(connector, "offsetUserFunction", ramp)
        sensors = [mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True, outputVariableType=kind))
                   for kind in (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t)]
        mbs.Assemble()
        cpu = _solve(mbs, _settings(h, case.simulated, rho, tolerances), n)
        c, c_t = (mbs.GetSensorStoredData(s)[:, 1:] for s in sensors)
        if len(c) != n + 1:
            raise RuntimeError(f"Exudyn stored {len(c)} samples, not {n + 1}")
        q = tree.angles(c, mech)
        energy = None
        if case.free:  # at the states, with MuJoCo's mass model (the same bodies): `simulate.state_energy`
            qdot = np.zeros_like(q)
            for k, link in enumerate(tree.links):
                qdot[:, link.joint] = link.sign * c_t[:, k]
            qpos, qvel = np.zeros((n + 1, model.nq)), np.zeros((n + 1, model.nv))
            qpos[:, binds.hinge_qpos], qvel[:, model.jnt_dofadr[_hinge_ids(model, binds)]] = (
                q[:, binds.hinge_joints], qdot[:, binds.hinge_joints])
            energy = state_energy(model, qpos, qvel)
        return Run(q, h, cpu, energy)

    return run


def _hinge_ids(model: mujoco.MjModel, binds: Bindings) -> np.ndarray:
    """MuJoCo joint ids of the mechanism's tree hinges in `Bindings.hinge_joints` order."""
    return np.array([model.jnt_qposadr.tolist().index(a) for a in binds.hinge_qpos], dtype=int)


def turning_period(x: np.ndarray, h: float) -> float:
    """The mean spacing (s) of the minima of x (samples every h s), each refined by a parabola through three
    samples; nan with fewer than two."""
    k = np.flatnonzero((x[1:-1] < x[:-2]) & (x[1:-1] <= x[2:])) + 1
    if len(k) < 2:
        return np.nan
    a, b, c = x[k - 1], x[k], x[k + 1]
    t = h * (k + 0.5 * (a - c) / (a - 2 * b + c))
    return float((t[-1] - t[0]) / (len(t) - 1))


def on_samples(run: Run, every: float) -> np.ndarray:
    """The run's angles at t = 0, every, 2 every, ... (its step must divide `every`)."""
    stride = round(every / run.h)
    if abs(stride * run.h - every) > 1e-12:
        raise ValueError(f"step {run.h:g} s does not divide {every:g} s")
    return run.q[::stride]


def free_case() -> Case:
    a04 = scenes.get("iftomm-a04").build()
    return Case(f"IFToMM A04, {FREE_S:g} s free under gravity", a04, a04.free_branch, a04.free_start, a04.free_start,
                FREE_S, True)


def driven_case(scene: Scene, label: str | None = None, branch: str | None = None) -> Case:
    """A scene's default sweep (first branch) as the fast preset times it."""
    branch = branch or scene.kinematics.branches()[0].name
    start, stop = scene.branch_path(branch)
    T = sweep_duration(scene, branch, FAST, start, stop)
    return Case(label or f"{scene.name}, {start:.3g} -> {stop:.3g} rad in {T:.3g} s", scene, branch, start, stop, T,
                False)


def free_settings(case: Case) -> list[tuple[str, str, Callable[[], Run]]]:
    """(tool, setting, run) of the free case, the fast preset first (the CPU reference)."""
    out = [
        ("MuJoCo", "fast (RK4 8 ms, closures 20 ms)", mujoco_run(case, FAST)),
        ("MuJoCo", "fast at 4 ms (closures 10 ms)", mujoco_run(case, FAST, h=0.004)),
        ("MuJoCo", "fast at 2 ms (closures 5 ms)", mujoco_run(case, FAST, h=0.002)),
        ("MuJoCo", "fast at 1 ms (closures 2.5 ms)", mujoco_run(case, FAST, h=0.001)),
        ("MuJoCo", "fast-projected (RK4 8 ms, closures 64 ms, 1 projection)", mujoco_run(case, FAST_PROJECTED)),
        ("MuJoCo", "fast-projected at 2 ms (closures 16 ms)", mujoco_run(case, FAST_PROJECTED, h=0.002)),
        ("MuJoCo", "accurate (RK4 0.1 ms, closures 0.4 ms)", mujoco_run(case, ACCURATE)),
    ]
    for h in (0.008, 0.004, 0.002, 0.001):
        for rho in (0.6, 0.9, 1.0):
            for name, tol in (("default", DEFAULT), ("tight", TIGHT)):
                out.append(("Exudyn tree", f"h {h * 1e3:g} ms, rho {rho:g}, Newton {name} {tol[0]:g}/{tol[1]:g}",
                            exudyn_tree_run(case, h, rho, tol)))
    for h in (0.008, 0.002):
        for name, tol in (("default", DEFAULT), ("tight", TIGHT)):
            out.append(("Exudyn body", f"h {h * 1e3:g} ms, rho 0.9, Newton {name} {tol[0]:g}/{tol[1]:g}",
                        exudyn_body_run(case, h, 0.9, tol)))
    return out


def driven_settings(case: Case, exudyn_h: tuple[float, ...] = (0.008,), body: bool = True):
    """(tool, setting, run) of a driven case, the fast preset first."""
    h0 = compile_model(case.scene, ModelOptions(preset=FAST)).model.opt.timestep
    out = [
        ("MuJoCo", f"fast (RK4 {h0 * 1e3:g} ms)", mujoco_run(case, FAST)),
        ("MuJoCo", f"fast-projected (RK4 {h0 * 1e3:g} ms, 1 projection)", mujoco_run(case, FAST_PROJECTED, h=h0)),
    ]
    for h in exudyn_h or (h0,):
        for name, tol in (("default", DEFAULT), ("tight", TIGHT)):
            out.append(("Exudyn tree", f"h {h * 1e3:g} ms, rho 0.6, Newton {name} {tol[0]:g}/{tol[1]:g}",
                        exudyn_tree_run(case, h, 0.6, tol)))
            if body and not case.scene.mechanism.couplings:
                out.append(("Exudyn body", f"h {h * 1e3:g} ms, rho 0.6, Newton {name} {tol[0]:g}/{tol[1]:g}",
                            exudyn_body_run(case, h, 0.6, tol)))
    return out


def measure(case: Case, runs: list, rounds: int, reference: Run | None = None) -> list[Result]:
    """Every setting once per round, in turn; scores from the last round, CPU the best of all rounds."""
    results = [Result(tool, label) for tool, label, _ in runs]
    if reference is not None:
        ref_q = on_samples(reference, SAMPLE_S)
        ref_period = turning_period(reference.q[:, case.scene.mechanism.joint_index(case.scene.drive_joint)],
                                    reference.h)
    for _ in range(rounds):
        for (_, _, make), result in zip(runs, results, strict=True):
            if result.failed:
                continue
            try:
                run = make()
            except RuntimeError as error:
                result.failed = str(error)
                continue
            result.cpu = min(result.cpu, run.cpu)
            result.steps = len(run.q) - 1
            result.path = compare(case.scene, case.branch, run.q[1:]).max_error()
            if run.energy is not None:
                result.drift = float(np.max(np.abs(run.energy - run.energy[0])))
            if reference is not None:
                d = on_samples(run, SAMPLE_S) - ref_q
                result.trajectory = float(np.max(np.abs((d + np.pi) % (2 * np.pi) - np.pi)))
                x = run.q[:, case.scene.mechanism.joint_index(case.scene.drive_joint)]
                result.period = abs(turning_period(x, run.h) - ref_period)
    return results


def reference_run(case: Case, h: float) -> Run:
    """MuJoCo `accurate` (RK4, closures 4 h) at step h."""
    return mujoco_run(case, ACCURATE, h=h)()


def print_free(results: list[Result]) -> None:
    fast = results[0].cpu
    print(f"`fast`: {fast:.3g} s of CPU (best of the rounds)\n")
    print("| tool | setting | trajectory error (rad, max over 10 s) | period error (s) | energy drift (J) | "
          "manifold distance (rad) | CPU vs `fast` |")
    print("|---|---|---|---|---|---|---|")
    for r in results:
        if r.failed:
            print(f"| {r.tool} | {r.label} | failed: {r.failed} | | | | |")
            continue
        print(f"| {r.tool} | {r.label} | {r.trajectory:.2g} | {r.period:.2g} | {r.drift:.2g} | {r.path:.2g} | "
              f"{r.cpu / fast:.2f} |")


def print_equal(results: list[Result], score: str) -> None:
    """Each tool's cheapest setting at each accuracy (decades of `score`), and the best accuracy at equal CPU."""
    fast = results[0].cpu
    ok = [r for r in results if not r.failed and np.isfinite(getattr(r, score))]
    tools = list(dict.fromkeys(r.tool for r in ok))
    print(f"\nEqual error ({score}): the cheapest setting of each tool reaching it, CPU vs `fast`\n")
    print("| error at most | " + " | ".join(tools) + " |")
    print("|---|" + "---|" * len(tools))
    last: list[str] = []
    for level in 10.0 ** np.arange(-2, -16, -1):  # a row where the cheapest settings change
        cells = []
        for tool in tools:
            within = [r for r in ok if r.tool == tool and getattr(r, score) <= level]
            best = min(within, key=lambda r: r.cpu) if within else None
            cells.append(f"{best.cpu / fast:.2f}: {best.label} ({getattr(best, score):.2g})" if best else "-")
        if any(c != "-" for c in cells) and cells != last:
            print(f"| {level:.0e} | " + " | ".join(cells) + " |")
        last = cells
    print(f"\nEqual CPU: the most accurate setting of each tool within the CPU ({score})\n")
    print("| CPU vs `fast` at most | " + " | ".join(tools) + " |")
    print("|---|" + "---|" * len(tools))
    last = []
    for budget in (0.5, 1, 2, 4, 8, 16, 32, 64, 128):
        cells = []
        for tool in tools:
            within = [r for r in ok if r.tool == tool and r.cpu <= budget * fast]
            best = min(within, key=lambda r: getattr(r, score)) if within else None
            cells.append(f"{getattr(best, score):.2g}: {best.label} ({best.cpu / fast:.2f})" if best else "-")
        if cells != last:
            print(f"| {budget:g} | " + " | ".join(cells) + " |")
        last = cells


def fold_sheet_scene() -> Scene:
    """A 16 x 16 Miura-ori sheet read from a FOLD file (as scripts/fold_bench.py writes it)."""
    from sim_origami.fold import write_fold
    from sim_origami.kinematics.miura_sheet import MiuraSheet
    from sim_origami.scenes.fold_file import fold_scene

    with tempfile.TemporaryDirectory() as tmp:
        path = write_fold(Path(tmp) / "miura16.fold", MiuraSheet(16, 16, 0.5, 0.5, np.deg2rad(60.0)).pattern)
        return fold_scene(path)


def scaling(rounds: int, only: set[str] | None = None) -> None:
    """CPU against bodies, both tools, each scene's default sweep, interleaved over every scene and setting; each
    scene's rows are printed once its last round is done (a long run shows what it has)."""
    builders = [("bennett", lambda: scenes.get("bennett").build(), None),
                ("miura-sheet", lambda: scenes.get("miura-sheet").build(), None),
                ("corrugated-sheet", lambda: scenes.get("corrugated-sheet").build(), None),
                ("waterbomb-tube", lambda: scenes.get("waterbomb-tube").build(), None),
                # Exudyn's dense solve on 255 links and 1125 closure rows: a step costs seconds, so only the sweep's
                # first steps are run (per-step CPU; the error is of those steps only)
                ("fold-sheet", fold_sheet_scene, FOLD_STEPS)]
    table = []
    for name, build, steps in builders:
        if only and name not in only:
            continue
        scene = build()
        case = driven_case(scene, name if steps is None else f"FOLD 16 x 16 Miura, first {steps} steps")
        if steps is not None:
            h = compile_model(scene, ModelOptions(preset=FAST)).model.opt.timestep
            case = dataclasses.replace(case, end=steps * h)
        table.append((case, driven_settings(case, exudyn_h=(), body=len(scene.mechanism.bodies) < 40)))
    results = [[Result(tool, label) for tool, label, _ in runs] for _, runs in table]
    print("| scene | bodies | hinges (cut) | couplings | tool, setting | path error (rad) | CPU s | CPU vs `fast` |")
    print("|---|---|---|---|---|---|---|---|", flush=True)  # bodies: the moving ones (the root is fixed)
    for round_ in range(rounds):  # one round takes every scene's every setting in turn
        for (case, runs), res in zip(table, results, strict=True):
            done = measure(case, runs, 1)
            for r, new in zip(res, done, strict=True):
                if r.failed or new.failed:
                    r.failed = r.failed or new.failed
                    continue
                r.cpu, r.path, r.steps = min(r.cpu, new.cpu), new.path, new.steps
            if round_ == rounds - 1:
                mech = case.scene.mechanism
                for k, r in enumerate(res):
                    head = (f"| {case.label} | {len(mech.bodies) - 1} | {len(mech.joints)} ({len(mech.cut_joints)}) | "
                            f"{len(mech.couplings)} " if k == 0 else "| | | | ")
                    if r.failed:
                        print(f"{head}| {r.tool}, {r.label} | failed: {r.failed} | | |", flush=True)
                    else:
                        print(f"{head}| {r.tool}, {r.label} | {r.path:.2g} | {r.cpu:.3g} | {r.cpu / res[0].cpu:.2f} |",
                              flush=True)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=3, help="rounds of every setting in turn (best CPU kept)")
    parser.add_argument("--scaling", action="store_true", help="CPU against bodies on five driven scenes")
    parser.add_argument("--scenes", help="with --scaling: only these (bennett, miura-sheet, corrugated-sheet, "
                        "waterbomb-tube, fold-sheet; comma-separated)")
    parser.add_argument("--long", action="store_true", help="only the free run at 100 s (a few settings)")
    args = parser.parse_args()
    if importlib.util.find_spec("exudyn") is None:
        print("Exudyn is not installed (pip install -e '.[peers]'); nothing to compare.")
        return 0
    import exudyn as exu

    print(f"MuJoCo {mujoco.__version__}, Exudyn {exu.config.Version()}, best of {args.rounds} interleaved rounds\n")
    if args.scaling:
        scaling(args.rounds, set(args.scenes.split(",")) if args.scenes else None)
        return 0
    if args.long:
        long_run(args.rounds)
        return 0
    case = free_case()
    reference = reference_run(case, REFERENCE_H)
    coarse = reference_run(case, 2 * REFERENCE_H)
    ref_q = on_samples(reference, SAMPLE_S)
    print(f"Reference: MuJoCo accurate at {REFERENCE_H * 1e3:g} ms; at twice the step it differs by "
          f"{np.max(np.abs(on_samples(coarse, SAMPLE_S) - ref_q)):.2g} rad over 10 s")
    results = measure(case, free_settings(case), args.rounds, reference)
    best_exudyn = min((r for r in results if r.tool != "MuJoCo" and not r.failed), key=lambda r: r.trajectory)
    print(f"Best Exudyn run against the reference: {best_exudyn.trajectory:.2g} rad ({best_exudyn.tool}, "
          f"{best_exudyn.label})\n")
    print(f"### {case.label}\n")
    print_free(results)
    print_equal(results, "trajectory")
    bennett = scenes.get("bennett").build()
    driven = driven_case(bennett, branch="bennett")
    print(f"\n### {driven.label}\n")
    runs = driven_settings(driven, exudyn_h=(0.008, 0.002, 0.03, 0.12))
    runs += [("MuJoCo", "fast at 1 ms", mujoco_run(driven, FAST, h=0.001)),
             ("MuJoCo", "fast-projected at 120 ms, 2 projections", mujoco_run(driven, FAST_PROJECTED, 0.12, 2))]
    results = measure(driven, runs, args.rounds)
    print("| tool | setting | path error (rad) | CPU vs `fast` |")
    print("|---|---|---|---|")
    for r in results:
        print(f"| {r.tool} | {r.label} | " + (f"failed: {r.failed} | |" if r.failed else
                                                 f"{r.path:.2g} | {r.cpu / results[0].cpu:.2f} |"))
    print_equal(results, "path")
    return 0


def long_run(rounds: int) -> None:
    """A04 at 100 s: a few settings against MuJoCo accurate at 0.1 ms, checked by a run at 0.2 ms."""
    a04 = free_case().scene
    case = Case("IFToMM A04, 100 s free", a04, a04.free_branch, a04.free_start, a04.free_start, 100.0, True)
    reference = reference_run(case, 1e-4)
    check = reference_run(case, 2e-4)
    print(f"Reference: MuJoCo accurate at 0.1 ms; at 0.2 ms it differs by "
          f"{np.max(np.abs(on_samples(check, SAMPLE_S) - on_samples(reference, SAMPLE_S))):.2g} rad over 100 s")
    runs = [("MuJoCo", "fast (RK4 8 ms, closures 20 ms)", mujoco_run(case, FAST)),
            ("MuJoCo", "fast-projected (RK4 8 ms, closures 64 ms, 1 projection)", mujoco_run(case, FAST_PROJECTED)),
            ("MuJoCo", "fast at 2 ms (closures 5 ms)", mujoco_run(case, FAST, h=0.002)),
            ("Exudyn tree", "h 8 ms, rho 1, Newton tight 1e-12/1e-14", exudyn_tree_run(case, 0.008, 1.0, TIGHT)),
            ("Exudyn tree", "h 2 ms, rho 1, Newton tight 1e-12/1e-14", exudyn_tree_run(case, 0.002, 1.0, TIGHT)),
            ("Exudyn tree", "h 1 ms, rho 1, Newton tight 1e-12/1e-14", exudyn_tree_run(case, 0.001, 1.0, TIGHT))]
    print(f"\n### {case.label}\n")
    print_free(measure(case, runs, rounds, reference))


if __name__ == "__main__":
    sys.exit(main())
