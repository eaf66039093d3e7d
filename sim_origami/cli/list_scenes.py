"""`sim-origami list`: the registered scenes."""

import argparse

from .. import scenes

NAME = "list"
HELP = "list the scenes"


def add_args(parser: argparse.ArgumentParser) -> None:
    """No options."""


def run(args: argparse.Namespace) -> int:
    for name in scenes.names():
        print(f"{name:12s} {scenes.get(name).summary}")
    return 0
