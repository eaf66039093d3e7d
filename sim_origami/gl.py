"""Headless OpenGL backend choice, made before MuJoCo is imported (MUJOCO_GL is read at import).

EGL is the default: Mesa's llvmpipe renders through it on machines without a GPU. OSMesa is the
fallback where no EGL library loads but libOSMesa does. With neither, MuJoCo's rendering is disabled
('disable'), so every command that does not render still runs, and `--render` is refused in one line
naming the packages to install (`require_rendering`). A user's MUJOCO_GL is never overridden.
"""

import ctypes
import ctypes.util
import os

# What a machine without a GL library needs, in Debian's package names (docs/install.md).
GL_PACKAGES = "Debian's libegl1 libgl1-mesa-dri (EGL), or libosmesa6 (OSMesa)"
DISABLED = ("disable", "disabled", "off", "false", "0")


def _loads(name: str) -> bool:
    """Whether the shared library `name` is found and loads: the linker cache may list a file that does not."""
    path = ctypes.util.find_library(name)
    if path is None:
        return False
    try:
        ctypes.CDLL(path)
    except OSError:
        return False
    return True


def choose_backend() -> str:
    """Set MUJOCO_GL to 'egl', else 'osmesa', else 'disable' (whichever library loads first) unless already set."""
    if "MUJOCO_GL" not in os.environ:
        os.environ["MUJOCO_GL"] = "egl" if _loads("EGL") else "osmesa" if _loads("OSMesa") else "disable"
    return os.environ["MUJOCO_GL"]


def rendering_disabled() -> bool:
    """Whether MuJoCo's rendering is off (no GL library loaded, or the user's MUJOCO_GL says so)."""
    return choose_backend().lower().strip() in DISABLED
