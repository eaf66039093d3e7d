"""Readable MJCF: short numbers, float noise snapped, boxes as primitives, comments next to what they explain.

The model a run steps is the tidied text itself (`mjcf.build_xml` ends here); `model.xml` is that text with replay
lines added (a position servo, keyframes with ctrl; marked in comments). Numbers within 1e-15 x the model's size (at
least 1 m) of zero are written as 0, others as the shortest decimal within 4 units in their last place:
`0.37499999999999994` -> `0.375`, `1.2246467991473532e-16` -> `0`, `-0.0` -> `0`. Keyframe poses are state, not
geometry: written as exact round-trip reprs, so that a run restarted from them in plain MuJoCo is bitwise the
harness's run.
"""

import itertools
import xml.etree.ElementTree as ET

import numpy as np
import trimesh
from numpy.typing import NDArray

from .geometry import quaternion

# Float noise: numbers within this (times the model's size) of 0 are written as 0; any other number is written as the
# shortest decimal within ULPS units in its last place. Snapping every number by 1e-15 x the size instead moved the
# triangle-twist 6R's kinematic projection from 1.8e-14 to 2.6e-13 rad off its closed form (its loop is
# ill-conditioned along the path: a 1e-15 change in geometry moves the closed pose 260 times as much).
NOISE = 1e-15
ULPS = 4
# Attributes whose words are names, not numbers (the rest are parsed as numbers when every word is one).
_WORDS = {"name", "class", "model", "mesh", "joint", "joint1", "joint2", "site1", "site2", "body1", "body2",
          "geom1", "geom2", "childclass", "material", "texture"}


def short(value: float, tol: float) -> str:
    """The shortest decimal (up to 17 significant digits) within ULPS units in the last place of `value`; '0' for
    |value| <= tol."""
    value = float(value)
    if abs(value) <= tol:
        return "0"
    tol = ULPS * float(np.spacing(abs(value)))
    if value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    lo, hi = 1, 17  # fewest digits within tol: more digits are never further away, so bisect
    while lo < hi:
        mid = (lo + hi) // 2
        if abs(float(f"{value:.{mid}g}") - value) <= tol:
            hi = mid
        else:
            lo = mid + 1
    text = repr(float(f"{value:.{lo}g}"))  # 100.0, 0.375, 1e-05
    if text.endswith(".0"):
        text = text[:-2]
    if "e" in text:
        mantissa, exponent = text.split("e")
        text = f"{mantissa}e{int(exponent)}"
    return text


def numbers(text: str, tol: float) -> str | None:
    """`text` rewritten with `short` numbers, or None if a word of it is not a number."""
    try:
        values = [float(word) for word in text.split()]
    except ValueError:
        return None
    return " ".join(short(v, tol) for v in values)


def tidy(root: ET.Element, size: float) -> None:
    """
    Rewrite every numeric attribute of the tree in place (keyframe qpos kept exact; size in metres); drop empty
    top-level sections and an identity `quat`.
    """
    for section in [e for e in root if e.tag is not ET.Comment and not len(e) and not e.attrib]:
        root.remove(section)
    tol = NOISE * max(size, 1.0)
    for element in root.iter():
        if element.tag == "key" or element.tag is ET.Comment:
            continue
        for attr, text in element.attrib.items():
            if attr in _WORDS:
                continue
            rewritten = numbers(text, tol)
            if rewritten is not None:
                element.set(attr, rewritten)
        if element.get("quat") == "1 0 0 0":
            del element.attrib["quat"]


_TRIPLES = np.array(list(itertools.combinations(range(7), 3)))


def box_of(mesh: trimesh.Trimesh, tol: float = 1e-9) -> tuple[NDArray, NDArray, NDArray] | None:
    """
    (centre (3,), quaternion (4,), half sizes (3,)) if the mesh is a rectangular box (8 vertices, 12 faces, its
    corners centre +- three orthogonal half edges, to `tol` x its size), else None.
    """
    V = np.asarray(mesh.vertices, dtype=float)
    if len(V) != 8 or len(mesh.faces) != 12:
        return None
    centre = V.mean(axis=0)
    scale = float(np.max(np.linalg.norm(V - centre, axis=1)))
    D = V[1:] - V[0]  # a box's are its three edges from V[0], their pairwise sums and the diagonal
    length = np.linalg.norm(D, axis=1)
    unit = D / np.where(length > tol * scale, length, np.inf)[:, None]  # too short: never an edge (cosines 0, below)
    cosines = np.abs(unit @ unit.T)
    # the first triple (in combinations order) of long, pairwise orthogonal ones: its three edges
    i, j, k = _TRIPLES.T
    fits = np.flatnonzero((length[_TRIPLES] > tol * scale).all(axis=1) & (cosines[i, j] <= tol) & (cosines[i, k] <= tol)
                          & (cosines[j, k] <= tol))
    if not len(fits):
        return None
    triple = _TRIPLES[fits[0]]
    axes, lengths = unit[triple], length[triple]
    # order and sign the edges so that the box's frame is nearest the body's (identity when aligned)
    order = [int(np.argmax(np.abs(axes[:, k]))) for k in range(3)]
    if sorted(order) == [0, 1, 2]:
        axes, lengths = axes[order], lengths[order]
        axes *= np.sign(np.diag(axes))[:, None]
    if np.linalg.det(axes) < 0:
        axes[2] = -axes[2]
    half = lengths / 2
    local = (V - centre) @ axes.T
    if np.max(np.abs(np.abs(local) - half)) > tol * scale:
        return None
    return centre, quaternion(axes.T), half


def attach_comments(root: ET.Element) -> list[list[ET.Element]]:
    """Top-level children grouped as (comments..., element): a comment travels with the element after it."""
    groups: list[list[ET.Element]] = []
    pending: list[ET.Element] = []
    for child in root:
        pending.append(child)
        if child.tag is not ET.Comment:
            groups.append(pending)
            pending = []
    if pending:
        groups.append(pending)
    return groups
