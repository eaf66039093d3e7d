"""
Property-based test of the bad-input contract on reference CSVs: a valid curve of the Miura vertex with cells,
headers and lines replaced at random (huge, tiny and overflowing numbers, NaN, inf, empty, NUL, quotes, thousands
of digits, unknown units, repeated columns, non-monotone inputs). Contract: `read_reference` and `compare_reference`
give a check or a one-line ParameterError; never another exception, never a traceback; the check's document is JSON
without NaN or inf. Fixed seed; SIM_ORIGAMI_FUZZ=big runs 10x as many.
"""

import json
import os

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim_origami import scenes
from sim_origami.checks.reference import compare_reference, read_reference
from sim_origami.errors import SimOrigamiError

EXAMPLES = 600 if os.environ.get("SIM_ORIGAMI_FUZZ") == "big" else 60
HEADER = ["theta[deg]", "phi[deg]", "psi[deg]", "rho_c[deg]"]
CELLS = ("0", "-0", "1e308", "1e+308", "1e400", "-1e400", "0e400", "1e-400", "nan", "inf", "-inf", "", " ", "abc",
         "1_0", "0x10", "1" * 400, "9e" + "9" * 400, '"12"', "12,5", "\x00", "١٢", "1e", ".", "-", "+1.5E-3",
         "180", "-180", "720")
HEADS = ("theta", "theta[rad]", "theta[deg", "[deg]", "phi[furlong]", "phi[deg]", "rho_a[deg]", "x[deg]", "", "\x00")


def _rows() -> list[list[str]]:
    theta = np.arange(10.0, 41.0, 5.0)
    kin = scenes.get("miura").build().kinematics
    values = np.rad2deg(kin.joint_angles("miura", np.deg2rad(theta)))
    names = list(kin.joint_names)
    return [[f"{t:.6f}"] + [f"{values[i, names.index(j)]:.6f}" for j in ("phi", "psi", "rho_c")]
            for i, t in enumerate(theta)]


@st.composite
def mutated(draw) -> str:
    header, rows = list(HEADER), _rows()
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(("cell", "cell", "header", "drop", "swap", "extra")))
        if kind == "cell":
            rows[draw(st.integers(0, len(rows) - 1))][draw(st.integers(0, 3))] = draw(st.sampled_from(CELLS))
        elif kind == "header":
            header[draw(st.integers(0, 3))] = draw(st.sampled_from(HEADS))
        elif kind == "drop" and len(rows) > 1:
            rows.pop(draw(st.integers(0, len(rows) - 1)))
        elif kind == "swap":
            i, j = draw(st.integers(0, len(rows) - 1)), draw(st.integers(0, len(rows) - 1))
            rows[i], rows[j] = rows[j], rows[i]
        elif kind == "extra":
            rows[draw(st.integers(0, len(rows) - 1))].append(draw(st.sampled_from(CELLS)))
    return "\n".join(",".join(r) for r in [header, *rows]) + "\n"


@pytest.fixture(scope="module")
def miura():
    return scenes.get("miura").build()


@pytest.mark.slow
def test_fuzz_reference_csv(tmp_path_factory, miura):
    folder = tmp_path_factory.mktemp("fuzz")

    @settings(derandomize=True, deadline=None, database=None, max_examples=EXAMPLES,
              suppress_health_check=list(HealthCheck))
    @given(mutated())
    def one(text: str) -> None:
        path = folder / "ref.csv"
        path.write_text(text)
        try:
            checked = compare_reference(read_reference(str(path), miura.kinematics), miura)
        except SimOrigamiError as err:
            assert "\n" not in str(err) and len(str(err)) < 1000, str(err)
            return
        json.dumps(checked.doc, allow_nan=False)
        assert all(isinstance(v.passed, bool) for v in checked.verdicts)

    one()
