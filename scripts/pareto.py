"""Run time against error over MuJoCo settings, in one run, and the Pareto front; the presets next to MuJoCo's
defaults (Euler, 2 ms, solref 0.02 1, solimp 0.9 0.95 0.001) and to the bare stepping loop.

For each scene (its first branch, its default sweep, the same 2 s ramp for every setting): integrators
RK4 / Euler / implicitfast, steps 0.625-5 ms, closure time constants 2h-8h, solimp 0.9999 or MuJoCo's default.
Error = max |MuJoCo - closed form| over the path; CPU = stepping thread. Writes pareto.csv and pareto.png.

    python scripts/pareto.py [scene ...]          (default: vertex4 waterbomb-vertex miura-sheet)
"""

import itertools
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import mujoco
import numpy as np

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.files import atomic_path, write_text
from sim_origami.mjcf import ModelOptions, build_xml
from sim_origami.simulate import Bindings, ramp, start_pose

INTEGRATORS = {"RK4": mujoco.mjtIntegrator.mjINT_RK4, "Euler": mujoco.mjtIntegrator.mjINT_EULER,
               "implicitfast": mujoco.mjtIntegrator.mjINT_IMPLICITFAST}  # fmt: skip
STEPS_MS = (0.625, 1.25, 2.5, 5.0, 6.5, 8.0)
TAU_OVER_H = (2, 4, 8)
HIGH_IMPEDANCE = (0.9999, 0.9999, 0.001, 0.5, 2.0)
MUJOCO_DEFAULT_IMPEDANCE = (0.9, 0.95, 0.001, 0.5, 2.0)
REPEATS = 3  # CPU time: best of


def run(scene, branch: str, model: mujoco.MjModel, duration: float) -> tuple[float, float]:
    """(max error rad, CPU s) of the harness's drive on `model` over the scene's default sweep."""
    data = mujoco.MjData(model)
    binds = Bindings(scene, model)
    start, stop = scene.branch_path(branch)
    binds.set_pose(data, start_pose(scene, branch, start))
    mujoco.mj_forward(model, data)
    eq = model.equality(f"drive_{scene.drive_joint}").id
    h = model.opt.timestep
    n = round(duration / h)
    phase = np.clip(h * np.arange(1, n + 1) / duration, 0, 1)
    shape, rate = ramp(phase)
    x = start + (stop - start) * shape
    tau = max(model.eq_solref[eq, 0], 2 * h)
    target = scene.drive_scale * (x + 2 * tau * model.eq_solref[eq, 1] * (stop - start) * rate / duration)
    qpos = np.empty((n, model.nq))
    setpoint, step = model.eq_data[eq], mujoco.mj_step
    cpu = time.thread_time()
    for value, row in zip(target.tolist(), qpos, strict=True):
        setpoint[0] = value
        step(model, data)
        row[:] = data.qpos
    cpu = time.thread_time() - cpu
    if not np.all(np.isfinite(qpos)):
        return float("inf"), cpu
    return compare(scene, branch, binds.angles(scene, qpos)).max_error(), cpu


def settings():
    """(label, integrator, h s, tau s, solimp) of every candidate, MuJoCo's defaults first."""
    yield "MuJoCo default", "Euler", 0.002, 0.02, MUJOCO_DEFAULT_IMPEDANCE
    for name, h_ms, k in itertools.product(INTEGRATORS, STEPS_MS, TAU_OVER_H):
        h = h_ms / 1000
        yield f"{name} h={h_ms:g}ms tau={k}h", name, h, k * h, HIGH_IMPEDANCE


def main(names: list[str]) -> None:
    rows, fig = [], plt.figure(figsize=(7, 5))
    ax = fig.add_subplot()
    for name in names or ["vertex4", "waterbomb-vertex", "miura-sheet"]:
        scene = scenes.get(name).build()
        branch = scene.kinematics.branches()[0].name
        duration = 2.0  # every setting on the same 2 s sweep
        points = []
        for label, integrator, h, tau, solimp in settings():
            model = mujoco.MjModel.from_xml_string(build_xml(scene, ModelOptions(preset="fast")))
            model.opt.integrator, model.opt.timestep = INTEGRATORS[integrator], h
            model.eq_solref[:, 0], model.eq_solimp[:] = tau, solimp
            results = [run(scene, branch, model, duration) for _ in range(REPEATS)]
            error, cpu = results[0][0], min(r[1] for r in results)  # deterministic error, best-of CPU
            points.append((label, error, cpu))
            rows.append(f"{name},{label},{error:.6g},{cpu:.6g}")
        default = points[0]
        front = [p for p in points if not any(q[1] <= p[1] and q[2] <= p[2] and q != p for q in points)]
        line = ax.loglog([p[2] for p in points], [p[1] for p in points], "o", ms=3, alpha=0.5, label=name)[0]
        ax.loglog([p[2] for p in sorted(front, key=lambda p: p[2])], [p[1] for p in sorted(front, key=lambda p: p[2])],
                  "-", color=line.get_color())  # fmt: skip
        ax.loglog([default[2]], [default[1]], "s", color=line.get_color(), ms=7, mfc="none")
        print(f"\n{name} ({branch}, {duration:g} s sweep): MuJoCo defaults {default[1]:.2e} rad in {default[2]:.3f} s")
        print(f"{'Pareto front':32s} {'error (rad)':>12s} {'CPU (s)':>9s} {'vs defaults':>22s}")
        for label, error, cpu in sorted(front, key=lambda p: p[2]):
            gain, cost = default[1] / error, cpu / default[2]
            print(f"{label:32s} {error:12.2e} {cpu:9.3f}   {gain:8.3g}x accurate, {cost:5.2f}x CPU")
    ax.set_xlabel("CPU time of stepping (s)")
    ax.set_ylabel("max angle error (rad)")
    ax.set_title("settings (dots), Pareto fronts (lines), MuJoCo defaults (squares)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    write_text("pareto.csv", "scene,setting,error_rad,cpu_s\n" + "\n".join(rows) + "\n")
    with atomic_path("pareto.png") as tmp:
        fig.savefig(tmp, dpi=110, format="png")


if __name__ == "__main__":
    main(sys.argv[1:])
