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


def rigid_model(scene: Scene, q: NDArray[np.float64]) -> RigidModel:
    """
    The scene at mechanism angles q (n_joints,) (a closed pose) as rigid bodies and hinges.

    Raises
    ------
    ParameterError
      For a mechanism with spherical joints or joint couplings (only plain hinge loops are written).
    """
    mech = scene.mechanism
    if mech.balls or mech.couplings:
        raise ParameterError(f"scene {scene.name!r}: the peer model takes hinges only (no ball joints, no couplings)")
    model, _ = compile_model(scene, ModelOptions(drive="none"))
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
                                poses[body.name] @ principal, principal))  # fmt: skip
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
               for b in rigid.bodies)  # fmt: skip


def potential_energy(rigid: RigidModel, position: dict[str, NDArray]) -> NDArray:
    """Gravitational potential energy (n,) (J) from centre-of-mass positions (n, 3) of every body."""
    return sum(-b.mass * position[b.name] @ rigid.gravity for b in rigid.bodies)
