"""The sweep's duration from the path's joint rates (`sim_origami.sweep_rate`): real MuJoCo runs, no mocks."""

from dataclasses import replace

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.kinematics.base import Branch
from sim_origami.kinematics.bennett import Bennett
from sim_origami.presets import FAST
from sim_origami.scenes.base import Tuning
from sim_origami.simulate import simulate
from sim_origami.sweep_rate import MAX_SCALE, path_acceleration, sweep_duration, sweep_scale

ALPHA = np.pi / 6
# theta1 across pi, where a Bennett linkage with K = sin((beta + alpha) / 2) / sin((beta - alpha) / 2) turns theta2
# K times as fast as its input
ACROSS_PI = (2.6, 3.7)


class TurnedBennett(Bennett):
    """The Bennett closed form on theta1 in [0, 2 pi]: the same motion, with theta1 = pi inside the domain."""

    def branches(self) -> tuple[Branch, ...]:
        return (Branch("bennett", "the single motion, theta1 in [0, 2 pi]", (0.0, 2 * np.pi)),)


def bennett_across_pi(b: float):
    """A correct Bennett linkage (a = 1 m, alpha = 30 deg, link b m, the Bennett twist) swept across theta1 = pi."""
    beta = float(np.arcsin(b * np.sin(ALPHA)))
    scene = scenes.get("bennett").build(a=1.0, alpha=ALPHA, b=b, beta=beta)
    return replace(scene, kinematics=TurnedBennett(1.0, ALPHA, b, beta), path=ACROSS_PI)


def peak_rate(scene) -> float:
    """The largest |d theta_j / d theta1| along the scene's sweep, on a fine grid."""
    x = np.linspace(*scene.branch_path("bennett"), 4001)
    q = np.unwrap(scene.kinematics.joint_angles("bennett", x), axis=0)
    return float(np.max(np.abs(np.gradient(q, x, axis=0))))


@pytest.mark.slow
def test_the_sweep_lengthens_with_the_paths_peak_rate():
    """Same sweep, Bennett linkages turning theta2 up to 3.9, 9.2, 17.9 and 35.2 times as fast as theta1: the chosen
    time grows with the peak rate (measured 4.0, 8.3, 15.9 and 31.1x the preset's 2 s)."""
    rates, times = [], []
    for b in (1.5, 1.2, 1.1, 1.05):
        scene = bennett_across_pi(b)
        rates.append(peak_rate(scene))
        times.append(sweep_duration(scene, "bennett", FAST, *ACROSS_PI))
    assert np.all(np.diff(rates) > 0) and np.all(np.diff(times) > 0)
    assert rates[-1] > 30 and times[0] >= FAST.sweep_duration


@pytest.mark.slow
def test_a_bennett_turning_its_output_18_times_as_fast_as_its_input_passes_the_default_preset():
    """b = 1.1 (K = 17.9): at the rule's 31.7 s measured 1.5e-7 rad (6.3e-7 at half of it), about
    `TARGET_FRACTION` of the tolerance."""
    scene = bennett_across_pi(1.1)
    assert peak_rate(scene) >= 10
    run = simulate(scene, "bennett")
    rule = sweep_duration(scene, "bennett", scene.tuning.preset, *ACROSS_PI)
    assert rule <= run.sweep_time_s < rule + scene.tuning.preset.timestep  # whole steps
    assert run.sweep_time_s > 10 * FAST.sweep_duration
    assert compare(scene, "bennett", run.q).max_error() < 0.5 * FAST.angle_rad
    assert np.max(run.closure_residual) < FAST.residual(scene.length_scale)


def test_a_narrow_fast_span_between_coarse_samples_is_found():
    """b = 1.02 (K = 87): theta2 turns pi / 2 within 0.02 rad of theta1 = pi, narrower than the coarse samples; the
    refinement finds the acceleration a fine grid gives."""
    scene = bennett_across_pi(1.02)
    found = path_acceleration(scene, "bennett", *ACROSS_PI)
    x = np.linspace(*ACROSS_PI, 20001)
    q = np.unwrap(scene.kinematics.joint_angles("bennett", x), axis=0)
    q_xx = np.gradient(np.gradient(q, x, axis=0), x, axis=0)
    # near the sweep's middle ds/dp is 15/8 and d2s/dp2 about 0: d2q/dp2 = q'' dx^2 (ds/dp)^2 there
    middle = np.abs(x - np.mean(ACROSS_PI)) < 0.05
    fine = np.max(np.abs(q_xx[middle])) * (ACROSS_PI[1] - ACROSS_PI[0]) ** 2 * (15 / 8) ** 2
    assert found >= 0.8 * fine


def test_the_scale_is_at_least_one_and_capped():
    """A path slower than the presets were measured on keeps the preset's duration; none runs past MAX_SCALE."""
    scene = scenes.get("bennett").build()
    assert sweep_scale(scene, "bennett", 1.0, 1.01) == 1.0
    assert sweep_scale(bennett_across_pi(1.0005), "bennett", *ACROSS_PI) == MAX_SCALE


def test_the_scenes_tuning_scales_the_sweep():
    """Softer fast closures (`Tuning.fast_softening`) lengthen the path rule's sweep in proportion, and
    `Tuning.sweep_time_scale` multiplies the whole duration."""
    scene = bennett_across_pi(1.2)
    rule = sweep_duration(scene, "bennett", FAST, *ACROSS_PI)
    assert rule > 2 * FAST.sweep_duration  # the rule's scale is above its floor of 1
    soft = replace(scene, tuning=Tuning(fast_step_scale=1.25, fast_timeconst_scale=1.2, why="test"))
    slow = replace(scene, tuning=Tuning(sweep_time_scale=3.0, why="test"))
    np.testing.assert_allclose(sweep_duration(soft, "bennett", FAST, *ACROSS_PI), 1.5 * rule, rtol=1e-12)
    np.testing.assert_allclose(sweep_duration(slow, "bennett", FAST, *ACROSS_PI), 3.0 * rule, rtol=1e-12)
