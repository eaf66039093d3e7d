"""The free waterbomb tube (no symmetry couplings: 4n - 6 DOF) driven at one crease, against the symmetric tube.

Both start on the closed-form contraction and drive the same crease over the scene's default sweep (preset of the
scene). The symmetric tube follows the closed form; the free one is free to do something else, and this prints
how far each crease ends up from the symmetric motion, with the closure gap (it stays a closed tube).

    python scripts/waterbomb_tube_free.py [n] [m]      (default 6 3)
"""

import dataclasses
import sys

import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.simulate import simulate

BRANCH = "radial-contraction"


def main(n: int = 6, m: int = 3) -> None:
    scene = scenes.get("waterbomb-tube").build(n=n, m=m)
    free = dataclasses.replace(scene, mechanism=scene.mechanism.uncoupled())
    print(f"{n} x {m} tube, {len(scene.mechanism.couplings)} symmetry couplings in the symmetric model")
    print(f"{'model':10s} {'max dev (rad)':>14s} {'median (rad)':>13s} {'creases > 0.1':>14s} {'closure gap (m)':>16s}")
    for label, model in (("symmetric", scene), ("free", free)):
        run = simulate(model, BRANCH)
        dev = np.nanmax(np.abs(compare(model, BRANCH, run.q).error), axis=0)
        print(f"{label:10s} {np.max(dev):14.3e} {np.median(dev):13.3e} {int(np.sum(dev > 0.1)):14d} "
              f"{np.max(run.closure_residual):16.3e}")


if __name__ == "__main__":
    main(*(int(v) for v in sys.argv[1:3]))
