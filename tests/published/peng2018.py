"""Peng 2018 (PhD thesis: spherical 4R networks, thick origami): the published numbers the tests check."""

from published import Correction, Number

DOCUMENT = "Peng 2018"

NUMBERS: tuple[Number, ...] = ()
CORRECTIONS: tuple[Correction, ...] = ()
