"""Curves: closed-form lines, simulated markers and an error panel per branch (PNG, degrees)."""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import to_rgba_array

from .files import atomic_path
from .studies.pareto import Point, front
from .validation import Report

# Simulated markers drawn per branch (the CSV keeps every sample); joints named in a legend at most.
MARKERS = 40
LEGEND_MAX = 16
# Reference samples per line where a legend names the joints. More joints are drawn from the closed form the
# projection was compared with (200 inputs over the sweep, already evaluated: each is a closed pose, and on the
# 16 x 16 Miura FOLD sheet's 480 creases 100 fresh samples took 0.26 s of CPU).
DENSE = 400


def plot_report(report: Report, path: str | Path) -> Path:
    """One column per branch: joint angles (deg) against the input (deg), then |error| (rad, log)."""
    kin = report.scene.kinematics
    runs = report.runs
    fig, axes = plt.subplots(2, len(runs), figsize=(5.5 * len(runs), 7), squeeze=False,
                             gridspec_kw={"height_ratios": [3, 2]}, constrained_layout=True)  # fmt: skip
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for col, run in enumerate(runs):
        top, bottom = axes[0, col], axes[1, col]
        sim = run.dynamic_path
        pick = np.linspace(0, len(sim.input) - 1, MARKERS).astype(int)
        if len(kin.joint_names) > LEGEND_MAX:
            ref = run.projection_path
            on = np.all(np.isfinite(ref.analytic), axis=1)
            _many_joints(top, bottom, np.rad2deg(ref.input[on]), ref.analytic[on], sim, pick, colors)
        else:
            dense = np.linspace(*kin.branch(run.requested).domain, DENSE)
            values, valid = kin.evaluate(run.requested, dense)
            for k, name in enumerate(kin.joint_names):
                c = colors[k % len(colors)]
                top.plot(np.rad2deg(dense[valid]), np.rad2deg(values[valid, k]), color=c, lw=1.2, label=name)
                top.plot(np.rad2deg(sim.input[pick]), np.rad2deg(sim.simulated[pick, k]), "o", ms=3.5,
                         mfc="none", color=c)  # fmt: skip
                bottom.semilogy(np.rad2deg(sim.input), np.maximum(sim.error[:, k], 1e-17), color=c, lw=1)
            top.legend(fontsize=8, ncol=2)
        if report.reference is not None:  # the user's curves: crosses on the curves, their error to the numeric solve
            ref = report.reference
            on = ref.on(run.requested)
            for m, name in enumerate(ref.joints):
                c = colors[kin.joint_names.index(name) % len(colors)]
                top.plot(np.rad2deg(ref.x[on]), np.rad2deg(ref.values[on, m]), "x", ms=5, color=c)
                bottom.semilogy(np.rad2deg(ref.x[on]), np.maximum(ref.error[on, m], 1e-17), "x", ms=4, color=c)
        top.set_title(f"{report.scene.name}: branch {run.requested}\n(followed {run.followed or '-'})", fontsize=10)
        top.set_xlabel(f"{kin.input_name} (deg)")
        top.set_ylabel("joint angle (deg)")
        top.grid(alpha=0.3)
        bottom.set_xlabel(f"{kin.input_name} (deg)")
        bottom.set_ylabel(f"|MuJoCo {report.preset} - closed form| (rad)")
        bottom.grid(alpha=0.3, which="both")
    crosses = "; crosses: reference curves (error: to the numeric solve)" if report.reference is not None else ""
    fig.suptitle(f"lines: closed form; markers: MuJoCo{crosses}", fontsize=9)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    return Path(path)


def _many_joints(top, bottom, x_deg, values, sim, pick, colors) -> None:
    """The same curves, markers and error lines for more joints than a legend names, one artist per kind: drawn as
    1440 separate lines the 16 x 16 Miura FOLD sheet's 480 creases took 1.5 s of CPU."""
    k = values.shape[1]
    c = [colors[j % len(colors)] for j in range(k)]
    top.add_collection(LineCollection([np.c_[x_deg, np.rad2deg(values[:, j])] for j in range(k)], colors=c,
                                      linewidths=1.2))  # fmt: skip
    edges = np.repeat(to_rgba_array(c), len(pick), axis=0)  # joint by joint, as the values below
    top.scatter(np.tile(np.rad2deg(sim.input[pick]), k), np.rad2deg(sim.simulated[pick].T).ravel(), s=12,
                facecolors="none", edgecolors=edges, linewidths=1.0)  # fmt: skip
    top.autoscale_view()
    bottom.set_yscale("log")
    error = np.maximum(sim.error, 1e-17)
    bottom.add_collection(LineCollection([np.c_[np.rad2deg(sim.input), error[:, j]] for j in range(k)], colors=c,
                                         linewidths=1.0))  # fmt: skip
    bottom.autoscale_view()


def plot_sweep(rows: list[dict], names: list[str], path: str | Path) -> Path:
    """
    A sweep's max angle error (rad, log): against the first parameter (one axis), or as a map over the first
    two (later axes folded in by their worst value). Failed points are marked with a cross.
    """
    error = np.array([r["angle_error_max_rad"] for r in rows], dtype=float)
    failed = np.array([not r["passed"] for r in rows])
    x = np.array([r[names[0]] for r in rows], dtype=float)
    fig, ax = plt.subplots(figsize=(6.5, 4.5), constrained_layout=True)
    if len(names) == 1:
        ax.semilogy(x, np.maximum(error, 1e-17), "o-", ms=3)
        ax.plot(x[failed], np.full(failed.sum(), np.nanmax(error, initial=1.0)), "rx", label="failed")
        ax.set_xlabel(names[0])
        ax.set_ylabel("max angle error (rad)")
    else:
        y = np.array([r[names[1]] for r in rows], dtype=float)
        xs, ys = np.unique(x), np.unique(y)
        grid = np.full((len(ys), len(xs)), np.nan)
        for xi, yi, e in zip(x, y, error, strict=True):
            i, j = np.searchsorted(ys, yi), np.searchsorted(xs, xi)
            if np.isfinite(e):
                grid[i, j] = e if np.isnan(grid[i, j]) else max(grid[i, j], e)
        image = ax.pcolormesh(xs, ys, np.log10(grid), shading="nearest")
        fig.colorbar(image, ax=ax, label="log10 max angle error (rad)")
        ax.plot(x[failed], y[failed], "rx", label="failed")
        ax.set_xlabel(names[0])
        ax.set_ylabel(names[1])
    if failed.any():
        ax.legend(fontsize=8)
    ax.set_title(f"{len(rows)} points, {int(failed.sum())} failed", fontsize=10)
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    return Path(path)


def plot_pareto(points: dict[str, list[Point]], path: str | Path) -> Path:
    """
    CPU time (s) against max error (rad), log-log, per scene: every setting (dots), its Pareto front (line), MuJoCo's
    defaults (open square) and the presets (filled triangles). `points`: scene name -> `pareto.Point`s, defaults
    first.
    """
    fig, ax = plt.subplots(figsize=(7, 5), constrained_layout=True)
    for name, pts in points.items():
        finite = [p for p in pts if np.isfinite(p.error)]
        line = ax.loglog([p.cpu for p in finite], [p.error for p in finite], "o", ms=3, alpha=0.5, label=name)[0]
        best = front(finite)
        ax.loglog([p.cpu for p in best], [p.error for p in best], "-", color=line.get_color())
        ax.loglog([pts[0].cpu], [pts[0].error], "s", color=line.get_color(), ms=8, mfc="none")
        presets = [p for p in pts if p.setting.label.startswith("preset ")]
        ax.loglog([p.cpu for p in presets], [p.error for p in presets], "^", color=line.get_color(), ms=6)
    ax.set_xlabel("CPU time of stepping (s)")
    ax.set_ylabel("max angle error (rad)")
    ax.set_title("settings (dots), Pareto fronts (lines), MuJoCo defaults (squares), presets (triangles)", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)
    return Path(path)
