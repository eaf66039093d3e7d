"""Transformable polyhedra as scenes: an analytic model read through its assembly of plates, bars, R and S joints.

The model (a `kinematics` module, numpy only) gives the world pose of every body along its transformation; the
assembly (a `Mechanism` whose spherical joints come from `mechanism.ball_joint`) is both the numeric truth (its
loop system) and the MuJoCo model (S joints as MuJoCo ball joints). Every body frame is the reference (deployed)
world frame, so the closed form's joint angles are `Mechanism.angles_from_poses` of the model's poses.

Input: the rotation (rad) of the assembly's input hinge from the reference pose, x = theta - theta_ref with
theta the model's own input. Outputs: the R-joint angles (rad), each the rotation of its child body relative to
its parent about the hinge's +z, 0 at the reference pose, in [-pi, pi]. `evaluate` takes them from the model's
`hinge_angles` (its closed form, no poses: the throughput path), which equal the hinge columns of
`angles_from_poses` of its poses to rounding. Points: the named vertices (m, unit edges), compared with the
vertices carried by the simulated bodies.
"""

from typing import Protocol

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..errors import ParameterError
from ..geometry import transform, unit
from ..kinematics.base import Branch, Event, Kinematics, input_blocks
from ..mechanism import Mechanism
from ..solids import inset_outline, prism

# Inputs per call of a model's `hinge_angles` in `AssemblyKinematics.evaluate`: 1e6 inputs of the truncated
# tetrahedron ran 1.3e6/s in one block, 2.5e6/s in blocks of 65536 and 1.7e6/s in blocks of 4096 (measured);
# writing 15 outputs of 1e6 inputs as columns of an (n, 15) array took 82 ms, as rows of a (15, n) one 26 ms.
CHUNK = 65536


class PolyhedronModel(Protocol):
    """What a transformable polyhedron's analytic model offers (see kinematics/truncated_octahedron.py)."""

    domain: tuple[float, float]

    def body_poses(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]: ...

    def vertices(self, theta: ArrayLike) -> NDArray[np.float64]: ...

    def hinge_angles(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        Angle (n,) (rad, in [-pi, pi]) of each of the assembly's R joints, by joint name, at inputs theta (rad,
        inside `domain`): its column of `Mechanism.angles_from_poses(body_poses(theta))`, without the poses.
        """
        ...

    def events(self) -> tuple[Event, ...]: ...


class AssemblyKinematics(Kinematics):
    """
    A polyhedron model as a `Kinematics`: one branch (named by the two shapes it joins), the assembly's loop
    system as the numeric truth, and the vertices as points.

    Parameters
    ----------
    model : the analytic model; `reference` is its input (rad) at the reference pose of the assembly.
    mechanism : the assembly; its joints are the loop joints, in order.
    revolute : names of the R joints reported as outputs; `input_joint` is one of them.
    vertex_bodies : {vertex name: body that carries it}, in the order of `model.vertices`;
      `reference_points` (V, 3) their reference coordinates (m).
    gruebler : the Kutzbach count of the assembly (idle spins of S-S bars removed).

    The model's events are moved to this input (x = theta - reference) and this branch.
    """

    def __init__(
        self,
        model: PolyhedronModel,
        mechanism: Mechanism,
        *,
        reference: float,
        revolute: tuple[str, ...],
        input_joint: str,
        branch: tuple[str, str],
        vertex_bodies: dict[str, str],
        reference_points: ArrayLike,
        gruebler: int,
    ):
        self.model, self.mechanism, self.reference = model, mechanism, float(reference)
        self.input_name, self.joint_names = input_joint, tuple(revolute)
        self._columns = [mechanism.joint_index(j) for j in revolute]
        self._input = mechanism.joint_index(input_joint)
        lo, hi = model.domain
        self._branch = Branch(branch[0], branch[1], (lo - self.reference, hi - self.reference))
        self._bodies = tuple(vertex_bodies.values())
        self._local = np.asarray(reference_points, dtype=float)
        self._gruebler = gruebler
        self._events = tuple(Event(e.kind, e.input - self.reference, (branch[0],), e.detail) for e in model.events())

    def branches(self) -> tuple[Branch, ...]:
        return (self._branch,)

    def angles(self, x: ArrayLike) -> NDArray[np.float64]:
        """Every assembly joint angle (n, n_joints) of the closed form at inputs x (rad, inside the domain)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return self.mechanism.angles_from_poses(self.model.body_poses(x + self.reference))

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        x, valid = self.in_domain(branch, x)
        if np.all(valid):
            return self._hinges(x), valid
        values = np.full((len(x), len(self.joint_names)), np.nan)
        if np.any(valid):
            values[valid] = self._hinges(x[valid])
        return values, valid

    def _hinges(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """
        The outputs (n, len(joint_names)) (rad) at inputs x inside the domain, from the model's `hinge_angles`, in
        blocks of CHUNK inputs (their temporaries stay in cache): the transpose of a (k, n) array filled by rows.
        """
        out = np.empty((len(self.joint_names), len(x)))
        for block in input_blocks(len(x), CHUNK):
            columns = self.model.hinge_angles(x[block] + self.reference)
            missing = sorted(set(self.joint_names) - set(columns))
            if missing:
                raise ParameterError(f"revolute joints {missing} have no closed-form angle in the model's hinge_angles")
            for k, name in enumerate(self.joint_names):
                out[k, block] = columns[name]
        return out.T

    def events(self) -> tuple[Event, ...]:
        return self._events

    def gruebler(self) -> int:
        return self._gruebler

    def loop_system(self) -> LoopSystem:
        return self.mechanism.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return self._input, 1.0

    def observe(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        return np.atleast_2d(np.asarray(q_loop, dtype=float))[:, self._columns]

    def loop_angles(self, values: ArrayLike) -> NDArray[np.float64]:
        values = np.atleast_2d(np.asarray(values, dtype=float))
        return self.angles(values[:, self.joint_names.index(self.input_name)])

    def points(self, branch: str, x: ArrayLike) -> NDArray[np.float64]:
        x, _ = self.in_domain(branch, x)
        return self.model.vertices(x + self.reference)

    def observe_points(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        poses = self.mechanism.body_poses(np.atleast_2d(np.asarray(q_loop, dtype=float)))
        return np.stack(
            [poses[b][:, :3, :3] @ p + poses[b][:, :3, 3] for b, p in zip(self._bodies, self._local, strict=True)], 1
        )


def kutzbach(mechanism: Mechanism) -> int:
    """Spatial Grubler-Kutzbach count 6 (n - 1 - j) + sum f of the assembly, minus its S-S bars' idle spins."""
    reduced = mechanism.reduced()
    freedoms = sum(3 if j.name in mechanism.balls else 1 for j in reduced.joints)
    return 6 * (len(reduced.bodies) - 1 - len(reduced.joints)) + freedoms - mechanism.idle_spins


# Collision plates (m): thinner than the visual plates and inset from every edge, so plates only touch when
# their edges meet: 9.8 mrad of A1 before the cube on the truncated octahedron (measured). A thinner plate
# (0.01 m, contact 3.7 mrad early) let the force-limited servo bounce off the contact and stop 5 mrad short
# of it after the 1 s hold.
COLLISION_THICKNESS = 0.02
COLLISION_INSET = 0.002


def plate(corners: ArrayLike, thickness: float, inset: float = 0.0) -> trimesh.Trimesh:
    """
    A convex plate on a planar convex face given by its corners (k, 3) in cyclic order (m): the face inset by
    `inset` from every edge, `thickness` thick, centred on the face's plane (visual solids and collision solids).
    """
    P = np.asarray(corners, dtype=float)
    centre = P.mean(0)
    x = unit(P[1] - P[0])
    z = unit(np.cross(P[1] - P[0], P[2] - P[1]))  # the outline is counter-clockwise about z
    R = np.stack([x, np.cross(z, x), z], axis=1)
    outline = (P - centre) @ R[:, :2]
    if inset:
        outline = inset_outline(outline, np.full(len(P), inset))
    return prism(outline, thickness).apply_transform(transform(R, centre))


def collision_plate(corners: ArrayLike) -> trimesh.Trimesh:
    """The collision solid of a face: `plate` COLLISION_THICKNESS thick, inset COLLISION_INSET."""
    return plate(corners, COLLISION_THICKNESS, COLLISION_INSET)
