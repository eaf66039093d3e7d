"""Kamrava et al. 2021 (closed form of the asymmetric Miura vertex): the published numbers the tests check."""

from published import Correction, Number

DOCUMENT = "Kamrava et al. 2021"

NUMBERS: tuple[Number, ...] = ()
CORRECTIONS: tuple[Correction, ...] = ()
