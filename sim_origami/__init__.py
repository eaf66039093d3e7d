"""sim_origami: closed-form kinematics, numeric loop closure and MuJoCo, cross-checked.

Layers, data flowing one way: kinematics (numpy) -> mechanism -> mjcf -> simulate -> checks ->
report / plots / render -> cli. Angles are radians in the API and JSON, degrees on the command line.
"""

from .gl import choose_backend

__version__ = "0.1.0"

# MUJOCO_GL must be set before the first `import mujoco` anywhere in the process.
choose_backend()
