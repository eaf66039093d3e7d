"""Transformable polyhedra of Yang 2017: cuboctahedron <-> octahedron (ch. 4).

Frame and units: the thesis's (4-1) frame, unit edges (m), origin at the body centre, z through the centre of
the top square IJKL; angles in radians. Every position below is given with triangle ABE held at its
cuboctahedron pose (the deployed world frame), so the deployed coordinates are exactly (4-1) (with the
misprinted second "G" of (4-1e) read as I = (sqrt2/2, 0, sqrt2/2), which makes every edge 1) and the octahedron
equals (4-2) up to one rigid motion.

Assembly (Yang 2017, §4.2): 8 rigid triangles, bottom ring ABE, BCF, CDG, DAH and top ring IJE, JKF, KLG, LIH; the
6 squares are hollow. R joints at A, B, C, D (Bennett 1, loop A B C D) and I, J, K, L (Bennett 2, loop I J K L)
along the printed axes (4-8, 4-9), through the vertices; S joints at E, F, G, H join a bottom triangle to a
top one. 8 bodies, 12 joints, 5 loops (2 Bennett + 4 RSRS), 1 DOF.

Bennett 1 (Yang 2017's D-H procedure, eqn 1-2, on the printed axes): a = sqrt(3/14) m, twists (alpha, -alpha) with alpha
= arccos(2/5), offsets 0, D-H angles (theta, phi, theta, phi) at (A, B, C, D) with tan(theta/2) tan(phi/2) =
1/cos(alpha) = 5/2 (Yang 2017, ch. 4: eqn 1-18 with beta = pi - alpha and some axes reversed). The input is theta =
theta_A, the D-H angle of triangle ABE relative to DAH about +s_A: theta_d = 2 atan(2 sqrt 5) = 154.7912 deg at the
cuboctahedron, theta_f = 2 atan(sqrt(5)/4) = 58.4119 deg at the octahedron (B = D). The thesis's angles are the
negatives (all axes reversed, (4-29), (4-42)).

Analytic model. The printed axes make the linkage symmetric under the three coordinate mirrors of (4-1), and
the motion keeps them (Yang 2017, §4.3): Bennett 1 keeps its mirrors x (A <-> C) and y (B <-> D) by the
uniqueness of its closed form, so E, F, G, H stay coplanar in the plane through E normal to
n = unit((A - C) x (H - E)), and Bennett 2 is the image of Bennett 1 in that plane (the image of the
deployed mirror z -> -z, which maps A, B, C, D, ABE, ... onto I, J, K, L, IJE, ...). This closes the four
RSRS loops exactly for every theta, with no equation left to solve. Hinge angles: the mirror negates
rotations, so q_I = -q_A, q_J = -q_B, q_K = -q_C, q_L = -q_D.

The path ends at the octahedron, a singular configuration of the whole assembly (found here, though Yang 2017, §4.3
reports none: the second-smallest singular value of the truss falls linearly to 0 there). Derived here: it is a
bifurcation: E = F and G = H, so the top pyramid can turn rigidly about the line through them with every hinge frozen
(`swing_poses`, exact closure), but its faces then cut through the bottom ones for either sign of the turn. Beyond
theta_f on the path, B and D, A and I, E and F pass through each other (the triangles' edges cross the opposite faces).
The cuboctahedron is not an end of the Bennett motion (no face crossing up to theta = 180 deg); the thesis's
transformation starts there, so `domain` is [theta_f, theta_d].
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..geometry import common_normal_foot, enclosed_volume, invert, rotation, transform, transform_z, unit
from .base import Event, transformation_inputs
from .dh import DHRow, dh_from_axes

HALF = np.sqrt(2.0) / 2
# (4-1), I corrected: the cuboctahedron, unit edges.
VERTICES: dict[str, NDArray[np.float64]] = {
    name: np.array(xyz, dtype=float)
    for name, xyz in {
        "A": (HALF, 0, -HALF), "B": (0, -HALF, -HALF), "C": (-HALF, 0, -HALF), "D": (0, HALF, -HALF),
        "E": (HALF, -HALF, 0), "F": (-HALF, -HALF, 0), "G": (-HALF, HALF, 0), "H": (HALF, HALF, 0),
        "I": (HALF, 0, HALF), "J": (0, -HALF, HALF), "K": (-HALF, 0, HALF), "L": (0, HALF, HALF),
    }.items()
}
NAMES: tuple[str, ...] = tuple(VERTICES)
# (4-2): the octahedron (same frame); merged vertices share a corner.
OCTAHEDRON: dict[str, NDArray[np.float64]] = {
    name: np.array(xyz, dtype=float)
    for pair, xyz in {
        "AI": (HALF, 0, 0), "BD": (0, 0, -HALF), "CK": (-HALF, 0, 0),
        "EF": (0, -HALF, 0), "GH": (0, HALF, 0), "JL": (0, 0, HALF),
    }.items()
    for name in pair
}
# (4-8, 4-9): the printed (not unit) R-joint axes, oriented as printed.
AXES: dict[str, NDArray[np.float64]] = {
    name: np.array(xyz, dtype=float) / 3
    for name, xyz in {
        "A": (-2, 0, 4), "B": (0, 4, 2), "C": (2, 0, 4), "D": (0, -4, 2),
        "I": (-2, 0, -4), "J": (0, 4, -2), "K": (2, 0, -4), "L": (0, -4, -2),
    }.items()
}
BOTTOM = ("ABE", "BCF", "CDG", "DAH")  # link k of Bennett 1 joins joint k to joint k + 1 (loop A B C D)
TOP = ("IJE", "JKF", "KLG", "LIH")  # mirror images of BOTTOM (z -> -z), link k of Bennett 2 (loop I J K L)
TRIANGLES = BOTTOM + TOP
# R joints: (hinge = vertex, parent = the link before it in loop order, child = the link after it).
REVOLUTE: tuple[str, ...] = ("A", "B", "C", "D", "I", "J", "K", "L")
HINGES: dict[str, tuple[str, str]] = {
    v: (ring[(k - 1) % 4], ring[k]) for ring, loop in ((BOTTOM, "ABCD"), (TOP, "IJKL")) for k, v in enumerate(loop)
}
# S joints: (vertex, parent = bottom triangle, child = top triangle).
SPHERICAL: tuple[tuple[str, str, str], ...] = (("E", "ABE", "IJE"), ("F", "BCF", "JKF"), ("G", "CDG", "KLG"),
                                               ("H", "DAH", "LIH"))
# The 6 hollow squares, outward (counter-clockwise seen from outside); used for the enclosed volume only.
SQUARES = ("ABCD", "ILKJ", "AHIE", "BEJF", "CFKG", "DGLH")
MIRROR_Z = np.diag([1.0, 1.0, -1.0, 1.0])
COS_ALPHA = 0.4  # (4-25): alpha = arccos 0.4
K_BENNETT = 1.0 / COS_ALPHA  # tan(theta/2) tan(phi/2), eqn 1-18 in this axis orientation
THETA_D = 2.0 * np.arctan(2.0 * np.sqrt(5.0))  # (4-28), sign of the printed axes: 154.7912 deg
THETA_F = 2.0 * np.arctan(np.sqrt(5.0) / 4.0)  # (4-41) corrected and (4-42): 58.4119 deg = phi_d
# Exact volumes for unit edges: cuboctahedron 5 sqrt2 / 3, octahedron sqrt2 / 3 (ch. 4 abstract: 5).
VOLUME_RATIO = 5.0


def faces() -> tuple[str, ...]:
    """The 14 faces as outward vertex cycles: 8 triangles (rings oriented outward) and the 6 squares."""
    out = []
    for face in TRIANGLES:
        P = np.array([VERTICES[v] for v in face])
        out.append(face if np.cross(P[1] - P[0], P[2] - P[0]) @ P.mean(0) > 0 else face[::-1])
    return (*out, *SQUARES)


def volume(points: ArrayLike) -> NDArray[np.float64]:
    """
    Volume (m^3) enclosed by `faces()` for vertex positions (..., 12, 3) in `NAMES` order. The squares are skew
    during the motion (hollow in the mechanism): `enclosed_volume` closes each by the four triangles to its
    centroid, a symmetric choice; exact at both ends, where the squares are planar or collapsed.
    """
    index = {v: k for k, v in enumerate(NAMES)}
    return enclosed_volume(points, [[index[v] for v in face] for face in faces()])


def _reflection(point: NDArray[np.float64], normal: NDArray[np.float64]) -> NDArray[np.float64]:
    """Reflections (n, 4, 4) in the planes through points (n, 3) with unit normals (n, 3)."""
    M = np.broadcast_to(np.eye(4), (len(point), 4, 4)).copy()
    M[:, :3, :3] -= 2.0 * normal[:, :, None] * normal[:, None, :]
    M[:, :3, 3] = 2.0 * np.einsum("ni,ni->n", point, normal)[:, None] * normal
    return M


class CuboctahedronOctahedron:
    """
    Cuboctahedron -> octahedron: 2 Bennett linkages and 4 RSRS loops, 1 DOF (Yang 2017, ch. 4).

    The input is theta = theta_A (rad), Bennett 1's D-H angle at A in the printed axes' orientation (triangle ABE
    relative to DAH about +s_A), from theta_d = 154.7912 deg (cuboctahedron, the reference pose) down to
    theta_f = 58.4119 deg (octahedron); `domain` is (theta_f, theta_d).
    """

    input_name = "theta_A"

    def __init__(self) -> None:
        points = np.array([VERTICES[v] for v in "ABCD"])
        self.dirs = unit(np.array([AXES[v] for v in "ABCD"]))
        rows, angles = dh_from_axes(points, self.dirs)
        self.rows: tuple[DHRow, ...] = rows
        self.theta_d, self.phi_d = float(angles[0]), float(angles[1])
        # Link ABE's D-H frame (after Rz(theta_A)) in the deployed world frame: origin at the foot on axis A of
        # the common normal to axis B (offsets are 0), x along that normal (D-H convention, Yang 2017, eqn 1-2).
        foot_a = common_normal_foot(points[1], self.dirs[1], points[0], self.dirs[0])
        x = unit(common_normal_foot(points[0], self.dirs[0], points[1], self.dirs[1]) - foot_a)
        self._abe = transform(np.stack([x, np.cross(self.dirs[0], x), self.dirs[0]], axis=1), foot_a)
        self._chain_d = self._chain(np.array([self.theta_d]))[0]

    @property
    def domain(self) -> tuple[float, float]:
        """Inputs (rad) from the octahedron (theta_f) to the cuboctahedron (theta_d)."""
        return THETA_F, THETA_D

    def _check(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Inputs as a 1-D array (rad); DomainError naming the first one outside `domain` (1e-12 rad slack)."""
        return transformation_inputs(theta, self.domain, "theta_A", "octahedron to cuboctahedron")

    def phi(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Bennett angle phi (rad) at B and D: tan(theta/2) tan(phi/2) = 5/2, written continuously in theta."""
        t = np.asarray(theta, dtype=float)
        return 2.0 * np.arctan2(K_BENNETT * np.cos(t / 2), np.sin(t / 2))

    def bennett_angles(self, theta: ArrayLike) -> NDArray[np.float64]:
        """D-H angles (n, 4) (rad) of Bennett 1 at A, B, C, D: (theta, phi, theta, phi)."""
        t = self._check(theta)
        p = self.phi(t)
        return np.stack([t, p, t, p], axis=-1)

    def _chain(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """D-H frames (n, 4, 4, 4) of links ABE, BCF, CDG, DAH relative to ABE's D-H frame."""
        phi = self.phi(theta)
        frames = [np.broadcast_to(np.eye(4), (len(theta), 4, 4))]
        for k, q in enumerate((phi, theta, phi)):
            frames.append(frames[-1] @ self.rows[k].link() @ transform_z(q))
        return np.stack(frames, axis=1)

    def _bottom(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """Poses (n, 4, 4, 4) of BOTTOM relative to their deployed poses (world frame, ABE fixed)."""
        return self._abe @ self._chain(theta) @ invert(self._chain_d) @ invert(self._abe)

    def body_poses(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        World poses (n, 4, 4) of the 8 triangles relative to their cuboctahedron poses (identity at theta_d),
        ABE fixed: Bennett 1 from its closed form, Bennett 2 its image in the plane of E, F, G, H.
        """
        t = self._check(theta)
        bottom = self._bottom(t)
        P = {v: np.einsum("nij,j->ni", bottom[:, k], np.append(VERTICES[v], 1.0))[:, :3]
             for k, face in enumerate(BOTTOM) for v in face}
        normal = unit(np.cross(P["A"] - P["C"], P["H"] - P["E"]))
        mirror = _reflection(P["E"], normal)
        out = {face: bottom[:, k] for k, face in enumerate(BOTTOM)}
        out |= {face: mirror @ bottom[:, k] @ MIRROR_Z for k, face in enumerate(TOP)}
        return out

    def vertices(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Vertex positions (n, 12, 3) in `NAMES` order (m, deployed frame, ABE fixed)."""
        poses = self.body_poses(theta)
        owner = {v: face for face in TRIANGLES for v in face}
        return np.stack([poses[owner[v]][:, :3, :3] @ VERTICES[v] + poses[owner[v]][:, :3, 3] for v in NAMES], 1)

    def revolute_angles(self, theta: ArrayLike) -> NDArray[np.float64]:
        """
        Hinge angles (n, 8) (rad) in `REVOLUTE` order, 0 at the cuboctahedron: rotation of the child triangle
        relative to the parent (`HINGES`) about +axis (4-8, 4-9). Bottom: D-H angle minus its deployed value;
        top: the negatives (mirror images).
        """
        return np.stack(list(self.hinge_angles(theta).values()), axis=-1)

    def hinge_angles(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """`revolute_angles` (n,) (rad) by hinge name (`REVOLUTE`); |q| <= theta_d - theta_f = 96.38 deg."""
        t = self._check(theta)
        dt, dp = t - self.theta_d, self.phi(t) - self.phi_d
        return dict(zip(REVOLUTE, (dt, dp, dt, dp, -dt, -dp, -dt, -dp), strict=True))

    def diagonals(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """The distances (m) the thesis tracks (Yang 2017, §4.3): BD, AI, EF (-> 0), AC, EH, BJ (-> sqrt 2)."""
        P = self.vertices(theta)
        k = {v: i for i, v in enumerate(NAMES)}
        return {
            a + b: np.linalg.norm(P[:, k[a]] - P[:, k[b]], axis=-1) for a, b in ("BD", "AI", "EF", "AC", "EH", "BJ")
        }

    def swing_poses(self, psi: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        Poses (n, 4, 4) on the octahedron's second branch: every hinge frozen at theta_f, the top pyramid turned
        by psi (rad) about the line from E (= F) to G (= H), which keeps all four ball centres fixed. It closes
        every loop exactly, but its faces cut through the bottom ones for either sign of psi (zero thickness).
        """
        psi = np.atleast_1d(np.asarray(psi, dtype=float))
        poses = {k: np.broadcast_to(v, (len(psi), 4, 4)) for k, v in self.body_poses(THETA_F).items()}
        P = self.vertices(THETA_F)[0]
        e, g = P[NAMES.index("E")], P[NAMES.index("G")]
        turn = np.broadcast_to(np.eye(4), (len(psi), 4, 4)).copy()
        turn[:, :3, :3] = rotation(unit(g - e), psi)
        turn[:, :3, 3] = e - turn[:, :3, :3] @ e
        return {k: turn @ v if k in TOP else v for k, v in poses.items()}

    def events(self) -> tuple[Event, ...]:
        """The octahedron end (theta_f, rad): the faces close (lock) and a second branch meets the path."""
        name = ("transformation",)
        return (
            Event("lock", THETA_F, name, "octahedron: B = D, A = I, E = F, C = K, G = H, J = L and every face meets "
                  "its neighbours; beyond it the triangles pass through each other"),
            Event("bifurcation", THETA_F, name, "octahedron: instantaneous mobility 2; the second branch turns the top "
                  "pyramid about the line E (= F) G (= H) with every hinge frozen (`swing_poses`), its faces cutting "
                  "the bottom ones at once"),
        )
