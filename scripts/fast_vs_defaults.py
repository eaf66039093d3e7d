"""`fast` against MuJoCo's defaults on every scene, in one run: issue 7's "at least 100x more accurate at no more CPU".

Each scene's first branch and default sweep, the same 2 s minimum-jerk ramp for every setting (`pareto.measure`,
CPU of the stepping thread, best of REPEATS rounds that run every setting once): MuJoCo's defaults (Euler 2 ms,
solref 0.02, solimp 0.9 0.95), the scene's `fast` (`pareto.scene_presets`), and `fast` with MuJoCo's own constraint
regulariser (scale 1 instead of the preset's 0.01), which shows what the scaled regulariser buys on each scene, and
`fast-projected` (fast plus a projection onto the closures after each step, `sim_origami.stabilize`; not plain
MuJoCo). Prints a markdown table.

    python scripts/fast_vs_defaults.py [scene ...]
"""

import dataclasses
import sys

from sim_origami import scenes
from sim_origami.presets import FAST
from sim_origami.studies import pareto

# The small scenes' 2 s sweeps take 3-20 ms of CPU and this machine has slow spells seconds long:
# `pareto.measure_all` takes the settings in turn, best of REPEATS rounds.
REPEATS = 7


def main(names: list[str]) -> None:
    print("| scene | defaults error (rad) | `fast` error | more accurate, CPU | with MuJoCo's regulariser "
          "| `fast-projected` error | more accurate, CPU |")
    print("|---|---|---|---|---|---|---|")
    for name in names or scenes.names():
        scene = scenes.get(name).build()
        branch = scene.kinematics.branches()[0].name
        fast = pareto.scene_presets(scene)[FAST]
        plain = dataclasses.replace(fast, label="fast, MuJoCo's regulariser", regularization=1.0)
        settings = [pareto.DEFAULTS, fast, plain, pareto.PROJECTED]
        default, ours, theirs, projected = pareto.measure_all(scene, branch, settings, REPEATS)
        print(f"| {name} | {default.error:.1e} | {ours.error:.1e} | {_gain(default, ours)} | {theirs.error:.1e} "
              f"| {projected.error:.1e} | {_gain(default, projected)} |", flush=True)


def _gain(default: pareto.Point, point: pareto.Point) -> str:
    """How many times more accurate than MuJoCo's defaults, and the CPU ratio to them."""
    ratio = default.error / point.error
    gain = (f"{ratio:.0f}x" if ratio < 1e6 else f"{ratio:.1e}x") if default.error < float("inf") else "defaults diverge"
    return f"{gain}, {point.cpu / default.cpu:.2f}x"


if __name__ == "__main__":
    main(sys.argv[1:])
