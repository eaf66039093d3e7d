"""Non-overconstrained forms of single-loop linkages as mechanisms: some revolute joints of a D-H loop replaced by
spherical joints (Yang 2017, ch. 3: Bennett -> RSSR with balls at joints 3 and 4, Myard -> RRSRR with
a ball at joint 1, RSRRR with a ball at joint 2).

Bodies and frames as in `linkage.dh_mechanism`: link k (k = 1..n) joins joint k to joint k+1, its frame is joint
k's D-H frame after Rz(theta_k), link n is the ground (root). A hinge is `joint_<k>` (angle theta_k); a ball is
`mechanism.ball_joint('ball_<k>', ...)` whose triad is joint k's D-H frame, so on the closed form's motion (a
turn about the former axis) its angles are (0, 0, theta_k), far from the triad's singularity (middle angle
+-pi/2). A ball whose last hinge is cut becomes one MuJoCo `connect` at its centre.

The RSSR of `fabrication.RSSR` is built on the D-H rows of its implied Bennett linkage: the ground twist only
sets the orientation of the ground's frame about DA (the ball at D has no axis), so the geometry MuJoCo sees is
the RSSR's alone (a1, a2, alpha and the perpendicularities), and its motion is an independent check of (3-5).
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .errors import ParameterError
from .geometry import transform_z
from .kinematics.dh import DHRow
from .kinematics.rssr import RSSR
from .linkage import bar
from .mechanism import Body, Joint, Mechanism, ball_joint
from .origami import PALETTE


def reduced_form(
    rows: tuple[DHRow, ...],
    spherical: tuple[int, ...],
    *,
    width: float = 0.05,
    anchor: float = 0.5,
    input_joint: int = 1,
) -> Mechanism:
    """
    A single D-H loop with the joints in `spherical` (1-based) as ball joints, the others as hinges.

    Parameters
    ----------
    rows : D-H rows of joints 1..n (length unit, radians).
    spherical : joints that become balls (not the input).
    width : side of the link bars (length unit).
    anchor : a cut hinge is closed at +-`anchor` along its axis from its D-H origin.
    input_joint : the driven hinge (1-based), kept in the spanning tree.
    """
    n = len(rows)
    bad = sorted({k for k in spherical if not 1 <= k <= n} | ({input_joint} & set(spherical)))
    if bad or not 1 <= input_joint <= n:
        raise ParameterError(f"spherical joints {sorted(spherical)}, input joint {input_joint}: joints are 1..{n} "
                             "and the input must stay a hinge")
    if not (width > 0 and anchor > 0):
        raise ParameterError(f"width = {width!r}, anchor = {anchor!r}; both must be positive lengths")
    bodies = [Body(f"link_{k + 1}", bar(np.zeros(3), row.link()[:3, 3], width), None, PALETTE[k % len(PALETTE)])
              for k, row in enumerate(rows)]
    joints: list[Joint] = []
    for j in range(1, n + 1):
        parent, child, frame = f"link_{(j - 2) % n + 1}", f"link_{j}", rows[(j - 2) % n].link()
        if j in spherical:
            spacers, hinges = ball_joint(f"ball_{j}", parent, child, frame, np.eye(4))
            bodies += spacers
            joints += hinges
        else:
            joints.append(Joint(f"joint_{j}", parent, child, frame, np.eye(4), anchors=(-anchor, anchor)))
    return Mechanism(tuple(bodies), tuple(joints), root=f"link_{n}", keep=(f"joint_{input_joint}",))


def chain_poses(rows: tuple[DHRow, ...], q: ArrayLike) -> dict[str, NDArray[np.float64]]:
    """World poses (m, 4, 4) of links 1..n of a closed D-H loop at loop angles q (m, n) (rad); link n fixed."""
    q = np.atleast_2d(np.asarray(q, dtype=float))
    n = len(rows)
    if q.shape[1] != n or not np.all(np.isfinite(q)):
        raise ParameterError(f"q has shape {q.shape}; rows must hold {n} finite loop angles (rad)")
    poses = {f"link_{n}": np.broadcast_to(np.eye(4), (len(q), 4, 4))}
    T = poses[f"link_{n}"]
    for k in range(n - 1):
        T = T @ rows[(k - 1) % n].link() @ transform_z(q[:, k])
        poses[f"link_{k + 1}"] = T
    return poses


@dataclass(frozen=True)
class FormMotion:
    """
    A reduced form's closed-form motion over its input (rad): D-H rows and loop angles (m, n) of inputs (m,).
    Meets `scenes.polyhedra.PolyhedronModel`: body poses, the joint origins as points (m, n, 3), no events.
    """

    rows: tuple[DHRow, ...]
    loop_angles: Callable[[NDArray[np.float64]], NDArray[np.float64]]
    domain: tuple[float, float] = (-np.pi, np.pi)

    def body_poses(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        return chain_poses(self.rows, self.loop_angles(np.atleast_1d(np.asarray(theta, dtype=float))))

    def vertices(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Joint k's origin (link k's frame origin), (m, n, 3)."""
        poses = self.body_poses(theta)
        return np.stack([poses[f"link_{k + 1}"][:, :3, 3] for k in range(len(self.rows))], axis=1)

    def hinge_angles(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        Loop angle k (n,) (rad) as 'joint_<k>', the hinge name `reduced_form` gives joint k, shifted into
        [-pi, pi] by 2 pi where it lies outside (the hinge angle of the poses; a ball's name is not among them).
        """
        q = self.loop_angles(np.atleast_1d(np.asarray(theta, dtype=float)))
        q = np.where(q > np.pi, q - 2 * np.pi, np.where(q < -np.pi, q + 2 * np.pi, q))
        return {f"joint_{k + 1}": q[:, k] for k in range(len(self.rows))}

    def events(self) -> tuple:
        return ()


def rssr_mechanism(rssr: RSSR, *, width: float | None = None) -> Mechanism:
    """The RSSR (balls at C = joint 3 and D = joint 4) on its implied Bennett's rows; bars 5% of a1 wide."""
    return reduced_form(rssr.bennett_rows(), (3, 4), width=0.05 * rssr.a1 if width is None else width,
                        anchor=0.5 * max(rssr.a1, rssr.a2))


def rssr_motion(rssr: RSSR) -> FormMotion:
    """The RSSR's exact motion (3-5) over theta1 (rad) as body poses of `rssr_mechanism`."""
    return FormMotion(rssr.bennett_rows(), rssr.loop_angles)
