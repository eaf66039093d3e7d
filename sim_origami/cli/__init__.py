"""Command line: `sim-origami COMMAND ...`. Degrees on the command line, radians in JSON.

Exit status: 0 when every check passes, 1 when one fails, 2 on bad input (one line on stderr
naming the value and the rule; a traceback only with --debug), 130 / 143 when interrupted by SIGINT / SIGTERM
(this run's files removed, the output folder as before; one line on stderr), 3 on an internal error (a bug: one
line; --debug shows it).
"""

import argparse
import contextlib
import os
import re
import shlex
import signal
import sys
import warnings

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


class Interrupted(BaseException):
    """SIGINT or SIGTERM arrived: unwinds the run (temporary files are removed on the way) to `main`."""

    def __init__(self, signum: int):
        super().__init__(signum)
        self.signum = signum


def _raise_interrupted(signum, frame):
    raise Interrupted(signum)


@contextlib.contextmanager
def _signals_unwind():
    """SIGINT and SIGTERM raise Interrupted while a command runs (main thread only); the old handlers come back."""
    try:
        old = {s: signal.signal(s, _raise_interrupted) for s in (signal.SIGINT, signal.SIGTERM)}
    except ValueError:  # not the main thread: leave signals alone
        yield
        return
    try:
        yield
    finally:
        for s, handler in old.items():
            signal.signal(s, handler)


# Values that start with '-' and a digit or a point (e.g. --input -30,10), or '-inf' and '-nan', are values, not
# options: so they reach the option's own check, which names them.
_NEGATIVE = re.compile(r"-([\d.]|inf|nan)", re.IGNORECASE)


def _join_negative_values(parser: argparse.ArgumentParser, argv: list[str]) -> list[str]:
    """
    argv with every option that takes a value and is followed by a negative number written as OPTION=VALUE:
    argparse reads '-30,10' after --input as an option ('expected one argument'); this keeps '--input -30,10'
    working for every such option.
    """
    takes_value = set()
    for action in parser._actions:  # the root and every sub-command
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                takes_value |= {o for a in sub._actions if a.option_strings and a.nargs != 0 for o in a.option_strings}
    out, k = [], 0
    while k < len(argv):
        if argv[k] in takes_value and k + 1 < len(argv) and _NEGATIVE.match(argv[k + 1]):
            out.append(f"{argv[k]}={argv[k + 1]}")
            k += 2
        else:
            out.append(argv[k])
            k += 1
    return out


def _refuse(message: str, code: int) -> int:
    sys.stderr.write(f"sim-origami: error: {message}\n")
    return code


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
    typed = list(sys.argv[1:] if argv is None else argv)
    try:
        args = parser.parse_args(_join_negative_values(parser, typed))
    except SystemExit as exc:  # --help (0) or a usage error (2), already printed
        return int(exc.code or 0)
    args.command_line = shlex.join(["sim-origami", *typed])  # as typed, for the report's provenance
    if args.version:
        print(_version())
        return 0
    if not args.command:
        parser.print_help()
        return 2
    # Warnings (numpy's RuntimeWarnings on degenerate geometry) are held back: a refusal stays one line, and a run
    # that finishes shows them after its output.
    with warnings.catch_warnings(record=True) as caught, _signals_unwind():
        warnings.simplefilter("default")
        try:
            code = args.func(args)
        except SimOrigamiError as exc:
            if args.debug:
                raise
            return _refuse(" ".join(str(exc).split()), 2)
        except BrokenPipeError:  # the reader went away (`sim-origami list | head`): not an error of ours
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error at exit's flush
            return 128 + signal.SIGPIPE
        except (Interrupted, KeyboardInterrupt) as exc:
            signum = exc.signum if isinstance(exc, Interrupted) else signal.SIGINT
            name = signal.Signals(signum).name
            return _refuse(f"interrupted by {name}; this run's files removed, the output folder's previous "
                           "results left as they were", 128 + signum)
        except Exception as exc:
            if args.debug:
                raise
            return _refuse(f"internal error (a bug, please report it): {type(exc).__name__}: "
                           f"{' '.join(str(exc).split())[:300]}; --debug shows the traceback", 3)
    for w in caught:
        warnings.showwarning(w.message, w.category, w.filename, w.lineno)
    return code
