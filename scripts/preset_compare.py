"""Presets fast and stiff on every scene's first branch, in one run: max angle error and CPU time of stepping.

python scripts/preset_compare.py [scene ...]
"""

import sys

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.presets import FAST, STIFF
from sim_origami.simulate import simulate


def main(names: list[str]) -> None:
    print(f"{'scene':20s} {'branch':24s} {'fast err':>9s} {'fast CPU':>9s} {'stiff err':>9s} {'stiff CPU':>9s}")
    for name in names or scenes.names():
        scene = scenes.get(name).build()
        branch = scene.kinematics.branches()[0].name
        row = []
        for preset in (FAST, STIFF):
            run = simulate(scene, branch, preset=preset)
            row += [compare(scene, branch, run.q).max_error(), run.cpu_time_s]
        print(f"{name:20s} {branch:24s} {row[0]:9.1e} {row[1]:8.3f}s {row[2]:9.1e} {row[3]:8.3f}s")


if __name__ == "__main__":
    main(sys.argv[1:])
