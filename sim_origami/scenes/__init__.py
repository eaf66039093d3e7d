"""Scene registry. Importing this package registers every scene module listed here."""

from . import bennett, bricard_threefold, iftomm_a04, miura, myard, thick_vertex4, vertex4  # noqa: F401
from .base import REGISTRY, Param, Scene, SceneType, get, names, register

__all__ = ["REGISTRY", "Param", "Scene", "SceneType", "get", "names", "register"]
