"""MuJoCo's lag against the path's joint acceleration: every branch of every scene (or those named), preset fast.

python scripts/sweep_lag.py [scene ...]

For each branch: max |d2q/dp2| of the path (`sweep_rate.path_acceleration`, rad), the path error at the preset's
duration (2 s, the scene's fast time constant) and at the rule's (`sweep_rate.sweep_duration`), and
error x T^2 / max |d2q/dp2| at 2 s (s^2): the constant `sweep_rate.LAG_S2` bounds.
"""

import sys

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.presets import FAST
from sim_origami.simulate import simulate
from sim_origami.sweep_rate import path_acceleration


def main(names: list[str]) -> None:
    base = FAST.sweep_duration
    print(f"{'scene':26s} {'branch':26s} {'max A':>7s} {'err 2 s':>9s} {'C (s^2)':>9s} {'rule T':>7s} {'err':>9s} "
          f"{'CPU':>7s}")
    for name in names or scenes.names():
        scene = scenes.get(name).build()
        for branch in (b.name for b in scene.kinematics.branches()):
            start, stop = scene.branch_path(branch)
            accel = path_acceleration(scene, branch, start, stop)
            soft = scene.tuning.fast_softening  # the lag grows as the time constant squared
            short = simulate(scene, branch, preset=FAST, duration=base)
            err = compare(scene, branch, short.q).max_error()
            run = simulate(scene, branch, preset=FAST)
            rule = compare(scene, branch, run.q).max_error()
            print(f"{name:26s} {branch[:26]:26s} {accel:7.2f} {err:9.2e} {err * base**2 / accel / soft**2:9.2e} "
                  f"{run.sweep_time_s:7.2f} {rule:9.2e} {run.cpu_time_s:7.3f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
