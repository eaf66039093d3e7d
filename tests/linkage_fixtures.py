"""Linkage-file fixtures shared by the linkage tests: the examples' folder and the Bennett linkage as a JSON dict."""

from pathlib import Path

EXAMPLES = Path(__file__).resolve().parents[1] / "docs" / "examples" / "linkages"
BENNETT = {
    "sim_origami_linkage": 1,
    "form": "dh",
    "name": "bennett-json",
    "joints": [{"name": f"theta{k + 1}", "a": a, "alpha": alpha}
               for k, (a, alpha) in enumerate([(1.0, 30.0), (1.5, 48.590377890729144)] * 2)],
    "input": {"joint": "theta1", "range": [20.0, 140.0]},
}
