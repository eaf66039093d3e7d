"""Draw the package's import graph by layer and write docs/architecture.md.

    python scripts/import_graph.py            # rewrite docs/architecture.md
    python scripts/import_graph.py --check    # exit 1 if the page is not current or a layer imports upward

Data flows one way: each module belongs to a layer (LAYERS, lowest first) and may import only from its own layer
or lower ones. tests/test_docs.py runs the check.
"""

import argparse
import ast
import sys
from collections import defaultdict
from pathlib import Path

from sim_origami.files import write_or_check

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "sim_origami"
PAGE = ROOT / "docs" / "architecture.md"

# (layer, what it is, the modules or subpackages in it), lowest first.
LAYERS = (
    ("base", "errors, units, atomic files, geometry, graphs, tolerances, typed precision, GL backend, peers' times",
     ("__init__", "errors", "conventions", "files", "geometry", "graph", "tolerances", "precision", "gl",
      "peer_times")),
    ("kinematics", "closed forms (numpy only), the numeric loop closure and path engine, crease patterns, FOLD files",
     ("kinematics", "closure", "path", "creases", "fold", "fold_mesh")),
    ("mechanism", "bodies, joints, spanning trees, panel and link solids, linkage files",
     ("mechanism", "origami", "linkage", "linkage_forms", "linkage_file", "solids")),
    ("mjcf", "MJCF text and its compiled model from a mechanism and options; the MuJoCo presets",
     ("mjcf", "mjcf_tidy", "presets")),
    ("scenes", "a kinematics model wired to a mechanism and a drive; the registry", ("scenes",)),
    ("simulation", "MuJoCo runs, their stabilised steps and sweep times; the truss method",
     ("stabilize", "sweep_rate", "simulate", "truss")),
    ("checks", "path errors, branch classification, blockage verdicts", ("checks",)),
    ("validation", "the three-way cross-check; sweeps", ("validation", "sweep")),
    ("outputs", "reports, plots, frames; studies built on the harness",
     ("report", "report_page", "plots", "render", "render_paper", "studies")),
    ("cli", "the sim-origami commands", ("cli", "__main__")),
)


def _module(path: Path) -> str:
    """Dotted module name of a file under the package."""
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _unit(module: str) -> str:
    """The first name under sim_origami (`kinematics`, `mjcf`, ...); `__init__` for the package itself."""
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def layer_of(module: str) -> int:
    """Index in LAYERS of a module's layer."""
    unit = _unit(module)
    for k, (_, _, units) in enumerate(LAYERS):
        if unit in units:
            return k
    raise SystemExit(f"{module}: no layer in LAYERS names {unit!r}; add it")


def _resolve(package: str, name: str) -> str:
    """`from package import name`: the module package.name if it is one, else package."""
    path = ROOT.joinpath(*package.split("."), name)
    return f"{package}.{name}" if path.with_suffix(".py").exists() or path.is_dir() else package


def imports() -> dict[str, set[str]]:
    """Module -> the sim_origami modules it imports (from-imports resolved to their module)."""
    out: dict[str, set[str]] = defaultdict(set)
    for path in sorted(PACKAGE.rglob("*.py")):
        module = _module(path)
        package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom):
                base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
                target = ".".join(base + ([node.module] if node.module else []))
                if target.startswith("sim_origami"):
                    out[module] |= {_resolve(target, a.name) for a in node.names}
            elif isinstance(node, ast.Import):
                out[module] |= {a.name for a in node.names if a.name.startswith("sim_origami")}
    return out


def upward(edges: dict[str, set[str]]) -> list[tuple[str, str]]:
    """Imports from a lower layer into a higher one, as (importer, imported)."""
    return sorted((a, b) for a, bs in edges.items() for b in bs if layer_of(b) > layer_of(a))


def page() -> str:
    """The whole docs/architecture.md text."""
    edges = imports()
    between: dict[str, set[str]] = defaultdict(set)
    for a, bs in edges.items():
        for b in bs:
            if _unit(a) != _unit(b):
                between[_unit(a)].add(_unit(b))
    rows = "\n".join(
        f"| {k} | {name} | {', '.join(f'`{u}`' for u in units)} | {what} |"
        for k, (name, what, units) in enumerate(LAYERS)
    )
    units = [u for _, _, us in LAYERS for u in us if u in between or any(u in v for v in between.values())]
    graph = "\n".join(f"{u:14s} -> {', '.join(sorted(between[u]))}" for u in units if between[u])
    wrong = upward(edges)
    verdict = "\n".join(f"- `{a}` imports `{b}`" for a, b in wrong) or "None: every import points down or sideways."
    return f"""# Architecture

Data flows one way through these layers; a module imports only from its own layer or lower ones, so MJCF is
built from a mechanism and never from a scene, and nothing below the CLI knows about the command line. Generated
by `scripts/import_graph.py`; `tests/test_docs.py` fails when an import points upward or this page is stale.

| layer | name | modules | what it holds |
|---|---|---|---|
{rows}

## Imports between modules (by first name under `sim_origami`)

```text
{graph}
```

## Imports pointing upward

{verdict}

## One numeric path engine

Every numeric path is followed by `sim_origami.path` (layer 1, numpy and scipy only), which holds the predictor
(secant or tangent), the correctors (damped Gauss-Newton; Newton with the rank-truncated pseudo-inverse), step
control, the numerical rank, and three modes: `sweep` (given input values: `LoopSystem.follow`, so validation's
closed-form-vs-numeric verdict, the user-curve check and the rigid-foldability test), `trace` (driven joints along
a polyline with stall, bound and mobility reports: the crease-pattern path `PatternPath`) and `follow_arc`
(pseudo-arc length through turning points, bifurcation detection, location, branch directions and switching: the
truss method's `truss.follow`). Callers give the system (a `LoopSystem` in joint angles, or an `ArcSystem` such as
the truss in node coordinates) and keep no stepping code of their own.
"""


def run(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="check the page and the layers instead of writing")
    args = parser.parse_args(argv)
    wrong = upward(imports()) if args.check else []
    for a, b in wrong:
        print(f"{a} imports {b}: a lower layer must not import a higher one", file=sys.stderr)
    return write_or_check(PAGE, page(), args.check, "python scripts/import_graph.py") or int(bool(wrong))


if __name__ == "__main__":
    raise SystemExit(run())
