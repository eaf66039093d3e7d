"""The kind of parameter map of Feng, Ma and Chen 2020, Fig. 8, for the waterbomb tube: over (alpha, beta), the largest
contraction angle theta_max of the rigid radial motion, and where the tube cannot contract rigidly at all;
computed from the closed form (`kinematics.waterbomb_tube.motion_range`) in parallel over the machine's cores.

    python scripts/waterbomb_tube_map.py [n] [m] [step_deg]      (default 6 5 1; writes tube_map.png/.csv)
"""

import os
import sys
from concurrent.futures import ProcessPoolExecutor

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from sim_origami.files import atomic_path, write_text
from sim_origami.kinematics.waterbomb_tube import motion_range, tube_layout


def theta_range(args: tuple[int, int, float, float]) -> tuple[float, float]:
    """(theta_min, theta_max) in degrees, NaN where the tube cannot contract rigidly."""
    n, m, alpha, beta = args
    found = motion_range(tube_layout(n, m, np.deg2rad(alpha), np.deg2rad(beta), 1.0))
    return (float("nan"), float("nan")) if found is None else tuple(np.rad2deg(found))


def main(n: int = 6, m: int = 5, step: float = 1.0) -> None:
    alphas = np.arange(20.0, 60.0 + 1e-9, step)
    betas = np.arange(20.0, 60.0 + 1e-9, step)
    tasks = [(n, m, a, b) for b in betas for a in alphas]
    with ProcessPoolExecutor(max_workers=os.cpu_count()) as pool:
        ranges = np.array(list(pool.map(theta_range, tasks, chunksize=16)))
    theta_max = ranges[:, 1].reshape(len(betas), len(alphas))
    rows = ["alpha_deg,beta_deg,theta_min_deg,theta_max_deg"]
    rows += [f"{a:g},{b:g},{lo:.6f},{hi:.6f}" for (_, _, a, b), (lo, hi) in zip(tasks, ranges, strict=True)]
    write_text("tube_map.csv", "\n".join(rows) + "\n")
    fig, ax = plt.subplots(figsize=(6.5, 5), constrained_layout=True)
    image = ax.pcolormesh(alphas, betas, theta_max, shading="nearest", cmap="viridis")
    fig.colorbar(image, ax=ax, label="theta_max of the rigid contraction (deg)")
    blocked = np.isnan(theta_max)
    A, B = np.meshgrid(alphas, betas)
    ax.plot(A[blocked], B[blocked], "x", color="0.5", ms=3, label="cannot contract rigidly")
    ax.set_xlabel("alpha (deg)")
    ax.set_ylabel("beta (deg)")
    ax.set_title(f"waterbomb tube n = {n}, m = {m}: {int((~blocked).sum())} of {blocked.size} points contract")
    ax.legend(fontsize=8, loc="upper right")
    with atomic_path("tube_map.png") as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    print(f"{blocked.size} points, {int(blocked.sum())} cannot contract rigidly; tube_map.png, tube_map.csv")


if __name__ == "__main__":
    main(*(int(v) if k < 2 else float(v) for k, v in enumerate(sys.argv[1:4])))
