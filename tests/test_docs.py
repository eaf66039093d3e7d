"""Generated documentation stays current with the code that generates it."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def load_script(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "scripts" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.slow
def test_scenes_page_is_current():
    """docs/scenes.md is what scripts/scenes_doc.py writes from the registry (regenerate it after changing a scene)."""
    scenes_doc = load_script("scenes_doc")
    assert scenes_doc.PAGE.read_text() == scenes_doc.page()


def test_scenes_page_lists_every_registered_scene():
    from sim_origami import scenes

    text = (ROOT / "docs" / "scenes.md").read_text()
    missing = [n for n in scenes.names() if f"\n## {n}\n" not in text]
    assert not missing


def test_layers_import_one_way_and_the_architecture_page_is_current():
    """No module imports from a higher layer (scripts/import_graph.py LAYERS), and docs/architecture.md shows it."""
    import_graph = load_script("import_graph")
    assert import_graph.upward(import_graph.imports()) == []
    assert import_graph.PAGE.read_text() == import_graph.page()
