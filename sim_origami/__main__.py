"""`python -m sim_origami` and the `sim-origami` command.

The command's modules (MuJoCo, matplotlib, ...) take a second or more to import; Ctrl-C in that time ends the
command in one line with status 130, as it does once a command runs, instead of a traceback.
"""

import sys


def main() -> int:
    """Import the command line, then run it; 130 if interrupted while importing."""
    try:
        from .cli import main as run
    except KeyboardInterrupt:
        sys.stderr.write("sim-origami: interrupted while starting\n")
        return 130
    return run()


if __name__ == "__main__":
    sys.exit(main())
