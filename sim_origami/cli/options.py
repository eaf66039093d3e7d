"""Argument helpers shared by commands: -p NAME=VALUE and degree lists."""

import argparse
import re
from pathlib import Path

import numpy as np

from ..conventions import deg_to_rad
from ..errors import ParameterError
from ..precision import Typed


def add_params(parser: argparse.ArgumentParser) -> None:
    """-p/--param NAME=VALUE, repeatable (degrees for angles, metres for lengths)."""
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="scene parameter in degrees or metres (see describe)")


# A plain decimal number as people type it: sign, digits with an optional point, an optional exponent. Python's
# float() also takes '1_0', 'inf', 'nan' and 'Infinity', which no command-line value means.
NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def parse_number(text: str, what: str) -> float:
    """A plain decimal number (NUMBER) that is finite as a float; ParameterError naming `what` otherwise."""
    text = text.strip()
    if not NUMBER.fullmatch(text):
        raise ParameterError(f"{what} = {text!r} is not a plain decimal number (e.g. 60, -0.5, 1e-3)")
    value = float(text)
    if not np.isfinite(value):
        raise ParameterError(f"{what} = {text} overflows a float; it must be a finite number")
    return value


def parse_params(items: list[str]) -> dict[str, float]:
    """
    ['alpha1=60', ...] -> {'alpha1': 60.0}, each a `precision.Typed` carrying half a unit in its last printed digit;
    ParameterError on a malformed item, a non-number or a repeated name.
    """
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ParameterError(f"parameter {item!r} is not NAME=VALUE")
        if name in out:
            raise ParameterError(f"parameter {name} is given twice; give each -p NAME once")
        parse_number(value, name)
        out[name] = Typed(value.strip())
    return out


def out_folder(text: str) -> Path:
    """An --out value; an empty one is refused (it would name the current folder, which the run would claim)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"{text!r} names no folder (an empty name would be the current folder)")
    return Path(text)


def number_at_least(option: str, low: float, *, open_low: bool = False):
    """An argparse type: a plain finite decimal number >= `low` (> `low` where `open_low`), refused at parse time
    in one line naming the option, the value and the rule."""

    def parse(text: str) -> float:
        try:
            value = parse_number(text, option)
        except ParameterError as err:
            raise argparse.ArgumentTypeError(str(err)) from None
        if value < low or (open_low and value == low):
            raise argparse.ArgumentTypeError(f"{option} = {text.strip()}; it must be {'>' if open_low else '>='} "
                                             f"{low:g}")
        return value

    return parse


def whole_number_at_least(option: str, low: int):
    """An argparse type: a whole number >= `low`, refused at parse time in one line."""

    def parse(text: str) -> int:
        if not re.fullmatch(r"[+-]?\d{1,9}", text.strip()) or int(text) < low:
            raise argparse.ArgumentTypeError(f"{option} = {text.strip()!r}; it must be a whole number >= {low}")
        return int(text)

    return parse


def parse_degrees(text: str) -> np.ndarray:
    """'10,20,30' (degrees) -> radians; ParameterError on anything that is not a finite number."""
    parts = [v for v in text.split(",") if v.strip()]
    if not parts:
        raise ParameterError(f"--input {text!r} needs comma-separated values in degrees")
    return deg_to_rad(np.array([parse_number(v, "--input value") for v in parts]))
