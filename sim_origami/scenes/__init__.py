"""Scene registry. Importing this package registers every scene module listed here; scenes of installed
packages (entry point group `sim_origami.scenes`, see `plugins`) join the first time `get` or `names` is called."""

from . import (  # noqa: F401  (registration side effect)
    bennett,
    bricard_plane,
    bricard_threefold,
    corrugated,
    corrugated_sheet,
    cuboctahedron,
    iftomm_a04,
    kokotsakis,
    miura,
    miura_sheet,
    myard,
    rssr,
    square_twist,
    thick_diamond,
    thick_square_twist,
    thick_vertex4,
    thick_vertex5,
    triangle_twist,
    truncated_octahedron,
    truncated_tetrahedron,
    twist_6r,
    vertex4,
    waterbomb,
    waterbomb_tube,
    waterbomb_twist,
)
from .base import REGISTRY, Param, Scene, SceneType, register
from .base import get as _get
from .base import names as _names
from .custom import custom_scene
from .plugins import load_plugins


def get(name: str) -> SceneType:
    """The registered scene `name` (built-in or from a plugin); ParameterError listing the names otherwise."""
    load_plugins()
    return _get(name)


def names() -> tuple[str, ...]:
    """Every registered scene name (built-in and from plugins), sorted."""
    load_plugins()
    return _names()


__all__ = ["REGISTRY", "Param", "Scene", "SceneType", "custom_scene", "get", "load_plugins", "names", "register"]
