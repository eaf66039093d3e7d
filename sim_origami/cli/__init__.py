"""Command line: `sim-origami COMMAND ...`. Degrees on the command line, radians in JSON.

Exit status: 0 when every check passes, 1 when one fails, 2 on bad input (one line on stderr
naming the value and the rule; a traceback only with --debug).
"""

import argparse
import sys

from .. import __version__
from ..errors import SimOrigamiError
from . import analytic, bench, describe, list_scenes, mobility, sweep, validate

COMMANDS = (list_scenes, describe, analytic, validate, mobility, sweep, bench)


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors and exit status 2."""

    def error(self, message: str):
        sys.stderr.write(f"sim-origami: error: {message}\n")
        raise SystemExit(2)


def _version() -> str:
    import mujoco

    from ..gl import choose_backend

    return f"sim_origami {__version__}, MuJoCo {mujoco.__version__}, MUJOCO_GL={choose_backend()}"


def main(argv: list[str] | None = None) -> int:
    """Run one command; returns the exit status."""
    parser = _Parser(prog="sim-origami", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="store_true", help="print versions and the GL backend")
    parser.add_argument("--debug", action="store_true", help="show tracebacks")
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)
    for module in COMMANDS:
        p = sub.add_parser(module.NAME, help=module.HELP, description=module.HELP)
        module.add_args(p)
        p.set_defaults(func=module.run)
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # --help (0) or a usage error (2), already printed
        return int(exc.code or 0)
    if args.version:
        print(_version())
        return 0
    if not args.command:
        parser.print_help()
        return 2
    try:
        return args.func(args)
    except SimOrigamiError as exc:
        if args.debug:
            raise
        sys.stderr.write(f"sim-origami: error: {exc}\n")
        return 2
