"""Generated documentation stays current with the code that generates it."""

import ast
import importlib.util
import re
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


@pytest.mark.slow
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


# --- citations a reader can resolve ------------------------------------------------------------------------
# The project cites its sources by author-year (docs/references.md). Our internal notes on them are not
# shipped, so a citation by our file numbers of the sources or by the notes' items leaves the reader nothing
# to look up (the pattern below). Random seeds, branch seeding (`seed='closed'`), "seed row", importlib's
# `spec_from_file_location` / `spec.loader` and "the FOLD 1.2 specification" are not citations.

_SCANNED = ("sim_origami", "mjcf_templates", "tests", "scripts", "docs", "README.md", "pyproject.toml")
_NOT_SCANNED = {".git", ".venv", "venv", "node_modules", "__pycache__", ".pytest_cache", ".ruff_cache", ".hypothesis",
                "build", "dist", "runs", "out"}
_UNRESOLVABLE_CITATION = re.compile(  # citation-guard pattern
    r"seeds? ?0\d\d|seed\d{3}"  # citation-guard pattern: a source by our file number
    r"|(?<![a-z])digest"  # citation-guard pattern: our notes on the sources
    r"|\bspec(?:\s+[\w.-]+\.md\b|\s*§|\s+M\d+\b)|\bthe spec\b"  # citation-guard pattern: our notes as "spec"
    r"|\bthe seed(?:['’]s|s['’])"  # citation-guard pattern: "the seed's" for the source document
    r"|\[(?:NEW|RECON)\b",  # citation-guard pattern: our notes' marks (say "derived here", "reconstructed here")
    re.IGNORECASE,
)


def _project_text_files() -> list[Path]:
    files = []
    for top in _SCANNED:
        path = ROOT / top
        candidates = [path] if path.is_file() else sorted(path.rglob("*"))
        for p in candidates:
            skipped = any(part in _NOT_SCANNED or part.endswith(".egg-info") for part in p.relative_to(ROOT).parts)
            if p.is_file() and not skipped:
                files.append(p)
    return files


@pytest.mark.slow
def test_no_citation_of_internal_notes():
    """Every citation names a source the reader can find ('Peng 2018, §3.3'), none our internal notes."""
    found = []
    for path in _project_text_files():
        data = path.read_bytes()
        if b"\0" in data:
            continue  # binary (images)
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            continue
        for number, line in enumerate(text.splitlines(), 1):
            if path == Path(__file__).resolve() and "citation-guard" in line:
                continue  # this guard's own patterns and samples
            if _UNRESOLVABLE_CITATION.search(line):
                found.append(f"{path.relative_to(ROOT)}:{number}: {line.strip()[:100]}")
    assert not found, f"{len(found)} citation(s) of internal notes:\n" + "\n".join(found)


@pytest.mark.parametrize(
    ("line", "cites"),
    [
        ("rng = np.random.default_rng(seed)", False),
        ('simulate(scene, branch, seed="flat", bias=1e-4)', False),
        ("the 3-row tube twists in one of its seed rows -1, 0, 1", False),
        ("spec = importlib.util.spec_from_file_location(name, path); spec.loader.exec_module(module)", False),
        ("the FOLD 1.2 specification (github.com/edemaine/fold, doc/spec.md)", False),
        ("hashlib.sha256(data).hexdigest()", False),
        ("against Peng 2018, §3.3, eqns 3-29 to 3-32", False),
        ("against seed 003 §3.3", True),  # citation-guard sample
        ("SEED004_RANGES = ...", True),  # citation-guard sample
        ("(digest M9, eqns 3-30 to 3-32)", True),  # citation-guard sample
        ("def test_formulas_reproduce_the_digest_table():", True),  # citation-guard sample
        ("soft loops take C, as spec mujoco.md 7 found", True),  # citation-guard sample
        ("the seed's Fig. 3-5", True),  # citation-guard sample
        ("the seeds' dihedrals", True),  # citation-guard sample
        ("closes on six combinations [NEW]", True),  # citation-guard sample
        ("Case 10 family **[NEW, verified]**", True),  # citation-guard sample
        ("the two-fold case [RECON]", True),  # citation-guard sample
        ("closes on six combinations (derived here)", False),
    ],
)
def test_citation_pattern_tells_citations_from_other_uses(line, cites):
    assert bool(_UNRESOLVABLE_CITATION.search(line)) == cites
