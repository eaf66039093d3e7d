"""The three-way cross-check of one scene: closed form, numeric loop closure and MuJoCo.

For each requested branch: the closed form is checked against its own loop residual and against
the numeric solver followed by continuation; MuJoCo runs the preset (dynamic) and the kinematic
projection, and each path is compared with the closed form at the simulated input and labelled
with the branch it followed. Thick scenes add a blockage run. The result is a `Report`.
"""

import dataclasses
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .checks.blockage import Blockage, assess
from .checks.branches import classify
from .checks.paths import PathComparison, closure_conditions, compare, floor_verdict_values
from .checks.reference import ReferenceCheck, ReferenceCurves, compare_reference
from .checks.verdict import Verdict
from .conventions import MIN_SWEEP_RAD
from .errors import ConvergenceError, SimulationError
from .mjcf import CompiledModel, ModelOptions
from .peer_times import FREE_RUN_PEERS
from .presets import FAST, Preset, as_preset
from .scenes.base import Scene
from .simulate import (
    Bindings,
    Trajectory,
    compile_model,
    contact_input,
    mujoco_mobility,
    project,
    projection_conditions,
    simulate,
    simulate_free,
)
from .stabilize import before_projection
from .tolerances import TOLERANCES
from .truss import truss_mobility

# Samples of the closed form and of the numeric solve along each path.
ANALYTIC_SAMPLES = 200
# A run must sweep its input over at least MIN_SWEEP_RAD to pass: below it the path's shape cannot show (the fast
# preset's angle tolerance is 1e-6 rad, three orders smaller; a frozen input gives error 0 on nothing). The shortest
# default sweep of a registered scene is far longer (every one spans at least a quarter of its domain).
# Events of a numerically traced reference (`kinematics.numeric_pattern`): where and why its trace ended, its
# mobility changes, an open chain. Reported with every run, inside the sweep or not.
REFERENCE_EVENTS = ("stall", "lock", "contact", "branch-point", "mobility-change", "open-chain", "off-target",
                    "frame")
# Free runs (scenes with gravity) last this long (s), as the IFToMM A04 benchmark.
FREE_DURATION = 10.0
# Bifurcation study: seed offsets (rad of input) tried in turn, and the length of each run (rad).
SEED_OFFSETS = (1e-4, 1e-3, 1e-2, 1e-1)
STUDY_SPAN = 0.3
# The blockage run holds its final target this long (s) before its stop is read. Near a singular end the servo
# creeps: the truncated octahedron at zeta = 15 deg touches at the contact, bounces, and is 3.1e-3 rad short of it
# after 1 s, 2.5e-5 after 3 s (stiff); the thick Miura vertex (t = 0.02) 3.2e-4 and 9.8e-6.
BLOCKAGE_HOLD = 3.0

# Each check's stable id (`Verdict.id`, report.json's `verdicts[].id`), by kind; the display names may change.
CLOSED_FORM_RESIDUAL = "closed-form-residual"  # the closed form's loop residual
CLOSED_FORM_VS_NUMERIC = "closed-form-vs-numeric"  # the closed form against the numeric continuation
SWEPT_RANGE = "swept-range"  # how far MuJoCo's run swept its input
MUJOCO_VERTEX_ERROR = "mujoco-vertex-error"  # a shape model's vertices, MuJoCo against the closed form
MUJOCO_PATH_ERROR = "mujoco-path-error"  # MuJoCo's path against the closed form (after projection if it projects)
MUJOCO_OWN_STEP_ERROR = "mujoco-path-error-before-projection"  # a projected preset's own steps
MUJOCO_CLOSURE_RESIDUAL = "mujoco-closure-residual"  # gaps between MuJoCo's paired closure sites
PROJECTION_PATH_ERROR = "projection-path-error"  # the projection onto MuJoCo's constraints against the closed form
BRANCH_FOLLOWED = "branch-followed"  # MuJoCo stayed on the branch it was started on
MOBILITY_AGREEMENT = "mobility-agreement"  # numeric rank, MuJoCo's rank and the truss count agree
TRACE_STOPS_AT_START = "trace-stops-at-start"  # a traced reference that never left its start
FRAMES_DISTANCE = "frames-distance"  # a FOLD file's frames from the rigid motion
FOLDED_STATE_DISTANCE = "folded-state-distance"  # a FOLD file's folded state from the rigid motion
FILE_STATE_DISTANCE = "file-state-distance"  # a FOLD file's state from the nearest rigid state
MV_CREASES_LEFT_FLAT = "mv-creases-left-flat"  # lettered creases the traced motion does not fold
FREEDOMS_NOT_DRIVEN = "freedoms-not-driven"  # mobility along a traced path beyond its inputs
BLOCKAGE_STOP = "blockage-stop-vs-contact"  # a force-limited drive's stop against the kinematic contact
FREE_RUN_ENERGY_DRIFT = "free-run-energy-drift"
FREE_RUN_OWN_STEP_ERROR = "free-run-path-error-before-projection"
FREE_RUN_PATH_ERROR = "free-run-path-error"
BIFURCATION_UNFOLLOWED = "bifurcation-branches-not-followed"  # branches a seeded run never took at a bifurcation


class ZeroSweepError(SimulationError):
    """
    A branch whose drive has zero length (a traced reference stuck at its start): no MuJoCo run is made, and the
    checks made without MuJoCo (`verdicts`, the trace's stop among them) and the reference's `events` say why.
    """

    def __init__(self, message: str, verdicts: tuple[Verdict, ...], events: tuple[dict, ...]):
        super().__init__(message)
        self.verdicts, self.events = verdicts, events


@dataclass(frozen=True)
class BranchRun:
    """One branch: requested and followed, MuJoCo path comparisons, events on the path."""

    requested: str
    followed: str
    flips: int
    dynamic: Trajectory
    dynamic_path: PathComparison
    projection_path: PathComparison
    projection_residual_m: float
    events: tuple[dict, ...]
    mobility: dict
    verdicts: tuple[Verdict, ...]


@dataclass(frozen=True)
class Report:
    """Everything `report.write` saves: verdicts, runs, events and timings (seconds)."""

    scene: Scene
    model: CompiledModel  # what the dynamic runs and the projection stepped (model.xml starts from its text)
    seed: str
    runs: tuple[BranchRun, ...]
    verdicts: tuple[Verdict, ...]
    blockage: Blockage | None
    bifurcations: tuple[dict, ...] = ()
    free_run: dict | None = None
    timings: dict[str, float | int] = field(default_factory=dict)
    reference: ReferenceCheck | None = None  # the user's curves against the numeric path and MuJoCo

    @property
    def preset(self) -> Preset:
        """The preset the runs used."""
        return self.model.preset

    @property
    def passed(self) -> bool:
        every = list(self.verdicts) + [v for r in self.runs for v in r.verdicts]
        return all(v.passed for v in every)


def closed_form_verdicts(scene: Scene, branch: str, x: np.ndarray) -> tuple[Verdict, ...]:
    """Closed form: its loop residual, and its distance to the numeric solve by continuation."""
    kin = scene.kinematics
    loops = kin.loop_system()
    values = kin.joint_angles(branch, x)
    q = kin.loop_angles(values)
    joints, held = kin.loop_inputs(x)
    residual = Verdict(
        f"{branch}: closed-form closure residual",
        float(np.max(loops.residual_norm(q))),
        TOLERANCES.loop_residual(scene.length_scale),
        "max |rotation vector, translation| of the loop product",
        compared=len(q), id=CLOSED_FORM_RESIDUAL, branch=branch,
    )
    name = f"{branch}: closed form vs numeric closure (rad)"
    try:
        numeric = loops.follow(q[0], joints[0], held[:, 0]) if len(joints) == 1 else loops.follow(q[0], joints, held)
    except ConvergenceError as err:
        # the continuation could not close where the reference did: this check fails (exit 1, with the report),
        # the input is not bad (a triangulated grid folded along one line and driven by fewer inputs than its
        # motion's freedoms, as --input may ask: 10 x 10, 37 of 109, 2.7e-12 where 1e-12 is asked)
        return residual, Verdict(name, float("inf"), TOLERANCES.closed_form_rad, f"damped-Newton continuation over "
                                 f"the same inputs did not reach the reference's states: {err}", len(x),
                                 id=CLOSED_FORM_VS_NUMERIC, branch=branch)
    error, tol, where = floor_verdict_values(scene, PathComparison(x, kin.observe(numeric), values),
                                             TOLERANCES.closed_form_rad, TOLERANCES.closed_form_cond_factor)
    return (
        residual,
        Verdict(name, error, tol, f"damped-Newton continuation over the same inputs, no closed form used; {where}",
                len(x), id=CLOSED_FORM_VS_NUMERIC, branch=branch),
    )


def path_events(
    scene: Scene, branch: str, x: np.ndarray, labels: tuple[str, ...], from_flat: bool = False
) -> tuple[dict, ...]:
    """
    Closed-form events of `branch` inside the swept input range, with the branch taken after each.
    A run seeded at the flat state starts at its bifurcation, which then counts as on the path.
    """
    lo, hi = float(np.min(x)), float(np.max(x))
    if from_flat:
        lo, hi = min(lo, 0.0), max(hi, 0.0)
    out = []
    for e in scene.kinematics.events():
        if e.kind in REFERENCE_EVENTS and branch in e.branches:
            out.append({"kind": e.kind, "input_rad": e.input, "branches": list(e.branches), "detail": e.detail,
                        "branch_after": ""})
        elif branch in e.branches and lo - 1e-9 <= e.input <= hi + 1e-9:
            past = [lab for xi, lab in zip(x, labels, strict=True) if lab and abs(xi - e.input) > 1e-6]
            after = max(set(past), key=past.count) if past else ""  # the branch held after it
            out.append({"kind": e.kind, "input_rad": e.input, "branches": list(e.branches), "detail": e.detail,
                        "branch_after": after})
    return tuple(out)


def mobility_report(scene: Scene, branch: str, start: float, model: CompiledModel | None = None) -> dict:
    """
    Grubler-Kutzbach count next to the numerical rank of the closure Jacobian, from the numeric
    loop and from MuJoCo's efc_J (on `model`, `simulate.mujoco_mobility`), and the truss method's mobility and states
    of self-stress (Yang 2017, ch. 2), at the path start and at each bifurcation point of the branch. The idle spins
    of bars held by two spherical joints are left out of every count (the truss method has none).
    """
    kin = scene.kinematics
    loops = kin.loop_system()

    idle = scene.mechanism.idle_spins  # S-S bars' spins: counted by loop ranks and MuJoCo, not by the truss

    def at(x: float) -> dict:
        q_loop = kin.loop_angles(kin.joint_angles(branch, x))
        q = scene.loop_to_mechanism(q_loop)[0]
        truss = truss_mobility(scene, q, stresses=False)  # counts only: the sparse Gram matrix ranks big trusses
        return {"input_rad": x, "numeric": loops.mobility(q_loop[0]) - idle,
                "mujoco": mujoco_mobility(scene, q, model) - idle, "truss": truss.mobility,
                "truss_self_stress": truss.self_stress}

    points = [e.input for e in kin.events() if e.kind == "bifurcation" and branch in e.branches]
    out = {"gruebler": kin.gruebler(), "idle_spins": idle, "inputs": len(scene.drives), "start": at(start),
           "bifurcations": [at(x) for x in points]}
    along = _along_path(kin)
    if along is not None:
        out["along_path"] = along
    return out


def _along_path(kin) -> dict | None:
    """A traced reference's mobility over its nodes (min, max, the most common), None for a closed form."""
    along = getattr(kin, "mobility", None)  # a traced reference's mobility at each of its nodes
    if along is None or callable(along):
        return None
    values, counts = np.unique(along, return_counts=True)
    return {"min": int(np.min(along)), "max": int(np.max(along)), "typical": int(values[np.argmax(counts)])}


def _followed(scene: Scene, branch: str, run: Trajectory) -> str:
    path = compare(scene, branch, run.q)
    return classify(scene.kinematics, path.input, path.simulated).followed


def bifurcation_study(scene: Scene, model: CompiledModel) -> list[dict]:
    """
    At each bifurcation point x_b: for each branch through it, start MuJoCo on that branch (a closed
    pose) at x_b + d for d in SEED_OFFSETS and drive STUDY_SPAN away; record the smallest d at which
    the engine follows the branch. Unseeded: start at x_b itself, at rest, and record what it takes.
    Each run lasts the preset's sweep time, without the scene's slow-down: telling branches apart needs
    far less accuracy than the path check (at most 1e-5 rad against branches >= 1e-2 apart here). The runs step
    `model` (an equality-driven `simulate.compile_model`).
    """
    duration = model.preset.sweep_duration
    out = []
    for event in scene.kinematics.events():
        if event.kind != "bifurcation":
            continue
        xb = event.input
        lo, hi = scene.kinematics.branch(event.branches[0]).domain
        sign = 1.0 if hi - xb >= xb - lo else -1.0
        seeded = {}
        for branch in event.branches:
            seeded[branch] = None
            for d in SEED_OFFSETS:
                start = xb + sign * d
                run = simulate(scene, branch, start=start, stop=start + sign * STUDY_SPAN, duration=duration,
                               model=model)
                if _followed(scene, branch, run) == branch:
                    seeded[branch] = d
                    break
        stop = xb + sign * STUDY_SPAN
        run = simulate(scene, event.branches[0], start=xb, stop=stop, duration=duration, model=model)
        unseeded = _followed(scene, event.branches[0], run)
        out.append(
            {
                "input_rad": xb,
                "branches": list(event.branches),
                "detail": event.detail,
                "seed_offset_followed_rad": seeded,
                "unseeded_followed": unseeded,
            }
        )
    return out


def _point_verdicts(scene: Scene, branch: str, preset: Preset, q: np.ndarray, x: np.ndarray) -> tuple[Verdict, ...]:
    """For shape models (polyhedra): the largest distance between simulated and closed-form vertices."""
    kin = scene.kinematics
    analytic = kin.points(branch, x)
    if analytic is None:
        return ()
    error = float(np.max(np.linalg.norm(kin.observe_points(scene.mechanism_to_loop(q)) - analytic, axis=-1)))
    return (Verdict(f"{branch}: MuJoCo {preset.name} vertex position error (edge lengths)", error,
                    preset.angle_rad, "max over samples and vertices, unit edges", len(x), id=MUJOCO_VERTEX_ERROR,
                    branch=branch),)


def run_branch(scene: Scene, branch: str, model: CompiledModel, seed: str) -> BranchRun:
    """MuJoCo dynamic run and projection on one branch, both on `model` (an equality-driven
    `simulate.compile_model`), compared and classified."""
    preset = model.preset
    with before_projection() as own:
        dynamic = simulate(scene, branch, seed=seed, model=model)
    dyn = compare(scene, branch, dynamic.q)
    labels = classify(scene.kinematics, dyn.input, dyn.simulated)
    start, stop = scene.branch_path(branch)
    proj_traj = project(scene, branch, np.linspace(start, stop, ANALYTIC_SAMPLES), model=model)
    proj = compare(scene, branch, proj_traj.q)
    proj_error, proj_tol, proj_where = floor_verdict_values(
        scene, proj, TOLERANCES.projection_rad, TOLERANCES.projection_cond_factor,
        other_condition=lambda k: projection_conditions(scene, proj_traj.q[k], model),
    )
    mobility = mobility_report(scene, branch, start, model)
    disagree = sum(
        len({p["numeric"], p["mujoco"], p["truss"]}) > 1 for p in [mobility["start"], *mobility["bifurcations"]]
    )
    swept = float(np.max(dyn.input) - np.min(dyn.input))
    verdicts = (
        Verdict(f"{branch}: swept range ({MIN_SWEEP_RAD:g} rad / input range swept)",
                MIN_SWEEP_RAD / swept if swept > 0 else float("inf"), 1.0,
                f"the input moved over {swept:.3g} rad; a run that sweeps less than {MIN_SWEEP_RAD:g} rad cannot pass",
                id=SWEPT_RANGE, branch=branch),
        *_point_verdicts(scene, branch, preset, dynamic.q, dyn.input),
        *_own_step_verdicts(scene, branch, model, own),
        Verdict(f"{branch}: MuJoCo {preset.name} path error" + (" after projection" if own else "") + " (rad)",
                dyn.max_error(), preset.angle_rad,
                "max over samples and joints of |sim - closed form at the simulated input|"
                + _singular_crossings(scene, branch, dyn.input, dyn.error, mobility)
                + _conditioning(scene, dyn, preset.angle_rad), len(dyn.input), id=MUJOCO_PATH_ERROR, branch=branch),
        Verdict(f"{branch}: MuJoCo {preset.name} closure residual (m)", float(np.max(dynamic.closure_residual)),
                preset.residual(scene.length_scale), "largest gap between paired closure sites",
                len(dynamic.closure_residual), id=MUJOCO_CLOSURE_RESIDUAL, branch=branch),
        Verdict(f"{branch}: MuJoCo projection path error (rad)", proj_error, proj_tol,
                f"Gauss-Newton on MuJoCo's equality residuals at each input, to the rounding floor; {proj_where}"
                + _singular_crossings(scene, branch, proj.input, proj.error, mobility), len(proj.input),
                id=PROJECTION_PATH_ERROR, branch=branch),
        Verdict(f"{branch}: branch followed", float(labels.followed != branch or labels.flips > 0), 0.0,
                f"followed {labels.followed or 'none'}, {labels.flips} flips", len(labels.labels), id=BRANCH_FOLLOWED,
                branch=branch),
        Verdict(f"{branch}: mobility, numeric rank vs MuJoCo rank vs truss (poses that differ)", float(disagree), 0.0,
                f"Kutzbach {mobility['gruebler']}"
                + (f" (+{mobility['idle_spins']} idle spin, taken off every count)" if mobility["idle_spins"] else "")
                + f", instantaneous {mobility['start']['numeric']} at the start", 1 + len(mobility["bifurcations"]),
                id=MOBILITY_AGREEMENT, branch=branch),
        *_input_count_verdict(scene, branch, mobility),
    )
    return BranchRun(
        requested=branch, followed=labels.followed, flips=labels.flips, dynamic=dynamic, dynamic_path=dyn,
        projection_path=proj, projection_residual_m=float(np.max(proj_traj.closure_residual)),
        events=path_events(scene, branch, dyn.input, labels.labels, from_flat=seed == "flat"), mobility=mobility,
        verdicts=verdicts,
    )


def _singular_crossings(scene: Scene, branch: str, x: np.ndarray, error: np.ndarray, mobility: dict) -> str:
    """
    The bifurcations of `branch` that a run's inputs x (n,) cross, as a clause for a failing check's detail, with
    where its per-sample error (n,) or (n, k) peaks: there the closure constraints lose rank, MuJoCo's soft closures
    hold the pose only weakly along the new freedom and its error peaks (the Myard with a ball at joint 2 through
    theta3 = 90 deg: 1.1e-3 rad 0.32 deg past the meeting, 2.6e-8 rad beyond 100 deg). Empty when none is crossed.
    """
    lo, hi = float(np.min(x)), float(np.max(x))
    crossed = [e for e in scene.kinematics.events() if e.kind == "bifurcation" and branch in e.branches
               and lo < e.input < hi]
    if not crossed:
        return ""
    error = np.where(np.isnan(error), np.inf, error).reshape(len(x), -1).max(axis=1)
    worst = float(x[int(np.argmax(error))])
    ranks = {round(p["input_rad"], 9): p for p in mobility["bifurcations"]}
    parts = []
    for e in crossed:
        at = ranks.get(round(e.input, 9))
        count = f"; mobility {at['numeric']} there by the closure rank, {at['mujoco']} by MuJoCo's" if at else ""
        parts.append(f"the sweep crosses a singular pose: the bifurcation at {e.input:.6g} rad ({e.detail}{count}); "
                     f"the largest error lies {abs(worst - e.input):.3g} rad from it, at {worst:.6g} rad")
    return "; " + "; ".join(parts)


def _conditioning(scene: Scene, path: PathComparison, tol: float) -> str:
    """
    For a path error over `tol`: where it peaks and the closure Jacobian's condition number there and at the sweep's
    start, as a clause for the check's detail. MuJoCo's soft closures let more lag through where the path is
    ill-conditioned (truncated-tetrahedron-i at delta = -62 deg, 0.02 deg inside its limit: 4.7e-4 rad where the
    condition number is 986, 32 at the start). Empty when the check passes or the error is not finite.
    """
    error = path.error.reshape(len(path.input), -1).max(axis=1)
    if not np.all(np.isfinite(error)) or np.max(error, initial=0.0) <= tol:
        return ""
    k = int(np.argmax(error))
    at, start = closure_conditions(scene, path.input[[k, 0]], path.analytic[[k, 0]])
    return (f"; largest at input {path.input[k]:.6g} rad, where the closure Jacobian's condition number is {at:.3g} "
            f"({start:.3g} at the sweep's start)")


def _input_count_verdict(scene: Scene, branch: str, mobility: dict) -> tuple[Verdict, ...]:
    """A numerically traced reference must be driven in every freedom it has: more freedoms than inputs leave the
    motion undetermined (MuJoCo and the reference may then part along the free directions). With a frames'
    tolerance (exact frame angles, or asked for), each frame's distance from the rigid motion is checked too, as is a
    single folded state's where the trace reaches its inputs (`PatternPath.target_check`); on a trace of M/V letters,
    that it folds every lettered crease (`PatternPath.unfolded_letters`)."""
    along = mobility.get("along_path")
    if along is None:
        return ()
    kin = scene.kinematics
    stuck = kin.start_check() if hasattr(kin, "start_check") else None  # a trace that never left its start
    frames = () if stuck is None else (Verdict(f"{branch}: traced motion stops at its start", *stuck,
                                                   id=TRACE_STOPS_AT_START, branch=branch),)
    tolerance = getattr(kin, "frames_tolerance", None)
    if tolerance is not None and getattr(kin, "frame_distances", None):
        far = [d["distance_rad"] for d in kin.frame_distances]
        worst = float("inf") if any(d is None for d in far) else max(far)
        frames += (Verdict(f"{branch}: frames' distance from the rigid motion (rad)", worst, tolerance,
                           f"{len(far)} frames; beyond the traced motion counts as infinite", id=FRAMES_DISTANCE,
                           branch=branch),)
    target = kin.target_check() if hasattr(kin, "target_check") else None  # a FOLD file's folded state, reached?
    if target is not None:
        frames += (Verdict(f"{branch}: folded state's distance from the rigid motion (rad)", *target,
                           id=FOLDED_STATE_DISTANCE, branch=branch),)
    state = kin.state_check() if hasattr(kin, "state_check") else None  # a FOLD file's folded form (fold.FormFit)
    if state is not None:
        frames += (Verdict(f"{branch}: file state's distance from the nearest rigid state (/ its precision)", *state,
                           id=FILE_STATE_DISTANCE, branch=branch),)
    unfolded = kin.unfolded_letters() if hasattr(kin, "unfolded_letters") else None
    if unfolded is not None:
        frames += (Verdict(f"{branch}: M/V creases the motion leaves flat", float(len(unfolded)), 0.0,
                           f"{', '.join(unfolded[:8])}{' ...' if len(unfolded) > 8 else ''}: the letters do not fold "
                           "rigidly with them folded" if unfolded else "every M/V crease folds",
                           id=MV_CREASES_LEFT_FLAT, branch=branch),)
    return (*frames, Verdict(f"{branch}: freedoms not driven (mobility along the path - inputs)",
                    float(max(along["typical"] - mobility["inputs"], 0)), 0.0,
                    f"mobility {along['typical']} along the traced path (min {along['min']}, max {along['max']}), "
                    f"{mobility['inputs']} input(s) "
                    f"{', '.join(scene.drives)}", id=FREEDOMS_NOT_DRIVEN, branch=branch),)


def _own_step_verdicts(scene: Scene, branch: str, model: CompiledModel, own: list[np.ndarray]) -> tuple[Verdict, ...]:
    """
    A projected preset's dynamic check: the path error of MuJoCo's own steps, each from the last projected state and
    read before its projection (`stabilize.before_projection`), held to the plain fast preset's tolerance; () for a
    plain preset (it records nothing). After the projection the path is on the closures whatever the dynamics did.
    `model` is the one the run stepped.
    """
    if not own:
        return ()
    path = compare(scene, branch, Bindings(model).angles(scene, np.array(own)))
    return (Verdict(f"{branch}: MuJoCo {model.preset.name} path error before projection (rad)", path.max_error(),
                    FAST.angle_rad, "MuJoCo's own step from each projected state, before its projection: "
                    "max over steps and joints of |sim - closed form at the simulated input|", len(own),
                    id=MUJOCO_OWN_STEP_ERROR, branch=branch),)


def run_blockage(scene: Scene, branch: str) -> tuple[Blockage, float]:
    """Force-limited servo from the path start to the branch's end in the direction of travel, held BLOCKAGE_HOLD,
    under the scene's preset; the kinematic contact on the same model."""
    start, stop = scene.branch_path(branch)
    lo, hi = scene.kinematics.branch(branch).domain
    lock = hi if stop >= start else lo
    t0 = time.thread_time()
    model = compile_model(scene, ModelOptions(preset=scene.tuning.preset, drive="servo", contact=True))
    touch = contact_input(scene, branch, start, lock, model=model)
    run = simulate(scene, branch, start=start, stop=lock, hold=BLOCKAGE_HOLD, model=model)
    x = run.q[:, scene.mechanism.joint_index(scene.drive_joint)] / scene.drive_scale
    result = assess(x, run.target, run.drive_force / scene.drive_scale, 20.0 / scene.drive_scale, touch, lock)
    return result, time.thread_time() - t0


def run_free(scene: Scene, preset: Preset) -> tuple[dict, list[Verdict]]:
    """Release the scene at rest under gravity for FREE_DURATION s: energy drift (at the run's states) and path error;
    under a projected preset also the path error of MuJoCo's own steps before their projections (`_own_step_verdicts`:
    after them the run is on the closures whatever the dynamics did)."""
    model = compile_model(scene, ModelOptions(preset=preset, drive="none", gravity=True))
    with before_projection() as own:
        run = simulate_free(scene, scene.free_branch, scene.free_start, FREE_DURATION, model=model)
    path = compare(scene, scene.free_branch, run.q)
    drift = float(np.max(np.abs(run.energy - run.energy[0])))
    doc = {"duration_s": FREE_DURATION, "steps": run.steps, "step_cpu_time_s": run.cpu_time_s,
           "energy_initial_J": float(run.energy[0]), "energy_drift_max_J": drift,
           "angle_error_max_rad": path.max_error(), "closure_residual_max_m": float(np.max(run.closure_residual)),
           "input_range_rad": [float(np.min(path.input)), float(np.max(path.input))]}
    peer = ""
    if scene.name in FREE_RUN_PEERS:
        tool, seconds = FREE_RUN_PEERS[scene.name]
        doc |= {"peer": tool, "peer_time_s": seconds, "peer_over_mujoco": seconds / run.cpu_time_s}
        peer = f" ({tool}: {seconds} s)"
    own_step = _own_step_verdicts(scene, scene.free_branch, model, own)
    if own_step:
        doc["angle_error_before_projection_max_rad"] = own_step[0].measured
    verdicts = [
        Verdict(f"free run ({FREE_DURATION:g} s under gravity): energy drift (J)", drift, preset.energy_j,
                f"E0 = {run.energy[0]:.6g} J at the release, E at each state after a step; "
                f"{run.cpu_time_s:.3g} s CPU{peer}", id=FREE_RUN_ENERGY_DRIFT, branch=scene.free_branch),
        *(dataclasses.replace(v, name=f"free run: {v.name}", id=FREE_RUN_OWN_STEP_ERROR) for v in own_step),
        Verdict("free run: path error against the closed form" + (" after projection" if own else "") + " (rad)",
                path.max_error(), preset.angle_rad,
                "unforced motion stays on the closed-form branch", id=FREE_RUN_PATH_ERROR, branch=scene.free_branch),
    ]
    return doc, verdicts


def validate(
    scene: Scene,
    *,
    preset: Preset | str | None = None,
    branch: str | None = None,
    seed: str = "closed",
    reference: ReferenceCurves | None = None,
    progress: Callable[[str, int, int], None] | None = None,
) -> Report:
    """
    Cross-check a scene on one branch (or all of them); with `reference` (`checks.reference.read_reference`) also
    the user's own curves against the numeric loop solve, the scene's kinematics and MuJoCo's runs. `progress`
    (phase, done, total) is called as each phase starts. `preset` is a `Preset` or its name; default the scene's.

    Raises
    ------
    ParameterError
      For an unknown branch or preset.
    """
    preset = as_preset(preset or scene.tuning.preset)
    names = [branch] if branch else [b.name for b in scene.kinematics.branches()]
    for name in names:
        scene.kinematics.branch(name)
    timings: dict[str, float | int] = {}
    verdicts: list[Verdict] = []
    phases = 2 * len(names) + bool(scene.contact_pairs) + (scene.gravity is not None) + (branch is None) + (
        reference is not None)
    done = iter(range(phases))

    def phase(text: str) -> None:
        if progress is not None:
            progress(text, next(done), phases)

    t0 = time.thread_time()
    for name in names:
        phase(f"closed form vs numeric loop closure, {name}")
        start, stop = scene.branch_path(name)
        verdicts += closed_form_verdicts(scene, name, np.linspace(start, stop, ANALYTIC_SAMPLES))
    timings["closed_form_and_numeric_cpu_s"] = time.thread_time() - t0
    model = compile_model(scene, ModelOptions(preset=preset))  # the dynamic runs', the projection's and model.xml's
    runs = []
    for name in names:
        phase(f"MuJoCo {preset.name} and its projection, {name}")
        start, stop = scene.branch_path(name)
        stuck = getattr(scene.kinematics, "start_check", None)
        if stuck is not None and stuck() is not None:
            # a trace that never left its start (or ended within MIN_SWEEP_RAD of it): MuJoCo would hold one pose, and
            # may diverge doing it on a start that does not close; the trace's stop is the cause. A sweep frozen
            # otherwise fails its swept range.
            known = _input_count_verdict(scene, name, {"along_path": _along_path(scene.kinematics),
                                                       "inputs": len(scene.drives)})
            events = path_events(scene, name, np.array([start]), ("",))
            raise ZeroSweepError(f"no MuJoCo run: the drive of {name} sweeps {abs(stop - start):.3g} rad ({start:.6g} "
                                 f"-> {stop:.6g} rad)",
                                 (*verdicts, *known), events)
        try:
            runs.append(run_branch(scene, name, model, seed))
        except SimulationError as err:  # the report keeps what is known without MuJoCo: often the first cause
            known = _input_count_verdict(scene, name, {"along_path": _along_path(scene.kinematics),
                                                       "inputs": len(scene.drives)})
            err.verdicts = (*verdicts, *known)
            raise
    timings["mujoco_step_cpu_s"] = sum(r.dynamic.cpu_time_s for r in runs)
    timings["mujoco_steps"] = sum(r.dynamic.steps for r in runs)  # a count (int), beside the times (s)
    blockage = None
    if scene.contact_pairs:
        phase("blockage: a force-limited drive against contact")
        blockage, timings["blockage_cpu_s"] = run_blockage(scene, names[0])
        verdicts.append(
            Verdict(
                "blockage: servo stop vs kinematic contact (rad)",
                blockage.error,
                TOLERANCES.blockage_rad,
                f"stopped at {blockage.stop_input:.6f}, contact at {blockage.contact_input:.6f}, "
                f"zero-thickness lock at {blockage.analytic_limit:.6f} rad",
                id=BLOCKAGE_STOP, branch=names[0],
            )
        )
    free = None
    if scene.gravity is not None:
        phase("free run under gravity")
        free, free_verdicts = run_free(scene, preset)
        verdicts += free_verdicts
    t1 = time.thread_time()
    if branch is None:
        phase("bifurcation study")
    study = tuple(bifurcation_study(scene, model)) if branch is None else ()
    for point in study:
        never = [b for b, d in point["seed_offset_followed_rad"].items() if d is None]
        verdicts.append(
            Verdict(
                f"bifurcation at {point['input_rad']:.6g} rad: branches MuJoCo never followed when seeded",
                float(len(never)),
                0.0,
                f"{', '.join(never) or 'none'}; unseeded it took {point['unseeded_followed'] or 'no clear branch'}",
                id=BIFURCATION_UNFOLLOWED,
            )
        )
    timings["bifurcation_study_cpu_s"] = time.thread_time() - t1
    checked = None
    if reference is not None:
        phase("your reference curves")
        t2 = time.thread_time()
        checked = compare_reference(reference, scene, runs, tuple(names))
        verdicts += checked.verdicts
        timings["reference_cpu_s"] = time.thread_time() - t2
    timings["total_cpu_s"] = time.thread_time() - t0
    return Report(scene, model, seed, tuple(runs), tuple(verdicts), blockage, study, free, timings, checked)
