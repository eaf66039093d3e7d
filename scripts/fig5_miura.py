"""Reproduce Fig. 5 of Kamrava et al. 2021: phi(theta) and psi(theta) of the asymmetric Miura
vertex (30, 60 deg), three ways and at many more points than the paper's 11 CAD samples.

Closed form (corrected eqns 38-39), the numeric loop closure followed by continuation, and MuJoCo
(fast preset dynamics and kinematic projection), on both sides of the flat state. Writes
fig5.png and fig5.csv into --out and prints the largest disagreements (radians).

    python scripts/fig5_miura.py --out runs/fig5
"""

import argparse
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.files import atomic_path
from sim_origami.simulate import project, simulate


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("runs/fig5"))
    parser.add_argument("--points", type=int, default=201, help="samples per side for solver and projection")
    args = parser.parse_args()

    scene = scenes.get("miura").build_from_user({"alpha1": 30, "alpha2": 60})
    kin = scene.kinematics
    lim = kin.theta_limit
    loops, (joint, scale) = kin.loop_system(), kin.loop_input()
    rows, worst = [], {"numeric": 0.0, "dynamic": 0.0, "projection": 0.0}
    fig, ax = plt.subplots(figsize=(7, 4.5), constrained_layout=True)
    dense = np.linspace(-lim, lim, 801)
    values = kin.joint_angles("miura", dense)
    for k, name in enumerate(("phi", "psi")):
        ax.plot(np.rad2deg(dense), np.rad2deg(values[:, k]), lw=1.5, label=f"{name}, closed form")
    for side in (1, -1):
        x = side * np.linspace(0.25 * lim, 0.95 * lim, args.points)
        exact = kin.joint_angles("miura", x)
        numeric = kin.observe(loops.follow(kin.loop_angles(exact[:1])[0], joint, scale * x))
        worst["numeric"] = max(worst["numeric"], float(np.max(np.abs(numeric - exact))))
        dyn = compare(scene, "miura", simulate(scene, "miura", start=x[0], stop=x[-1]).q)
        worst["dynamic"] = max(worst["dynamic"], dyn.max_error())
        proj = compare(scene, "miura", project(scene, "miura", x).q)
        worst["projection"] = max(worst["projection"], proj.max_error())
        pick = np.linspace(0, len(dyn.input) - 1, 25).astype(int)
        for k, marker in ((0, "o"), (1, "s")):
            ax.plot(np.rad2deg(dyn.input[pick]), np.rad2deg(dyn.simulated[pick, k]), marker, mfc="none", ms=4,
                    color=f"C{k}", label=f"{('phi', 'psi')[k]}, MuJoCo" if side == 1 else None)
        for i in range(len(x)):
            rows.append([x[i], *exact[i, :2], *numeric[i, :2], *proj.simulated[i, :2]])
    ax.axvline(np.rad2deg(lim), color="0.5", ls=":", lw=1)
    ax.axvline(-np.rad2deg(lim), color="0.5", ls=":", lw=1)
    ax.set_xlabel("theta (deg)")
    ax.set_ylabel("angle (deg)")
    ax.set_title("Asymmetric Miura vertex 30/60 deg (Kamrava et al. 2021, Fig. 5); dotted: theta_limit")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    with atomic_path(args.out / "fig5.png") as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    with atomic_path(args.out / "fig5.csv") as tmp, open(tmp, "w", newline="") as fh:
        writer = csv.writer(fh)
        writer.writerow(["theta_rad", "phi_rad", "psi_rad", "phi_numeric_rad", "psi_numeric_rad",
                         "phi_projection_rad", "psi_projection_rad"])
        writer.writerows(rows)
    print(f"theta_limit = {np.rad2deg(lim):.4f} deg; {2 * args.points} samples per method")
    for method, err in worst.items():
        print(f"max |{method} - closed form| over phi, psi and folds: {err:.2e} rad")
    print(f"wrote {args.out / 'fig5.png'} and {args.out / 'fig5.csv'}")


if __name__ == "__main__":
    main()
