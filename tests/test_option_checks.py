"""Options are checked when they are parsed, before any work: a non-finite or out-of-range value, and a companion
option given without the option it qualifies, are refused in one line (exit 2)."""

import pytest

from sim_origami.cli import main

GOLDBERG = "docs/examples/linkages/goldberg-5r.json"
GOLDBERG_CURVES = "docs/examples/linkages/goldberg-5r_curves.csv"
FOLD = "docs/examples/reference/vertex4.fold"


@pytest.mark.parametrize(
    ("argv", "naming"),
    [
        (["validate", "vertex4", "--frames-tolerance", "nan"], "--frames-tolerance = 'nan' is not a plain decimal"),
        (["validate", "--fold", FOLD, "--frames-tolerance", "-1"], "--frames-tolerance = -1; it must be >= 0"),
        (["validate", "vertex4", "--frames-tolerance", "1"], "--frames-tolerance holds a --fold file's frames"),
        (["validate", "vertex4", "--size", "100x100"], "--size sets the frames' size; give it with --render"),
        (["bench", "--repeats", "0"], "--repeats = '0'; it must be a whole number >= 1"),
        (["validate", "--linkage", GOLDBERG, "--reference", GOLDBERG_CURVES, "--reference-tol", "-inf"],
         "--reference-tol = '-inf' is not a plain decimal"),
        (["validate", "--linkage", GOLDBERG, "--reference", GOLDBERG_CURVES, "--reference-tol", "0"],
         "--reference-tol = 0; it must be > 0"),
    ],
)
def test_option_values_and_companions_are_refused_at_once(capsys, tmp_path, monkeypatch, argv, naming):
    monkeypatch.chdir(__file__.rsplit("/tests/", 1)[0])
    with pytest.raises(SystemExit) as done:  # argparse's own refusals end the parse
        code = main([*argv, "--out", str(tmp_path / "out")])
        raise SystemExit(code)
    err = capsys.readouterr().err.strip().splitlines()
    assert done.value.code == 2 and len(err) == 1 and naming in err[0], err
    assert not (tmp_path / "out").exists()  # refused before the folder was claimed
