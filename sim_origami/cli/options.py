"""Argument helpers shared by commands: -p NAME=VALUE and degree lists."""

import argparse

import numpy as np

from ..conventions import deg_to_rad
from ..errors import ParameterError


def add_params(parser: argparse.ArgumentParser) -> None:
    """-p/--param NAME=VALUE, repeatable (degrees for angles, metres for lengths)."""
    parser.add_argument("-p", "--param", action="append", default=[], metavar="NAME=VALUE",
                        help="scene parameter in degrees or metres (see describe)")  # fmt: skip


def parse_params(items: list[str]) -> dict[str, float]:
    """['alpha1=60', ...] -> {'alpha1': 60.0}; ParameterError on a malformed item."""
    out = {}
    for item in items:
        name, sep, value = item.partition("=")
        if not sep or not name:
            raise ParameterError(f"parameter {item!r} is not NAME=VALUE")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise ParameterError(f"parameter {name}={value!r} is not a number") from None
    return out


def parse_degrees(text: str) -> np.ndarray:
    """'10,20,30' (degrees) -> radians; ParameterError on anything that is not a finite number."""
    try:
        values = np.array([float(v) for v in text.split(",") if v.strip()])
    except ValueError:
        raise ParameterError(f"--input {text!r} is not a comma-separated list of numbers (degrees)") from None
    if not values.size or not np.all(np.isfinite(values)):
        raise ParameterError(f"--input {text!r} needs finite values in degrees")
    return deg_to_rad(values)
