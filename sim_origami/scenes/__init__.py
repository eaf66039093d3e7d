"""Scene registry. Importing this package registers every scene module listed here."""

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
from .base import REGISTRY, Param, Scene, SceneType, get, names, register

__all__ = ["REGISTRY", "Param", "Scene", "SceneType", "get", "names", "register"]
