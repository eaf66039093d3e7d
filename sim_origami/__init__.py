"""sim_origami: closed-form kinematics, numeric loop closure and MuJoCo, cross-checked.

Layers, data flowing one way: kinematics (numpy) -> mechanism -> mjcf -> simulate -> checks ->
report / plots / render -> cli. Angles are radians in the API and JSON, degrees on the command line.
"""

__version__ = "0.1.0"
