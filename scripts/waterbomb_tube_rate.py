"""Steps per second of waterbomb tubes from 180 to 300 panels under MuJoCo's options, contact off and on, and the
path error each option gives on the scene's sweep (issue 5).

Every run is the `waterbomb-tube` scene's default sweep (preset stiff, SWEEP_TIME_SCALE) of an n x m tube with
alpha = beta = 40 deg, driven by the joint-equality drive as `simulate` drives it, with one option changed on the
compiled model or the scene. Rates are steps / CPU time (`time.thread_time`, this thread only) of the stepping loop:

* "off": the whole sweep (a fixed number of mj_step calls: sweep time / step), contact off; its path error is the
  largest |simulated - closed form| over every crease (rad), which must stay <= ACCURACY for the option to count;
* "window off" / "window on": the first WINDOW steps of the same sweep, contact off and on (collision solids of
  every panel, vertex-sharing pairs excluded; the default tube never touches on its sweep, so both runs move alike
  and the ratio is the cost of collision detection).

    python scripts/waterbomb_tube_rate.py              # every option but pgs on the 300-panel tube;
                                                       # baseline and independent-closures on all
    python scripts/waterbomb_tube_rate.py --sizes 10x5 --options pgs

Measured (MuJoCo 4.0.1, the 2-core machine; 12800-step sweeps), on the tube's shortest-path spanning tree from the
input crease's face (depth 20 on 10 x 5; the strip's crease-order tree was 59 deep and stepped 297/s):

    tube  panels  rows option                off /s  error rad  window off  window on
    6x5      180   639  newton-sparse          1406    1.4e-07        1487        929
    6x5      180   201  independent-closures   4054    1.4e-07        4055       1467
    8x5      240   855  newton-sparse           837    2.5e-07         840        557
    8x5      240   261  independent-closures   2510    2.5e-07        2496        895
    10x5     300  1071  newton-sparse           543    3.5e-07         560        346
    10x5     300  1071  newton-dense            322    3.5e-07         301        201
    10x5     300  1071  newton-1-iteration      538    3.5e-07         589        345
    10x5     300  1071  newton-tol-1e-12        575    3.5e-07         563        355
    10x5     300  1071  newton-no-island        590    3.5e-07         589        350
    10x5     300  1071  newton-no-warmstart     590    3.5e-07         600        369
    10x5     300  1071  cg                      373    4.6e-07         324        237
    10x5     300  1071  cg-dense                 64    4.6e-07          54         52
    10x5     300  1071  cg-5                   1738    3.3e-04        1787        608
    10x5     300  1071  pgs            11 (first 400 steps, crease-order tree; on: 10), full sweep not run
    10x5     300  1071  implicitfast            577    3.5e-07         574        357
    10x5     300   321  independent-closures   1793    3.0e-07        1820        579
    10x5     300   787  no-couplings            688    3.1e+00         694        394

`independent-closures` reaches TARGET on every tube: the symmetry couplings and 6 of the 131 cut creases close the
other 125 loops (`scenes.base.without_implied_closures`), which are then measured and not imposed, so the rows fall
from 1071 to 321 and the step's Hessian with them. With every loop imposed no MuJoCo option does within ACCURACY
(the Newton rows within 10 % of each other are run-to-run noise): Newton needs one iteration per step (warm start)
and its Hessian and factorisation over nv = 299 with 1071 rows are most of a step (timers: constraint 1.7 of 2.1
ms; the bare tree, equalities off, steps at 8300/s). CG is only faster when cut to a few iterations, which loses
the path; the couplings cannot go (the free tube leaves the symmetric path), nor can one of the two connects of
every cut crease (6 x 3: 2.4 rad). Contact on, with no contact on the sweep, costs 35-45 % with every loop imposed
and 64-68 % with the independent ones (broad phase and the exclusions, the same work on a cheaper step).
The scene itself imposes every loop: under `fast` the left-out loops cost accuracy (`without_implied_closures`).
"""

import argparse
import dataclasses
import time
from collections.abc import Callable

import mujoco
import numpy as np

import sim_origami.scenes.waterbomb_tube  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.kinematics.waterbomb_tube import BRANCH
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import STIFF
from sim_origami.scenes.base import Scene, without_implied_closures
from sim_origami.simulate import Bindings, compile_model, drive_targets

ACCURACY = STIFF.angle_rad  # rad, the path-error tolerance of the stiff and fast presets (1e-6)
# The cheapest step (one force evaluation): the scene itself now runs fast (RK4, four per step, 1.5e-8 rad at 8x).
PRESET = STIFF
TARGET = 1000.0  # steps/s
WINDOW = 1600  # steps of the windowed runs (2 s of the sweep at 1.25 ms)
SIZES = ((6, 5), (8, 5), (10, 5))
Solver, Jacobian, Integrator, Disable = mujoco.mjtSolver, mujoco.mjtJacobian, mujoco.mjtIntegrator, mujoco.mjtDisableBit


@dataclasses.dataclass(frozen=True)
class Option:
    """One change to the scene's stiff model: `apply` edits the compiled model, `prepare` the scene before it is
    compiled."""

    name: str
    apply: Callable[[mujoco.MjModel], None]
    prepare: Callable[[Scene], Scene] = lambda scene: scene


def uncoupled(scene: Scene) -> Scene:
    """The scene without its symmetry couplings: the free tube, every loop closed."""
    return dataclasses.replace(scene, mechanism=scene.mechanism.uncoupled())


def _set(**fields) -> Callable[[mujoco.MjModel], None]:
    def apply(model: mujoco.MjModel) -> None:
        for key, value in fields.items():
            setattr(model.opt, key, value)

    return apply


def _disable(bit: int) -> Callable[[mujoco.MjModel], None]:
    def apply(model: mujoco.MjModel) -> None:
        model.opt.disableflags |= int(bit)

    return apply


OPTIONS = {
    o.name: o
    for o in (
        Option("newton-sparse", _set()),  # the stiff preset as it is (jacobian auto: sparse above nv = 60)
        Option("newton-dense", _set(jacobian=Jacobian.mjJAC_DENSE)),
        Option("newton-1-iteration", _set(iterations=1, tolerance=1e-6)),
        Option("newton-tol-1e-12", _set(tolerance=1e-12)),
        Option("newton-no-island", _disable(Disable.mjDSBL_ISLAND)),
        Option("newton-no-warmstart", _disable(Disable.mjDSBL_WARMSTART)),
        Option("cg", _set(solver=Solver.mjSOL_CG)),
        Option("cg-dense", _set(solver=Solver.mjSOL_CG, jacobian=Jacobian.mjJAC_DENSE)),
        Option("cg-5", _set(solver=Solver.mjSOL_CG, iterations=5)),
        Option("pgs", _set(solver=Solver.mjSOL_PGS)),
        Option("implicitfast", _set(integrator=Integrator.mjINT_IMPLICITFAST)),
        Option("independent-closures", _set(), without_implied_closures),
        Option("no-couplings", _set(), uncoupled),
    )
}
BASELINE = "newton-sparse"
FEWEST_ROWS = "independent-closures"
SLOW = ("pgs",)  # 11 steps/s on the 300-panel tube: only when named


@dataclasses.dataclass(frozen=True)
class Run:
    """A sweep's stepping CPU time (s), steps, largest contact count and the mechanism angles (n, n_joints)."""

    cpu: float
    steps: int
    contacts: int
    q: np.ndarray


def tube(n: int, m: int, option: Option) -> Scene:
    """The default tube of n x m units, prepared for the option."""
    return option.prepare(scenes.get("waterbomb-tube").build(n=n, m=m))


def sweep(scene: Scene, option: Option, contact: bool, steps: int | None = None) -> Run:
    """The scene's default sweep as `simulate` runs it (equality drive, feed-forward), the option applied; only its
    first `steps` steps if given."""
    compiled = compile_model(scene, ModelOptions(preset=PRESET, contact=contact))
    model, data = compiled.fresh()
    option.apply(model)
    binds = Bindings(compiled)
    start, stop = scene.branch_path(BRANCH)
    binds.set_pose(data, scene.pose(BRANCH, start))
    mujoco.mj_forward(model, data)
    T = PRESET.sweep_duration * scene.tuning.sweep_time_scale
    h = model.opt.timestep
    _, target = drive_targets(scene, model, compiled.ids, start, stop, T, round(T / h))
    target, t = target[:steps], h * np.arange(1, len(target) + 1)[:steps]
    eq = compiled.ids.drive_equalities[0]
    log = np.empty((len(t), model.nq))
    setpoint, qpos, step = model.eq_data[eq], data.qpos, mujoco.mj_step
    contacts = 0
    cpu = time.thread_time()
    for value, row in zip(target.tolist(), log, strict=True):
        setpoint[0] = value
        step(model, data)
        row[:] = qpos
        contacts = max(contacts, data.ncon)
    cpu = time.thread_time() - cpu
    if any(w.number for w in data.warning) or not np.all(np.isfinite(data.qpos)):
        return Run(cpu, len(t), contacts, np.full((len(t), len(scene.mechanism.joints)), np.nan))
    return Run(cpu, len(t), contacts, binds.angles(scene, log))


def measure(n: int, m: int, option: Option) -> dict:
    """Rates (steps/s) and path error (rad) of one option on one tube."""
    scene = tube(n, m, option)
    full = sweep(scene, option, contact=False)
    error = compare(scene, BRANCH, full.q).max_error()
    off = sweep(scene, option, contact=False, steps=WINDOW)
    on = sweep(scene, option, contact=True, steps=WINDOW)
    model, data = compile_model(scene, ModelOptions(preset=PRESET)).fresh()
    mujoco.mj_forward(model, data)
    return {
        "panels": len(scene.mechanism.bodies), "nv": model.nv, "rows": data.nefc, "steps": full.steps,
        "off": full.steps / full.cpu, "error": error, "window_off": off.steps / off.cpu,
        "window_on": on.steps / on.cpu, "contacts": on.contacts,
        "counts": bool(error <= ACCURACY and full.steps / full.cpu >= TARGET),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--sizes", default=",".join(f"{n}x{m}" for n, m in SIZES), help="tubes n x m, comma-separated")
    parser.add_argument("--options", default="", help=f"option names (default: all but {', '.join(SLOW)} on the "
                        f"largest tube, {BASELINE} and {FEWEST_ROWS} on every tube); any of "
                        f"{', '.join(OPTIONS)}")
    args = parser.parse_args()
    sizes = [tuple(int(v) for v in s.split("x")) for s in args.sizes.split(",")]
    largest = max(sizes, key=lambda s: s[0] * s[1])
    header = (f"{'tube':>6s} {'panels':>6s} {'nv':>4s} {'rows':>5s} {'option':20s} {'steps':>6s} {'off /s':>7s} "
              f"{'error rad':>9s} {'win off':>7s} {'win on':>7s} {'ncon':>4s}  counts")
    print(header, flush=True)
    for n, m in sizes:
        every = [name for name in OPTIONS if name not in SLOW]
        names = args.options.split(",") if args.options else (every if (n, m) == largest else [BASELINE, FEWEST_ROWS])
        for name in names:
            r = measure(n, m, OPTIONS[name])
            print(f"{n:>3d}x{m:<2d} {r['panels']:6d} {r['nv']:4d} {r['rows']:5d} {name:20s} {r['steps']:6d} "
                  f"{r['off']:7.0f} {r['error']:9.1e} {r['window_off']:7.0f} {r['window_on']:7.0f} "
                  f"{r['contacts']:4d}  {'yes' if r['counts'] else 'no'}", flush=True)


if __name__ == "__main__":
    main()
