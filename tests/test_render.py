"""Real headless rendering (EGL on Mesa llvmpipe without a GPU): frames are not blank, files decode, and a run keeps
a few PNG stills and a small GIF (the main job's output size, issue 30)."""

import imageio.v2 as imageio
import imageio.v3 as iio
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.render import GIF_SHRINK, STILLS, framing, render_frames, shrink, still_indices


@pytest.fixture(scope="module")
def frames(tmp_path_factory):
    scene = scenes.get("miura").build()
    q = np.stack([scene.pose("miura", x) for x in np.linspace(0.2, 0.9, 6)])
    out = tmp_path_factory.mktemp("render")
    return render_frames(scene, q, out, width=160, height=120, fps=10, stills=None), out


def test_frames_have_the_size_and_are_not_blank(frames):
    result, out = frames
    assert len(result.pngs) == result.count == 6  # stills=None: every frame
    assert sorted(p.name for p in (out / "frames").iterdir()) == [f"frame_{k:04d}.png" for k in range(6)]
    for png in result.pngs:
        image = iio.imread(png)
        assert image.shape == (120, 160, 3)
        # A uniform sky has a pixel standard deviation near 1; the panels give tens.
        assert image.std() > 5.0


def test_still_indices_are_the_start_middle_and_end():
    assert STILLS == 3 and still_indices(60) == [0, 30, 59]
    assert still_indices(2) == [0, 1] and still_indices(5, 2) == [0, 4] and still_indices(4, None) == [0, 1, 2, 3]


def test_shrink_averages_pixel_blocks():
    image = np.zeros((5, 7, 3), np.uint8)
    image[0, 0] = 200  # one bright pixel in the top-left 2 x 2 block: its average, 50
    small = shrink(image, 2)
    assert small.shape == (2, 3, 3) and small[0, 0, 0] == 50 and small.sum() == 150
    assert shrink(image, 1) is image


@pytest.fixture(scope="module")
def validated(tmp_path_factory):
    """`validate --render` as the main job runs it (default size, 60 frames): what it writes and its sizes."""
    from sim_origami.cli import main

    out = tmp_path_factory.mktemp("validate") / "miura"
    assert main(["validate", "miura", "--render", "--out", str(out)]) == 0
    return out


@pytest.mark.slow
def test_a_rendered_run_keeps_three_stills_and_a_half_size_gif(validated):
    stills = sorted(p.name for p in (validated / "frames").iterdir())
    assert stills == ["frame_0000.png", "frame_0030.png", "frame_0059.png"]  # start, middle, end of 60
    assert all(iio.imread(validated / "frames" / name).shape == (480, 640, 3) for name in stills)
    gif = iio.imread(validated / "fold.gif")
    assert gif.shape[:3] == (60, 480 // GIF_SHRINK, 640 // GIF_SHRINK)  # every frame, at half size
    reader = imageio.get_reader(validated / "fold.mp4")
    assert reader.get_meta_data()["size"] == (640, 480) and sum(1 for _ in reader) == 60  # full size, every frame
    reader.close()
    # measured (miura, 640 x 480): stills 3 x 35 kB, GIF about 200 kB (60 PNG frames were 2 MB, the GIF 0.3 MB)
    assert sum((validated / "frames" / name).stat().st_size for name in stills) < 200_000
    assert (validated / "fold.gif").stat().st_size < 400_000


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


@pytest.fixture(scope="module")
def folding_tube_gif(tmp_path_factory):
    """The same tube's motion at 640 x 480 in 5 frames: its GIF, half size on one palette."""
    scene = scenes.get("waterbomb-tube").build(n=4, m=3)
    start, stop = scene.branch_path("radial-contraction")
    q = np.stack([scene.pose("radial-contraction", x) for x in np.linspace(start, stop, 5)])
    result = render_frames(scene, q, tmp_path_factory.mktemp("tube_gif"), mp4=False)
    return iio.imread(result.gif).astype(int), [iio.imread(p).astype(int) for p in result.pngs]


def test_the_gif_keeps_the_crease_colours_and_the_frames(folding_tube_gif):
    gif, stills = folding_tube_gif
    assert gif.shape[:3] == (5, 240, 320) and len(stills) == 3
    for image in gif:
        r, g, b = image[..., 0], image[..., 1], image[..., 2]
        # halved, the lines are thinner: measured hundreds of red and tens of blue pixels per frame
        assert np.sum((r > 150) & (g < 80) & (b < 80)) > 50 and np.sum((b > 150) & (r < 80) & (g < 120)) > 3
    # the GIF's frames are the stills averaged 2 x 2, within the shared palette's error
    for k, still in zip((0, 2, 4), stills, strict=True):
        assert np.abs(gif[k, ..., :3] - shrink(still.astype(np.uint8), 2)).mean() < 6.0


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
                               image[:, -3:].reshape(-1, 3)])
        assert np.all(ring[:, 2] >= ring[:, 0])  # only the bluish sky at the border: nothing cut off


def test_render_model_has_a_front_and_a_back_surface_per_panel():
    from sim_origami.mjcf import ModelOptions
    from sim_origami.simulate import compile_model

    scene = scenes.get("vertex4").build()
    model = compile_model(scene, ModelOptions(render=True)).model
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
