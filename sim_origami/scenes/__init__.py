"""Scene registry. The built-in scene modules listed in BUILTIN register themselves the first time the registry is
asked for a scene or the names (`get`, `names`, `load_plugins`), or one of them is used as an attribute of this
package: `validate --fold` needs none of them (about 0.2 s of imports). Scenes of installed packages (entry point group
`sim_origami.scenes`, see `plugins`) join at the same time, after them."""

import importlib
from types import ModuleType

from .base import REGISTRY, Param, Scene, SceneType, Tuning, register
from .base import get as _get
from .base import names as _names
from .custom import custom_scene
from .plugins import load_plugins

# Built-in scene modules, imported on first use of the registry.
BUILTIN = (
    "bennett",
    "bricard_plane",
    "bricard_threefold",
    "corrugated",
    "corrugated_sheet",
    "cuboctahedron",
    "iftomm_a04",
    "kokotsakis",
    "miura",
    "miura_sheet",
    "myard",
    "rssr",
    "square_twist",
    "thick_diamond",
    "thick_square_twist",
    "thick_vertex4",
    "thick_vertex5",
    "triangle_twist",
    "truncated_octahedron",
    "truncated_tetrahedron",
    "twist_6r",
    "vertex4",
    "waterbomb",
    "waterbomb_tube",
    "waterbomb_twist",
)


def load_builtins() -> None:
    """Register the built-in scenes (importing each module once registers its scenes)."""
    for name in BUILTIN:
        importlib.import_module(f"{__name__}.{name}")


def __getattr__(name: str) -> ModuleType:
    """`scenes.bennett` and the like: a built-in scene module, imported (and registered) on first use."""
    if name in BUILTIN:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def get(name: str) -> SceneType:
    """The registered scene `name` (built-in or from a plugin); ParameterError listing the names otherwise."""
    load_plugins()  # the built-in scenes first
    return _get(name)


def names() -> tuple[str, ...]:
    """Every registered scene name (built-in and from plugins), sorted."""
    load_plugins()  # the built-in scenes first
    return _names()


__all__ = ["REGISTRY", "Param", "Scene", "SceneType", "Tuning", "custom_scene", "get", "load_builtins", "load_plugins",
           "names", "register"]
