"""`python -m sim_origami`: the sim-origami command."""

import sys

from .cli import main

sys.exit(main())
