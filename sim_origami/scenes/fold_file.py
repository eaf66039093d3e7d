"""A scene from a FOLD 1.2 file: any crease pattern, with the numeric loop closure as the reference.

The file's last frame with fold angles (or its key frame's `edges_foldAngle`) is the folded state the motion
passes through; the input is the crease folded most there unless one is named. MuJoCo sweeps the input from
30% of that state's value to the state itself (`kinematics.numeric_pattern` for the trace and its limits).
"""

from pathlib import Path

import numpy as np

from ..errors import ParameterError
from ..fold import read_fold
from ..kinematics.numeric_pattern import PatternPath
from .base import Scene
from .patterns import pattern_scene

# The default sweep runs from this fraction of the folded state's input to the state.
SWEEP_FROM = 0.3
# The sweep lasts this many times the preset's duration. MuJoCo's lag behind the driven path falls as 1/T^2
# (x4.0-4.1 per doubling), measured on the tool's own motion.fold files read back (fast, x1 / x2 / x4): square
# twist 1.17e-6 / 2.85e-7 / 7.06e-8 rad, Miura sheet 2 x 2 1.04e-6 / 2.62e-7 / 6.63e-8, corrugated unit
# 1.56e-7 / 3.82e-8 / 9.59e-9; x4 keeps 14x below the 1e-6 rad tolerance (the square-twist scene's own choice).
SWEEP_TIME_SCALE = 4.0


def fold_scene(path: str | Path, input_crease: str | None = None) -> Scene:
    """
    Build a scene from a FOLD file.

    Raises
    ------
    ParameterError
      For a file without fold angles (no folded state to trace through) or an unknown input crease.
    AssemblyError
      When the folded state does not close (the pattern does not reach it rigidly).
    """
    fold = read_fold(path)
    if fold.frames is not None and len(fold.frames):
        target = fold.frames[-1]
    elif fold.fold_angles is not None and np.any(fold.fold_angles != 0):
        target = fold.fold_angles
    else:
        raise ParameterError(
            f"{path}: no folded state (edges_foldAngle all zero or absent in every frame); the numeric reference "
            "traces the motion through a folded state, so the file needs one"
        )
    pattern = fold.pattern
    names = [c.name for c in pattern.creases]
    drive = input_crease or names[int(np.argmax(np.abs(target)))]
    kinematics = PatternPath(pattern, drive, target)
    x_target = float(target[names.index(drive)])
    return pattern_scene(
        f"fold-{Path(path).stem}",
        {},
        kinematics,
        pattern,
        drive=drive,
        path=(SWEEP_FROM * x_target, x_target),
        sweep_time_scale=SWEEP_TIME_SCALE,
        notes=f"from {Path(path).name}: numeric reference traced through its folded state, input {drive}",
    )
