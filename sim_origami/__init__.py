"""sim_origami: closed-form kinematics, numeric loop closure and MuJoCo, cross-checked.

Layers, data flowing one way: kinematics (numpy) -> mechanism -> mjcf -> simulate -> checks ->
report / plots / render -> cli. Angles are radians in the API and JSON, degrees on the command line.
"""

import os

from .gl import choose_backend

__version__ = "0.1.0"

# One OpenBLAS thread unless the environment says otherwise; read when numpy loads OpenBLAS, so it acts only when
# sim_origami is imported first (the CLI, the tests, scripts that import it first). The harness's dense matrices are at
# most about 1350 x 480 (the 16 x 16 Miura FOLD sheet's closure rows), where threads cost far more CPU than they save
# (docs/performance.md, FOLD files); sweeps run one process per core anyway.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

# MUJOCO_GL must be set before the first `import mujoco` anywhere in the process.
choose_backend()
