"""Feng, Ma and Chen 2020 (generalized waterbomb tubes): the published numbers the tests check."""

from published import Correction, Number

DOCUMENT = "Feng, Ma and Chen 2020"

NUMBERS: tuple[Number, ...] = ()
CORRECTIONS: tuple[Correction, ...] = ()
