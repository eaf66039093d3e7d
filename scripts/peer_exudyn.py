"""MuJoCo (the harness's presets) and Exudyn side by side on the same mechanism, path and samples.

Two cases: the Bennett sweep (theta1 0.6 -> 2.4 rad along the harness's minimum-jerk ramp in 6 s, the fast
preset's sweep) and IFToMM A04 (10 s free under gravity from rest). The Exudyn model is built from the project's
own mechanism (`sim_origami.peer_model`: the same bodies, MuJoCo's masses and inertias, the same hinges): rigid
bodies with Euler parameters, tree hinges as revolute joints, the cut hinge a generic joint with five constrained
axes, the driven hinge a generic joint with all six and the ramp as its rotation offset (a Python offset user
function); generalized-alpha, index 3, modified Newton, dense solver ignoring the singular Jacobian of the redundant
closure rows, one thread. Both tools are scored by `checks.paths.compare` (max |angle - closed form| at the
simulated input, rad) and, on A04, by the total-energy drift max |E - E0| (J). CPU is the stepping thread's time
(MuJoCo: the stepping loop; Exudyn: SolveDynamic), best of `--rounds` rounds that run every setting once in turn
(as `pareto.measure_all`), as a ratio to the fast preset's.

Exudyn is an optional extra: `pip install -e '.[peers]'`. Without it the script says so and exits 0.

    .venv/bin/python scripts/peer_exudyn.py [--rounds 5]
"""

import argparse
import dataclasses
import importlib.util
import sys
import time
from collections.abc import Callable

import mujoco
import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.mjcf import ModelOptions, preset_duration
from sim_origami.scenes.base import Scene
from sim_origami.simulate import Bindings, captured_warnings, compile_model, drive_targets, start_pose, track
from sim_origami.stabilize import run_step
from sim_origami.studies.peer_model import body_poses, kinetic_energy, potential_energy, rigid_model

FREE_S = 10.0  # the A04 benchmark's free run


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


@dataclasses.dataclass
class Result:
    """A setting's scores: max path error (rad), energy drift (J, free runs), best CPU (s), samples."""

    label: str
    error: float = np.inf
    drift: float = np.nan
    cpu: float = np.inf
    samples: int = 0


def cases() -> list[Case]:
    """The Bennett sweep as the fast preset runs it, and A04's free run."""
    bennett = scenes.get("bennett").build()
    start, stop = bennett.branch_path("bennett")
    sweep = preset_duration("fast") * bennett.sweep_time_scale
    a04 = scenes.get("iftomm-a04").build()
    return [
        Case(f"Bennett, theta1 {start:g} -> {stop:g} rad in {sweep:g} s", bennett, "bennett", start, stop, sweep,
             False),
        Case(f"IFToMM A04, {FREE_S:g} s free under gravity", a04, a04.free_branch, a04.free_start, a04.free_start,
             FREE_S, True),
    ]  # fmt: skip


def mujoco_run(case: Case, preset: str, h: float | None = None, iterations: int = 1) -> Callable[[], tuple]:
    """
    One MuJoCo setting as a function returning (mechanism angles, energy or None, CPU s): the harness's own
    stepping (`simulate.track` / the free run's loop, the preset's step function) on `preset`, with the timestep
    set to `h` (closure time constant scaled with it) and `iterations` projection steps when given.
    """
    scene = case.scene
    model, data = compile_model(scene, ModelOptions(preset=preset, drive="none" if case.free else "equality",
                                                    gravity=case.free))  # fmt: skip
    if h is not None:
        model.eq_solref[:, 0] *= h / model.opt.timestep
        model.opt.timestep = h
    binds = Bindings(scene, model)
    pose = start_pose(scene, case.branch, case.start)
    n = round(case.duration / model.opt.timestep)

    def run() -> tuple:
        mujoco.mj_resetData(model, data)
        binds.set_pose(data, pose)
        mujoco.mj_forward(model, data)
        log = np.empty((n, model.nq))
        with captured_warnings() as messages:
            if case.free:
                step = run_step(model, data, preset, iterations=iterations)
                energy, qpos = np.empty(n + 1), data.qpos
                energy[0] = data.energy.sum()
                cpu = time.thread_time()
                for k in range(n):
                    step(model, data)
                    log[k] = qpos
                    energy[k + 1] = data.energy[0] + data.energy[1]
                cpu = time.thread_time() - cpu
            else:
                step = run_step(model, data, preset, scene.drives, iterations=iterations)
                _, setpoints = drive_targets(scene, model, "equality", case.start, case.stop, case.duration, n)
                eq = model.equality(f"drive_{scene.drive_joint}").id
                energy, cpu = None, track(model, data, model.eq_data[eq], 0, setpoints, log, step)
        if messages:
            raise RuntimeError(f"MuJoCo warned: {messages[0]}")
        return binds.angles(scene, log), energy, cpu

    return run


def exudyn_run(case: Case, h: float, rho: float, rtol: float) -> Callable[[], tuple]:
    """One Exudyn setting (step h s, spectral radius rho, Newton relative tolerance) as a function like mujoco_run's."""
    import exudyn as exu
    from exudyn.advancedUtilities import CreateSymbolicUserFunction
    from exudyn.itemInterface import SensorBody
    from exudyn.rigidBodyUtilities import RigidBodyInertia

    scene = case.scene
    rigid = rigid_model(scene, start_pose(scene, case.branch, case.start))
    n = round(case.duration / h)
    span = case.stop - case.start

    def offset(mbs, t, itemNumber, offsetUserFunctionParameters):
        """The ramp (`simulate.ramp`, t <= duration) as the driven joint's turn about its axis (rad). Exudyn compiles
        it to a symbolic user function: a Python callback per Newton iteration doubled Exudyn's CPU on Bennett."""
        p = t / case.duration
        return [0, 0, 0, 0, 0, span * p * p * p * (10 - 15 * p + 6 * p * p)]

    def run() -> tuple:
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        items = {rigid.root: mbs.CreateGround()}
        sensors = {}
        for b in rigid.bodies:
            items[b.name] = mbs.CreateRigidBody(
                inertia=RigidBodyInertia(b.mass, np.diag(b.inertia)), referencePosition=b.pose[:3, 3],
                referenceRotationMatrix=b.pose[:3, :3], gravity=rigid.gravity,
                nodeType=exu.NodeType.RotationEulerParameters,
            )  # fmt: skip
            kinds = ["Position", "RotationMatrix"] + (["Velocity", "AngularVelocityLocal"] if case.free else [])
            sensors[b.name] = {
                kind: mbs.AddSensor(SensorBody(bodyNumber=items[b.name], storeInternal=True,
                                               outputVariableType=getattr(exu.OutputVariableType, kind)))
                for kind in kinds
            }  # fmt: skip
        for j in rigid.hinges:
            pair, point, axes = [items[j.parent], items[j.child]], j.frame[:3, 3], j.frame[:3, :3]
            if j.driven and not case.free:
                drive = CreateSymbolicUserFunction(mbs, offset, "offsetUserFunction", itemTypeName="ObjectJointGeneric")
                mbs.CreateGenericJoint(itemNumbers=pair, position=point, rotationMatrixAxes=axes,
                                       constrainedAxes=[1] * 6, offsetUserFunction=drive, show=False)  # fmt: skip
            elif j.cut:
                mbs.CreateGenericJoint(itemNumbers=pair, position=point, rotationMatrixAxes=axes,
                                       constrainedAxes=[1, 1, 1, 1, 1, 0], show=False)  # fmt: skip
            else:
                mbs.CreateRevoluteJoint(itemNumbers=pair, position=point, axis=axes[:, 2], show=False)
        mbs.Assemble()
        settings = exu.SimulationSettings()
        ti = settings.timeIntegration
        ti.numberOfSteps, ti.endTime, ti.verboseMode = n, case.duration, 0
        ti.generalizedAlpha.spectralRadius = rho
        ti.generalizedAlpha.useIndex2Constraints = False
        ti.generalizedAlpha.useNewmark = False
        ti.newton.useModifiedNewton = True
        ti.newton.relativeTolerance = rtol
        settings.linearSolver.solverType = exu.LinearSolverType.EigenDense
        settings.linearSolver.ignoreSingularJacobian = True
        settings.parallel.numberOfThreads = 1
        settings.solution.file.write = False
        settings.solution.sensors.writePeriod = h
        settings.show.statistics = False
        settings.show.computationTime = False
        cpu = time.thread_time()
        mbs.SolveDynamic(settings)
        cpu = time.thread_time() - cpu
        data = {b: {kind: mbs.GetSensorStoredData(s)[:, 1:] for kind, s in of_body.items()}
                for b, of_body in sensors.items()}  # fmt: skip
        stored = len(next(iter(data.values()))["Position"])
        if stored != n + 1:
            raise RuntimeError(f"Exudyn stored {stored} samples, not {n + 1}")
        principal = {}
        for b, d in data.items():
            T = np.zeros((n + 1, 4, 4))
            T[:, :3, :3], T[:, :3, 3], T[:, 3, 3] = d["RotationMatrix"].reshape(-1, 3, 3), d["Position"], 1.0
            principal[b] = T[1:]  # the samples after each step, as MuJoCo's log
        q = scene.mechanism.angles_from_poses(body_poses(rigid, principal))
        energy = None
        if case.free:
            energy = kinetic_energy(rigid, {b: d["Velocity"] for b, d in data.items()},
                                    {b: d["AngularVelocityLocal"] for b, d in data.items()}) + potential_energy(
                rigid, {b: d["Position"] for b, d in data.items()})  # fmt: skip
        return q, energy, cpu

    return run


def settings(case: Case) -> list[tuple[str, Callable[[], tuple]]]:
    """The settings of a case, the fast preset first (the CPU reference)."""
    if case.free:
        return [
            ("sim_origami fast (RK4 8 ms)", mujoco_run(case, "fast")),
            ("sim_origami accurate (RK4 0.1 ms)", mujoco_run(case, "accurate")),
            ("sim_origami fast-projected (RK4 8 ms)", mujoco_run(case, "fast-projected")),
            ("sim_origami fast-projected, h 10 ms", mujoco_run(case, "fast-projected", h=0.010)),
            ("sim_origami fast-projected, h 2 ms", mujoco_run(case, "fast-projected", h=0.002)),
            ("Exudyn rho 0.9, h 2 ms", exudyn_run(case, 0.002, 0.9, 1e-8)),
            ("Exudyn rho 0.6, h 10 ms", exudyn_run(case, 0.010, 0.6, 1e-8)),
            ("Exudyn rho 0.6, h 8 ms", exudyn_run(case, 0.008, 0.6, 1e-8)),
        ]
    return [
        ("sim_origami fast (RK4 8 ms)", mujoco_run(case, "fast")),
        ("sim_origami RK4 1 ms", mujoco_run(case, "fast", h=0.001)),
        ("sim_origami fast-projected (RK4 8 ms)", mujoco_run(case, "fast-projected")),
        ("sim_origami fast-projected, h 120 ms, 2 projection steps", mujoco_run(case, "fast-projected", 0.12, 2)),
        ("Exudyn h 8 ms, Newton rtol 1e-8", exudyn_run(case, 0.008, 0.6, 1e-8)),
        ("Exudyn h 8 ms, rtol 1e-4", exudyn_run(case, 0.008, 0.6, 1e-4)),
        ("Exudyn h 120 ms", exudyn_run(case, 0.12, 0.6, 1e-8)),
    ]


def measure(case: Case, rounds: int) -> list[Result]:
    """Every setting of the case once per round, in turn; scores from the last round, CPU the best of all."""
    runs = settings(case)
    results = [Result(label) for label, _ in runs]
    for _ in range(rounds):
        for (_, run), result in zip(runs, results, strict=True):
            q, energy, cpu = run()
            result.cpu = min(result.cpu, cpu)
            result.samples = len(q)
            result.error = compare(case.scene, case.branch, q).max_error()
            if energy is not None:
                result.drift = float(np.max(np.abs(energy - energy[0])))
    return results


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--rounds", type=int, default=5, help="rounds of every setting in turn (best CPU kept)")
    args = parser.parse_args()
    if importlib.util.find_spec("exudyn") is None:
        print("Exudyn is not installed (pip install -e '.[peers]'); nothing to compare.")
        return 0
    import exudyn as exu

    print(f"MuJoCo {mujoco.__version__}, Exudyn {exu.config.Version()}, best of {args.rounds} interleaved rounds\n")
    print("| case | tool, setting | max path error (rad) | energy drift (J) | CPU vs `fast` | samples |")
    print("|---|---|---|---|---|---|")
    for case in cases():
        results = measure(case, args.rounds)
        for k, r in enumerate(results):
            drift = f"{r.drift:.2g}" if np.isfinite(r.drift) else ""
            print(f"| {case.label if k == 0 else ''} | {r.label} | {r.error:.2g} | {drift} | "
                  f"{r.cpu / results[0].cpu:.2f} | {r.samples} |", flush=True)  # fmt: skip
    return 0


if __name__ == "__main__":
    sys.exit(main())
