"""Scene `truncated-octahedron`: the truncated octahedron <-> cube transformation of Yang 2017, ch. 5.

The thesis's 1-DOF design: 6 squares and 12 bars, two threefold-symmetric Bricard linkages, R joints at A3,
B3, C3 joining squares A, B, C to the bars A3E3, B3F3, C3D3, and 9 spherical joints (E3, F3, D3 and both
ends of the bars A4F4, B4D4, C4E4), which MuJoCo models as ball joints (`mechanism.ball_joint`). The S-S bars'
idle spins are free coordinates of the loop system and of MuJoCo, not counted as mobility.

Frames: every body frame is the deployed world frame of `kinematics.truncated_octahedron` (square A is the
root), every joint angle is 0 at the truncated octahedron, and the input joint 'A1' (Bricard 1's odd joint on
square A, parent bar B2A1, axis O -> A1) equals theta - theta_d. Outputs: the 15 R-joint angles.
"""

import itertools

import numpy as np

from ..errors import ParameterError
from ..geometry import frame_along
from ..kinematics.truncated_octahedron import (
    BARS,
    NAMES,
    RS_BARS,
    SQUARES,
    SS_BARS,
    VERTICES,
    PathOutcome,
    TruncatedOctahedronCube,
    revolute_axes,
)
from ..linkage import bar
from ..mechanism import Body, Joint, Mechanism, ball_joint
from ..origami import PALETTE
from .base import Param, Scene, Tuning, register
from .polyhedra import AssemblyKinematics, collision_plate, kutzbach, plate

WIDTH = 0.04  # bar and plate thickness (m); geometry only, the kinematics has zero thickness
INPUT_JOINT = "A1"
SQUARE_PAIRS = tuple(itertools.combinations([square[0][0] for square in SQUARES], 2))  # no square shares a joint
# Why it sweeps slower than its path's rates ask (`Tuning.why`; the measurements in `interference_scene`).
WHY = ("its blockage run stops at the cube's contact only at about 16x the preset's sweep: at the path "
       "rule's 3.5x it stopped 1.5e-2 rad short (tolerance 3e-3), at 4.5 x that 9.6e-10 rad")


def _bodies() -> list[Body]:
    """The 6 squares (thin plates with collision plates) and the 12 bars, named 'A'..'F' and e.g. 'A2C1'."""
    out = []
    for k, square in enumerate(SQUARES):
        corners = [VERTICES[v] for v in square]
        out.append(Body(square[0][0], plate(corners, WIDTH), collision_plate(corners), PALETTE[k % len(PALETTE)]))
    for a, b in BARS:
        out.append(Body(a + b, bar(VERTICES[a], VERTICES[b], WIDTH), None, (0.3, 0.3, 0.3, 1.0)))
    return out


def _hinge(name: str, parent: str, child: str, vertex: str, axis: np.ndarray) -> Joint:
    frame = frame_along(axis, VERTICES[vertex])
    return Joint(name, parent, child, frame, frame, anchors=(0.25, 0.5))


def _revolute(zeta: float) -> list[Joint]:
    """The 15 R joints, each from the bar at its vertex (parent) to the square of its letter (child)."""
    return [_hinge(vertex, next(a + b for a, b in BARS if vertex in (a, b)), vertex[0], vertex, axis)
            for vertex, axis in revolute_axes(zeta).items()]


def _spherical() -> tuple[list[Body], list[Joint]]:
    """
    The 9 S joints as ball joints from bar (parent) to square (child). Each triad has z along the vertex's
    radius: on the path the middle angle stays within 0.83 rad of 0 (measured; singular at pi/2).
    """
    bodies, joints = [], []
    for start, end in RS_BARS + SS_BARS + tuple((e, s) for s, e in SS_BARS):
        triad = frame_along(VERTICES[end], VERTICES[end])
        spacers, hinges = ball_joint(end, start + end if (start, end) in BARS else end + start, end[0], triad, triad)
        bodies += spacers
        joints += hinges
    return bodies, joints


def assembly(zeta: float = 0.0) -> Mechanism:
    """
    The 1-DOF truncated-octahedron assembly (Yang 2017, §5.3); root square A, joint 'A1' kept in the spanning
    tree as the input.
    """
    spacers, balls = _spherical()
    return Mechanism(tuple(_bodies() + spacers), tuple(_revolute(zeta) + balls), root="A", keep=(INPUT_JOINT,))


@register(
    "truncated-octahedron",
    "truncated octahedron <-> cube (Yang 2017, ch. 5): two threefold Bricards, 15 R + 9 S joints, input A1",
    # Yang 2017, §5.5's feasible designs, rounded outward: outside, the trace that `build` refuses them after (5-10 s
    # of CPU) is skipped; inside, the few designs near the ends that are not drivable are still traced and refused.
    (Param("zeta", "deg", 0.0, "deviation of the A3, B3, C3 axes from the direction to the centre",
           lo=-61.0, hi=19.5, limit="designs outside reach no cube with A1 rising (Yang 2017, §5.5); "
           "interference_scene(zeta) simulates any"),),
)
def build(zeta: float) -> Scene:
    """
    The scene of a design whose path reaches the cube with A1 rising monotonically (measured here: zeta in
    about [-60.7, 18.9] deg; Yang 2017, §5.5 gives -60.9 to 19.5); ParameterError naming zeta and how its path
    ends otherwise (`interference_scene` builds such a design for simulation from the deployed pose).
    """
    model = TruncatedOctahedronCube(zeta)
    outcome = model.outcome()
    if not outcome.drivable:
        raise ParameterError(
            f"zeta = {np.rad2deg(zeta):.6g} deg: {describe(outcome)}; the closed form follows only designs whose "
            "path reaches the cube (rho1 = rho2 = 0 together) with theta rising monotonically (Yang 2017, §5.5: "
            "feasible -60.9 <= zeta <= 19.5 deg); simulate it with interference_scene(zeta)"
        )
    return interference_scene(zeta, model, drivable=True)


def describe(outcome: PathOutcome) -> str:
    """One line (degrees) on how a design's path ends (`TruncatedOctahedronCube.outcome`)."""
    deg = np.rad2deg
    turns = f", theta turns back at {', '.join(f'{deg(t):.4g}' for t in outcome.turns)} deg" if outcome.turns else ""
    ends = {
        "cube": "reaches the cube",
        "rho1-negative": f"Bricard 1 folds (rho1 = 0) while rho2 = {deg(outcome.rho2):.4g} deg, so squares A, B, C "
        "would pass through each other",
        "rho2-negative": f"Bricard 2 folds (rho2 = 0) while rho1 = {deg(outcome.rho1):.4g} deg, so squares D, E, F "
        "would pass through each other",
        "loop": "closes back on the truncated octahedron without reaching a fold",
        "no-end": "reaches no fold",
    }
    return f"the path {ends[outcome.kind]}{turns}"


def interference_scene(
    zeta: float, model: TruncatedOctahedronCube | None = None, drivable: bool | None = None
) -> Scene:
    """
    The scene of any design (zeta in rad), without `build`'s check: for designs outside the feasible range only
    the mechanism, its drive and its contact pairs are meaningful (simulate from the deployed pose, `initial` =
    zeros, to A1 = theta_f - theta_d); the closed form's poses exist only where its path is a function of theta.
    `drivable`: whether the closed form follows the design to the cube (`outcome`, traced when not given).
    """
    model = model or TruncatedOctahedronCube(zeta)
    drivable = model.outcome().drivable if drivable is None else drivable
    mechanism = assembly(zeta)
    revolute = tuple(revolute_axes(zeta))
    cube = model.theta_f - model.theta_d
    kinematics = AssemblyKinematics(
        model, mechanism, reference=model.theta_d, revolute=revolute, input_joint=INPUT_JOINT,
        branch=("octahedron-to-cube", "truncated octahedron (A1 = 0) to cube (A1 = theta_f - theta_d)"),
        vertex_bodies={v: v[0] for v in NAMES}, reference_points=[VERTICES[v] for v in NAMES],
        gruebler=kutzbach(mechanism),
    )
    return Scene(
        name="truncated-octahedron",
        params={"zeta": zeta},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=tuple(j.name for j in mechanism.joints),
        drive_joint=INPUT_JOINT,
        drive_scale=1.0,
        path=(0.0, cube),
        # Seven coupled loops swept through 2.3 rad: stiff measured 1.8e-5 rad at the preset's 2 s sweep and
        # 6.9e-8 rad (vertices 6.8e-8) 16x slower, in 0.45 s of CPU; fast 16x gave 4.4e-7 with MuJoCo's own
        # regulariser and 8.0e-9 with the presets' (8x: 3.1e-8). Near the singular cube the blockage servo is
        # slow to settle (it bounces off the contact and creeps back): held 1 s, fast stopped 1.3e-2 rad short;
        # held 3 s (validation.BLOCKAGE_HOLD) fast 16x stops 9.6e-10 (zeta = 0) and 5.5e-6 rad (15 deg) from the
        # contact in 5.1-5.7 s of CPU, stiff 16x 2.0e-11 and 2.4e-5 in 8.5 s; fast 8x 3.5e-4 and 1.1e-2 (too short at
        # 15 deg). The path's rates ask for 3.4-3.6x (`sweep_rate`), at which the blockage stops 1.5e-2 rad short.
        # A design the closed form cannot follow to the cube has no path rates past its turning point (`sweep_rate`
        # then times the preset's duration alone): it keeps the 16x the blockage needs.
        tuning=Tuning(sweep_time_scale=4.5 if drivable else 16.0, why=WHY),
        # Squares share no joint: every pair may collide (faces passing through each other, Yang 2017's
        # "interference"); the collision plates touch 9.8 mrad of A1 before the cube, where the servo stops
        # (blockage study).
        contact_pairs=SQUARE_PAIRS,
        notes="input A1 = theta - theta_d (rad); S joints as MuJoCo ball joints; outputs the 15 R joints",
    )
