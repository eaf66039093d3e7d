"""Scene `cuboctahedron`: the cuboctahedron <-> octahedron transformation of Yang 2017, ch. 4.

Bodies: the 8 rigid triangles of `kinematics.cuboctahedron` (thin plates); every body frame is the deployed
world frame (4-1), root ABE. R joints at A, B, C, D, I, J, K, L are hinges through the vertex along the printed
axes (4-8, 4-9), parent the link before the joint in Bennett loop order (`HINGES`), so hinge 'A' equals
theta_A - theta_d and the hinge angles are `CuboctahedronOctahedron.revolute_angles`. S joints at E, F, G, H
are `ball_joint`s from the bottom triangle (parent) to the top one (child). No S-S bar: the assembly has no
idle spin, and its loop system has exactly the mechanism's 1 DOF.

Ball triads: x along the ball's turn axis at the octahedron (the child's rotation relative to the parent from
the cuboctahedron to the octahedron, a turn by theta_d - theta_f = 96.38 deg about (-2, 1, 0)/sqrt 5 at E,
measured to 1e-16), y = +z of (4-1), z = x cross y. The relative turn axis stays in the deployed xy plane, so
the middle angle stays within 11.6 deg of 0 on the whole path (measured on 401 samples), clear of +-90 deg.

`assembly(revolute=...)` also builds variants for mobility counts (all S, as in Yang 2017, §4.2; only Bennett 1
as R; an R joint at E, both derived here): vertices not
listed get ball joints (triad: z along the R axis it replaces), and E, F, G, H listed get hinges along the
direction to the centre.
"""

import itertools

import numpy as np

from ..errors import ParameterError
from ..geometry import frame_along, rotation_vector, transform, unit
from ..kinematics.cuboctahedron import (
    AXES,
    BOTTOM,
    HINGES,
    REVOLUTE,
    SPHERICAL,
    THETA_F,
    TRIANGLES,
    VERTICES,
    CuboctahedronOctahedron,
    faces,
)
from ..mechanism import Body, Joint, Mechanism, ball_joint
from ..origami import PALETTE
from .base import Scene, register
from .polyhedra import AssemblyKinematics, collision_plate, kutzbach, plate

WIDTH = 0.02  # plate thickness (m); geometry only, the kinematics has zero thickness
INPUT_JOINT = "A"
# Pairs of triangles that share no vertex (no joint): 16 of the 28.
CONTACT_PAIRS = tuple((a, b) for a, b in itertools.combinations(TRIANGLES, 2) if not set(a) & set(b))
ANCHORS = (0.25, 0.5)  # closure points (m) along a cut hinge's axis from its vertex, inside the polyhedron


def _bodies() -> list[Body]:
    """The 8 triangles, named by their vertices ('ABE', ...); bottom ring and top ring in two colours."""
    outward = {"".join(sorted(f)): f for f in faces()}
    out = []
    for t in TRIANGLES:
        face = outward["".join(sorted(t))]
        collision = collision_plate([VERTICES[v] for v in face])
        out.append(Body(t, plate([VERTICES[v] for v in face], WIDTH), collision, PALETTE[1 if t in BOTTOM else 2]))
    return out


def ball_triad(vertex: str) -> np.ndarray:
    """Rotation (3, 3) whose columns are the triad of the ball at E, F, G or H (see the module docstring)."""
    model = CuboctahedronOctahedron()
    parent, child = next((p, c) for v, p, c in SPHERICAL if v == vertex)
    poses = model.body_poses(THETA_F)
    x = unit(rotation_vector(poses[parent][0, :3, :3].T @ poses[child][0, :3, :3]))
    y = np.array([0.0, 0.0, 1.0])
    return np.stack([x, y, np.cross(x, y)], axis=1)


def _ends(vertex: str) -> tuple[str, str]:
    """(parent, child) triangles of the joint at a vertex."""
    return HINGES[vertex] if vertex in HINGES else next((p, c) for v, p, c in SPHERICAL if v == vertex)


def assembly(revolute: tuple[str, ...] = REVOLUTE) -> Mechanism:
    """
    The cuboctahedral linkage (Yang 2017, §4.2): hinges at the vertices in `revolute` (default the two Bennett
    linkages), balls at the other vertices; root ABE, hinge 'A' kept in the spanning tree as the input when
    it is a hinge.
    """
    unknown = sorted(set(revolute) - set(VERTICES))
    if unknown:
        raise ParameterError(f"revolute vertices {unknown} are not vertices of the cuboctahedron {sorted(VERTICES)}")
    spacers, joints = [], []
    for v, p in VERTICES.items():
        parent, child = _ends(v)
        axis = AXES[v] if v in AXES else -p  # E..H as hinges: toward the centre (a variant defined here)
        if v in revolute:
            frame = frame_along(axis, p)
            joints.append(Joint(v, parent, child, frame, frame, anchors=ANCHORS))
            continue
        frame = frame_along(axis, p) if v in AXES else transform(ball_triad(v), p)
        bodies, hinges = ball_joint(v, parent, child, frame, frame)
        spacers += bodies
        joints += hinges
    keep = (INPUT_JOINT,) if INPUT_JOINT in revolute else ()
    return Mechanism(tuple(_bodies() + spacers), tuple(joints), root="ABE", keep=keep)


@register(
    "cuboctahedron",
    "cuboctahedron <-> octahedron (Yang 2017, ch. 4): 2 Bennett linkages and 4 RSRS loops, 8 R + 4 S joints, input A",
    (),
)
def build() -> Scene:
    model = CuboctahedronOctahedron()
    mechanism = assembly()
    kinematics = AssemblyKinematics(
        model, mechanism, reference=model.theta_d, revolute=REVOLUTE, input_joint=INPUT_JOINT,
        branch=("cuboctahedron-to-octahedron", "cuboctahedron (A = 0) to octahedron (A = theta_f - theta_d < 0)"),
        vertex_bodies={v: next(t for t in TRIANGLES if v in t) for v in VERTICES},
        reference_points=list(VERTICES.values()), gruebler=kutzbach(mechanism),
    )
    lo, _ = kinematics.branch("cuboctahedron-to-octahedron").domain
    return Scene(
        name="cuboctahedron",
        params={},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=tuple(j.name for j in mechanism.joints),
        drive_joint=INPUT_JOINT,
        drive_scale=1.0,
        path=(0.0, lo),
        contact_pairs=CONTACT_PAIRS,
        notes="input A = theta_A - theta_d (rad, falls to the octahedron); S joints as MuJoCo ball joints",
    )
