"""Pareto fronts of several scenes in one run and one plot (`sim-origami bench SCENE` does one scene).

For each scene (its first branch, its default sweep, the same 2 s ramp for every setting): MuJoCo's defaults,
the presets, every integrator (RK4 / Euler / implicitfast) x step (0.625-8 ms) x closure time constant (2h-8h,
solimp 0.9999), and the presets with one connect per cut hinge, with only the loops nothing else implies and with
the servo drive (`sim_origami.pareto`).
Prints each front with its ratios to the defaults; writes pareto.csv and pareto.png.

    python scripts/pareto.py [scene ...]          (default: vertex4 waterbomb-vertex miura-sheet)
"""

import sys

from sim_origami import scenes
from sim_origami.cli.bench import pareto_table
from sim_origami.files import write_text
from sim_origami.plots import plot_pareto
from sim_origami.studies import pareto


def main(names: list[str]) -> None:
    points, rows = {}, []
    for name in names or ["vertex4", "waterbomb-vertex", "miura-sheet"]:
        branch, points[name], harness = pareto.sweep(scenes.get(name).build())
        rows += [f"{name},{p.setting.label},{p.error:.6g},{p.cpu:.6g}" for p in points[name]]
        print(pareto_table(f"\n{name} ({branch}, {pareto.SWEEP_S:g} s sweep)", points[name], harness))
    write_text("pareto.csv", "scene,setting,error_rad,cpu_s\n" + "\n".join(rows) + "\n")
    plot_pareto(points, "pareto.png")


if __name__ == "__main__":
    main(sys.argv[1:])
