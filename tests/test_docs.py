"""Generated documentation stays current with the code that generates it."""

import ast
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


# --- docs/results.md: the published numbers in tests/published/, each entry naming a real test ----------


def _test_functions(path: Path) -> set[str]:
    tree = ast.parse(path.read_text())
    return {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef) and n.name.startswith("test_")}


@pytest.mark.slow
def test_every_published_entry_names_a_test_that_exists_and_reads_it():
    results_doc = load_script("results_doc")
    for name in results_doc.MODULES:
        module = results_doc.load(name)
        assert module.NUMBERS or module.CORRECTIONS, name
        for entry in (*module.NUMBERS, *module.CORRECTIONS):
            file, function = entry.test.split("::")
            path = ROOT / "tests" / file
            assert function in _test_functions(path), entry
            # the test reads the entry by its name (checked_by / check_every), not a copy of the number
            text = path.read_text()
            assert f'"{function}"' in text or f'"{file}::{function}"' in text, entry
        for where, _, test in getattr(module, "CHECKED_ELSEWHERE", ()):
            file, function = test.split("::")
            assert function in _test_functions(ROOT / "tests" / file), where


def test_printed_values_parse_and_tolerances_are_positive():
    results_doc = load_script("results_doc")
    for name in results_doc.MODULES:
        for entry in results_doc.load(name).NUMBERS:
            assert entry.value.size >= 1 and entry.tol > 0, entry


@pytest.mark.slow
def test_results_page_is_current():
    """docs/results.md is what scripts/results_doc.py writes (regenerate it after changing a published entry)."""
    assert load_script("results_doc").run(["--check"]) == 0
