"""
Property-based test of the bad-input contract on linkage files: each example of docs/examples/linkages/ with fields
replaced at random by junk (huge, tiny and overflowing numbers, integers of hundreds and thousands of digits, NaN,
inf, strings with NUL, control characters or thousands of characters, nested lists and tables, nesting thousands
deep), fields removed, unknown fields and extra joint rows added, written back as JSON or TOML.

Contract: `read_linkage` gives a spec or one typed `SimOrigamiError` line; where the file reads and the example's
scene builds in well under a second, `linkage_scene` as well. Never another exception (an exit 3 on the command line).

Profiles: the default ("ci") runs a fixed seed and EXAMPLES examples per file (about half a minute on 2 cores);
SIM_ORIGAMI_FUZZ=big runs 10x as many. The counts (examples, reads, refusals, scenes built) are printed at the end
(`pytest -s`). Measured: ci 250 examples, 23 read, 5 scenes built and 2 refused, 33 s; big 2500 examples, 315 read,
103 scenes built and 53 refused, 310 s; no other exception in either.
"""

import atexit
import copy
import json
import math
import os
import signal
import sys
from collections import Counter
from pathlib import Path
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim_origami.errors import SimOrigamiError
from sim_origami.linkage_file import read_linkage
from sim_origami.scenes.linkage_file import linkage_scene

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

FOLDER = Path(__file__).resolve().parents[1] / "docs" / "examples" / "linkages"
SOURCES = sorted(p.name for p in FOLDER.iterdir() if p.suffix in (".json", ".toml"))
BIG = os.environ.get("SIM_ORIGAMI_FUZZ") == "big"
EXAMPLES = 250 if BIG else 25
# Examples whose scene builds in under 0.7 s: their mutants are built into scenes as well (the others are read only).
CHEAP = {"bennett.toml", "myard.toml", "vertex4.toml", "goldberg-5r.json", "bricard-plane.json"}
# A scene build longer than this is a hang (the examples build in 0.4 - 3 s; a mutant may need the nearest mobile
# linkage, a few seconds more).
HANG_S = 60

COUNTS: Counter = Counter()


class Raw(str):
    """Text written into the file as it is (numbers and nesting Python's json cannot write)."""


JUNK = (None, True, False, "", "x", "\x00", "a\x00b", "two\nlines", "\ud800", "x" * 5000, 0, -1, 1, 7, 1e308, -1e308,
        1e-300, -1e-300, 5e-324, 1e9, 2e9, float("nan"), float("inf"), float("-inf"), 10**20, 2**63, -(2**64),
        Raw("1" + "0" * 400), Raw("-1" + "0" * 400), Raw("1" + "0" * 5000), Raw("1e400"), Raw("-1e400"),
        Raw("[" * 3000 + "]" * 3000), Raw("[" * 40 + "]" * 40), [], [[1]], [1, 2, 3, 4], [0.0, 0.0, 0.0],
        [1e308, 1e308, 1e308], [1e-300, 0, 0], {}, {"a": 1}, [["a"], "b"], ["link_1", "link_1"], [-1e-300, 1e-300],
        "revolute", "spherical", "rad", "deg", "mm", "nm", "km")


def _json(value: Any) -> str:
    if isinstance(value, Raw):
        return str(value)
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))}: {_json(v)}" for k, v in value.items()) + "}"
    if isinstance(value, list):
        return "[" + ", ".join(_json(v) for v in value) + "]"
    return json.dumps(value)  # NaN and Infinity as Python's json reads them


def _toml(value: Any) -> str:
    if isinstance(value, Raw):
        return str(value)
    if value is None:  # TOML has no null
        return "{}"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, str):
        return json.dumps(value)  # \uXXXX escapes, as TOML's basic strings take them
    if isinstance(value, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {_toml(v)}" for k, v in value.items()) + "}"
    return "[" + ", ".join(_toml(v) for v in value) + "]"


def _places(doc: Any, path: tuple = ()) -> list[tuple]:
    """Every value's path in a document (tables and lists included)."""
    out = [path]
    children = doc.items() if isinstance(doc, dict) else enumerate(doc) if isinstance(doc, list) else ()
    for key, value in children:
        out += _places(value, (*path, key))
    return out


def _load(name: str) -> dict:
    text = (FOLDER / name).read_text()
    return tomllib.loads(text) if name.endswith(".toml") else json.loads(text)


def _junk(draw) -> Any:
    """A junk value, a copy of its own: a later change (a row appended) must not alter JUNK, nor make a cycle."""
    return copy.deepcopy(draw(st.sampled_from(JUNK)))


@st.composite
def mutant(draw, name: str) -> tuple[str, str]:
    """(file suffix, text): the example with 1-3 changes (junk, plausible numbers, fields dropped or added, rows
    repeated), written as JSON or TOML."""
    doc = _load(name)
    for _ in range(draw(st.sampled_from((1, 1, 2, 3)))):
        places = _places(doc)[1:]
        path = draw(st.sampled_from(places))
        parent = doc
        for key in path[:-1]:
            parent = parent[key]
        kind = draw(st.sampled_from(("junk", "junk", "near", "near", "drop", "extra", "row", "field")))
        value = parent[path[-1]]
        if kind == "near" and isinstance(value, (int, float)) and not isinstance(value, bool):
            # a plausible number: the linkage changed, its file still well formed
            parent[path[-1]] = value * draw(st.sampled_from((0.0, -1.0, 0.5, 0.999, 1.001, 2.0, 1e3, 1e-3)))
        elif kind in ("junk", "near"):
            parent[path[-1]] = _junk(draw)
        elif kind == "drop":
            parent.pop(path[-1])
        elif kind == "extra" and isinstance(parent, list):
            parent.append(_junk(draw))
        elif kind == "row" and isinstance(doc.get("joints"), list) and doc["joints"]:
            rows = doc["joints"]
            row = draw(st.sampled_from(rows))
            rows += [copy.deepcopy(row) for _ in range(draw(st.sampled_from((1, 4, 40))))]
        elif kind == "field" and isinstance(parent, dict):
            parent[draw(st.sampled_from(("bogus", "anchor", "notes", "shapes", "precision", "contact")))] = \
                _junk(draw)
    if draw(st.booleans()):
        return ".json", _json(doc)
    return ".toml", "\n".join(f"{json.dumps(str(k))} = {_toml(v)}" for k, v in doc.items()) + "\n"


class _Hang(BaseException):
    """A scene build over HANG_S."""


def _on_alarm(signum, frame):
    raise _Hang()


def _refused(err: SimOrigamiError, where: str) -> None:
    text = str(err)
    assert "\n" not in text and len(text) < 1000, f"{where}: {text[:2000]}"


@pytest.mark.slow
@pytest.mark.parametrize("name", SOURCES)
def test_fuzz_linkage_file(tmp_path, name):
    # the examples' meshes and curves, beside them, stay reachable: the mutant is written into the same folder's copy
    for other in FOLDER.iterdir():
        if other.is_file():
            (tmp_path / other.name).write_bytes(other.read_bytes())

    @settings(derandomize=True, deadline=None, database=None, max_examples=EXAMPLES, print_blob=False,
              suppress_health_check=list(HealthCheck))
    @given(mutant(name))
    def one(mutated: tuple[str, str]) -> None:
        suffix, text = mutated
        path = tmp_path / f"mutant{suffix}"
        path.write_text(text)
        COUNTS["examples"] += 1
        try:
            read_linkage(path)
        except SimOrigamiError as err:
            COUNTS["read refusals"] += 1
            _refused(err, f"read {name} as {suffix}")
            return
        COUNTS["reads"] += 1
        if name not in CHEAP:
            return
        previous = signal.signal(signal.SIGALRM, _on_alarm)
        signal.alarm(HANG_S)
        try:
            linkage_scene(path)
            COUNTS["scenes"] += 1
        except SimOrigamiError as err:
            COUNTS["scene refusals"] += 1
            _refused(err, f"scene of {name} as {suffix}")
        except _Hang:
            pytest.fail(f"scene of a mutant of {name} ran over {HANG_S} s:\n{text[:3000]}")
        finally:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, previous)

    one()


def _report() -> None:
    if COUNTS:
        print(f"\nlinkage fuzz counts ({'big' if BIG else 'ci'}): examples {COUNTS['examples']}, read "
              f"{COUNTS['reads']}, refused on reading {COUNTS['read refusals']}, scenes built {COUNTS['scenes']}, "
              f"refused by the scene {COUNTS['scene refusals']}")


atexit.register(_report)
