"""Headless frames of a trajectory: PNG stills, GIF and MP4.

The backend is chosen in `sim_origami.gl` before MuJoCo loads (EGL, Mesa llvmpipe without a GPU;
OSMesa as fallback) and the GL renderer in use is reported. Frames are rendered in a separate
pass from recorded joint angles, with a model that alone carries lights and the sky texture, and
with shadows and multisampling off (measured here: 5-20x faster on llvmpipe).
"""

import os
import time
from dataclasses import dataclass
from pathlib import Path

import imageio.v2 as imageio
import imageio.v3 as iio
import mujoco
import numpy as np
from PIL import Image

from .errors import RenderError
from .files import atomic_path
from .gl import GL_PACKAGES, rendering_disabled
from .mjcf import ModelOptions
from .render_paper import add_crease_lines, crease_lines, fit_camera
from .scenes.base import Scene
from .simulate import Bindings, compile_model

# Frames written as PNG stills: this many, evenly spaced from the first to the last (start, middle, end), each named
# by its index in the animation (frames/frame_0030.png is the GIF's and MP4's frame 30). The GIF and MP4 carry the
# motion: all 60 frames of `validate --render` as PNG were 49.5 MB of the main job's 160 MB, three are 2.15 MB.
# `render_frames(..., stills=None)` writes every frame.
STILLS = 3
# fold.gif's frames are averaged GIF_SHRINK x GIF_SHRINK pixels (320 x 240 from 640 x 480; the MP4 keeps the full
# size) unless that would leave them under GIF_MIN_WIDTH pixels wide, and share one palette of GIF_COLOURS (Pillow's
# fast octree over every frame, no dithering: a pixel as unchanged as the motion leaves it, so each frame stores
# only the box that moved). Waterbomb-twist's GIF, every frame kept: 1.39 MB at full size with a palette per frame,
# 0.59 MB at half size, 0.44 MB with the shared palette (mean pixel error 2.4 of 255, 15 in the worst 0.1 %).
GIF_SHRINK = 2
GIF_MIN_WIDTH = 160
GIF_COLOURS = 256


@dataclass(frozen=True)
class Frames:
    """
    Rendered output: the PNG stills written (`STILLS`), GIF and MP4 paths, the GL renderer string, the mean time per
    frame (s) and how many frames were rendered (each one is in the GIF and the MP4).
    """

    pngs: tuple[Path, ...]
    gif: Path | None
    mp4: Path | None
    gl_renderer: str
    seconds_per_frame: float
    count: int


def still_indices(n: int, stills: int | None = STILLS) -> list[int]:
    """Which of n frames are written as PNG: `stills` evenly spaced from the first to the last, all where None."""
    if stills is None or n <= stills:
        return list(range(n))
    return sorted({int(k) for k in np.linspace(0, n - 1, stills).round()})


def write_gif(path: Path, images: list[np.ndarray], fps: float) -> None:
    """`images` (h, w, 3) uint8 as a looping GIF at `fps`, on one palette (GIF_COLOURS) made from all of them."""
    both = Image.fromarray(np.concatenate(images, axis=0))
    palette = both.quantize(colors=GIF_COLOURS, method=Image.Quantize.FASTOCTREE)
    frames = [Image.fromarray(image).quantize(palette=palette, dither=Image.Dither.NONE) for image in images]
    with atomic_path(path) as tmp:
        frames[0].save(tmp, format="GIF", save_all=True, append_images=frames[1:], duration=round(1000 / fps),
                       loop=0, optimize=True)


def shrink(image: np.ndarray, k: int) -> np.ndarray:
    """An (h, w, 3) uint8 image averaged over k x k pixel blocks (the last rows and columns that fill no block cut)."""
    if k <= 1:
        return image
    h, w = image.shape[0] // k * k, image.shape[1] // k * k
    blocks = image[:h, :w, :3].reshape(h // k, k, w // k, k, 3).astype(np.float32)
    return blocks.mean(axis=(1, 3)).round().astype(np.uint8)


def framing(scene: Scene, q: np.ndarray) -> tuple[np.ndarray, float]:
    """Centre (3,) and radius (m) of a sphere holding every panel over the poses q (n, n_joints)."""
    poses = scene.mechanism.body_poses(q)
    points = []
    for body in scene.mechanism.bodies:
        v = np.c_[body.solid.vertices, np.ones(len(body.solid.vertices))]
        points.append((poses[body.name] @ v.T)[..., :3, :].transpose(0, 2, 1).reshape(-1, 3))
    points = np.concatenate(points)
    lo, hi = points.min(axis=0), points.max(axis=0)
    return (lo + hi) / 2, float(np.linalg.norm(hi - lo) / 2)


def require_rendering() -> None:
    """RenderError naming the packages to install when no GL library loaded (`gl.choose_backend`)."""
    if rendering_disabled():
        raise RenderError(f"rendering needs an OpenGL library and none loads (MUJOCO_GL={os.environ['MUJOCO_GL']}); "
                          f"install {GL_PACKAGES}")


def render_frames(
    scene: Scene,
    q: np.ndarray,
    out: str | Path,
    *,
    width: int = 640,
    height: int = 480,
    fps: int = 20,
    gif: bool = True,
    mp4: bool = True,
    stills: int | None = STILLS,
) -> Frames:
    """
    Render mechanism angles q (n, n_joints), one frame each, into `out`: `stills` of them as PNG in frames/
    (`still_indices`; every one where None), all of them into fold.gif (at 1 / GIF_SHRINK the size) and fold.mp4
    (full size). Paper front and back in two colours, creases as mountain (red) and valley (blue) lines
    (`render_paper`), one camera that holds every frame.
    """
    out = Path(out)
    compiled = compile_model(scene, ModelOptions(render=True))
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    model.vis.global_.offwidth = max(model.vis.global_.offwidth, width)  # the offscreen buffer holds the frame
    model.vis.global_.offheight = max(model.vis.global_.offheight, height)
    _, radius = framing(scene, q)
    camera = fit_camera(scene, q, model.vis.global_.fovy, width / height)
    lines = crease_lines(scene, 0.006 * radius)
    poses = scene.mechanism.body_poses(q) if len(lines.joints) else None
    images = []
    require_rendering()
    try:
        renderer = mujoco.Renderer(model, height=height, width=width, max_geom=model.ngeom + len(lines.joints) + 100)
    except Exception as exc:  # the GL stack reports many exception types
        raise RenderError(f"no headless OpenGL context ({exc}); install {GL_PACKAGES}") from exc
    with renderer:
        from OpenGL import GL

        gl_name = GL.glGetString(GL.GL_RENDERER)
        gl_name = gl_name.decode() if gl_name else "unknown"
        t0 = time.perf_counter()
        for k, row in enumerate(q):
            binds.set_pose(data, row)
            mujoco.mj_forward(model, data)
            renderer.update_scene(data, camera=camera)
            if poses is not None:
                add_crease_lines(renderer.scene, lines, {name: T[k] for name, T in poses.items()}, row)
            images.append(renderer.render().copy())
        per_frame = (time.perf_counter() - t0) / max(len(q), 1)
    pngs = []
    for k in still_indices(len(images), stills):
        with atomic_path(out / "frames" / f"frame_{k:04d}.png") as tmp:
            iio.imwrite(tmp, images[k])
        pngs.append(out / "frames" / f"frame_{k:04d}.png")
    gif_path = mp4_path = None
    if gif:
        gif_path = out / "fold.gif"
        k = GIF_SHRINK if width // GIF_SHRINK >= GIF_MIN_WIDTH else 1
        write_gif(gif_path, [shrink(image, k) for image in images], fps)
    if mp4:
        mp4_path = out / "fold.mp4"
        with atomic_path(mp4_path) as tmp:
            imageio.mimwrite(tmp, images, fps=fps, codec="libx264", quality=7, macro_block_size=8)
    return Frames(tuple(pngs), gif_path, mp4_path, gl_name, per_frame, len(images))
