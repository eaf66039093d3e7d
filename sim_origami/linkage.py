"""Spatial linkages from Denavit-Hartenberg rows: link bodies and revolute joints.

Link k (k = 1..n) joins joint k to joint k+1. Its body frame is joint k's D-H frame after
Rz(theta_k), so joint k+1 sits at `rows[k].link()` = Tz(R_k) Tx(a_k) Rx(alpha_k) in it, and joint k+1's
angle is theta_(k+1) exactly (child link k+1 relative to parent link k about +z). Link n is the
ground (fixed to the world); the input joint stays in the spanning tree and one other joint is cut
to close the loop, with two anchors on its axis.
"""

import numpy as np
import trimesh

from .kinematics.dh import DHRow
from .mechanism import Body, Joint, Mechanism
from .origami import PALETTE


def bar(p0: np.ndarray, p1: np.ndarray, width: float) -> trimesh.Trimesh:
    """A square bar (box) of side `width` from p0 to p1 (at least `width` long)."""
    d = np.asarray(p1, float) - np.asarray(p0, float)
    length = max(float(np.linalg.norm(d)), width)
    x = d / np.linalg.norm(d) if np.linalg.norm(d) > 1e-12 else np.array([1.0, 0.0, 0.0])
    helper = np.array([0.0, 0.0, 1.0]) if abs(x[2]) < 0.9 else np.array([0.0, 1.0, 0.0])
    y = np.cross(helper, x)
    y /= np.linalg.norm(y)
    T = np.eye(4)
    T[:3, :3] = np.stack([x, y, np.cross(x, y)], axis=1)
    T[:3, 3] = (np.asarray(p0, float) + np.asarray(p1, float)) / 2
    return trimesh.creation.box(extents=(length, width, width), transform=T)


def dh_mechanism(
    rows: tuple[DHRow, ...], *, width: float = 0.05, anchor: float = 0.5, input_joint: int = 1
) -> Mechanism:
    """
    Links and joints of a single D-H loop; joints are named joint_1 .. joint_n.

    Parameters
    ----------
    rows : D-H rows of joints 1..n (metres, radians).
    width : float
      Side of the link bars (m).
    anchor : float
      The cut joint is closed at +/- `anchor` (m) along its axis from its D-H origin.
    input_joint : int
      Joint (1-based) that is driven; it stays in the spanning tree, and the cut falls on the
      highest-numbered joint that closes the loop (joint n unless that is the input).
    """
    n = len(rows)
    bodies = []
    for k, row in enumerate(rows):
        end = row.link()[:3, 3]
        bodies.append(Body(f"link_{k + 1}", bar(np.zeros(3), end, width), None, PALETTE[k % len(PALETTE)]))
    joints = []
    for j in range(n):
        joints.append(
            Joint(
                f"joint_{j + 1}",
                parent=f"link_{(j - 1) % n + 1}",
                child=f"link_{j + 1}",
                frame_parent=rows[(j - 1) % n].link(),
                frame_child=np.eye(4),
                anchors=(-anchor, anchor),
            )
        )
    return Mechanism(tuple(bodies), tuple(joints), root=f"link_{n}", keep=(f"joint_{input_joint}",))
