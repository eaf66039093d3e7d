"""A scene as plain rigid bodies and hinges, for building the same model in another multibody code.

The bodies are the mechanism's, with the masses and inertias MuJoCo computes from their solids (the models the
harness runs), each posed by its principal frame at a start pose; the hinges are the mechanism's joints as world
points and axes at that pose, marked cut (a loop closure) or driven (the input). `body_poses` turns the principal
frames another code reports back into mechanism body frames, so its joint angles come from
`Mechanism.angles_from_poses` and its path error from `checks.paths.compare`, as MuJoCo's do.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..geometry import invert, quaternion_matrix
from ..mjcf import ModelOptions
from ..scenes.base import Scene
from ..simulate import compile_model


@dataclass(frozen=True)
class RigidBody:
    """
    One moving body: mass (kg), principal moments (3,) (kg m^2) about its centre of mass, `pose` (4, 4) the world
    pose of its principal frame at the start, `principal` (4, 4) that frame in the mechanism body's frame.
    """

    name: str
    mass: float
    inertia: NDArray[np.float64]
    pose: NDArray[np.float64]
    principal: NDArray[np.float64]


@dataclass(frozen=True)
class Hinge:
    """A revolute joint at the start pose: `frame` (4, 4) world frame with z along the axis; parent and child bodies
    (the root is fixed to the world); `cut` closes a loop, `driven` is the input."""

    name: str
    parent: str
    child: str
    frame: NDArray[np.float64]
    cut: bool
    driven: bool


@dataclass(frozen=True)
class RigidModel:
    """Bodies, hinges, the root body (fixed to the world) and gravity (3,) (m/s^2, world frame)."""

    bodies: tuple[RigidBody, ...]
    hinges: tuple[Hinge, ...]
    root: str
    gravity: NDArray[np.float64]


def rigid_model(scene: Scene, q: NDArray[np.float64], couplings: bool = False) -> RigidModel:
    """
    The scene at mechanism angles q (n_joints,) (a closed pose) as rigid bodies and hinges.

    Raises
    ------
    ParameterError
      For a mechanism with spherical joints, or joint couplings unless `couplings` says the caller imposes them
      (`Mechanism.couplings`: in body coordinates a coupling of two hinge angles is no standard joint).
    """
    mech = scene.mechanism
    if mech.balls or (mech.couplings and not couplings):
        raise ParameterError(f"scene {scene.name!r}: the peer model takes hinges only (no ball joints, no couplings)")
    model = compile_model(scene, ModelOptions(drive="none")).model
    poses, cut = mech.body_poses(np.asarray(q, dtype=float)), set(mech.cut_joints)
    bodies = []
    for body in mech.bodies:
        if body.name == mech.root:
            continue
        i = model.body(body.name).id
        principal = np.eye(4)
        principal[:3, :3] = quaternion_matrix(model.body_iquat[i])
        principal[:3, 3] = model.body_ipos[i]
        bodies.append(RigidBody(body.name, float(model.body_mass[i]), model.body_inertia[i].copy(),
                                poses[body.name] @ principal, principal))
    hinges = tuple(
        Hinge(j.name, j.parent, j.child, poses[j.parent] @ j.frame_parent, k in cut, j.name == scene.drive_joint)
        for k, j in enumerate(mech.joints)
    )
    gravity = np.zeros(3) if scene.gravity is None else np.asarray(scene.gravity, dtype=float)
    return RigidModel(tuple(bodies), hinges, mech.root, gravity)


def body_poses(rigid: RigidModel, principal_poses: dict[str, NDArray[np.float64]]) -> dict[str, NDArray]:
    """Mechanism body frames (n, 4, 4) from world poses (n, 4, 4) of each body's principal frame; the root fixed."""
    out = {b.name: np.asarray(principal_poses[b.name]) @ invert(b.principal) for b in rigid.bodies}
    n = len(next(iter(out.values())))
    out[rigid.root] = np.broadcast_to(np.eye(4), (n, 4, 4))
    return out


def kinetic_energy(rigid: RigidModel, velocity: dict[str, NDArray], omega_local: dict[str, NDArray]) -> NDArray:
    """Kinetic energy (n,) (J) from centre-of-mass velocities (n, 3) and angular velocities in the principal
    frames (n, 3) of every body."""
    return sum(0.5 * b.mass * np.sum(velocity[b.name] ** 2, axis=1) + 0.5 * omega_local[b.name] ** 2 @ b.inertia
               for b in rigid.bodies)


def potential_energy(rigid: RigidModel, position: dict[str, NDArray]) -> NDArray:
    """Gravitational potential energy (n,) (J) from centre-of-mass positions (n, 3) of every body."""
    return sum(-b.mass * position[b.name] @ rigid.gravity for b in rigid.bodies)


@dataclass(frozen=True)
class TreeLink:
    """
    One link of the spanning tree in minimal coordinates: `parent` the parent link's index (-1: the root, fixed to
    the world), `joint` the mechanism joint it turns about and `sign` its direction (the link's coordinate is
    sign (q_joint - q0_joint)), `transform` (4, 4) its joint frame at coordinate 0 in the parent link's frame (the
    world for the root), `body` the moving body it carries, whose principal frame in the link's frame is `com_frame`.
    """

    parent: int
    joint: int
    sign: int
    transform: NDArray[np.float64]
    body: str
    com_frame: NDArray[np.float64]


@dataclass(frozen=True)
class TreeModel:
    """
    The scene as a kinematic tree (a minimal-coordinate multibody model) at the closed pose `q0`: `links` in tree
    order (parents first), each link frame's world pose `frames` (n_links, 4, 4) at q0; the cut hinges close the
    loops, the couplings tie two tree coordinates.
    """

    rigid: RigidModel
    links: tuple[TreeLink, ...]
    frames: NDArray[np.float64]
    q0: NDArray[np.float64]
    link_of_body: dict[str, int]

    def angles(self, coordinates: NDArray[np.float64], mechanism) -> NDArray[np.float64]:
        """Every mechanism joint angle (n, n_joints) from the tree's coordinates (n, n_links): tree joints directly,
        the cut ones from the body poses (`Mechanism.angles_from_poses`)."""
        c = np.atleast_2d(coordinates)
        q = np.broadcast_to(self.q0, (len(c), len(self.q0))).copy()
        for k, link in enumerate(self.links):
            q[:, link.joint] = self.q0[link.joint] + link.sign * c[:, k]
        return mechanism.angles_from_poses(mechanism.body_poses(q))


def tree_model(scene: Scene, q: NDArray[np.float64]) -> TreeModel:
    """
    The scene at mechanism angles q (a closed pose) as the spanning tree of `Scene.mechanism` in minimal coordinates:
    the same bodies, masses and inertias as `rigid_model`, each tree hinge a link whose coordinate is 0 at q.

    Raises
    ------
    ParameterError
      As `rigid_model` for ball joints; couplings are the caller's (they tie two tree coordinates).
    """
    mech = scene.mechanism
    if mech.balls:
        raise ParameterError(f"scene {scene.name!r}: the peer model takes hinges only (no ball joints)")
    q0 = np.asarray(q, dtype=float)
    rigid = rigid_model(scene, q0, couplings=True)
    bodies = {b.name: b for b in rigid.bodies}
    poses = mech.body_poses(q0)
    link_of_body: dict[str, int] = {}
    links, frames = [], []
    for edge in mech.tree:
        j = mech.joints[edge.joint]
        start, sign = (j.frame_parent, 1) if edge.parent == j.parent else (j.frame_child, -1)
        frame = poses[edge.parent] @ start @ _turn_z(sign * q0[edge.joint])
        parent = link_of_body.get(edge.parent, -1)
        base = np.eye(4) if parent < 0 else frames[parent]
        link_of_body[edge.child] = len(links)
        links.append(TreeLink(parent, edge.joint, sign, invert(base) @ frame, edge.child,
                              invert(frame) @ bodies[edge.child].pose))
        frames.append(frame)
    return TreeModel(rigid, tuple(links), np.array(frames), q0, link_of_body)


def _turn_z(angle: float) -> NDArray[np.float64]:
    """A turn by `angle` (rad) about z as a (4, 4) transform."""
    c, s = np.cos(angle), np.sin(angle)
    out = np.eye(4)
    out[:2, :2] = [[c, -s], [s, c]]
    return out
