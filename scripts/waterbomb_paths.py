"""Feng 2018, ch. 5, by simulation: the thick waterbomb cell is kinematically the zero-thickness path I, and
it follows that one path where the zero-thickness cell has four.

For each branch of the zero-thickness cell (scene waterbomb-vertex): MuJoCo seeded on it follows it (fast
preset, error against its closed form). Then the thick cell (scene waterbomb-thick), started at that
branch's pose near flat (x = START), is driven to STOP: the branch it ends on, classified against the
zero-thickness closed forms, and its error against path I.

    python scripts/waterbomb_paths.py [alpha_deg beta_deg mu]
"""

import sys

import numpy as np

from sim_origami import scenes
from sim_origami.checks.branches import classify
from sim_origami.checks.paths import compare
from sim_origami.kinematics.waterbomb import LINE
from sim_origami.simulate import simulate

START, STOP = -0.05, -1.0  # rad of rho_A4


def main(alpha_deg: float = 40.0, beta_deg: float = 40.0, mu: float = 0.5) -> None:
    angles = {"alpha": np.deg2rad(alpha_deg), "beta": np.deg2rad(beta_deg)}
    zero = scenes.get("waterbomb-vertex").build(**angles)
    thick = scenes.get("waterbomb-thick").build(**angles, mu=mu)
    drive = thick.mechanism.joint_index(thick.drive_joint)
    loops = thick.kinematics.loop_system()
    print(f"alpha {alpha_deg:g} deg, beta {beta_deg:g} deg, mu {mu:g}; thick branches: "
          f"{', '.join(b.name for b in thick.kinematics.branches())}")
    print(f"{'zero-thickness branch':22s} {'zero: MuJoCo error':>19s} {'thick loops at pose':>20s} "
          f"{'thick from pose ->':>20s} {'error vs path I':>16s}")
    for branch in zero.kinematics.branches():
        own = compare(zero, branch.name, simulate(zero, branch.name).q).max_error()
        pose = zero.pose(branch.name, START)
        gap = loops.residual_norm(thick.mechanism_to_loop(pose))[0]
        run = simulate(thick, LINE, initial=pose, stop=STOP)
        took = classify(zero.kinematics, run.q[:, drive], thick.outputs(run.q)).followed
        late = compare(thick, LINE, run.q).error[len(run.q) // 2 :]
        print(f"{branch.name:22s} {own:19.2e} {gap:20.2e} {took:>20s} {np.max(np.abs(late)):16.2e}")


if __name__ == "__main__":
    main(*(float(v) for v in sys.argv[1:4]))
