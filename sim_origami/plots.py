"""Curves: reference lines, simulated markers and an error panel per branch (PNG and SVG, degrees)."""

import io
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection
from matplotlib.colors import to_rgba_array
from PIL import Image

from .files import atomic_path
from .studies.pareto import Point, front
from .validation import MUJOCO_PATH_ERROR, Report

# Simulated markers drawn per branch (the CSV keeps every sample); joints named in a legend at most, and drawn as
# one error line each (more are drawn as their envelope: 250 lines were unreadable).
MARKERS = 40
LEGEND_MAX = 16
# Reference samples per line where a legend names the joints. More joints are drawn from the closed form the
# projection was compared with (200 inputs over the sweep, already evaluated: each is a closed pose, and on the
# 16 x 16 Miura FOLD sheet's 480 creases 100 fresh samples took 0.26 s of CPU).
DENSE = 400
# Kinematics whose reference is a numeric trace, not a closed form (a FOLD file's pattern, a linkage file), by
# module name: plots need not import them.
NUMERIC_TRACES = ("numeric_pattern", "linkage_path")
# Event marks on both panels: colour and line style by kind (others grey).
EVENT_STYLE = {"bifurcation": ("#7b2cbf", "--"), "lock": ("#b3131b", "-."), "blockage": ("#e08000", ":"),
               "contact": ("#e08000", ":"), "stall": ("#555555", ":")}
# Errors are drawn on a log axis; an exact zero sits at this floor.
FLOOR = 1e-17
# curves.png's colours: a palette of PNG_COLOURS (Pillow's median cut, no dithering) holds the plot's few colours and
# their anti-aliased edges within a mean 0.3 of 255 per pixel, white exactly, at a third to a quarter of the bytes of
# full colour (corrugated-unit's six branches: 741 kB -> 237 kB); report.html embeds it, so it counts twice.
PNG_COLOURS = 256


def joint_colors(k: int) -> list:
    """k colours, distinct up to 20 (tab10, then tab20), beyond that spread evenly over a perceptual map."""
    if k <= 10:
        return list(plt.get_cmap("tab10").colors[:k])
    if k <= 20:
        return list(plt.get_cmap("tab20").colors[:k])
    return list(plt.get_cmap("turbo")(np.linspace(0.05, 0.95, k)))


def _tolerance(report: Report, run) -> float | None:
    """
    The path-error tolerance the run's verdict used: its MuJoCo path error check (`validation.MUJOCO_PATH_ERROR`,
    after projection under a projected preset: the path drawn), not the one before projection.
    """
    return next((v.tolerance for v in run.verdicts if v.id == MUJOCO_PATH_ERROR), None)


def _events(report: Report, run) -> list[dict]:
    """Events on this run's branch (bifurcation, lock, contact, stall...), and the blockage stop on the first."""
    out = [e for e in run.events if run.requested in e.get("branches", [run.requested]) and e.get("input_rad")
           is not None]
    if report.blockage is not None and run is report.runs[0]:
        out.append({"kind": "blockage", "input_rad": report.blockage.stop_input})
    return out


def plot_report(report: Report, path: str | Path) -> Path:
    """
    One column per branch: joint angles (deg) against the input (deg), then |error| (rad, log) with the check's
    tolerance and the events in the sweep marked. Written as PNG at `path` and as SVG beside it.
    """
    kin = report.scene.kinematics
    runs = report.runs
    reference = "numeric trace" if type(kin).__module__.rsplit(".", 1)[-1] in NUMERIC_TRACES else "closed form"
    fig, axes = plt.subplots(2, len(runs), figsize=(5.5 * len(runs), 7.5), squeeze=False,
                             gridspec_kw={"height_ratios": [3, 2]}, constrained_layout=True)
    colors = joint_colors(len(kin.joint_names))
    for col, run in enumerate(runs):
        top, bottom = axes[0, col], axes[1, col]
        sim = run.dynamic_path
        pick = np.linspace(0, len(sim.input) - 1, MARKERS).astype(int)
        # a driven joint follows its input exactly (error 0): a flat line at the floor says nothing
        driven = [k for k in range(len(kin.joint_names)) if np.all(sim.error[:, k] == 0)]
        # MuJoCo's angles a whole turn from the reference's are drawn on it, as the error measures them (a marker at
        # -180 deg under a line at +180 deg looked like a disagreement)
        turn = np.angle(np.exp(1j * (sim.simulated - sim.analytic)))
        shown = np.where(np.isfinite(sim.analytic), sim.analytic + turn, sim.simulated)
        if len(kin.joint_names) > LEGEND_MAX:
            ref = run.projection_path
            on = np.all(np.isfinite(ref.analytic), axis=1)
            _many_joints(top, np.rad2deg(ref.input[on]), ref.analytic[on], sim, shown, pick, colors)
            kept = [k for k in range(len(kin.joint_names)) if k not in driven]
            _envelope(bottom, np.rad2deg(sim.input), sim.error[:, kept], [kin.joint_names[k] for k in kept])
        else:
            dense = np.linspace(*kin.branch(run.requested).domain, DENSE)
            values, valid = kin.evaluate(run.requested, dense)
            for k, name in enumerate(kin.joint_names):
                c = colors[k]
                top.plot(np.rad2deg(dense[valid]), np.rad2deg(values[valid, k]), color=c, lw=1.2, label=name)
                top.plot(np.rad2deg(sim.input[pick]), np.rad2deg(shown[pick, k]), "o", ms=3.5,
                         mfc="none", color=c)
                if k not in driven:
                    bottom.semilogy(np.rad2deg(sim.input), np.maximum(sim.error[:, k], FLOOR), color=c, lw=1,
                                    label=name)
            top.legend(fontsize=8, ncol=2)
        if report.reference is not None:  # the user's curves: crosses on the curves, their error to the numeric solve
            ref = report.reference
            on = ref.on(run.requested)
            for m, name in enumerate(ref.joints):
                c = colors[kin.joint_names.index(name)]
                top.plot(np.rad2deg(ref.x[on]), np.rad2deg(ref.values[on, m]), "x", ms=5, color=c)
                bottom.semilogy(np.rad2deg(ref.x[on]), np.maximum(ref.error[on, m], FLOOR), "x", ms=4, color=c)
        tol = _tolerance(report, run)
        if tol is not None and tol > 0:
            bottom.axhline(tol, color="k", ls="--", lw=1.2, label=f"tolerance {tol:.2g} rad", gid=f"tolerance-{col}")
        # both panels over the reference's span (the branch's domain, where its ends lock): the sweep in context
        lo, hi = top.get_xlim()
        bottom.set_xlim(lo, hi)
        for e in _events(report, run):
            x = np.rad2deg(e["input_rad"])
            if lo <= x <= hi:  # events farther off are listed on the page, not drawn
                color, style = EVENT_STYLE.get(e["kind"], ("#777777", ":"))
                top.axvline(x, color=color, ls=style, lw=1.2)
                bottom.axvline(x, color=color, ls=style, lw=1.2, label=f"{e['kind']} at {x:.4g} deg")
        top.set_title(f"{report.scene.name}: branch {run.requested}\n(followed {run.followed or '-'})", fontsize=10)
        top.set_xlabel(f"{kin.input_name} (deg)")
        top.set_ylabel("joint angle (deg)")
        top.grid(alpha=0.3)
        bottom.set_xlabel(f"{kin.input_name} (deg)")
        bottom.set_ylabel(f"|MuJoCo {report.preset.name} - {reference}| (rad)")
        bottom.grid(alpha=0.3, which="both")
        if driven:
            names = ", ".join(kin.joint_names[k] for k in driven[:3]) + (", ..." if len(driven) > 3 else "")
            bottom.set_title(f"driven, not drawn (error 0): {names}", fontsize=8)
        if bottom.get_legend_handles_labels()[0]:
            # on the side the sweep leaves free, not "best": its search of every error line for room took 13 s on
            # corrugated-unit's six branches
            free = "left" if np.rad2deg(np.mean(sim.input[[0, -1]])) > (lo + hi) / 2 else "right"
            bottom.legend(fontsize=7, ncol=2 if len(kin.joint_names) <= LEGEND_MAX else 1, loc=f"lower {free}")
    crosses = ";\ncrosses: reference curves (error: to the numeric solve)" if report.reference is not None else ""
    fig.suptitle(f"lines: {reference}; markers: MuJoCo{crosses}", fontsize=9)
    path = Path(path)
    save_png(fig, path)
    # text kept as text in the SVG: searchable and selectable
    with atomic_path(path.with_suffix(".svg")) as tmp, plt.rc_context({"svg.fonttype": "none"}):
        fig.savefig(tmp, format="svg")
    plt.close(fig)
    return path


def save_png(fig, path: Path, dpi: int = 110) -> None:
    """`fig` as a PNG at `path` (atomically) on a palette of PNG_COLOURS."""
    buf = io.BytesIO()
    fig.savefig(buf, dpi=dpi, format="png")
    image = Image.open(buf).convert("RGB")
    image = image.quantize(PNG_COLOURS, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    with atomic_path(path) as tmp:
        image.save(tmp, format="PNG", optimize=True)


def _many_joints(top, x_deg, values, sim, shown, pick, colors) -> None:
    """
    The same curves and markers for more joints than a legend names, one artist per kind: drawn as 1440 separate
    lines the 16 x 16 Miura FOLD sheet's 480 creases took 1.5 s of CPU. Both are pixels in the SVG (waterbomb-tube's
    250 joints: 1.8 MB and 3.5 s of vectors).
    """
    k = values.shape[1]
    top.add_collection(LineCollection([np.c_[x_deg, np.rad2deg(values[:, j])] for j in range(k)], colors=colors,
                                      linewidths=1.2, rasterized=True))
    edges = np.repeat(to_rgba_array(colors), len(pick), axis=0)  # joint by joint, as the values below
    top.scatter(np.tile(np.rad2deg(sim.input[pick]), k), np.rad2deg(shown[pick].T).ravel(), s=12,
                facecolors="none", edgecolors=edges, linewidths=1.0, rasterized=True)
    top.autoscale_view()


def _envelope(bottom, x_deg, error, names: list[str]) -> None:
    """Many joints' errors (named `names`) as their spread: the min-max band, the median and the worst joint."""
    error = np.maximum(np.where(np.isfinite(error), error, np.nan), FLOOR)
    bottom.set_yscale("log")
    if error.shape[1] == 0:
        return
    bottom.fill_between(x_deg, np.nanmin(error, axis=1), np.nanmax(error, axis=1), color="#4c72b0", alpha=0.25,
                        lw=0, label=f"min-max over {error.shape[1]} joints")
    bottom.plot(x_deg, np.nanmedian(error, axis=1), color="#4c72b0", lw=1, label="median")
    worst = int(np.nanargmax(np.nanmax(error, axis=0)))
    bottom.plot(x_deg, error[:, worst], color="#c44e52", lw=1, label=f"worst: {names[worst]}")


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
