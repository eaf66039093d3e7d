"""curves.png / curves.svg: the error panel's tolerance line, event marks, the driven input left out, many joints, and
the PNG on a palette (report.html embeds it)."""

import xml.etree.ElementTree as ET

import numpy as np
import pytest
from matplotlib.colors import to_rgb
from PIL import Image

from sim_origami import scenes
from sim_origami.plots import LEGEND_MAX, PNG_COLOURS, joint_colors, plot_report
from sim_origami.presets import FAST_PROJECTED
from sim_origami.validation import MUJOCO_PATH_ERROR, validate

SVG = "{http://www.w3.org/2000/svg}"


def svg_text(path) -> list[str]:
    """Every text of an SVG written with its fonts as text."""
    return ["".join(t.itertext()).strip() for t in ET.parse(path).getroot().iter(f"{SVG}text")]


@pytest.mark.parametrize("k", [1, 4, 10, 11, 20, 21, 120])
def test_joint_colours_stay_distinct_for_many_joints(k):
    colours = {tuple(np.round(to_rgb(c), 3)) for c in joint_colors(k)}
    assert len(colours) == k


@pytest.mark.slow
def test_error_panel_marks_tolerance_events_and_leaves_out_the_driven_input(tmp_path):
    # thick-vertex4: four joints, rho1 driven; its slabs block the fold (a blockage event), its branch locks at
    # +-180 deg (the domain's ends, drawn at the edges of both panels)
    report = validate(scenes.get("thick-vertex4").build())
    plot_report(report, tmp_path / "curves.png")
    assert (tmp_path / "curves.png").stat().st_size > 10_000
    texts = svg_text(tmp_path / "curves.svg")
    tol = next(v.tolerance for v in report.runs[0].verdicts if v.id == MUJOCO_PATH_ERROR)
    assert f"tolerance {tol:.2g} rad" in texts
    root = ET.parse(tmp_path / "curves.svg").getroot()
    assert any(g.get("id") == "tolerance-0" for g in root.iter(f"{SVG}g"))
    stop = np.rad2deg(report.blockage.stop_input)
    assert f"blockage at {stop:.4g} deg" in texts and "lock at 180 deg" in texts and "lock at -180 deg" in texts
    assert "driven, not drawn (error 0): rho1" in texts
    assert "lines: closed form; markers: MuJoCo" in texts
    # the error legend names the three joints that move freely, not the driven one
    assert {"rho2", "rho3", "rho4"} <= set(texts) and texts.count("rho1") == 1  # rho1: the top legend only


@pytest.mark.slow
def test_many_joints_error_is_an_envelope(tmp_path):
    scene = scenes.get("miura-sheet").build()
    assert len(scene.kinematics.joint_names) > LEGEND_MAX
    plot_report(validate(scene), tmp_path / "curves.png")
    texts = svg_text(tmp_path / "curves.svg")
    band = [t for t in texts if t.startswith("min-max over ")]
    assert len(band) == 1 and int(band[0].split()[2]) <= len(scene.kinematics.joint_names)
    assert "median" in texts and any(t.startswith("worst: ") for t in texts)
    assert (tmp_path / "curves.svg").stat().st_size < 400_000  # the many curves are pixels inside the SVG


@pytest.mark.slow
def test_a_projected_preset_draws_the_tolerance_of_the_path_it_plots(tmp_path):
    # fast-projected checks the path after projection (drawn) and MuJoCo's own steps before it (not drawn)
    report = validate(scenes.get("bennett").build(), preset=FAST_PROJECTED)
    plot_report(report, tmp_path / "curves.png")
    drawn = next(v for v in report.runs[0].verdicts if v.id == MUJOCO_PATH_ERROR)  # after projection
    texts = svg_text(tmp_path / "curves.svg")
    assert f"tolerance {drawn.tolerance:.2g} rad" in texts and sum(t.startswith("tolerance ") for t in texts) == 1


@pytest.mark.slow
def test_curves_png_is_a_palette_image_that_keeps_the_plot_colours(tmp_path):
    report = validate(scenes.get("bennett").build())
    plot_report(report, tmp_path / "curves.png")
    png = Image.open(tmp_path / "curves.png")
    assert png.mode == "P" and len(png.getcolors()) <= PNG_COLOURS
    rgb = np.asarray(png.convert("RGB")).reshape(-1, 3)
    colours = {tuple(c) for c in np.unique(rgb, axis=0)}
    assert tuple(rgb[0]) == (255, 255, 255)  # the background stays white
    # each joint's line colour (tab10), drawn in full, is in the palette exactly
    assert {tuple(round(255 * v) for v in to_rgb(c)) for c in joint_colors(4)} <= colours
    # measured: 25-30 kB (88 kB in full colour)
    assert 10_000 < (tmp_path / "curves.png").stat().st_size < 50_000
