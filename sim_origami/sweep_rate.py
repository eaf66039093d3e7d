"""
The sweep's duration from the path it drives: MuJoCo's soft closures lag a moving target by about their time
constant squared times the joints' acceleration, so a path whose joints turn fast needs a slower sweep.

Every dynamic run drives its input along a minimum-jerk ramp over T seconds (`ramp`). Along it a joint q_j moves
with acceleration A_j(p) / T^2, where p in [0, 1] is the ramp's phase and A_j = d^2 q_j / dp^2 (rad) comes from the
path alone: q_j'(x) dx s''(p) + q_j''(x) dx^2 s'(p)^2 for a sweep of dx rad. Under the `fast` preset the largest path
error of every registered scene's branches was at most LAG_S2 * max A / T^2 (docs/performance.md, "The sweep's
duration"), so a sweep lasting T = (tau / tau_fast) sqrt(LAG_S2 max A / (TARGET_FRACTION tolerance)) keeps the lag at
TARGET_FRACTION of the path-error tolerance, whatever the linkage or pattern.
"""

import numpy as np
from numpy.typing import NDArray

from .errors import ConvergenceError
from .geometry import wrap
from .presets import FAST, Preset
from .scenes.base import Scene

# Largest path error x T^2 / max A measured under `fast` (RK4 8 ms, closures 20 ms) on every registered scene's
# branches (s^2): 1.5e-7 to 4.5e-7 where the joints' acceleration sets the error, lower on well-conditioned loops.
LAG_S2 = 4.5e-7
# The lag a sweep is timed for, as a fraction of the `fast` path-error tolerance.
TARGET_FRACTION = 0.2
# A sweep never runs faster than its preset's own duration (the presets' errors were measured on it) nor slower than
# this many times it: 512 s of `fast`, 64000 steps, about 1.5 s of CPU for a Bennett linkage. The registered scenes
# ask for 1.4-5.6x (blockage runs included); a Bennett linkage with K = 87 swept across theta1 = pi (150 -> 210 deg)
# for 48x (3.3e-7 rad).
MAX_SCALE = 256.0
# Samples of the path; then windows of ZOOM_POINTS samples around the largest acceleration, each spanning four of the
# previous spacings, until that spacing is below MIN_SPACING_RAD or the peak stops growing: a near-singular span can be
# narrower than one sample (a Bennett linkage with K = 87 turns theta2 by pi / 2 within 2 / K rad of theta1 = pi).
# Finite differences at 1e-4 rad keep the closed forms' rounding (1e-14 rad) to about 1e-5 rad of acceleration.
SAMPLES = 33
ZOOM_POINTS = 17
MIN_SPACING_RAD = 1e-4
# Clearance kept from a branch's domain ends, as `Scene.branch_path` keeps it: a lock's rates grow without bound.
END_CLEARANCE = 0.05


def ramp(phase: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """
    Minimum-jerk ramp s(p) = 10 p^3 - 15 p^4 + 6 p^5 and ds/dp, for phase p in [0, 1].

    Velocity and acceleration vanish at both ends, so a run starts and ends without a transient.
    Measured against a cosine ramp (fast preset, same duration): 7.0e-9 vs 7.4e-9 rad on the
    general vertex, 6.5e-7 vs 8.3e-7 rad on the Miura vertex swept from 0.1 theta_limit.
    """
    p = np.asarray(phase, dtype=float)
    return p**3 * (10 - 15 * p + 6 * p**2), 30 * p**2 * (1 - p) ** 2


def _joints(scene: Scene, branch: str, x: NDArray[np.float64]) -> NDArray[np.float64]:
    """The closed form's output joints and the driven joints (n, k) at inputs x (rad); NaN off the domain."""
    values, _ = scene.kinematics.evaluate(branch, x)
    return np.hstack([values, scene.drive_values(x)])


def _accelerations(
    scene: Scene, branch: str, x: NDArray[np.float64], start: float, stop: float
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The inputs x where the branch is defined and, at each, the largest |d^2 q_j / dp^2| (rad) over the joints."""
    q = _joints(scene, branch, x)
    keep = np.all(np.isfinite(q), axis=1)
    x, q = x[keep], q[keep]
    if len(x) < 3:
        return x, np.zeros(len(x))
    q = q[0] + np.cumsum(np.vstack([np.zeros_like(q[:1]), wrap(np.diff(q, axis=0))]), axis=0)  # continuous across +-pi
    q_x = np.gradient(q, x, axis=0, edge_order=2)
    q_xx = np.gradient(q_x, x, axis=0, edge_order=2)
    dx = stop - start
    table = np.linspace(0.0, 1.0, 4097)
    p = np.interp((x - start) / dx, ramp(table)[0], table)
    ds = ramp(p)[1]
    dds = 60 * p * (1 - p) * (1 - 2 * p)
    return x, np.max(np.abs(q_x * (dx * dds)[:, None] + q_xx * (dx**2 * ds**2)[:, None]), axis=1)


def path_acceleration(scene: Scene, branch: str, start: float, stop: float) -> float:
    """
    The largest |d^2 q_j / dp^2| (rad) of any output or driven joint over a minimum-jerk sweep start -> stop (rad) on
    `branch`, p the ramp's phase: on a sweep of T seconds the joints' peak acceleration is this / T^2 (rad/s^2).
    Inputs within END_CLEARANCE of the branch's domain ends are left out; 0 where the closed form cannot be evaluated
    over the sweep (the preset's own duration is then used).
    """
    lo, hi = scene.kinematics.branch(branch).domain
    margin = min(END_CLEARANCE * max(abs(lo), abs(hi)), 0.25 * (hi - lo))
    a, b = np.clip(sorted((start, stop)), lo + margin, hi - margin)
    if b <= a:
        return 0.0
    try:
        x, accel = _accelerations(scene, branch, np.linspace(a, b, SAMPLES), start, stop)
        best = 0.0
        while len(x) > 2 and np.max(accel) > 1.02 * best:
            best, i, h = float(np.max(accel)), int(np.argmax(accel)), float(np.min(np.diff(x)))
            if h < MIN_SPACING_RAD:
                break
            window = np.linspace(max(a, x[i] - 2 * h), min(b, x[i] + 2 * h), ZOOM_POINTS)
            x, accel = _accelerations(scene, branch, window, start, stop)
    except ConvergenceError:  # a design driven past its closed form's turning point (a blockage run into contact)
        return 0.0
    return max(best, float(np.max(accel, initial=0.0)))


def sweep_scale(scene: Scene, branch: str, start: float, stop: float) -> float:
    """
    The sweep start -> stop (rad) on `branch` over its preset's duration: long enough that the `fast` preset's lag
    stays near TARGET_FRACTION of its path-error tolerance, at least 1 and at most MAX_SCALE. A scene whose fast
    closures are softer (`Tuning.fast_softening`) lags as their time constant squared, so it sweeps slower in
    proportion.
    """
    base = FAST.sweep_duration
    needed = np.sqrt(LAG_S2 * path_acceleration(scene, branch, start, stop) / (TARGET_FRACTION * FAST.angle_rad))
    return float(np.clip(scene.tuning.fast_softening * needed / base, 1.0, MAX_SCALE))


def sweep_duration(scene: Scene, branch: str, preset: Preset, start: float, stop: float) -> float:
    """
    Sweep time (s) of a run start -> stop (rad) on `branch` with `preset`: the preset's duration times the path's
    `sweep_scale` times the scene's `Tuning.sweep_time_scale`.
    """
    return preset.sweep_duration * sweep_scale(scene, branch, start, stop) * scene.tuning.sweep_time_scale
