"""Transformable polyhedra of Yang 2017: truncated octahedron <-> cube (ch. 5).

Frame and units: the thesis's (5-1) frame, unit edges (m), origin at the body centre; angles in radians.
Every position below is given with square A held at its truncated-octahedron pose (the deployed world
frame), so the deployed coordinates are exactly (5-1) and the cube coordinates equal (5-2) up to one
rigid motion.

Assembly (1-DOF design, Yang 2017, §5.3): 6 rigid squares A..F and 12 rigid bars. Bricard 1 is the
hexagon A1 A2 C1 C2 B1 B2 (links: square A, bar A2C1, square C, bar C2B1, square B, bar B2A1) with R joints
at its six vertices; Bricard 2 = D1 D2 E1 E2 F1 F2 is its image under the half-turn R2: (x, y, z) ->
(-y, -x, -z), which maps the squares A, B, C onto E, D, F with the same vertex indices. R joints at A3,
B3, C3 join squares A, B, C to the bars A3E3, B3F3, C3D3 (axis in the bisecting plane of angle A2 A3 E3,
turned by zeta from the direction to the centre); S joints at E3, F3, D3 and at both ends of the bars
A4F4, B4D4, C4E4. 15 R + 9 S joints, 18 bodies, 7 loops, 1 DOF.

Bricard axes (the thesis's vectors, oriented as listed, with (5-3), (5-16), (5-17) corrected here: its s_B1 is
OB2, and its s_A2, s_B2 have permuted components, which leaves gaps of 1.49 and 0.85 between axes that must meet):
odd joints A1, C1, B1 along O -> vertex; even joints s_C2 = (p, q, r), s_A2 = (r, p, q), s_B2 = (q, r, p) with
p = (1 - 2 sqrt 2)/2, q = -(sqrt 2 + 1)/2, r = -3/2. Yang 2017's D-H procedure (eqn 1-2) gives a threefold-symmetric
Bricard (1-27) with a = 0.713234 m, alpha = 214.7865 deg, R = 0: `BricardThreefold` gives its closed form,
theta at the odd joints (A1, C1, B1), phi at the even ones, on its 'even-axes-along' branch (phi_d = 147.4964
deg at theta_d = 34.3147 deg). Angles are D-H joint angles in this axis orientation (eqn 1-2).

Analytic model (a reduced C3-symmetric model, derived here). The motion keeps the threefold symmetry about
the common axis of both Bricards, so it is fixed by the input theta = theta_A (Bricard 1's odd joint angle)
and three unknowns x = (theta_D, psi, h): Bricard 2's odd joint angle, and the turn psi (rad) and shift h (m)
of Bricard 2 along Bricard 1's symmetry axis, relative to their deployed relative pose. Three equations
close the remaining loops (the other six follow by symmetry): |A3E3| = 1, (E3 - A3) . s_A3 = its deployed
value (the R joint at A3), |A4F4| = 1. Both Bricards follow the closed form exactly; only this 3 x 3 system
is solved (Newton, from the deployed state, continued in theta). Its Jacobian is regular on the whole path
(smallest singular value 0.10 on 101 samples, zeta = 0).

The 15 R-joint angles alone (`hinge_angles`, what `evaluate` reports; no poses) come from the same closure in
two unknowns, theta_D and the turn beta of the bar A3E3 about s_A3 (which holds E3 on a circle and is the
angle at A3, B3, C3): in cylindrical coordinates about the common axis E3 fixes psi and h, leaving E3's radius
= that of A3 on Bricard 2 and |A4F4| = 1 (`_closure`). Both Bricards' axes come from their closed form
(`bricard_threefold.bricard_axis`); one chord step from a table dense in the input closes them to rounding.

The path ends at the cube (theta_f = 166.1251 deg: A1 = B1 = C1, Bricard 1 folded, delta2 = 0 in (5-40));
beyond it the squares pass through each other (rho < 0, signed here: the thesis does not sign it).
"""

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConvergenceError, ParameterError
from ..geometry import (
    common_normal_foot,
    enclosed_volume,
    minimal_rotation,
    rigid_fit,
    rotation,
    transform,
    transform_z,
    unit,
)
from .base import Event, transformation_inputs
from .bricard_threefold import ALONG, BricardThreefold, bricard_axis, bricard_trig
from .dh import DHRow, dh_from_axes
from .path_table import PathTable, polish, wrap_if_needed

SQ2, HALF, R3 = np.sqrt(2.0), np.sqrt(2.0) / 2, np.sqrt(3.0)
# (5-1): the truncated octahedron, unit edges.
VERTICES: dict[str, NDArray[np.float64]] = {
    name: np.array(xyz, dtype=float)
    for name, xyz in {
        "A1": (SQ2, HALF, 0), "A2": (SQ2, 0, HALF), "A3": (SQ2, -HALF, 0), "A4": (SQ2, 0, -HALF),
        "B1": (0, SQ2, HALF), "B2": (HALF, SQ2, 0), "B3": (0, SQ2, -HALF), "B4": (-HALF, SQ2, 0),
        "C1": (HALF, 0, SQ2), "C2": (0, HALF, SQ2), "C3": (-HALF, 0, SQ2), "C4": (0, -HALF, SQ2),
        "D1": (-SQ2, 0, -HALF), "D2": (-SQ2, -HALF, 0), "D3": (-SQ2, 0, HALF), "D4": (-SQ2, HALF, 0),
        "E1": (-HALF, -SQ2, 0), "E2": (0, -SQ2, -HALF), "E3": (HALF, -SQ2, 0), "E4": (0, -SQ2, HALF),
        "F1": (0, -HALF, -SQ2), "F2": (-HALF, 0, -SQ2), "F3": (0, HALF, -SQ2), "F4": (HALF, 0, -SQ2),
    }.items()
}
NAMES: tuple[str, ...] = tuple(VERTICES)
# (5-2): the cube (edge 1) each vertex reaches; merged vertices share a corner.
CUBE: dict[str, NDArray[np.float64]] = {
    name: 0.5 * np.array(signs, dtype=float)
    for corner, signs in {
        ("A1", "B1", "C1"): (1, 1, 1), ("B4", "C2", "D3"): (-1, 1, 1), ("C3", "D2", "E4"): (-1, -1, 1),
        ("A2", "C4", "E3"): (1, -1, 1), ("A4", "B2", "F3"): (1, 1, -1), ("B3", "D4", "F2"): (-1, 1, -1),
        ("D1", "E1", "F1"): (-1, -1, -1), ("A3", "E2", "F4"): (1, -1, -1),
    }.items()
    for name in corner
}
SQUARES = tuple(tuple(f"{s}{k}" for k in range(1, 5)) for s in "ABCDEF")
BRICARD_BARS = (("A2", "C1"), ("C2", "B1"), ("B2", "A1"), ("D2", "E1"), ("E2", "F1"), ("F2", "D1"))
RS_BARS = (("A3", "E3"), ("B3", "F3"), ("C3", "D3"))  # R joint at the first vertex, S at the second
SS_BARS = (("A4", "F4"), ("B4", "D4"), ("C4", "E4"))
BARS = BRICARD_BARS + RS_BARS + SS_BARS
BRICARD_1 = ("A1", "A2", "C1", "C2", "B1", "B2")  # D-H loop order; link k joins joint k to joint k+1
LINKS_1 = ("A", "A2C1", "C", "C2B1", "B", "B2A1")  # body of link k: its vertices move with it
# The half-turn R2 maps Bricard 1 onto Bricard 2 (letters A, B, C -> E, D, F, same index).
R2 = np.array([[0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
IMAGE = str.maketrans("ABC", "EDF")
# The threefold turn (x, y, z) -> (z, x, y) about (1, 1, 1): square A -> B -> C, A3 -> B3 -> C3.
THREEFOLD = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
# Rounding floor (m^2) of the reduced closure's residuals (`TruncatedOctahedronCube._closure`): Newton's method
# stalls at 3.6e-15 (measured on 1e6 inputs).
RESIDUAL_FLOOR = 8e-15
# Exact volumes for unit edges: truncated octahedron 8 sqrt 2, cube 1 (Yang 2017, ch. 5 abstract: 11.3).
VOLUME_RATIO = 8.0 * SQ2


def even_axes() -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """s_A2, s_C2, s_B2 (not unit): (r, p, q), (p, q, r), (q, r, p) of (5-13) and corrected (5-16, 5-17)."""
    p, q, r = (1 - 2 * SQ2) / 2, -(SQ2 + 1) / 2, -1.5
    return np.array([r, p, q]), np.array([p, q, r]), np.array([q, r, p])


def bricard_axes() -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Points and unit directions (6, 3) of Bricard 1's axes in loop order A1, A2, C1, C2, B1, B2."""
    s_a2, s_c2, s_b2 = even_axes()
    dirs = np.array([VERTICES["A1"], s_a2, VERTICES["C1"], s_c2, VERTICES["B1"], s_b2])
    return np.array([VERTICES[v] for v in BRICARD_1]), unit(dirs)


def axis_a3(zeta: float) -> NDArray[np.float64]:
    """
    Unit axis of the R joint at A3 (deployed frame): Rot(unit(A2 - E3), zeta) unit(O - A3) (Yang 2017, §5.3):
    zeta = 0 points to the centre, positive zeta right-handed about A2 - E3.
    """
    return rotation(unit(VERTICES["A2"] - VERTICES["E3"]), zeta) @ unit(-VERTICES["A3"])


def revolute_axes(zeta: float = 0.0) -> dict[str, NDArray[np.float64]]:
    """
    Unit axis (deployed frame) of each of the 15 R joints, by the vertex it sits on: Bricard 1's six, their
    images under R2 (Bricard 2), and A3, B3, C3 (threefold images of `axis_a3`). Each joins the square named by
    the vertex's letter to the bar at that vertex.
    """
    _, dirs = bricard_axes()
    out = {}
    for vertex, d in zip(BRICARD_1, dirs, strict=True):
        out[vertex], out[vertex.translate(IMAGE)] = d, R2 @ d
    axis = axis_a3(zeta)
    for vertex, _ in RS_BARS:
        out[vertex], axis = axis, THREEFOLD @ axis
    return out


def faces() -> tuple[tuple[str, ...], ...]:
    """
    The 14 faces as outward (counter-clockwise seen from outside) vertex cycles: the 6 squares and the
    8 hexagons (hollow in the mechanism; used for the enclosed volume only).
    """
    out = []
    for square in SQUARES:
        P = np.array([VERTICES[v] for v in square])
        normal = np.cross(P[1] - P[0], P[2] - P[0])
        out.append(square if normal @ P.mean(0) > 0 else square[::-1])
    for octant in np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).T.reshape(-1, 3):
        ring = [v for v in NAMES if abs(VERTICES[v] @ octant - 1.5 * SQ2) < 1e-9]
        centre = sum(VERTICES[v] for v in ring) / 6
        e1 = unit(VERTICES[ring[0]] - centre)
        e2 = np.cross(unit(octant.astype(float)), e1)
        ring.sort(key=lambda v: np.arctan2((VERTICES[v] - centre) @ e2, (VERTICES[v] - centre) @ e1))
        out.append(tuple(ring))
    return tuple(out)


def volume(points: ArrayLike) -> NDArray[np.float64]:
    """Volume (m^3) enclosed by `faces()` for vertex positions (..., 24, 3) in `NAMES` order (`enclosed_volume`)."""
    index = {v: k for k, v in enumerate(NAMES)}
    return enclosed_volume(points, [[index[v] for v in face] for face in faces()])


@dataclass(frozen=True)
class PathOutcome:
    """
    How the reduced model's path leaves the truncated octahedron for one design (the zeta study of Yang 2017,
    §5.5, redone here).

    `kind` names the first of these events along the path (pseudo-arclength from the deployed state with
    d theta > 0): 'cube' (rho1 and rho2 reach 0 together), 'rho1-negative' (Bricard 1 folds first, theta =
    theta_f with rho2 > 0: going on passes squares A, B, C through each other), 'rho2-negative' (Bricard 2 folds
    first: D, E, F), 'loop' (the path closes back on the truncated octahedron without a fold) or 'no-end' (none
    within `max_length`, or a Bricard angle reaches +-pi, the end of its closed form). Angles in radians, signed
    rho (signed here, negative beyond the Bricard's fold). `theta`, `rho1`, `rho2`: at that event;
    `turns`: the inputs theta at which theta turned back before it (the input A1 = theta - theta_d cannot drive
    the path past the first); `rho1_min`, `rho1_max`: extremes of rho1 before the event (> 120 deg:
    over-opening); `gap_max`: largest |rho1 - rho2|.
    """

    zeta: float
    kind: str
    theta: float
    rho1: float
    rho2: float
    turns: tuple[float, ...]
    rho1_min: float
    rho1_max: float
    gap_max: float

    @property
    def feasible(self) -> bool:
        """The cube is reached before any signed fold angle turns negative (turning points allowed)."""
        return self.kind == "cube"

    @property
    def drivable(self) -> bool:
        """Feasible, and the input theta rises monotonically to the cube (a drive on A1 follows it)."""
        return self.feasible and not self.turns


def _dot(a: tuple | NDArray, b: tuple | NDArray) -> NDArray[np.float64]:
    """a . b for 3-vectors given as 3-tuples of (n,) arrays or (3,) arrays (any mix)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


class TruncatedOctahedronCube:
    """
    Truncated octahedron -> cube, 1-DOF design with R joints at A3, B3, C3 (Yang 2017, ch. 5).

    Parameters
    ----------
    zeta : float
      Deviation (rad) of the A3 axis from the direction to the centre, in the bisecting plane of angle
      A2 A3 E3 (Yang 2017, §5.3); the thesis's prototype and the default use 0. Must lie in (-pi/2, pi/2).

    The input is theta = theta_A (rad), Bricard 1's odd-joint D-H angle, from theta_d (the truncated
    octahedron) to theta_f (the cube); `domain` is that closed interval.
    """

    def __init__(self, zeta: float = 0.0):
        if not (np.isfinite(zeta) and abs(zeta) < np.pi / 2):
            raise ParameterError(
                f"zeta = {np.rad2deg(zeta):.6g} deg; it must lie in (-90, 90) deg (at +/-90 deg the A3 axis lies "
                "along the bar A3E3's plane normal, outside Yang 2017's range of designs)"
            )
        self.zeta = float(zeta)
        points, dirs = bricard_axes()
        rows, angles = dh_from_axes(points, dirs)
        self.rows: tuple[DHRow, ...] = rows
        self.bricard = BricardThreefold(rows[0].a, rows[0].alpha % (2 * np.pi))
        self.theta_d, self.phi_d = float(angles[0]), float(angles[1])
        # Joint 1's D-H frame (before Rz(theta_1)) in the deployed world frame: origin at the foot on axis
        # A1 of the common normal from axis B2, x along that normal (D-H convention, Yang 2017, eqn 1-2).
        foot_out = common_normal_foot(points[0], dirs[0], points[5], dirs[5])
        foot_in = common_normal_foot(points[5], dirs[5], points[0], dirs[0])
        x = unit(foot_in - foot_out)
        frame = transform(np.stack([x, np.cross(dirs[0], x), dirs[0]], axis=1), foot_in)
        # Square A's pose (link 1) at the deployed angles; every Bricard-1 body is placed relative to it.
        self._square_a = frame @ transform_z(self.theta_d)
        self._local = self._link_coordinates()
        self.s_a3 = axis_a3(self.zeta)
        self._sym0 = self._symmetry_frame(self.bricard_points(np.array([self.theta_d])))[0]
        self._r2_sym = np.linalg.inv(self._sym0) @ transform(R2) @ self._sym0
        self._bar_a3 = float((VERTICES["E3"] - VERTICES["A3"]) @ self.s_a3)

    # --- Bricard 1 from the closed form --------------------------------------------------------

    def phi(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Even-joint angle phi (rad) of a Bricard on the thesis's branch ('even-axes-along' of (5-42))."""
        values, _ = self.bricard.evaluate(ALONG, np.atleast_1d(np.asarray(theta, dtype=float)))
        return values[:, 1]

    def _link_poses(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """Poses (n, 6, 4, 4) of links 1..6 of Bricard 1 at odd/even angles (theta, phi(theta)), square A fixed."""
        phi = self.phi(theta)
        poses = [np.broadcast_to(self._square_a, (len(theta), 4, 4))]
        for k in range(5):
            q = phi if k % 2 == 0 else theta  # joint k + 2 is even when k is even
            poses.append(poses[-1] @ self.rows[k].link() @ transform_z(q))
        return np.stack(poses, axis=1)

    def _link_coordinates(self) -> dict[str, tuple[int, NDArray[np.float64]]]:
        """Each Bricard-1 vertex (A, B, C squares, bar ends) as (link index, coordinates in that link's frame)."""
        deployed = self._link_poses(np.array([self.theta_d]))[0]
        out = {}
        for k, link in enumerate(LINKS_1):
            members = [f"{link}{i}" for i in range(1, 5)] if len(link) == 1 else [link[:2], link[2:]]
            for v in members:
                out.setdefault(v, (k, np.linalg.solve(deployed[k], np.append(VERTICES[v], 1.0))[:3]))
        return out

    def bricard_points(self, theta: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
        """Bricard-1 vertex positions (n, 3) by name (the 12 vertices of squares A, B, C), square A fixed."""
        poses = self._link_poses(theta)
        out = {}
        for v, (k, local) in self._local.items():
            out[v] = poses[:, k, :3, :3] @ local + poses[:, k, :3, 3]
        return out

    @staticmethod
    def _symmetry_frame(points: dict[str, NDArray[np.float64]]) -> NDArray[np.float64]:
        """
        Frames (n, 4, 4) on a Bricard's threefold axis: origin the centroid of A3, B3, C3 (threefold images,
        never merged), z the normal of their triangle, x toward A3.
        """
        a, b, c = points["A3"], points["B3"], points["C3"]
        origin = (a + b + c) / 3
        z = unit(np.cross(b - a, c - a))
        x = unit(a - origin)
        frames = np.zeros((len(a), 4, 4))
        frames[:, :3, :3] = np.stack([x, np.cross(z, x), z], axis=-1)
        frames[:, :3, 3], frames[:, 3, 3] = origin, 1.0
        return frames

    # --- the assembly --------------------------------------------------------------------------

    def _points(self, theta: NDArray, theta_d2: NDArray, psi: NDArray, h: NDArray) -> NDArray[np.float64]:
        """All 24 vertices (n, 24, 3) in `NAMES` order for Bricard 1 at theta and Bricard 2 at (theta_d2, psi, h)."""
        one = self.bricard_points(theta)
        two = self.bricard_points(theta_d2)
        sym1 = self._symmetry_frame(one)
        sym2 = self._symmetry_frame(two)
        screw = transform_z(psi)
        screw[:, 2, 3] = h
        place = sym1 @ screw @ self._r2_sym @ np.linalg.inv(sym2)
        out = dict(one)
        for v, p in two.items():
            out[v.translate(IMAGE)] = np.einsum("nij,nj->ni", place[:, :3, :3], p) + place[:, :3, 3]
        return np.stack([out[v] for v in NAMES], axis=1)

    def equations(self, theta: ArrayLike, x: ArrayLike) -> NDArray[np.float64]:
        """
        The three closure equations (n, 3) in m^2, m, m^2: |A3E3|^2 - 1, (E3 - A3) . s_A3 - deployed value,
        |A4F4|^2 - 1; x = (theta_D, psi, h) per row.
        """
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        x = np.atleast_2d(np.asarray(x, dtype=float))
        P = self._points(t, x[:, 0], x[:, 1], x[:, 2])
        k = {v: i for i, v in enumerate(NAMES)}
        a3e3 = P[:, k["E3"]] - P[:, k["A3"]]
        a4f4 = P[:, k["F4"]] - P[:, k["A4"]]
        return np.stack(
            [np.sum(a3e3**2, -1) - 1.0, a3e3 @ self.s_a3 - self._bar_a3, np.sum(a4f4**2, -1) - 1.0], axis=-1
        )

    def _jacobian(self, theta: NDArray[np.float64], x: NDArray[np.float64]) -> NDArray[np.float64]:
        """d equations / d x (n, 3, 3) by central differences (step 1e-7)."""
        step, probes = 1e-7, np.vstack([np.eye(3), -np.eye(3)])
        g = self.equations(np.repeat(theta, 6), (x[:, None, :] + step * probes).reshape(-1, 3)).reshape(-1, 6, 3)
        return np.swapaxes(g[:, :3] - g[:, 3:], 1, 2) / (2 * step)

    def _newton(
        self, theta: NDArray[np.float64], x: NDArray[np.float64], J: NDArray[np.float64] | None = None
    ) -> NDArray[np.float64]:
        """
        Close the three equations at inputs theta (n,) from states x (n, 3), all inputs at once: chord steps with
        the Jacobians J (n, 3, 3) when given (from nearby states), else Newton's method; inputs the chord steps
        leave open are restarted with Newton's method (near the cube the Jacobian turns fast: zeta = 15 deg left
        theta = 165.811 deg open). ConvergenceError names the first input that does not close.
        """
        start, active, previous = x, np.arange(len(theta)), np.full(len(theta), np.inf)
        x = x.copy()
        for _ in range(30):
            f = self.equations(theta[active], x[active])
            size = np.max(np.abs(f), axis=-1)
            # done: closed, or stalled at the rounding floor (no longer halving below 1e-13)
            going = ~(size < 1e-15) & ~((size < 1e-13) & (size > 0.5 * previous[active]))  # NaN: not closed
            previous[active] = size
            active, f = active[going], f[going]
            if not len(active):
                return x
            step_J = self._jacobian(theta[active], x[active]) if J is None else J[active]
            x[active] -= np.linalg.solve(step_J, f[..., None])[..., 0]
        bad = ~(np.max(np.abs(self.equations(theta, x)), axis=-1) < 1e-13)  # NaN (no real Bricard 2) is open
        if np.any(bad) and J is not None:
            x[bad] = self._newton(theta[bad], start[bad])
            return x
        if np.any(bad):
            raise ConvergenceError(f"the reduced model did not close at theta = {np.rad2deg(theta[bad][0]):.6g} deg")
        return x

    @cached_property
    def _track(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """
        The state marched from the deployed one through the domain in steps of at most 0.5 deg: inputs (k,),
        states (k, 3) and their Jacobians (k, 3, 3).
        """
        lo, hi = self.domain
        grid = np.linspace(lo, hi, int(np.ceil((hi - lo) / np.deg2rad(0.5))) + 1)
        states, x = np.empty((len(grid), 3)), np.array([[self.theta_d, 0.0, 0.0]])
        for k, t in enumerate(grid):
            x = states[k] = self._newton(np.array([t]), x)[0][None]
        return grid, states, self._jacobian(grid, states)

    @cached_property
    def theta_f(self) -> float:
        """Input (rad) at the cube: Bricard 1 folds, A1 = B1 = C1 (|B1 - C1| = 0, bisected to 1e-15 rad)."""

        def gap(t: float) -> float:
            p = self.bricard_points(np.array([t]))
            return float(np.sum((p["B1"] - p["C1"]) ** 2, -1)[0])

        # |B1C1|^2 has a double zero at the fold, so bisect on the sign of its slope d/dt.
        def slope(t: float) -> float:
            return gap(t + 1e-7) - gap(t - 1e-7)

        lo, hi = np.deg2rad(150.0), np.deg2rad(175.0)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if slope(mid) < 0 else (lo, mid)
        return 0.5 * (lo + hi)

    @property
    def domain(self) -> tuple[float, float]:
        """Inputs (rad) from the truncated octahedron to the cube."""
        return self.theta_d, self.theta_f

    def events(self) -> tuple[Event, ...]:
        """The cube (theta_f, rad): Bricard 1 folds, A1 = B1 = C1 and the squares meet (a lock)."""
        return (Event("lock", self.theta_f, ("transformation",), "the cube: A1 = B1 = C1, the squares meet; beyond "
                      "it they pass through each other (Yang 2017, §5.4)"),)

    def state(self, theta: ArrayLike) -> NDArray[np.float64]:
        """
        x = (theta_D, psi, h) per input (n, 3), rad, rad, m: chord steps from the state interpolated on `_track`
        (the branch continued from the deployed state (theta_d, 0, 0)).

        Raises
        ------
        DomainError
          When an input lies outside `domain`.
        """
        t = self._inputs(theta)
        grid, track, jacobians = self._track
        start = np.stack([np.interp(t, grid, track[:, i]) for i in range(3)], axis=-1)
        nearest = np.clip(np.searchsorted(grid, t), 0, len(grid) - 1)
        return self._newton(t, start, jacobians[nearest])

    def _inputs(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Inputs as a 1-D array (rad); DomainError naming the first one not finite or outside `domain` (+-1e-12)."""
        return transformation_inputs(theta, self.domain, "theta", "truncated octahedron to cube")

    # --- the R-joint angles without poses (the throughput path of `hinge_angles`) ----------------------------------

    def hinge_angles(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        Angle (n,) (rad) of each of the 15 R joints (`revolute_axes`, bar -> square about +axis, 0 deployed) at
        inputs theta (rad), from the reduced closure (`_solve`), no poses: a Bricard's odd joints turn by its
        theta - theta_d, its even ones by -(phi - phi_d) (the D-H angle turns the bar relative to the square), A3,
        B3, C3 by -beta (the bar turns by beta relative to square A).
        """
        t = self._inputs(theta)
        theta_d2, beta = self._solve(t, self._table)
        out = {}
        for bricard, angle in (("A1", t), ("E1", theta_d2)):
            cp, sp = bricard_trig(self.bricard, angle)[2:]
            dt, dp = wrap_if_needed(angle - self.theta_d), wrap_if_needed(self.phi_d - np.arctan2(sp, cp))
            for k, vertex in enumerate(BRICARD_1):
                out[vertex if bricard == "A1" else vertex.translate(IMAGE)] = dp if k % 2 else dt
        q = wrap_if_needed(-beta)
        return out | {vertex: q for vertex, _ in RS_BARS}

    @cached_property
    def _circle(self) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """
        E3 on its circle about s_A3 through A3 (|A3E3| = 1, (E3 - A3) . s_A3 fixed), in square A's D-H frame:
        rows centre, e1, e2 (3, 3) of E3 = centre + e1 cos beta + e2 sin beta (m), beta = 0 deployed and
        right-handed about s_A3; and A3, A4 (3,) there.
        """
        to_a = np.linalg.inv(self._square_a)
        a3, a4, e3 = (to_a[:3, :3] @ VERTICES[v] + to_a[:3, 3] for v in ("A3", "A4", "E3"))
        s = to_a[:3, :3] @ self.s_a3
        centre = a3 + ((e3 - a3) @ s) * s
        e1 = e3 - centre
        return np.stack([centre, e1, np.cross(s, e1)]), a3, a4

    def _cylinder(self, theta: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
        """
        Square A in the cylindrical frame of the Bricard's axis at theta (n,) (`bricard_axis`, square A's D-H
        frame): A3's radius (m), A4's planar coordinates X4, Y4 and height z4 from A3 (m), and the frame's unit
        vectors x (toward A3), y, z (the axis) as 3-tuples of (n,) arrays.
        """
        u, p, _, _ = bricard_axis(self.bricard, theta)
        _, a3, a4 = self._circle
        d = a3[0] - p[0], a3[1] - p[1], a3[2] - p[2]
        height = _dot(d, u)
        x = d[0] - height * u[0], d[1] - height * u[1], d[2] - height * u[2]
        radius = np.sqrt(_dot(x, x))
        x = x[0] / radius, x[1] / radius, x[2] / radius
        y = u[1] * x[2] - u[2] * x[1], u[2] * x[0] - u[0] * x[2], u[0] * x[1] - u[1] * x[0]
        step = a4 - a3  # A4 - p = (A3 - p) + step, and A3 - p = radius x + height u
        return radius, radius + _dot(step, x), _dot(step, y), _dot(step, u), x, y, u

    def _bricard_1(self, theta: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
        """
        What the closure needs of Bricard 1 at inputs theta (n,): A4's X4, Y4, z4 (`_cylinder`) and E3's frame
        coordinates (x, y, height from A3) as k0 + k1 cos beta + k2 sin beta, k0, k1, k2 each (3, n) (m).
        """
        radius, X4, Y4, z4, *frame = self._cylinder(theta)
        circle, a3, _ = self._circle
        k0 = np.array([_dot(circle[0] - a3, w) for w in frame])
        k0[0] += radius  # E3 - p = (E3 - A3) + radius x + height u
        k1, k2 = (np.array([_dot(v, w) for w in frame]) for v in circle[1:])
        return X4, Y4, z4, k0, k1, k2

    @staticmethod
    def _closure(one: tuple[NDArray[np.float64], ...], two: tuple[NDArray[np.float64], ...], beta: NDArray) -> NDArray:
        """
        The reduced closure (n, 2) (m^2) from Bricard 1's `_bricard_1`, Bricard 2's shape `_cylinder` (at theta_D)
        and beta: E3's radius about the common axis squared minus that of A3 about Bricard 2's own, and
        |A4F4|^2 - 1. Bricard 2 is Bricard 1's shape turned over onto the common axis, (radius, angle, height) ->
        (radius, psi - angle, zeta - height), psi and zeta fixed by E3 (the image of its A3); F4 is the image of
        its C4, which is its A4 turned +120 deg about its axis: in complex planar coordinates F4 = E3 conj(w A4') /
        |A3'| with w = exp(i 120 deg).
        """
        X4, Y4, z4, k0, k1, k2 = one
        radius, X4b, Y4b, z4b = two[:4]
        cb, sb = np.cos(beta), np.sin(beta)
        Xe, Ye, ze = k0 + k1 * cb + k2 * sb
        mr, mi = -0.5 * X4b - 0.5 * R3 * Y4b, 0.5 * Y4b - 0.5 * R3 * X4b
        Fr, Fi = (Xe * mr - Ye * mi) / radius, (Xe * mi + Ye * mr) / radius
        return np.stack(
            [Xe * Xe + Ye * Ye - radius * radius, (X4 - Fr) ** 2 + (Y4 - Fi) ** 2 + (z4 - ze + z4b) ** 2 - 1.0], -1
        )

    @cached_property
    def _table(self) -> PathTable:
        """
        `_columns` of the path (theta_D, beta, inverse Jacobian) on N = 16385 inputs, solved by `_solve` from the
        same on 1025 inputs, solved by Newton's method from `_track` (the tracked path); the guesses it interpolates
        are within about 1e-14 (m^2 residual).
        """
        lo, hi = self.domain
        theta = PathTable.inputs(lo, hi, 1025)
        rough = PathTable(lo, hi, self._columns(theta, self._newton_2(theta, self._tracked(theta))))
        theta = PathTable.inputs(lo, hi, 16385)
        return PathTable(lo, hi, self._columns(theta, np.stack(self._solve(theta, rough), axis=-1)))

    def _tracked(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """(theta_D, beta) (n, 2) at inputs theta, linear between the states of `_track` (0.5 deg apart)."""
        grid, track, _ = self._track
        e3 = self._points(grid, track[:, 0], track[:, 1], track[:, 2])[:, NAMES.index("E3")]
        to_a = np.linalg.inv(self._square_a)
        circle = self._circle[0]
        arm = e3 @ to_a[:3, :3].T + to_a[:3, 3] - circle[0]
        beta = np.unwrap(np.arctan2(arm @ circle[2], arm @ circle[1]))
        return np.stack([np.interp(theta, grid, track[:, 0]), np.interp(theta, grid, beta)], -1)

    def _newton_2(self, theta: NDArray[np.float64], guess: NDArray[np.float64]) -> NDArray[np.float64]:
        """(theta_D, beta) (n, 2) closing `_closure` at inputs theta, by Newton's method (central differences)."""
        one = self._bricard_1(theta)

        def residual(y: NDArray[np.float64], rows: NDArray[np.intp]) -> NDArray[np.float64]:
            return self._closure(tuple(a[..., rows] for a in one), self._cylinder(y[:, 0]), y[:, 1])

        def correction(y: NDArray[np.float64], rows: NDArray[np.intp], r: NDArray[np.float64]) -> NDArray:
            inverse = self._columns(theta[rows], y)[:, 2:].reshape(-1, 2, 2)
            return np.einsum("nij,nj->ni", inverse, r)

        return polish(guess, residual, correction, "theta_D and beta", RESIDUAL_FLOOR)

    def _columns(self, theta: NDArray[np.float64], path: NDArray[np.float64]) -> NDArray[np.float64]:
        """
        The `_table` values (N, 6) at inputs theta for (theta_D, beta) (N, 2) on the path: those and the inverse
        Jacobian of `_closure` with respect to them (row-major; central differences, step 1e-7).
        """
        one = self._bricard_1(theta)
        J = np.empty((len(theta), 2, 2))
        for k, step in enumerate(np.eye(2) * 1e-7):
            up, down = path + step, path - step
            J[:, :, k] = (self._closure(one, self._cylinder(up[:, 0]), up[:, 1])
                          - self._closure(one, self._cylinder(down[:, 0]), down[:, 1])) / 2e-7
        return np.column_stack([path, np.linalg.inv(J).reshape(-1, 4)])

    def _solve(self, theta: NDArray[np.float64], table: PathTable) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """
        theta_D and beta (n,) (rad) at inputs theta inside `domain`: chord steps on `_closure` from the guesses of
        `table` (`_table`), with its inverse Jacobians. The same closure as `equations`, reduced to two unknowns:
        the R joint at A3 holds E3 on a circle, and E3 fixes Bricard 2's turn psi and shift h on the common axis.
        """
        one = self._bricard_1(theta)
        where = table.locate(theta)

        def residual(y: NDArray[np.float64], rows: NDArray[np.intp]) -> NDArray[np.float64]:
            return self._closure(tuple(a[..., rows] for a in one), self._cylinder(y[:, 0]), y[:, 1])

        def correction(y: NDArray[np.float64], rows: NDArray[np.intp], r: NDArray[np.float64]) -> NDArray:
            return np.einsum("nij,nj->ni", table.at(where, slice(2, 6), rows).reshape(-1, 2, 2), r)

        y = polish(table.at(where, slice(0, 2)), residual, correction, "theta_D and beta", RESIDUAL_FLOOR)
        return y[:, 0], y[:, 1]

    def vertices(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Vertex positions (n, 24, 3) in `NAMES` order (m, deployed frame, square A fixed)."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        x = self.state(t)
        return self._points(t, x[:, 0], x[:, 1], x[:, 2])

    def body_poses(self, theta: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        World poses (n, 4, 4) of the 6 squares ('A'..'F') and 12 bars (e.g. 'A2C1') relative to the deployed
        state (identity there; square A fixed), fitted to the vertices. A bar with an R joint is fixed by its
        two ends and its R axis, which turns with the square; an S-S bar's idle spin about its own axis is
        taken as the smallest rotation of its direction (any spin closes every loop).
        """
        P = self.vertices(theta)
        at = {v: P[:, k] for k, v in enumerate(NAMES)}
        poses = {sq[0][0]: rigid_fit([VERTICES[v] for v in sq], np.stack([at[v] for v in sq], 1)) for sq in SQUARES}
        for vertex, axis in revolute_axes(self.zeta).items():
            bar = next(a + b for a, b in BARS if vertex in (a, b))
            tip = poses[vertex[0]][:, :3, :3] @ axis + at[vertex]
            ends = [bar[:2], bar[2:]]
            poses.setdefault(bar, rigid_fit([VERTICES[v] for v in ends] + [VERTICES[vertex] + axis],
                                            np.stack([at[v] for v in ends] + [tip], 1)))
        for a, b in SS_BARS:
            T = np.zeros((len(P), 4, 4))
            T[:, :3, :3] = minimal_rotation(unit(VERTICES[b] - VERTICES[a]), unit(at[b] - at[a]))
            T[:, :3, 3], T[:, 3, 3] = at[a] - T[:, :3, :3] @ VERTICES[a], 1.0
            poses[a + b] = T
        return poses

    # --- the zeta study: pseudo-arclength through turning points and folds ------------------------------------

    def _equations_u(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        """`equations` (n, 3) for states u = (theta, theta_D, psi, h) (n, 4)."""
        return self.equations(u[:, 0], u[:, 1:])

    def _jacobian_u(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        """d equations / du (3, 4) at one state u (4,), central differences (step 1e-7)."""
        g = self._equations_u(u + 1e-7 * np.vstack([np.eye(4), -np.eye(4)]))
        return (g[:4] - g[4:]).T / 2e-7

    def _correct_u(self, u: NDArray[np.float64], row: NDArray[np.float64], value: float) -> NDArray[np.float64]:
        """Newton on [equations(u); row . u - value] = 0 from u; ConvergenceError naming zeta if it does not close."""
        for _ in range(30):
            r = np.append(self._equations_u(u[None])[0], row @ u - value)
            if np.max(np.abs(r)) < 1e-14:
                return u
            u = u - np.linalg.solve(np.vstack([self._jacobian_u(u), row]), r)
        if np.all(np.isfinite(u)) and np.max(np.abs(self._equations_u(u[None]))) < 1e-12:
            return u
        raise ConvergenceError(
            f"zeta = {np.rad2deg(self.zeta):.6g} deg: the reduced model did not close near state {np.round(u, 6)}"
        )

    def _signed_rho(self, u: NDArray[np.float64]) -> tuple[float, float]:
        """Signed (rho1, rho2) (rad) at a state u (4,): negative beyond its Bricard's fold (theta > theta_f)."""
        P = self._points(u[None, 0], u[None, 1], u[None, 2], u[None, 3])[0]
        k = {v: i for i, v in enumerate(NAMES)}

        def angle(a: str, at: str, b: str) -> float:
            p, q = P[k[a]] - P[k[at]], P[k[b]] - P[k[at]]
            return float(np.arctan2(np.linalg.norm(np.cross(p, q)), p @ q))

        rho1, rho2 = angle("B1", "C2", "C1"), angle("D1", "F2", "F1")
        return float(np.copysign(rho1, self.theta_f - u[0])), float(np.copysign(rho2, self.theta_f - u[1]))

    def outcome(self, step: float = 0.02, max_length: float = 20.0) -> PathOutcome:
        """
        The path from the deployed state by pseudo-arclength (step in the mixed rad / m norm of u), up to its
        first fold event (see `PathOutcome`); each fold is solved exactly (theta or theta_D = theta_f).
        ConvergenceError names zeta when the corrector fails.
        """
        u = np.array([self.theta_d, self.theta_d, 0.0, 0.0])
        t = np.linalg.svd(self._jacobian_u(u))[2][-1]
        t = t if t[0] > 0 else -t
        start, turns, length = u.copy(), [], 0.0
        rho1_min, rho1_max, gap_max = 2 * np.pi / 3, 2 * np.pi / 3, 0.0

        def end(kind: str, at: NDArray[np.float64]) -> PathOutcome:
            rho1, rho2 = self._signed_rho(at)
            return PathOutcome(self.zeta, kind, float(at[0]), rho1, rho2, tuple(turns), rho1_min, rho1_max, gap_max)

        while length < max_length:
            guess = u + step * t
            if np.max(np.abs(guess[:2])) >= np.pi:  # a Bricard angle leaves its closed form's domain
                return end("no-end", u)
            new = self._correct_u(guess, t, t @ guess)
            t_new = np.linalg.svd(self._jacobian_u(new))[2][-1]
            t_new = t_new if t_new @ t > 0 else -t_new
            if t_new[0] * t[0] < 0:  # theta turned back within this step (to the step's O(step^2))
                turns.append(float(max(u[0], new[0]) if t[0] > 0 else min(u[0], new[0])))
            for i in (0, 1):  # a Bricard reaches its fold within this step
                if (u[i] - self.theta_f) * (new[i] - self.theta_f) <= 0 and new[i] != u[i]:
                    w = (self.theta_f - u[i]) / (new[i] - u[i])
                    fold = self._correct_u(u + w * (new - u), np.eye(4)[i], self.theta_f)
                    cube = abs(fold[1 - i] - self.theta_f) < 1e-9
                    return end("cube" if cube else ("rho1-negative", "rho2-negative")[i], fold)
            rho1, rho2 = self._signed_rho(new)
            rho1_min, rho1_max = min(rho1_min, rho1), max(rho1_max, rho1)
            gap_max = max(gap_max, abs(rho1 - rho2))
            length += float(np.linalg.norm(new - u))
            u, t = new, t_new
            if length > 2 * step and np.linalg.norm(u - start) < step:
                return end("loop", start)
        return end("no-end", u)

    def fold_angles(self, theta: ArrayLike) -> NDArray[np.float64]:
        """
        (rho1, rho2, delta_A, delta_D) per input (n, 4), rad (Yang 2017's rho^A, rho^D, delta^A, delta^D): rho1 = angle
        B1 C2 C1, rho2 = angle D1 F2 F1 (120 deg -> 0), delta_A = angle C2 C1 A2, delta_D = angle F2 F1 E2 (120 -> 90
        deg).
        """
        P = self.vertices(theta)
        k = {v: i for i, v in enumerate(NAMES)}

        def angle(a: str, at: str, b: str) -> NDArray[np.float64]:
            u, w = P[:, k[a]] - P[:, k[at]], P[:, k[b]] - P[:, k[at]]
            return np.arctan2(np.linalg.norm(np.cross(u, w), axis=-1), np.einsum("ni,ni->n", u, w))

        return np.stack(
            [angle("B1", "C2", "C1"), angle("D1", "F2", "F1"), angle("C2", "C1", "A2"), angle("F2", "F1", "E2")], -1
        )
