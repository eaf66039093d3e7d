"""Scenes from installed packages: the entry point group `sim_origami.scenes`.

An installed package names a module (registers its scenes with `scenes.register` when imported) or a callable
(called once, with no arguments, and registers them) under the group, e.g. in its pyproject.toml:

    [project.entry-points."sim_origami.scenes"]
    four-bar = "sim_origami_fourbar.scene"

Plugins load once, the first time the registry is asked for a scene or the names (`scenes.get`,
`scenes.names`). A plugin that fails to load, or that would replace a scene already registered, is left out
with one line on stderr naming it (also kept in `FAILED`); the built-in scenes and the other plugins stay. A
plugin's builder that fails with anything but a SimOrigamiError raises one SimOrigamiError naming the scene and
the plugin (one line and exit 2 on the command line).
"""

import functools
import sys
from collections.abc import Callable
from dataclasses import replace
from importlib.metadata import EntryPoint, entry_points
from types import ModuleType

from ..errors import SimOrigamiError
from .base import REGISTRY, Scene

GROUP = "sim_origami.scenes"
# One line per plugin left out: "name (value): why".
FAILED: list[str] = []
_loaded = False


def _fail(ep: EntryPoint, why: str) -> None:
    line = f"scene plugin {ep.name!r} ({ep.value}) left out: {' '.join(why.split())}"
    FAILED.append(line)
    sys.stderr.write(f"sim-origami: warning: {line}\n")


def load_one(ep: EntryPoint) -> tuple[str, ...]:
    """Load one entry point; returns the scene names it added (none if it failed, which is reported)."""
    before = dict(REGISTRY)
    try:
        target = ep.load()
        if callable(target) and not isinstance(target, ModuleType):
            target()
    except (Exception, SystemExit) as exc:  # a plugin's own bug must not take the built-in scenes down
        REGISTRY.clear()
        REGISTRY.update(before)
        _fail(ep, f"{type(exc).__name__}: {exc}")
        return ()
    replaced = sorted(n for n, kind in before.items() if REGISTRY.get(n) is not kind)
    if replaced:
        REGISTRY.clear()
        REGISTRY.update(before)
        _fail(ep, f"it registers {', '.join(replaced)}, which is already registered; rename its scene")
        return ()
    added = tuple(sorted(n for n in REGISTRY if n not in before))
    if not added:
        _fail(ep, "loading it registered no scene (does its module call sim_origami.scenes.register?)")
    for name in added:
        REGISTRY[name] = replace(REGISTRY[name], build_fn=_guarded(ep, name, REGISTRY[name].build_fn))
    return added


def _guarded(ep: EntryPoint, name: str, build: Callable[..., Scene]) -> Callable[..., Scene]:
    """The plugin's builder, with its own bugs (anything but a SimOrigamiError, which names the bad value already)
    turned into one SimOrigamiError naming the scene and the plugin, so the command line prints one line."""

    @functools.wraps(build)
    def guarded(**values: float) -> Scene:
        try:
            scene = build(**values)
        except SimOrigamiError:
            raise
        except Exception as exc:
            raise SimOrigamiError(f"scene {name!r} of plugin {ep.name!r} ({ep.value}) failed to build: "
                                  f"{type(exc).__name__}: {' '.join(str(exc).split())}") from exc
        if not isinstance(scene, Scene):
            raise SimOrigamiError(
                f"scene {name!r} of plugin {ep.name!r} ({ep.value}): its builder returned a {type(scene).__name__}, "
                "not a Scene (see sim_origami.scenes.custom_scene)"
            )
        return scene

    return guarded


def load_plugins(*, force: bool = False) -> tuple[str, ...]:
    """Load every plugin of the group once (again with `force`); returns the scene names they added."""
    global _loaded
    from . import load_builtins  # at call time: this module is imported by the package's own __init__

    if _loaded and not force:
        return ()
    load_builtins()  # before any plugin: a plugin may not replace a built-in scene
    _loaded = True
    added: list[str] = []
    for ep in sorted(entry_points(group=GROUP), key=lambda e: e.name):
        added += load_one(ep)
    return tuple(added)
