"""Run time against error over MuJoCo settings, measured in one run, and the Pareto front.

A `Setting` is one point of the sweep: integrator, step h (s), closure time constant tau (s), solimp, closure
type and drive. Every setting drives the scene's first branch over its default sweep with the same 2 s
minimum-jerk ramp (the harness's own loop, `simulate`), and is scored by the largest |MuJoCo - closed form|
(rad, at the simulated input) and the CPU time of the stepping thread (s, best of `repeats`). MuJoCo's defaults
(Euler, 2 ms, solref 0.02 1, solimp 0.9 0.95 0.001, two connects per cut hinge, equality drive) come first so
every ratio is taken in the same run.

Closure types: `connect2`, the harness's two connects on each cut hinge's axis (6 rows, one redundant),
`connect1`, one connect at the far anchor (3 rows: enough where the rest of the loop holds the axis, e.g. a
spherical loop; a scene it under-constrains shows up as a large error), and `independent`, connect2 on only the
loops that the couplings and the other loops do not imply (`scenes.base.without_implied_closures`; the rest are
measured, not imposed). Drives: `equality`, the joint equality the harness tracks with feed-forward, and `servo`,
the force-limited position actuator of blockage runs.
"""

import dataclasses
import itertools
import time
from collections.abc import Iterator

import mujoco
import numpy as np
from numpy.typing import NDArray

from ..checks.paths import compare
from ..mjcf import CompiledModel, ModelIds, ModelOptions, scale_regularization
from ..presets import FAST, FAST_PROJECTED, STIFF, Preset
from ..scenes.base import Scene, without_implied_closures
from ..simulate import Bindings, compile_model, drive_targets, simulate, start_pose, track
from ..stabilize import drive_step

INTEGRATORS = {"RK4": mujoco.mjtIntegrator.mjINT_RK4, "Euler": mujoco.mjtIntegrator.mjINT_EULER,
               "implicitfast": mujoco.mjtIntegrator.mjINT_IMPLICITFAST}
STEPS_MS = (0.625, 1.25, 2.5, 5.0, 6.5, 8.0)
TAU_OVER_H = (2, 4, 8)
HIGH_IMPEDANCE = (0.9999, 0.9999, 0.001, 0.5, 2.0)
MUJOCO_DEFAULT_IMPEDANCE = (0.9, 0.95, 0.001, 0.5, 2.0)
SWEEP_S = 2.0  # every setting on the same sweep time


@dataclasses.dataclass(frozen=True)
class Setting:
    """One MuJoCo configuration: integrator name, step h (s), closure time constant tau (s), solimp, closure, drive."""

    label: str
    integrator: str
    h: float
    tau: float
    solimp: tuple[float, ...]
    closure: str = "connect2"
    drive: str = "equality"
    regularization: float = 1.0  # scale on MuJoCo's constraint regulariser R (mjcf.scale_regularization)
    stabilize: str = "none"  # projection onto the closures after each step (sim_origami.stabilize)


@dataclasses.dataclass(frozen=True)
class Point:
    """A measured setting: max path error (rad; inf if it diverged) and stepping CPU time (s)."""

    setting: Setting
    error: float
    cpu: float


DEFAULTS = Setting("MuJoCo defaults", "Euler", 0.002, 0.02, MUJOCO_DEFAULT_IMPEDANCE)


def preset_setting(preset: Preset) -> Setting:
    """A preset's integrator, step, closure solref/solimp, regulariser scale and stabilisation."""
    return Setting(f"preset {preset.name}", preset.integrator, preset.timestep, preset.closure_timeconst,
                   preset.closure_solimp, regularization=preset.regularization_scale, stabilize=preset.stabilize)


# The plain-MuJoCo presets the study varies.
PRESET_SETTINGS = {preset: preset_setting(preset) for preset in (FAST, STIFF)}
# Not plain MuJoCo: measured next to the presets, without their closure, drive and regulariser variants.
PROJECTED = preset_setting(FAST_PROJECTED)


def scene_presets(scene: Scene) -> dict[Preset, Setting]:
    """The presets as `scene` runs them (`mjcf.build_xml`): fast with its step and time constant times
    `Tuning.fast_step_scale`, the time constant times `Tuning.fast_timeconst_scale` too, its regulariser times
    `Tuning.fast_regularization_scale` (`Scene.tuning`)."""
    fast, tuning = PRESET_SETTINGS[FAST], scene.tuning
    k = tuning.fast_step_scale
    scaled = dataclasses.replace(fast, h=fast.h * k, tau=fast.tau * k * tuning.fast_timeconst_scale,
                                 regularization=fast.regularization * tuning.fast_regularization_scale)
    return PRESET_SETTINGS | {FAST: scaled}


def settings(closures: tuple[str, ...] = ("connect2", "connect1", "independent"),
             drives: tuple[str, ...] = ("equality", "servo"), quick: bool = False,
             presets: dict[Preset, Setting] = PRESET_SETTINGS) -> Iterator[Setting]:
    """
    MuJoCo's defaults, the presets (as a scene runs them: `scene_presets`), fast-projected, then every integrator x
    step x tau (solimp 0.9999, the presets' regulariser scale) with the default closure and drive, then each other
    closure type and drive at the presets' settings, and the presets with MuJoCo's own regulariser (scale 1).
    `quick`: RK4 and Euler only, three steps.
    """
    yield DEFAULTS
    yield from presets.values()
    yield PROJECTED
    integrators = ("RK4", "Euler") if quick else tuple(INTEGRATORS)
    steps = (1.25, 2.5, 5.0) if quick else STEPS_MS
    for name, h_ms, k in itertools.product(integrators, steps, TAU_OVER_H):
        yield Setting(f"{name} h={h_ms:g}ms tau={k}h", name, h_ms / 1000, k * h_ms / 1000, HIGH_IMPEDANCE,
                      regularization=FAST.regularization_scale)
    for preset, base in presets.items():
        yield dataclasses.replace(base, label=f"{preset.name}, MuJoCo's regulariser", regularization=1.0)
        for closure in closures[1:]:
            yield dataclasses.replace(base, label=f"{preset.name}, {closure}", closure=closure)
        for drive in drives[1:]:
            yield dataclasses.replace(base, label=f"{preset.name}, {drive} drive", drive=drive)


def _scene_for(scene: Scene, closure: str) -> Scene:
    """The scene with each cut hinge closed by `closure` (connect1: its far anchor only; independent: only the
    loops nothing else implies)."""
    if closure == "connect2":
        return scene
    if closure == "independent":
        return without_implied_closures(scene)
    mech = scene.mechanism
    cut = set(mech.cut_joints)
    joints = tuple(dataclasses.replace(j, anchors=j.anchors[-1:]) if i in cut and not j.ball else j
                   for i, j in enumerate(mech.joints))
    return dataclasses.replace(scene, mechanism=dataclasses.replace(mech, joints=joints))


def fast_model(scene: Scene, setting: Setting) -> CompiledModel:
    """The fast preset's model of `scene` with `setting`'s closures and drive, on which `model_for` applies the rest."""
    return compile_model(_scene_for(scene, setting.closure), ModelOptions(preset=FAST, drive=setting.drive))


def model_for(compiled: CompiledModel, setting: Setting) -> mujoco.MjModel:
    """`compiled`'s MJCF (`fast_model`) compiled afresh with `setting` applied on top of the fast preset's options."""
    model = mujoco.MjModel.from_xml_string(compiled.xml)
    model.opt.integrator, model.opt.timestep = INTEGRATORS[setting.integrator], setting.h
    model.eq_solref[:, 0], model.eq_solimp[:] = setting.tau, setting.solimp
    scale_regularization(model, setting.regularization)
    return model


@dataclasses.dataclass
class _Run:
    """One setting's compiled sweep, ready to step again (a fresh MjData each time: a tube's arena is 46 MB, and a
    sweep holds some 60 settings at once)."""

    scene: Scene
    setting: Setting
    model: mujoco.MjModel
    ids: ModelIds
    binds: Bindings
    target: NDArray
    pose: NDArray
    qpos: NDArray
    cpu: float = np.inf

    def step_through(self) -> None:
        """Run the sweep from its start pose once; keep the lowest stepping CPU time."""
        model, data, ids = self.model, mujoco.MjData(self.model), self.ids
        if self.setting.drive == "equality":
            setpoint, index = model.eq_data[ids.drive_equalities[0]], 0
        else:
            setpoint, index = data.ctrl, ids.drive_actuators[0]
        self.binds.set_pose(data, self.pose)
        mujoco.mj_forward(model, data)
        step = drive_step(model, data, self.setting.stabilize, ids)
        self.cpu = min(self.cpu, track(model, data, setpoint, index, self.target, self.qpos, step))


def _prepare(scene: Scene, branch: str, setting: Setting, compiled: CompiledModel) -> _Run:
    """One setting's sweep on `compiled` (`fast_model` of the setting's closures and drive), the setting applied."""
    scene = _scene_for(scene, setting.closure)
    model = model_for(compiled, setting)
    start, stop = scene.branch_path(branch)
    _, target = drive_targets(scene, model, compiled.ids, start, stop, SWEEP_S, round(SWEEP_S / model.opt.timestep))
    qpos = np.empty((len(target), model.nq))
    return _Run(scene, setting, model, compiled.ids, Bindings(compiled), target, start_pose(scene, branch, start), qpos)


def measure_all(scene: Scene, branch: str, settings: list[Setting], repeats: int = 3) -> list[Point]:
    """
    Max error and best CPU time of the harness's drive with each setting over the default sweep, in `repeats`
    rounds that step every setting once: a slow spell of the machine falls on all settings alike instead of on one
    setting's repeats (which put one 0.92x scene at 1.31x and 1.44x the defaults' CPU in two runs of
    scripts/fast_vs_defaults.py).
    """
    kinds = {(s.closure, s.drive): s for s in settings}  # one model per closure type and drive, settings on copies
    models = {kind: fast_model(scene, setting) for kind, setting in kinds.items()}
    runs = [_prepare(scene, branch, setting, models[setting.closure, setting.drive]) for setting in settings]
    for _ in range(repeats):
        for run in runs:
            run.step_through()
    return [Point(r.setting, _error(r, branch), r.cpu) for r in runs]


def _error(run: _Run, branch: str) -> float:
    if not np.all(np.isfinite(run.qpos)):
        return float("inf")
    return compare(run.scene, branch, run.binds.angles(run.scene, run.qpos)).max_error()


def measure(scene: Scene, branch: str, setting: Setting, repeats: int = 3) -> Point:
    """Max error and best-of-`repeats` CPU time of the harness's drive with `setting` over the default sweep."""
    return measure_all(scene, branch, [setting], repeats)[0]


def front(points: list[Point]) -> list[Point]:
    """The points no other point beats in both error and CPU time, by CPU time."""
    return sorted((p for p in points if not any(q.error <= p.error and q.cpu <= p.cpu and q is not p
                                                 and (q.error, q.cpu) != (p.error, p.cpu) for q in points)),
                  key=lambda p: p.cpu)


def bare_loop_cpu(scene: Scene, branch: str, target: NDArray, repeats: int = 3) -> float:
    """
    CPU time (s) of the minimal loop driving the same path with the fast preset: one eq_data write and one mj_step
    per step from the same start pose, with no logging, checks or feed-forward bookkeeping.
    """
    setting = scene_presets(scene)[FAST]
    compiled = fast_model(scene, setting)
    model = model_for(compiled, setting)
    data = mujoco.MjData(model)
    setpoint = model.eq_data[compiled.ids.drive_equalities[0]]
    targets, pose = (scene.drive_scale * target).tolist(), start_pose(scene, branch, float(target[0]))
    best = np.inf
    for _ in range(repeats):
        mujoco.mj_resetData(model, data)
        Bindings(compiled).set_pose(data, pose)
        mujoco.mj_forward(model, data)
        step, cpu = mujoco.mj_step, time.thread_time()
        for value in targets:
            setpoint[0] = value
            step(model, data)
        best = min(best, time.thread_time() - cpu)
    return best


def sweep(scene: Scene, *, quick: bool = False, repeats: int = 3) -> tuple[str, list[Point], float]:
    """
    The whole sweep on the scene's first branch: (branch, points with MuJoCo's defaults first, the harness's
    stepping CPU over a bare mj_step loop's on the fast preset's sweep).
    """
    branch = scene.kinematics.branches()[0].name
    points = measure_all(scene, branch, list(settings(quick=quick, presets=scene_presets(scene))), repeats)
    run = simulate(scene, branch, preset=FAST, duration=SWEEP_S)
    return branch, points, run.cpu_time_s / bare_loop_cpu(scene, branch, run.target, repeats)
