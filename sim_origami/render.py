"""Headless frames of a trajectory: PNG frames, GIF and MP4.

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

from .errors import RenderError
from .files import atomic_path
from .gl import GL_PACKAGES, rendering_disabled
from .mjcf import ModelOptions
from .render_paper import add_crease_lines, crease_lines, fit_camera
from .scenes.base import Scene
from .simulate import Bindings, compile_model


@dataclass(frozen=True)
class Frames:
    """Rendered output: paths, the GL renderer string and the mean time per frame (s)."""

    pngs: tuple[Path, ...]
    gif: Path | None
    mp4: Path | None
    gl_renderer: str
    seconds_per_frame: float


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
                          f"install {GL_PACKAGES}")  # fmt: skip


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
) -> Frames:
    """
    Render mechanism angles q (n, n_joints), one frame each, into `out` (frames/, fold.gif, fold.mp4): paper
    front and back in two colours, creases as mountain (red) and valley (blue) lines (`render_paper`), one
    camera that holds every frame.
    """
    out = Path(out)
    model, data = compile_model(scene, ModelOptions(render=True))
    binds = Bindings(scene, model)
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
    for k, image in enumerate(images):
        with atomic_path(out / "frames" / f"frame_{k:04d}.png") as tmp:
            iio.imwrite(tmp, image)
        pngs.append(out / "frames" / f"frame_{k:04d}.png")
    gif_path = mp4_path = None
    if gif:
        gif_path = out / "fold.gif"
        with atomic_path(gif_path) as tmp:
            iio.imwrite(tmp, np.stack(images), duration=1000 / fps, loop=0)
    if mp4:
        mp4_path = out / "fold.mp4"
        with atomic_path(mp4_path) as tmp:
            imageio.mimwrite(tmp, images, fps=fps, codec="libx264", quality=7, macro_block_size=8)
    return Frames(tuple(pngs), gif_path, mp4_path, gl_name, per_frame)
