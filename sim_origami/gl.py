"""Headless OpenGL backend choice, made before MuJoCo is imported (MUJOCO_GL is read at import).

EGL is the default: Mesa's llvmpipe renders through it on machines without a GPU. OSMesa is the
fallback where no EGL library exists but libOSMesa does. A user's MUJOCO_GL is never overridden.
"""

import ctypes.util
import os


def choose_backend() -> str:
    """Set MUJOCO_GL to 'egl' (or 'osmesa' when only OSMesa is installed) unless already set."""
    if "MUJOCO_GL" not in os.environ:
        has_egl = ctypes.util.find_library("EGL") is not None
        has_osmesa = ctypes.util.find_library("OSMesa") is not None
        os.environ["MUJOCO_GL"] = "osmesa" if (not has_egl and has_osmesa) else "egl"
    return os.environ["MUJOCO_GL"]
