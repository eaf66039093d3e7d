"""What makes a frame of folded paper read: mountain and valley creases drawn as lines, a camera that holds the motion.

Creases follow the crease-pattern convention of ORIPA and Origami Simulator: mountain folds red, valley folds
blue, solid lines, coloured by the sign of each crease's fold angle in that frame (rho > 0 is a valley seen from
+z, FOLD's sign); creases within FLAT rad of flat are grey. The paper's two sides (front +z of the flat sheet,
back -z) are coloured by the render model (`mjcf`, classes `paper_front` / `paper_back`).
"""

from dataclasses import dataclass

import mujoco
import numpy as np
from numpy.typing import NDArray

from .scenes.base import Scene

MOUNTAIN = (0.85, 0.12, 0.10, 1.0)
VALLEY = (0.10, 0.30, 0.85, 1.0)
UNFOLDED = (0.45, 0.45, 0.45, 1.0)
# |fold angle| (rad) below which a crease is drawn as unfolded.
FLAT = 1e-3
# Room around the motion in the frame (x its projected half size).
MARGIN = 1.08


@dataclass(frozen=True)
class CreaseLines:
    """Each crease's two ends (m) in its parent body's frame, the joint it is, and the line radius (m)."""

    joints: NDArray[np.int64]
    parents: tuple[str, ...]
    ends: NDArray[np.float64]  # (n, 2, 3)
    radius: float


def crease_lines(scene: Scene, radius: float) -> CreaseLines:
    """
    The crease hinges' segments: the extent, along each hinge axis, of the parent panel's solid vertices nearest
    to that axis (a crease's edge); lines `radius` m thick, at least enough to show through a nominal plate.
    """
    mech = scene.mechanism
    bodies = {b.name: b for b in mech.bodies}
    names = scene.crease_hinges
    joints, parents, ends = [], [], []
    thickest = 0.0
    for i, joint in enumerate(mech.joints):
        if joint.name not in names or bodies[joint.parent].spacer:
            continue
        origin, axis = joint.frame_parent[:3, 3], joint.frame_parent[:3, 2]
        V = np.asarray(bodies[joint.parent].solid.vertices) - origin
        t = V @ axis
        distance = np.linalg.norm(V - np.outer(t, axis), axis=1)
        near = distance <= distance.min() * (1 + 1e-6) + 1e-9
        thickest = max(thickest, float(distance.min()))
        joints.append(i)
        parents.append(joint.parent)
        ends.append([origin + t[near].min() * axis, origin + t[near].max() * axis])
    return CreaseLines(np.array(joints, dtype=int), tuple(parents), np.array(ends).reshape(-1, 2, 3),
                       max(radius, 2.0 * thickest))


def add_crease_lines(scn: mujoco.MjvScene, lines: CreaseLines, poses: dict, q: NDArray[np.float64]) -> None:
    """Append one capsule per crease to the scene's extra geoms, at body poses `poses` {name: (4, 4)}."""
    for k, (joint, parent) in enumerate(zip(lines.joints, lines.parents, strict=True)):
        if scn.ngeom >= scn.maxgeom:
            return
        T = poses[parent]
        a, b = (T[:3, :3] @ p + T[:3, 3] for p in lines.ends[k])
        rho = q[joint]
        rgba = UNFOLDED if abs(rho) < FLAT else VALLEY if rho > 0 else MOUNTAIN
        geom = scn.geoms[scn.ngeom]
        mujoco.mjv_initGeom(geom, mujoco.mjtGeom.mjGEOM_CAPSULE, np.zeros(3), np.zeros(3), np.zeros(9),
                            np.array(rgba, dtype=np.float32))
        mujoco.mjv_connector(geom, mujoco.mjtGeom.mjGEOM_CAPSULE, lines.radius, a, b)
        scn.ngeom += 1


def side_azimuth(points: NDArray[np.float64], elevation: float, default: float = -55.0) -> float:
    """
    Camera azimuth (deg) for points (n, 3) seen at `elevation` (deg): when they are elongated (principal spreads
    differ by more than 1.5x: a tube, a strip), the azimuth nearest `default` that looks square to their long axis,
    so that it lies in the picture at full length; `default` otherwise or when no azimuth is square to it.
    """
    centred = points - points.mean(axis=0)
    values, vectors = np.linalg.eigh(centred.T @ centred)
    if values[2] <= 2.25 * max(values[1], 1e-30):
        return default
    a = vectors[:, 2]
    # forward (cos el cos az, cos el sin az, sin el) . a = 0  <=>  |a_xy| cos(az - phi) = -tan(el) a_z
    horizontal, phi = float(np.hypot(a[0], a[1])), float(np.arctan2(a[1], a[0]))
    ratio = -np.tan(np.radians(elevation)) * a[2] / max(horizontal, 1e-30)
    if abs(ratio) > 1:
        return default
    turns = np.degrees(phi + np.array([1.0, -1.0]) * np.arccos(ratio))
    wrapped = (turns - default + 180.0) % 360.0 - 180.0 + default
    return float(wrapped[np.argmin(np.abs(wrapped - default))])


def fit_camera(
    scene: Scene, q: NDArray[np.float64], fovy_deg: float, aspect: float, elevation: float = -30.0
) -> mujoco.MjvCamera:
    """
    A free camera at `elevation` (deg) and the azimuth of `side_azimuth`, whose view holds every body vertex over
    all poses q (n, n_joints): centred on the projected bounding box, backed off until its half height and half
    width fit the field of view (vertical `fovy_deg`, width/height `aspect`) with MARGIN, in perspective.
    """
    poses = scene.mechanism.body_poses(q)
    points = []
    for body in scene.mechanism.bodies:
        if body.spacer or not len(body.solid.vertices):
            continue
        v = np.c_[body.solid.vertices, np.ones(len(body.solid.vertices))]
        points.append((poses[body.name] @ v.T)[..., :3, :].transpose(0, 2, 1).reshape(-1, 3))
    P = np.concatenate(points)
    azimuth = side_azimuth(P, elevation)
    az, el = np.radians(azimuth), np.radians(elevation)
    forward = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])  # camera looks along this
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    x, y, z = P @ right, P @ up, P @ forward
    centre = ((x.max() + x.min()) / 2) * right + ((y.max() + y.min()) / 2) * up + ((z.max() + z.min()) / 2) * forward
    tan = np.tan(np.radians(fovy_deg) / 2)
    # a point at (x, y) off the view axis and z beyond the centre is in view when |y| <= tan (D + z) (and x with
    # the aspect): the nearest distance D that holds every point, with MARGIN
    x, y, z = x - (x.max() + x.min()) / 2, y - (y.max() + y.min()) / 2, z - (z.max() + z.min()) / 2
    distance = float(np.max(MARGIN * np.maximum(np.abs(y) / tan, np.abs(x) / (tan * aspect)) - z))
    camera = mujoco.MjvCamera()
    camera.type = mujoco.mjtCamera.mjCAMERA_FREE
    camera.lookat[:] = centre
    camera.distance = max(distance, 1e-3)
    camera.azimuth, camera.elevation = azimuth, elevation
    return camera
