"""The truncated-octahedron assembly of seed 001 ch. 5 as a mechanism graph (numeric loop closure only).

No scene is registered: the seed's 1-DOF design has 9 spherical joints (E3, F3, D3 and both ends of the
bars A4F4, B4D4, C4E4), and `Mechanism` / `mjcf` know revolute joints only (the change they need is in the
issue report). For the numeric truth each spherical joint is written here as concurrent revolute joints
through the vertex, which is exact kinematics as long as the chain stays away from its gimbal lock:

* at E3, F3, D3, F4, D4, E4: three hinges along an orthonormal triad (a full ball);
* at A4, B4, C4: two hinges square to the bar (a universal joint), which drops the bar's idle spin about
  its own axis, as the seed does (digest §5), so the loop system has exactly the mechanism's 1 DOF.

Frames: every body frame is the deployed world frame of `kinematics.polyhedra` (square A is the root), every
joint angle is 0 at the truncated octahedron, and joint 'A1' (Bricard 1's odd joint on square A, parent bar
B2A1, axis O -> A1) equals theta - theta_d.
"""

import numpy as np
import trimesh

from ..geometry import frame_along, transform, unit
from ..kinematics.polyhedra import (
    BARS,
    BRICARD_1,
    IMAGE,
    R2,
    RS_BARS,
    SQUARES,
    SS_BARS,
    VERTICES,
    TruncatedOctahedronCube,
    bricard_axes,
)
from ..linkage import bar
from ..mechanism import Body, Joint, Mechanism
from ..origami import PALETTE

WIDTH = 0.04  # bar and plate thickness (m); geometry only, the kinematics has zero thickness
INPUT_JOINT = "A1"


def threefold(v: np.ndarray) -> np.ndarray:
    """The threefold turn (x, y, z) -> (z, x, y) about (1, 1, 1), which maps square A onto B and C onto A."""
    return np.array([v[2], v[0], v[1]])


def _plate(corners: list[np.ndarray]) -> trimesh.Trimesh:
    """A thin box of thickness WIDTH spanning a unit square given by its 4 corners in cyclic order."""
    x, y = unit(corners[1] - corners[0]), unit(corners[3] - corners[0])
    frame = transform(np.stack([x, y, np.cross(x, y)], axis=1), np.mean(corners, axis=0))
    return trimesh.creation.box(extents=(1.0, 1.0, WIDTH), transform=frame)


def _bodies() -> list[Body]:
    """The 6 squares (thin plates) and the 12 bars, named 'A'..'F' and e.g. 'A2C1'."""
    out = []
    for k, square in enumerate(SQUARES):
        out.append(Body(square[0][0], _plate([VERTICES[v] for v in square]), None, PALETTE[k % len(PALETTE)]))
    for a, b in BARS:
        out.append(Body(a + b, bar(VERTICES[a], VERTICES[b], WIDTH), None, (0.3, 0.3, 0.3, 1.0)))
    return out


def _hinge(name: str, parent: str, child: str, vertex: str, axis: np.ndarray) -> Joint:
    frame = frame_along(axis, VERTICES[vertex])
    return Joint(name, parent, child, frame, frame, anchors=(0.25, 0.5))


def _revolute(zeta: float) -> list[Joint]:
    """The 15 R joints: both Bricards (parent = the link before the joint in loop order) and A3, B3, C3."""
    _, dirs = bricard_axes()
    links = ("B2A1", "A", "A2C1", "C", "C2B1", "B")  # the link before joint k of BRICARD_1
    joints = []
    for k, vertex in enumerate(BRICARD_1):
        parent, child = links[k], links[(k + 1) % 6]
        joints.append(_hinge(vertex, parent, child, vertex, dirs[k]))
        image = vertex.translate(IMAGE)
        joints.append(_hinge(image, parent.translate(IMAGE), child.translate(IMAGE), image, R2 @ dirs[k]))
    axis = TruncatedOctahedronCube(zeta).s_a3
    for (vertex, end), square in zip(RS_BARS, "ABC", strict=True):
        joints.append(_hinge(vertex, square, vertex + end, vertex, axis))
        axis = threefold(axis)
    return joints


def _triad(u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An orthonormal triad whose first vector is unit(u)."""
    frame = frame_along(u)
    return frame[:3, 2], frame[:3, 0], frame[:3, 1]


def _spherical() -> tuple[list[Body], list[Joint]]:
    """The 9 S joints as hinge chains through the vertex (see the module docstring), with their spacer bodies."""
    bodies, joints = [], []

    def chain(vertex: str, parent: str, child: str, axes: tuple[np.ndarray, ...]) -> None:
        names = [parent] + [f"{vertex}_g{k}" for k in range(1, len(axes))] + [child]
        for name in names[1:-1]:
            bodies.append(Body(name, bar(VERTICES[vertex], VERTICES[vertex] + WIDTH, WIDTH), None))
        for k, axis in enumerate(axes):
            joints.append(_hinge(f"{vertex}_s{k + 1}", names[k], names[k + 1], vertex, axis))

    for start, end in RS_BARS:
        chain(end, start + end, end[0], _triad(VERTICES[end]))
    for start, end in SS_BARS:
        along = unit(VERTICES[end] - VERTICES[start])
        _, u, v = _triad(along)
        chain(start, start[0], start + end, (u, v))
        chain(end, start + end, end[0], _triad(VERTICES[end]))
    return bodies, joints


def assembly(zeta: float = 0.0) -> Mechanism:
    """
    The 1-DOF truncated-octahedron assembly (seed 001 §2.7), spherical joints as hinge chains; root square A,
    joint 'A1' kept in the spanning tree as the input.
    """
    spacers, balls = _spherical()
    return Mechanism(tuple(_bodies() + spacers), tuple(_revolute(zeta) + balls), root="A", keep=(INPUT_JOINT,))
