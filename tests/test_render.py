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
