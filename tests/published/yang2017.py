"""Yang 2017 (PhD thesis: truss method, transformable polyhedra): the published numbers the tests check."""

from published import Correction, Number

DOCUMENT = "Yang 2017"

NUMBERS: tuple[Number, ...] = ()
CORRECTIONS: tuple[Correction, ...] = ()
