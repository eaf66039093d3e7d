"""Speed and error of a large Miura-ori sheet folding from 5% to 90% of its range, contact off and on.

Preset fast (RK4, 8 ms, closure regulariser scaled by 0.01), the sheet's closed form as the reference; CPU time
of the stepping thread. Prints one row per setting; the largest contact count tells whether panels met.

Measured (16 x 16, 256 panels, 480 creases, 225 closed by connects; breadth-first tree of depth 16, drive
mid-sheet; 2-core machine shared with other jobs): 2 s sweep 3.0e-6 rad, 1.0 s CPU (contact on 1.8 s); 4 s
sweep 7.3e-7 rad, 2.0 s CPU (contact on 3.7 s), no panels touching. Before (Kruskal tree of depth 27-31,
MuJoCo's regulariser, drive near a corner): 1.2e-3 rad in 2.7 s.

    python scripts/miura_sheet_bench.py [rows cols]
"""

import sys

import mujoco
import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.mjcf import ModelOptions
from sim_origami.simulate import Bindings, compile_model, simulate


def most_contacts(scene, q: np.ndarray, samples: int = 50) -> int:
    """Largest number of contacts MuJoCo detects at `samples` poses of a run (contact enabled)."""
    compiled = compile_model(scene, ModelOptions(contact=True))
    model, data = compiled.fresh()
    binds, most = Bindings(compiled), 0
    for row in q[np.linspace(0, len(q) - 1, samples).astype(int)]:
        binds.set_pose(data, row)
        mujoco.mj_fwdPosition(model, data)
        most = max(most, data.ncon)
    return most


def main(rows: int = 16, cols: int = 16) -> None:
    scene = scenes.get("miura-sheet").build(rows=rows, cols=cols)
    mech = scene.mechanism
    print(f"{rows} x {cols} Miura sheet: {len(mech.bodies)} panels, {len(mech.joints)} creases, "
          f"{len(mech.cut_joints)} closed by connects")
    print(
        f"{'contact':8s} {'sweep (s)':>9s} {'steps':>6s} {'CPU (s)':>8s} {'max error (rad)':>16s} {'max contacts':>13s}"
    )
    for duration in (2.0, 4.0):
        for contact in (False, True):
            run = simulate(scene, "miura", contact=contact, duration=duration)
            error = compare(scene, "miura", run.q).max_error()
            touching = most_contacts(scene, run.q) if contact else 0
            print(f"{contact!s:8s} {duration:9.1f} {run.steps:6d} {run.cpu_time_s:8.2f} {error:16.2e} {touching:13d}")


if __name__ == "__main__":
    main(*(int(v) for v in sys.argv[1:3]))
