"""Which analytic branch a simulated path followed.

Each sample is labelled with the nearest branch (max-norm over output joints at the simulated
input), but only where the branches are told apart: the second-nearest must be `separation`
times farther than the nearest. Near a bifurcation point the branches coincide and no label is
given. A path flips if its labels are not all the same.
"""

import itertools
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..geometry import wrap
from ..kinematics.base import Kinematics


@dataclass(frozen=True)
class BranchLabels:
    """Per-sample labels ('' where ambiguous) and the branch followed ('' if never told apart)."""

    labels: tuple[str, ...]
    followed: str
    flips: int


def classify(
    kinematics: Kinematics, x: NDArray[np.float64], outputs: NDArray[np.float64], separation: float = 100.0
) -> BranchLabels:
    """Label each sample (x (n,), outputs (n, k)) with the nearest branch."""
    names = [b.name for b in kinematics.branches()]
    dist = np.full((len(names), len(x)), np.inf)
    for i, name in enumerate(names):
        values, valid = kinematics.evaluate(name, x)
        dist[i, valid] = np.max(np.abs(wrap(outputs[valid] - values[valid])), axis=1)
    order = np.sort(dist, axis=0)
    nearest = np.argmin(dist, axis=0)
    clear = (order[1] > separation * order[0]) if len(names) > 1 else np.isfinite(order[0])
    labels = tuple(names[k] if c else "" for k, c in zip(nearest, clear, strict=True))
    told = [lab for lab in labels if lab]
    followed = max(set(told), key=told.count) if told else ""
    flips = sum(1 for a, b in itertools.pairwise(told) if a != b)
    return BranchLabels(labels, followed, flips)
