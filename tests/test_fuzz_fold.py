"""
Property-based test of the bad-input contract on FOLD files: small files as other tools write them (a text editor's
degree-4 vertex with letters or with a folded state, Rabbit Ear's letters-only Miura sheet, the FOLD examples'
simple.fold folded form) with fields replaced at random by junk (integers beyond a double or over 4300 digits, NaN,
Infinity, strings, booleans, nested arrays and objects, JSON nested thousands deep), single entries replaced, and
keys dropped, written as JSON text. Contract: reading and building the scene (`read_fold`, `fold_scene`: the trace,
no MuJoCo) end in a scene or in one SimOrigamiError line; never another exception, never a traceback. Fixed
examples (derandomized); SIM_ORIGAMI_FUZZ=big runs 10x as many.
"""

import copy
import json
import os
import warnings

import pytest
from fold_fixtures import degree4_letters, miura_letters_only
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_fold_read import simple_fold

from sim_origami.errors import SimOrigamiError
from sim_origami.fold import read_fold
from sim_origami.scenes.fold_file import fold_scene

EXAMPLES = 400 if os.environ.get("SIM_ORIGAMI_FUZZ") == "big" else 40


class Raw:
    """JSON text written as it is (numbers Python's json.dumps cannot write: NaN as a FOLD writer might, huge ones)."""

    def __init__(self, text: str):
        self.text = text


JUNK = (Raw("1" + "0" * 330), Raw("-" + "9" * 5000), Raw("NaN"), Raw("Infinity"), Raw("-Infinity"), Raw("1e400"),
        Raw("[" * 5000 + "]" * 5000), "90", "", "M", True, False, None, [], [[]], [[[1.0]]], [None], {}, {"a": 1},
        1e308, -1e308, 0, -1, 7, 2**70, 0.5, 180.0, -181.0)
BASES = {
    "degree4-letters": degree4_letters(),
    "degree4-state": degree4_letters() | {"edges_foldAngle": [-70.0, 60.0, 60.0, 60.0, 0, 0, 0, 0]},
    "miura-letters": miura_letters_only(2, 2),
    "simple-folded": simple_fold(),
}
FIELDS = ("vertices_coords", "edges_vertices", "edges_assignment", "faces_vertices", "edges_foldAngle", "frame_unit",
          "file_frames", "frame_classes", "edges_sim_origami:hingeHeight", "frame_sim_origami:precision")


def text(doc: dict) -> str:
    """`doc` as JSON text, each Raw value written as its own text."""
    raws: list[str] = []

    def mark(value):
        if isinstance(value, Raw):
            raws.append(value.text)
            return f"@@raw{len(raws) - 1}@@"
        if isinstance(value, list):
            return [mark(v) for v in value]
        if isinstance(value, dict):
            return {k: mark(v) for k, v in value.items()}
        return value

    out = json.dumps(mark(doc))
    for k, raw in enumerate(raws):
        out = out.replace(f'"@@raw{k}@@"', raw, 1)
    return out


@st.composite
def mutated(draw) -> dict:
    doc = copy.deepcopy(BASES[draw(st.sampled_from(sorted(BASES)))])
    for _ in range(draw(st.integers(1, 3))):
        field = draw(st.sampled_from(FIELDS))
        kind = draw(st.sampled_from(("field", "entry", "entry", "inner", "drop")))
        value = doc.get(field)
        if kind == "drop":
            doc.pop(field, None)
        elif kind == "entry" and isinstance(value, list) and value:
            value[draw(st.integers(0, len(value) - 1))] = draw(st.sampled_from(JUNK))
        elif kind == "inner" and isinstance(value, list) and value and isinstance(value[0], list) and value[0]:
            row = value[draw(st.integers(0, len(value) - 1))]
            if isinstance(row, list) and row:
                row[draw(st.integers(0, len(row) - 1))] = draw(st.sampled_from(JUNK))
        else:
            doc[field] = draw(st.sampled_from(JUNK))
    return doc


@pytest.mark.slow
def test_fuzz_fold_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("fuzz")

    @settings(derandomize=True, deadline=None, database=None, max_examples=EXAMPLES, print_blob=False,
              suppress_health_check=list(HealthCheck))
    @given(mutated())
    def one(doc: dict) -> None:
        path = folder / "mutated.fold"
        path.write_text(text(doc))
        try:
            with warnings.catch_warnings():  # the command line holds numpy's warnings back; here they are no failure
                warnings.simplefilter("ignore", RuntimeWarning)
                read_fold(path)
                fold_scene(path)
        except SimOrigamiError as err:
            assert "\n" not in str(err) and len(str(err)) < 2000, str(err)

    one()
