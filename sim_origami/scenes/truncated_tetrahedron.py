"""Scenes `truncated-tetrahedron-i` and `-ii`: the truncated tetrahedron <-> tetrahedron of Yang 2017, ch. 6.

Bodies: the 4 triangles (thin plates)
and the 6 bars (`linkage.bar`) of `kinematics.truncated_tetrahedron`, every body frame the deployed world
frame (6-1), root triangle ABG. R joints are hinges through their vertex along the model's axes (parent ->
child as in `PARENTS`, so every hinge angle equals the model's `revolute_angles`); S joints are `ball_joint`s
at their vertex: scheme I at K, L, M (bar -> KLM), scheme II at G, H, J (triangle -> bar). No bar has a ball
at both ends, so there is no idle spin: 9 R + 3 S (18 joint angles), 16 bodies with the spacers, 3 loops,
mobility 1.

Ball triads: z along the axis of the largest relative turn of the ball's two bodies on the path, x turned
about z to the one of 12 angles in [0, 180) deg that keeps the middle angle b smallest along the path
(max |b| about 12 deg scheme I, 3.5 deg scheme II at delta = 0; `max_middle_angle`).
"""

import itertools

import numpy as np

from ..errors import ParameterError
from ..geometry import frame_along, rotation_vector, transform, transform_z
from ..kinematics.truncated_tetrahedron import (
    BARS,
    NAMES,
    PARENTS,
    ROOT,
    TRIANGLES,
    VERTICES,
    SchemeI,
    SchemeII,
    Transformation,
    bricard_axes,
)
from ..linkage import bar
from ..mechanism import Body, Joint, Mechanism, ball_joint
from ..origami import PALETTE
from .base import ANGLE_MARGIN, Param, Scene, register
from .polyhedra import AssemblyKinematics, collision_plate, kutzbach, plate

WIDTH = 0.04  # bar and plate thickness (m); geometry only, the kinematics has zero thickness
INPUT_JOINT = {"I": "G", "II": "A"}  # the model's input: theta_G (scheme I), the Bricard theta at A (II)
BALLS = {"I": ("K", "L", "M"), "II": ("G", "H", "J")}
TRIANGLE_PAIRS = tuple(itertools.combinations(TRIANGLES, 2))  # no two triangles share a joint


def model(scheme: str, delta: float = 0.0) -> Transformation:
    """The closed form of scheme 'I' or 'II' with axis deviation delta (rad)."""
    if scheme not in INPUT_JOINT:
        raise ParameterError(f"scheme {scheme!r} is not one of 'I', 'II' (Yang 2017, §6.3-6.4)")
    return SchemeI(delta) if scheme == "I" else SchemeII(delta)


def _bodies() -> list[Body]:
    """
    The 4 triangles 'ABG', 'CDH', 'EFJ', 'KLM' (thin plates with the collision plates of
    `polyhedra.collision_plate`) and the 6 bars 'BC', ..., 'JM'.
    """
    out = []
    for k, t in enumerate(TRIANGLES):
        corners = [VERTICES[v] for v in t]
        out.append(Body(t, plate(corners, WIDTH), collision_plate(corners), PALETTE[k % len(PALETTE)]))
    for b in BARS:
        out.append(Body(b, bar(VERTICES[b[0]], VERTICES[b[1]], WIDTH), None, (0.3, 0.3, 0.3, 1.0)))
    return out


def _hinge(name: str, axis: np.ndarray) -> Joint:
    parent, child = PARENTS[name]
    frame = frame_along(axis, VERTICES[name])
    return Joint(name, parent, child, frame, frame, anchors=(0.25, 0.5))


def revolute_axes(kinematics: Transformation) -> dict[str, np.ndarray]:
    """Unit axes (3,) of the model's R joints in the deployed frame, by name."""
    out = dict(zip("ABCDEF", bricard_axes(), strict=True))
    top = kinematics.REVOLUTE[6:]
    axis = kinematics.s_g if isinstance(kinematics, SchemeI) else kinematics.s_k
    for k, name in enumerate(top):
        turn = transform_z(2 * np.pi * k / 3)[:3, :3]
        out[name] = turn @ axis
    return out


def ball_triads(kinematics: Transformation, samples: int = 41) -> dict[str, np.ndarray]:
    """
    Triad frames (4, 4) (deployed frame, origin at the vertex) of the three S joints, chosen on `samples`
    poses of the path as the module docstring says; the three are threefold images of each other.
    """
    names = BALLS["I" if isinstance(kinematics, SchemeI) else "II"]
    parent, child = _ball_bodies(names[0])
    poses = kinematics.body_poses(np.linspace(*kinematics.domain, samples))
    R = np.swapaxes(poses[parent][:, :3, :3], 1, 2) @ poses[child][:, :3, :3]
    turns = rotation_vector(R)
    base = frame_along(turns[np.argmax(np.linalg.norm(turns, axis=1))])[:3, :3]
    best, frame = np.inf, base
    for a in np.linspace(0.0, np.pi, 12, endpoint=False):
        F = base @ transform_z(a)[:3, :3]
        worst = np.max(np.abs((F.T @ R @ F)[:, 0, 2]))
        if worst < best:
            best, frame = worst, F
    out = {}
    for k, name in enumerate(names):
        turn = transform_z(2 * np.pi * k / 3)[:3, :3]
        out[name] = transform(turn @ frame, VERTICES[name])
    return out


def _ball_bodies(name: str) -> tuple[str, str]:
    """(parent, child) of the S joint at vertex `name`: triangle -> bar at G, H, J; bar -> KLM at K, L, M."""
    bars = {"G": "GK", "H": "HL", "J": "JM", "K": "GK", "L": "HL", "M": "JM"}
    triangles = {"G": "ABG", "H": "CDH", "J": "EFJ"}
    return (triangles[name], bars[name]) if name in triangles else (bars[name], "KLM")


def assembly(scheme: str = "II", delta: float = 0.0) -> Mechanism:
    """
    The 1-DOF truncated-tetrahedron assembly of scheme 'I' or 'II' (Yang 2017, ch. 6) with axis deviation delta
    (rad, delta1 or delta2); root triangle ABG, the input hinge (`INPUT_JOINT`) kept in the spanning tree.
    """
    return assembly_of(model(scheme, delta))


def assembly_of(kinematics: Transformation) -> Mechanism:
    """The assembly of an existing closed form (`SchemeI` or `SchemeII`), as `assembly` describes."""
    scheme = "I" if isinstance(kinematics, SchemeI) else "II"
    axes = revolute_axes(kinematics)
    hinges = [_hinge(name, axes[name]) for name in kinematics.REVOLUTE]
    spacers, balls = [], []
    for name, frame in ball_triads(kinematics).items():
        parent, child = _ball_bodies(name)
        bodies, joints = ball_joint(name, parent, child, frame, frame)
        spacers += bodies
        balls += joints
    return Mechanism(tuple(_bodies() + spacers), tuple(hinges + balls), root=ROOT, keep=(INPUT_JOINT[scheme],))


def _scene(scheme: str, delta: float) -> Scene:
    closed_form = model(scheme, delta)
    mechanism = assembly_of(closed_form)
    name = f"truncated-tetrahedron-{scheme.lower()}"
    lo, hi = closed_form.domain
    end = "tetrahedron" if any("tetrahedron:" in e.detail for e in closed_form.events()) else "bricard-fold"
    kinematics = AssemblyKinematics(
        closed_form, mechanism, reference=closed_form.reference, revolute=closed_form.REVOLUTE,
        input_joint=INPUT_JOINT[scheme], branch=(f"deployed-to-{end}", f"truncated tetrahedron to the {end}"),
        vertex_bodies={v: next(t for t in TRIANGLES if v in t) for v in NAMES},
        reference_points=[VERTICES[v] for v in NAMES], gruebler=kutzbach(mechanism),
    )
    far = hi if abs(hi - closed_form.reference) > abs(lo - closed_form.reference) else lo
    return Scene(
        name=name,
        params={"delta": delta},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=tuple(j.name for j in mechanism.joints),
        drive_joint=INPUT_JOINT[scheme],
        drive_scale=1.0,
        path=(0.0, far - closed_form.reference),
        # The default tuning. At the preset's 2 s sweep: stiff 1.2e-5 rad (I) and 1.1e-5 (II); fast 9.1e-5 and 3.6e-5
        # with MuJoCo's regulariser, 2.0e-6 and 1.2e-6 with the presets' (scaled 0.01). Without the former 1.25x fast
        # step `validate` measured the same path errors (the path rule lengthened the sweep with the step) at 0.93x
        # (II) and 1.17x (I) the CPU, all of it in the blockage run.
        contact_pairs=TRIANGLE_PAIRS,
        notes=f"input {INPUT_JOINT[scheme]} = {closed_form.input_name} - its deployed value (rad); "
        "S joints as MuJoCo ball joints",
    )


@register(
    "truncated-tetrahedron-i",
    "truncated tetrahedron <-> tetrahedron, scheme I (Yang 2017, ch. 6): Bricard + S joints at K, L, M, input G",
    (Param("delta", "deg", 0.0, "delta1: turn of the G, H, J axes (Yang 2017, §6.5); <= -3.5 deg reaches the end",
           lo=ANGLE_MARGIN - 90, hi=90 - ANGLE_MARGIN),),
)
def build_scheme_1(delta: float) -> Scene:
    return _scene("I", delta)


@register(
    "truncated-tetrahedron-ii",
    "truncated tetrahedron <-> tetrahedron, scheme II (Yang 2017, ch. 6): Bricard + S joints at G, H, J, input A",
    (Param("delta", "deg", 0.0, "delta2: turn of the K, L, M axes (Yang 2017, §6.5); >= 0 reaches the tetrahedron",
           lo=ANGLE_MARGIN - 90, hi=90 - ANGLE_MARGIN),),
)
def build_scheme_2(delta: float) -> Scene:
    return _scene("II", delta)
