"""Real headless rendering (EGL on Mesa llvmpipe without a GPU): frames are not blank, files decode."""

import imageio.v2 as imageio
import imageio.v3 as iio
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.render import framing, render_frames


@pytest.fixture(scope="module")
def frames(tmp_path_factory):
    scene = scenes.get("miura").build()
    q = np.stack([scene.pose("miura", x) for x in np.linspace(0.2, 0.9, 6)])
    out = tmp_path_factory.mktemp("render")
    return render_frames(scene, q, out, width=160, height=120, fps=10), out


def test_frames_have_the_size_and_are_not_blank(frames):
    result, _ = frames
    assert len(result.pngs) == 6
    for png in result.pngs:
        image = iio.imread(png)
        assert image.shape == (120, 160, 3)
        # A uniform sky has a pixel standard deviation near 1; the panels give tens.
        assert image.std() > 5.0


def test_consecutive_frames_differ_as_the_vertex_folds(frames):
    result, _ = frames
    first, last = (iio.imread(p).astype(float) for p in (result.pngs[0], result.pngs[-1]))
    assert np.abs(first - last).mean() > 1.0


def test_gif_and_mp4_decode_to_the_frames(frames):
    result, _ = frames
    assert iio.imread(result.gif).shape[0] == 6
    reader = imageio.get_reader(result.mp4)  # ffmpeg
    count = sum(1 for _ in reader)
    reader.close()
    assert count == 6


def test_gl_renderer_is_reported(frames):
    result, _ = frames
    assert result.gl_renderer and result.gl_renderer != "unknown"


def test_framing_holds_every_panel():
    scene = scenes.get("vertex4").build()
    center, radius = framing(scene, np.zeros((1, 4)))
    # flat sheet of 1 m creases: centred near the vertex, about 1 m in radius
    assert np.linalg.norm(center[:2]) < 0.5
    assert 0.8 < radius < 1.6


@pytest.fixture(scope="module")
def folding_tube(tmp_path_factory):
    """A 4 x 3 waterbomb tube over its radial contraction, 320 x 240: many mountains and valleys at once."""
    scene = scenes.get("waterbomb-tube").build(n=4, m=3)
    start, stop = scene.branch_path("radial-contraction")
    q = np.stack([scene.pose("radial-contraction", x) for x in np.linspace(start, stop, 3)])
    out = tmp_path_factory.mktemp("tube")
    result = render_frames(scene, q, out, width=320, height=240, gif=False, mp4=False)
    return [iio.imread(p).astype(int) for p in result.pngs]


def test_mountain_and_valley_creases_are_drawn_red_and_blue(folding_tube):
    for image in folding_tube:
        r, g, b = image[..., 0], image[..., 1], image[..., 2]
        red = np.sum((r > 150) & (g < 80) & (b < 80))
        blue = np.sum((b > 150) & (r < 80) & (g < 120))
        # measured: thousands of red (mountain) and tens to hundreds of blue (valley) pixels per frame
        assert red > 200 and blue > 10


def test_paper_front_is_coloured_and_the_camera_holds_every_frame(folding_tube):
    for image in folding_tube:
        r, b = image[..., 0], image[..., 2]
        assert np.sum(r > b + 60) > 0.05 * r.size  # the yellow front of the paper fills a good part of the view
        ring = np.concatenate([image[:3].reshape(-1, 3), image[-3:].reshape(-1, 3), image[:, :3].reshape(-1, 3),
                               image[:, -3:].reshape(-1, 3)])  # fmt: skip
        assert np.all(ring[:, 2] >= ring[:, 0])  # only the bluish sky at the border: nothing cut off


def test_render_model_has_a_front_and_a_back_surface_per_panel():
    from sim_origami.mjcf import ModelOptions
    from sim_origami.simulate import compile_model

    scene = scenes.get("vertex4").build()
    model, _ = compile_model(scene, ModelOptions(render=True))
    for body in scene.mechanism.bodies:
        front, back = model.geom(f"{body.name}_front"), model.geom(f"{body.name}_back")
        assert front.rgba[0] - front.rgba[2] > 0.5 and abs(back.rgba[0] - back.rgba[2]) < 0.05  # yellow, white
        assert model.geom(f"{body.name}_solid").group[0] == 3  # the massive solid is hidden behind them
        assert front.contype[0] == back.contype[0] == 0 and model.geom_bodyid[front.id] == model.geom_bodyid[back.id]


@pytest.mark.parametrize("size", ["10x10", "640", "wide"])
def test_validate_refuses_a_bad_frame_size_before_any_work(size, capsys):
    from sim_origami.cli import main

    assert main(["validate", "bennett", "--render", "--size", size]) == 2
    err = capsys.readouterr().err
    assert f"--size {size!r}" in err and err.count("\n") == 1
