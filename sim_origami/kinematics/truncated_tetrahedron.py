"""Transformable polyhedron of Yang 2017, ch. 6: truncated tetrahedron <-> tetrahedron, schemes I and II.

Frame and units: the thesis's (6-1) frame, unit edges (m): origin at the centre of hexagon ABCDEF, z its normal,
x toward F; angles in radians. Every position returned is given with triangle ABG (the root body) held at its
deployed pose, so the deployed coordinates are exactly (6-1).

Assembly (Yang 2017, §6.2): 4 rigid triangles ABG, CDH, EFJ, KLM and 6 rigid bars BC, DE, FA, GK, HL, JM.
The threefold Bricard is the hexagon A B C D E F (links ABG, BC, CDH, DE, EFJ, FA) with R joints at A..F along
the printed (6-4, 6-13, 6-14) axes. Scheme I adds R joints at G, H, J (triangle -> bar, axis s_G) and S joints
at K, L, M (bar -> triangle KLM); scheme II adds S joints at G, H, J (triangle -> bar) and R joints at K, L, M
(bar -> triangle KLM, axis s_K). 9 R + 3 S, 10 bodies, 3 loops, 1 DOF (truss j = 21, b = 57, r = 56, s = 1).

Axes (the printed (6-17), (6-18) and (6-33) corrected here): s_G(delta1) = Rot(unit(B - K), delta1) unit(G - Q)
and s_K(delta2) = Rot(unit(G - M), delta2) unit(K - Q), Q = (0, 0, sqrt 6 / 4) the body centre; H, J and L, M get
the +-120 deg images about z. The thesis's printed s_G (6-17) is the direction of OG, not QG, and its s_M (6-18)
= (sqrt 210/35, -2 sqrt 35/35, sqrt 35/7) is not the image of s_K; the symmetric s_M is (sqrt 22/11, -sqrt 66/33,
5 sqrt 33/33).

Reduced model (derived here for scheme I and extended to scheme II). The motion keeps the threefold
symmetry about the Bricard's axis (the normal of triangle BDF through its centroid; the "symmetric frame",
which is the (6-1) frame at deployment). The Bricard follows its closed form (`BricardThreefold`, branch
'even-axes-along': theta at A, C, E, phi at B, D, F, the thesis's '-' root of (6-52)); triangle KLM stays centred on
the axis, turned by psi (rad) and shifted by h (m) along it. The state u = (theta, q, psi, h), with q the
scheme's R-joint angle (q_G or q_K, 0 deployed), obeys three equations, the closure of the loop through G and K:

* scheme I: K carried by the bar GK (turned by q_G about s_G through G, relative to ABG) = K of KLM;
* scheme II: G carried by the bar GK (held by KLM through the R joint at K at angle q_K) = G of ABG.

The 1-D solution set is traced from the deployed state (pseudo-arclength, step 0.02) in the direction in
which KLM turns positively about z (d psi > 0: the thesis's KLM rotation 0 -> 30 deg), up to the Bricard fold
theta_f (A = C = E, Yang 2017, §6.3.2), where the path ends: beyond it the Bricard's links pass through each
other. For delta beyond measured limits the direction d psi > 0 heads instead for the Bricard's other fold
B = D = F (theta falling to theta_b = -106.0 deg): a ParameterError (`_heads_for_bdf`). A path that reaches the
tetrahedron ends exactly on its state (`tetrahedron_state`), where theta turns back; one that misses it (scheme I,
delta1 >= -3 deg) ends at theta_f with K short of B (`end_gap`).
Queries are solved by Newton from a cubic Hermite guess on the trace. The R-joint angles alone (`hinge_angles`,
what `evaluate` reports; no poses) need only theta and q: KLM turns and slides on the Bricard's threefold axis,
so the closure reduces to one equation, the distance of K (scheme I) or G (scheme II) from that axis
(`bricard_axis`, in closed form), solved from a table dense in the input (`PathTable`).

Inputs (the thesis's driving angles): scheme I is driven by theta_G = theta_G0 + q_G (the thesis's quartic unknown,
the signed angle from B - G to K - G about s_G, 146.4427 deg deployed for delta1 = 0), which falls
monotonically; the Bricard's theta cannot drive it, since theta has a turning point at deployment (delta1 = 0)
or dips below theta_d first (delta1 < 0, measured here). Scheme II is driven by the Bricard angle theta at A,
which rises monotonically to theta_f for delta2 >= 0. Derived here: with delta2 = 0 the deployed state is a turning
point of theta too (dtheta/ds = 0; the two directions are distinct motions, of which d psi > 0 reaches the
tetrahedron): near theta_d the state is fixed by theta only to sqrt(theta - theta_d).
"""

from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ConvergenceError, ParameterError
from ..geometry import (
    common_normal_foot,
    enclosed_volume,
    invert,
    rotation,
    signed_angle,
    transform,
    transform_z,
    unit,
    wrap,
)
from ..path import hermite
from .base import Event, transformation_inputs
from .bricard_threefold import ALONG, BricardThreefold, bricard_axis, bricard_trig
from .dh import DHRow, dh_from_axes
from .path_table import PathTable, polish, wrap_if_needed

R2, R3, R6 = np.sqrt(2.0), np.sqrt(3.0), np.sqrt(6.0)
# (6-1): the truncated tetrahedron, unit edges.
VERTICES: dict[str, NDArray[np.float64]] = {
    name: np.array(xyz, dtype=float)
    for name, xyz in {
        "A": (0.5, R3 / 2, 0), "B": (-0.5, R3 / 2, 0), "C": (-1, 0, 0), "D": (-0.5, -R3 / 2, 0),
        "E": (0.5, -R3 / 2, 0), "F": (1, 0, 0), "G": (0, 2 * R3 / 3, R6 / 3), "H": (-1, -R3 / 3, R6 / 3),
        "J": (1, -R3 / 3, R6 / 3), "K": (0, R3 / 3, 2 * R6 / 3), "L": (-0.5, -R3 / 6, 2 * R6 / 3),
        "M": (0.5, -R3 / 6, 2 * R6 / 3),
    }.items()
}
NAMES: tuple[str, ...] = tuple(VERTICES)
# (6-3): the tetrahedron (edge 1) each vertex reaches; merged vertices share a corner.
TETRAHEDRON: dict[str, NDArray[np.float64]] = {
    name: np.array(xyz, dtype=float)
    for corner, xyz in {
        "ACE": (0, 0, 0), "BHK": (-R3 / 6, 0.5, R6 / 3), "DJL": (-R3 / 6, -0.5, R6 / 3), "FGM": (R3 / 3, 0, R6 / 3)
    }.items()
    for name in corner
}
Q = np.array([0.0, 0.0, R6 / 4])  # body centre (6-2)
TRIANGLES = ("ABG", "CDH", "EFJ", "KLM")
BARS = ("BC", "DE", "FA", "GK", "HL", "JM")
BODIES = TRIANGLES + BARS
LINKS = ("ABG", "BC", "CDH", "DE", "EFJ", "FA")  # Bricard link k joins joint k (A..F) to joint k + 1
ROOT = "ABG"
# R joints in `revolute_angles` order; parent -> child (the angle turns the child about +axis).
REVOLUTE_I = ("A", "B", "C", "D", "E", "F", "G", "H", "J")
REVOLUTE_II = ("A", "B", "C", "D", "E", "F", "K", "L", "M")
PARENTS = {"A": ("FA", "ABG"), "B": ("ABG", "BC"), "C": ("BC", "CDH"), "D": ("CDH", "DE"), "E": ("DE", "EFJ"),
           "F": ("EFJ", "FA"), "G": ("ABG", "GK"), "H": ("CDH", "HL"), "J": ("EFJ", "JM"),
           "K": ("GK", "KLM"), "L": ("HL", "KLM"), "M": ("JM", "KLM")}
# Rounding floor (m^2) of the squared radii (<= 4/3 m^2) in `Transformation._solve`'s residual: the residuals of
# Newton's method stall at 1.9e-15 (measured on 1e6 inputs, either scheme).
RESIDUAL_FLOOR = 4e-15
# Exact volumes for unit edges: truncated tetrahedron 23 sqrt 2 / 12, tetrahedron sqrt 2 / 12 (Yang 2017, ch. 6: 23).
VOLUME_RATIO = 23.0


def _turn(k: int) -> NDArray[np.float64]:
    """Rz(k 120 deg) (3, 3): k = 1 maps A -> C, F -> B, G -> H, K -> L (Yang 2017, §6.2)."""
    return rotation(np.array([0.0, 0.0, 1.0]), 2 * np.pi * k / 3)


def bricard_axes() -> NDArray[np.float64]:
    """Unit axes (6, 3) of the R joints A..F (6-4, 6-13, 6-14), oriented as printed."""
    s_a = np.array([np.sqrt(22) / 11, np.sqrt(66) / 11, -np.sqrt(33) / 11])
    s_f = np.array([-2 * np.sqrt(166) / 83, 0.0, 5 * np.sqrt(249) / 83])
    return np.array([s_a, _turn(1) @ s_f, _turn(1) @ s_a, _turn(-1) @ s_f, _turn(-1) @ s_a, s_f])


def axis_g(delta: float) -> NDArray[np.float64]:
    """Unit s_G (scheme I) = Rot(unit(B - K), delta) unit(G - Q) (sign chosen here); delta = 0: (0, 4√66/33, √33/33)."""
    return rotation(unit(VERTICES["B"] - VERTICES["K"]), delta) @ unit(VERTICES["G"] - Q)


def axis_k(delta: float) -> NDArray[np.float64]:
    """Unit s_K (scheme II) = Rot(unit(G - M), delta) unit(K - Q); delta = 0 is (0, 2√66/33, 5√33/33)."""
    return rotation(unit(VERTICES["G"] - VERTICES["M"]), delta) @ unit(VERTICES["K"] - Q)


def faces() -> tuple[tuple[str, ...], ...]:
    """The 4 triangles and 4 hexagons (hollow in the mechanism) as outward (counter-clockwise) vertex cycles."""
    out = []
    for face in (*TRIANGLES, "ABCDEF", "BCHLKG", "DEJMLH", "FAGKMJ"):
        P = np.array([VERTICES[v] for v in face])
        normal = np.cross(P[1] - P[0], P[2] - P[0])
        out.append(tuple(face) if normal @ (P.mean(0) - Q) > 0 else tuple(face[::-1]))
    return tuple(out)


def volume(points: ArrayLike) -> NDArray[np.float64]:
    """Volume (m^3) enclosed by `faces()` for vertex positions (..., 12, 3) in `NAMES` order (`enclosed_volume`)."""
    index = {v: k for k, v in enumerate(NAMES)}
    return enclosed_volume(points, [[index[v] for v in face] for face in faces()])


def _about_line(point: NDArray, axis: NDArray, angle: ArrayLike) -> NDArray[np.float64]:
    """Rigid transforms (..., 4, 4): rotation by `angle` (rad) about the line through `point` along unit `axis`."""
    R = rotation(axis, angle)
    T = np.zeros((*R.shape[:-2], 4, 4))
    T[..., :3, :3], T[..., 3, 3] = R, 1.0
    T[..., :3, 3] = point - R @ point
    return T


def _screw(psi: ArrayLike, h: ArrayLike) -> NDArray[np.float64]:
    """Tz(h) Rz(psi), (..., 4, 4): the pose of KLM in the symmetric frame (identity deployed)."""
    T = transform_z(psi)
    T[..., 2, 3] = h
    return T


def _apply(T: NDArray, p: NDArray) -> NDArray[np.float64]:
    """Transforms (..., 4, 4) applied to one point (3,) -> (..., 3)."""
    return T[..., :3, :3] @ p + T[..., :3, 3]


def _angle_about(u: ArrayLike, v: ArrayLike, axis: ArrayLike) -> NDArray[np.float64]:
    """Right-handed angle (...) (rad) from u to v about unit `axis`, both projected onto the plane normal to it."""
    u, v, axis = (np.asarray(w, dtype=float) for w in (u, v, axis))
    u = u - np.einsum("...i,...i", u, axis)[..., None] * axis
    v = v - np.einsum("...i,...i", v, axis)[..., None] * axis
    return signed_angle(u, v, axis)


class Transformation:
    """
    Shared closed form of both schemes (see the module docstring); subclasses set the top joints.

    `delta` (rad) turns the scheme's R axis (delta1 or delta2, Yang 2017, §6.5); it must lie in (-90, 90) deg.
    """

    input_name: str
    REVOLUTE: tuple[str, ...]
    _input: int  # index of the input in the state u = (theta, q, psi, h)
    _symbol: str  # "delta1" or "delta2", for messages
    _reach: str  # the open delta interval (deg) whose paths head for the fold A = C = E (`_heads_for_bdf`)

    def __init__(self, delta: float = 0.0):
        if not (np.isfinite(delta) and abs(delta) < np.pi / 2):
            raise ParameterError(
                f"{self._symbol} = {np.rad2deg(delta):.6g} deg; it must lie in (-90, 90) deg (the R axis must "
                "stay on the outer side of the bisecting plane it is turned in)"
            )
        self.delta = float(delta)
        dirs = bricard_axes()
        points = np.array([VERTICES[v] for v in "ABCDEF"])
        rows, angles = dh_from_axes(points, dirs)
        self.rows: tuple[DHRow, ...] = rows
        self.bricard = BricardThreefold(rows[0].a, rows[0].alpha % (2 * np.pi))
        self.theta_d, self.phi_d = float(angles[0]), float(angles[1])
        # Joint A's D-H frame (before Rz(theta)), fixed to bar FA: origin at the foot on axis A of the common
        # normal from axis F, x along that normal (Yang 2017's D-H convention, eqn 1-2); the chain below is placed
        # from it.
        foot_out = common_normal_foot(points[0], dirs[0], points[5], dirs[5])
        foot_in = common_normal_foot(points[5], dirs[5], points[0], dirs[0])
        x = unit(foot_in - foot_out)
        self._frame = transform(np.stack([x, np.cross(dirs[0], x), dirs[0]], axis=1), foot_in)
        self._deployed_inv = invert(self._chain(np.array([self.theta_d]))[0])
        self._setup_axes()

    # --- the Bricard ---------------------------------------------------------------------------------

    def phi(self, theta: ArrayLike) -> NDArray[np.float64]:
        """Even-joint angle phi (rad, at B, D, F) of the Bricard on the thesis's branch; theta may pass pi."""
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        return self.bricard.evaluate(ALONG, wrap(t))[0][:, 1]

    def _chain(self, theta: NDArray[np.float64]) -> NDArray[np.float64]:
        """D-H link frames (n, 6, 4, 4) of links ABG..FA at (theta, phi(theta)), bar FA fixed."""
        phi = self.phi(theta)
        poses = [self._frame @ transform_z(theta)]
        for k in range(5):
            poses.append(poses[-1] @ self.rows[k].link() @ transform_z(phi if k % 2 == 0 else theta))
        return np.stack(poses, axis=1)

    def bricard_motion(self, theta: ArrayLike) -> NDArray[np.float64]:
        """
        Motions (n, 6, 4, 4) of the links ABG..FA in the symmetric frame: each maps deployed (6-1) coordinates
        to current ones in the frame with origin at the centroid of BDF, z its normal (B, D, F counter-
        clockwise) and x toward F; identity at theta_d.
        """
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        M = self._chain(t) @ self._deployed_inv
        b, d, f = (_apply(M[:, k], VERTICES[v]) for k, v in ((0, "B"), (2, "D"), (4, "F")))
        origin = (b + d + f) / 3
        z = unit(np.cross(d - b, f - b))
        x = unit(f - origin)
        S = np.zeros((len(t), 4, 4))
        S[:, :3, :3] = np.stack([x, np.cross(z, x), z], axis=-1)
        S[:, :3, 3], S[:, 3, 3] = origin, 1.0
        return invert(S)[:, None] @ M

    @cached_property
    def theta_f(self) -> float:
        """Bricard angle (rad) at its fold A = C = E (Yang 2017, §6.3.2: 186.90 deg; 186.9018 here): A crosses the
        symmetric axis."""

        def y_a(t: float) -> float:  # A's y in the symmetric frame: > 0 before the fold, < 0 after
            return float(_apply(self.bricard_motion(t)[0, 0], VERTICES["A"])[1])

        lo, hi = np.deg2rad(170.0), np.deg2rad(200.0)
        if not y_a(lo) > 0 > y_a(hi):
            raise ConvergenceError("the Bricard fold A = C = E is not bracketed by theta in [170, 200] deg")
        for _ in range(80):  # bisection to the last bit
            mid = 0.5 * (lo + hi)
            if mid in (lo, hi):
                break
            lo, hi = (mid, hi) if y_a(mid) > 0 else (lo, mid)
        return 0.5 * (lo + hi)

    @cached_property
    def theta_b(self) -> float:
        """Bricard angle (rad) at its other fold B = D = F (-106.0 deg), theta falling from theta_d: the sampled
        minimum of |BD| on [-130, -80] deg (0.01 deg apart), the frame of `bricard_motion` being undefined there."""
        theta = np.deg2rad(np.linspace(-130.0, -80.0, 5001))
        M = self._chain(theta) @ self._deployed_inv
        gap = _apply(M[:, 0], VERTICES["B"]) - _apply(M[:, 2], VERTICES["D"])
        return float(theta[np.argmin(np.linalg.norm(gap, axis=-1))])

    # --- the top: scheme equations -------------------------------------------------------------------

    def _setup_axes(self) -> None:
        raise NotImplementedError

    def _bar(self, u: NDArray[np.float64], abg: NDArray[np.float64]) -> NDArray[np.float64]:
        """Motion (n, 4, 4) of bar GK in the symmetric frame for states u (n, 4) and ABG's motion (n, 4, 4)."""
        raise NotImplementedError

    def equations(self, u: ArrayLike) -> NDArray[np.float64]:
        """The closure (n, 3) (m) of the loop through G and K for states u = (theta, q, psi, h) (n, 4)."""
        raise NotImplementedError

    def _jacobian(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        """d equations / du (3, 4) at one state, central differences (step 1e-7)."""
        probes = u + 1e-7 * np.vstack([np.eye(4), -np.eye(4)])
        g = self.equations(probes)
        return (g[:4] - g[4:]).T / 2e-7

    def _correct(self, u: NDArray[np.float64], row: NDArray[np.float64], value: float) -> NDArray[np.float64]:
        """
        Newton on [equations(u); row . u - value] = 0 from u (a regular square system off turning points);
        stops when the step falls below 1e-15 or the residual below 4e-16 (m, rad).
        """
        for _ in range(30):
            r = np.append(self.equations(u)[0], row @ u - value)
            if np.max(np.abs(r)) < 4e-16:
                return u
            step = np.linalg.solve(np.vstack([self._jacobian(u), row]), r)
            u = u - step
            if np.max(np.abs(step)) < 1e-15:
                break
        residual = float(np.max(np.abs(self.equations(u))))
        if residual < 1e-14:
            return u
        raise ConvergenceError(f"the closure did not converge at state {u} (residual {residual:.3g} m)")

    @staticmethod
    def _tangent(J: NDArray[np.float64], previous: NDArray[np.float64]) -> NDArray[np.float64]:
        """Unit null vector of J (3, 4) oriented along `previous`."""
        t = np.linalg.svd(J)[2][-1]
        return t if t @ previous > 0 else -t

    @cached_property
    def trace(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """
        The path (s (k,), u (k, 4)) from the deployed state to the Bricard fold: pseudo-arclength s (mixed rad/m
        norm), step 0.02, leaving in the direction d psi > 0; the last row is the tetrahedron state or lies exactly at
        theta = theta_f.
        """
        u = np.zeros(4)
        u[0] = self.theta_d
        t = self._tangent(self._jacobian(u), np.array([0.0, 0.0, 1.0, 0.0]))
        ds, s, us, ts = 0.02, [0.0], [u], [t]
        target = self.tetrahedron_state()
        while us[-1][0] < self.theta_f:
            if len(us) > 5000:
                raise ConvergenceError("the path did not reach the Bricard fold within 5000 steps of 0.02")
            guess = us[-1] + ds * ts[-1]
            u = self._correct(guess, ts[-1], ts[-1] @ guess)
            ts.append(self._tangent(self._jacobian(u), ts[-1]))
            us.append(u)
            s.append(s[-1] + float(np.linalg.norm(u - us[-2])))
            if u[0] < self.theta_b / 2:
                self._heads_for_bdf()
            # The tetrahedron solves the equations for every delta (the axes stay in their bisecting planes) and
            # theta turns back there, so a step can jump it: a path that reaches it passes within the chord error
            # of a step (<= 6e-5 measured), one that misses passes >= 0.012 away (delta1 = -3 deg).
            a, b = us[-2], us[-1]
            w = np.clip((target - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
            if np.linalg.norm(a + w * (b - a) - target) < 1e-3:
                us[-1], s[-1] = target, s[-2] + float(np.linalg.norm(target - a))
                ts[-1] = self._tangent(self._jacobian(target), ts[-2])
                self._tangents = np.array(ts)
                return np.array(s), np.array(us)
        # end exactly at theta_f: Newton with theta fixed from the secant between the last two states
        a, b = us[-2], us[-1]
        guess = a + (self.theta_f - a[0]) / (b[0] - a[0]) * (b - a)
        us[-1] = self._correct(guess, np.eye(4)[0], self.theta_f)
        s[-1] = s[-2] + float(np.linalg.norm(us[-1] - us[-2]))
        ts[-1] = self._tangent(self._jacobian(us[-1]), ts[-2])
        self._tangents = np.array(ts)
        return np.array(s), np.array(us)

    def _heads_for_bdf(self) -> None:
        """
        ParameterError: the path heads for the fold B = D = F, not A = C = E (called once theta < theta_b / 2).

        Paths that reach A = C = E dip at most to theta = -25.2 deg before rising (delta2 = -27.55 deg); past a critical
        delta the direction d psi > 0 instead runs down to B = D = F, where the symmetric frame (triangle BDF)
        degenerates: Newton's residual stalled at 1.3e-14 m (rounding 6e-15 m there, 1.3e-15 deployed) at
        theta = -104 deg, |BD| = 0.03 m (delta1 = 89.999 deg), or the trace jumped branches (delta2 = -28 deg:
        theta -824 deg). theta_b / 2 = -53 deg lies between the two. The limits (`_reach`) were bisected to 0.005 deg;
        the other direction is a different design (e.g. delta2 = 89.999 deg: KLM turns the other way and
        ends 1.36 m short of the tetrahedron), not this scene's.
        """
        raise ParameterError(
            f"{self._symbol} = {np.rad2deg(self.delta):.6g} deg: the path from the truncated tetrahedron heads for "
            f"the Bricard's other fold B = D = F (theta = {np.rad2deg(self.theta_b):.1f} deg), not for the fold "
            f"A = C = E or the tetrahedron: {self._symbol} must lie in {self._reach} deg (measured)"
        )

    def tetrahedron_state(self) -> NDArray[np.float64]:
        """The state u (4,) of the tetrahedron (6-3): theta = theta_f, K on B (so L on D, M on F), the bar GK on BF."""
        abg = self.bricard_motion(self.theta_f)[0, 0]
        b, k0 = _apply(abg, VERTICES["B"]), VERTICES["K"]
        psi, h = np.arctan2(b[1], b[0]) - np.arctan2(k0[1], k0[0]), b[2] - k0[2]
        return np.array([self.theta_f, self._top_angle(abg, _screw(psi, h)), psi, h])

    def _top_angle(self, abg: NDArray[np.float64], klm: NDArray[np.float64]) -> float:
        """The R-joint angle q (rad) at the tetrahedron, from the motions of ABG and KLM there."""
        raise NotImplementedError

    def _input_of(self, u: NDArray[np.float64]) -> NDArray[np.float64]:
        """Input values (...) of states u (..., 4)."""
        return u[..., self._input] + self._offset

    _offset = 0.0

    @cached_property
    def _monotone(self) -> float:
        """+1 / -1: the sign with which the input moves along the trace; ParameterError where it turns back."""
        x = self._input_of(self.trace[1])
        step = np.sign(np.diff(x))
        if not (np.all(step == step[-1]) and step[-1] != 0):
            k = int(np.argmax(step != step[-1]))
            raise ParameterError(
                f"{self._symbol} = {np.rad2deg(self.delta):.6g} deg: the input {self.input_name} turns back at "
                f"{np.rad2deg(x[k + 1]):.6g} deg on the way to the Bricard fold, so it cannot drive this design "
                "(the input must be monotone along the path)"
            )
        return float(step[-1])

    @property
    def reference(self) -> float:
        """The input (rad) at the deployed truncated tetrahedron, where every body is at its reference pose."""
        return float(self._input_of(self.trace[1][0]))

    @property
    def domain(self) -> tuple[float, float]:
        """Closed input interval (rad) from the truncated tetrahedron to the end of the path (Bricard fold)."""
        ends = self._input_of(self.trace[1][[0, -1]])
        return (float(ends[0]), float(ends[1])) if self._monotone > 0 else (float(ends[1]), float(ends[0]))

    def state(self, x: ArrayLike) -> NDArray[np.float64]:
        """
        States u = (theta, q, psi, h) (n, 4) (rad, rad, rad, m) at inputs x (rad), on the traced path.

        Raises
        ------
        DomainError
          When an input is not finite or lies outside `domain`.
        """
        x = self._inputs(x)
        s, us = self.trace
        xs = self._monotone * self._input_of(us)
        rate = self._monotone * self._tangents[:, self._input]  # d(input)/ds >= 0 along the trace
        target = self._monotone * x
        k = np.clip(np.searchsorted(xs, target) - 1, 0, len(s) - 2)
        # cubic Hermite in s on [s_k, s_k+1]: invert the input by bisection (all inputs at once), then take u there
        h = s[k + 1] - s[k]
        a, b = np.zeros(len(x)), np.ones(len(x))
        for _ in range(60):
            mid = 0.5 * (a + b)
            below = hermite(xs[k], xs[k + 1], h * rate[k], h * rate[k + 1], mid) < target
            a, b = np.where(below, mid, a), np.where(below, b, mid)
        w = 0.5 * (a + b)[:, None]
        guess = hermite(us[k], us[k + 1], h[:, None] * self._tangents[k], h[:, None] * self._tangents[k + 1], w)
        out = self._correct_inputs(guess, x - self._offset)
        out[target <= xs[0]], out[target >= xs[-1]] = us[0], us[-1]
        return out

    def _inputs(self, x: ArrayLike) -> NDArray[np.float64]:
        """Inputs as a 1-D array (rad); DomainError naming the first one not finite or outside `domain` (+-1e-12)."""
        return transformation_inputs(x, self.domain, self.input_name, "truncated tetrahedron to the Bricard fold")

    def _correct_inputs(self, u: NDArray[np.float64], value: NDArray[np.float64]) -> NDArray[np.float64]:
        """
        Newton on [equations(u); u_input - value] = 0 for states u (n, 4) at once (a regular square system off
        turning points), each row until its residual is below 4e-16 or its step below 1e-15 (m, rad).
        """
        u, active = u.copy(), np.arange(len(u))
        row = np.eye(4)[self._input]
        for _ in range(30):
            r = np.concatenate([self.equations(u[active]), (u[active, self._input] - value[active])[:, None]], 1)
            active, r = active[np.max(np.abs(r), 1) >= 4e-16], r[np.max(np.abs(r), 1) >= 4e-16]
            if not len(active):
                return u
            probes = (u[active, None, :] + 1e-7 * np.vstack([np.eye(4), -np.eye(4)])).reshape(-1, 4)
            g = self.equations(probes).reshape(-1, 8, 3)
            J = np.concatenate(
                [np.swapaxes(g[:, :4] - g[:, 4:], 1, 2) / 2e-7, np.broadcast_to(row, (len(active), 1, 4))], 1
            )
            step = np.linalg.solve(J, r[..., None])[..., 0]
            u[active] -= step
            active = active[np.max(np.abs(step), 1) >= 1e-15]
        residual = np.max(np.abs(self.equations(u)), axis=1)
        if np.any(residual >= 1e-14):
            bad = int(np.argmax(residual))
            raise ConvergenceError(f"the closure did not converge at state {u[bad]} (residual {residual[bad]:.3g} m)")
        return u

    # --- poses and outputs ---------------------------------------------------------------------------

    def _motions(self, u: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
        """Motions (n, 4, 4) of every body in the symmetric frame (deployed coordinates -> current)."""
        links = self.bricard_motion(u[:, 0])
        out = {name: links[:, k] for k, name in enumerate(LINKS)}
        out["KLM"] = _screw(u[:, 2], u[:, 3])
        gk = self._bar(u, out["ABG"])
        for k, name in enumerate(("GK", "HL", "JM")):
            turn = transform(_turn(k))
            out[name] = turn @ gk @ turn.T
        return out

    def body_poses(self, x: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        World poses (n, 4, 4) of the 10 bodies relative to their deployed poses (identity at the deployed
        input), root ABG fixed: body frame = deployed world frame, as in `scenes.truncated_tetrahedron`.
        """
        motions = self._motions(self.state(x))
        to_root = invert(motions[ROOT])
        return {name: to_root @ M for name, M in motions.items()}

    def vertices(self, x: ArrayLike) -> NDArray[np.float64]:
        """Vertex positions (n, 12, 3) in `NAMES` order (m, deployed frame, triangle ABG fixed)."""
        poses = self.body_poses(x)
        owner = {v: body for body in TRIANGLES for v in body}
        return np.stack([_apply(poses[owner[v]], VERTICES[v]) for v in NAMES], axis=1)

    def revolute_angles(self, x: ArrayLike) -> NDArray[np.float64]:
        """
        R-joint angles (n, 9) (rad) in `REVOLUTE` order, 0 deployed: the child's turn relative to the parent
        about +axis (`PARENTS`); Bricard joints are D-H angle minus deployed value (theta at A, C, E, phi at
        B, D, F), the top joints all equal q; wrapped to (-pi, pi] (every one stays inside (-pi, pi) on the
        path, so they are continuous).
        """
        return np.stack(list(self.hinge_angles(x).values()), axis=-1)

    def hinge_angles(self, x: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        `revolute_angles` (n,) (rad) by joint name (`REVOLUTE`), from theta and q of `_solve` (no poses): the
        assembly's R joints (`scenes.truncated_tetrahedron`).
        """
        theta, q = self._solve(self._inputs(x), self._table)
        cp, sp = bricard_trig(self.bricard, theta)[2:]
        dt, dp, q = (wrap_if_needed(a) for a in (theta - self.theta_d, np.arctan2(sp, cp) - self.phi_d, q))
        return dict(zip(self.REVOLUTE, (dt, dp, dt, dp, dt, dp, q, q, q), strict=True))

    # --- theta and q without poses: one scalar equation per input ------------------------------------------------

    def _solve(self, x: NDArray[np.float64], table: PathTable) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """
        The Bricard angle theta and the top R-joint angle q (n,) (rad) at inputs x (rad) inside `domain`, solved
        from the guesses of `table` (`_table`).
        """
        raise NotImplementedError

    def _radius2(self, theta: NDArray[np.float64], point: NDArray[np.float64]) -> NDArray[np.float64]:
        """
        Squared distance (n,) (m^2) from the Bricard's threefold axis at Bricard angles theta (n,) of points (3,) or
        (3, n) given in ABG's D-H frame (joint A's, after Rz(theta)): `bricard_axis`, no poses.
        """
        u, p, _, _ = bricard_axis(self.bricard, theta)
        d = point[0] - p[0], point[1] - p[1], point[2] - p[2]
        return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) ** 2

    @cached_property
    def _to_abg(self) -> NDArray[np.float64]:
        """Deployed coordinates -> ABG's D-H frame (4, 4): the inverse of that frame at theta_d."""
        return invert(self._frame @ transform_z(self.theta_d))

    @cached_property
    def _table(self) -> PathTable:
        """
        `_columns` of the path (theta, q, ...) on N = 16385 inputs, solved by `_solve` from the same on 1025 inputs
        from `state` (the traced path); the guesses it interpolates are within about 1e-14 (m^2 residual).
        """
        lo, hi = self.domain
        rough = PathTable(lo, hi, self._columns(self.state(PathTable.inputs(lo, hi, 1025))[:, :2]))
        x = PathTable.inputs(lo, hi, 16385)
        return PathTable(lo, hi, self._columns(np.stack(self._solve(x, rough), axis=-1)))

    def _columns(self, path: NDArray[np.float64]) -> NDArray[np.float64]:
        """The `_table` values (N, m) for (theta, q) (N, 2) on the path."""
        return path

    def monitors(self, x: ArrayLike) -> dict[str, NDArray[np.float64]]:
        """
        The thesis's monitors (n,) (Yang 2017, §6.3.2): rho = angle AFE, delta = angle BAF, lambda1 = angle BGK,
        lambda2 = angle GKM (rad); height of KLM's centroid above plane BDF (m); rotation of KLM about the BDF
        normal, signed from F - c_BDF to K - c_KLM (rad, 90 deg deployed); |AE|, |BK| (m); theta_G = signed
        angle from B - G to K - G about s_G (rad; scheme I's input, the thesis's quartic unknown).
        """
        P = self.vertices(x)
        p = {v: P[:, k] for k, v in enumerate(NAMES)}

        def angle(a: str, at: str, b: str) -> NDArray[np.float64]:
            return np.arccos(np.clip(np.einsum("ni,ni->n", unit(p[a] - p[at]), unit(p[b] - p[at])), -1.0, 1.0))

        base = (p["B"] + p["D"] + p["F"]) / 3
        normal = unit(np.cross(p["D"] - p["B"], p["F"] - p["B"]))
        top = (p["K"] + p["L"] + p["M"]) / 3
        return {
            "rho": angle("A", "F", "E"),
            "delta": angle("B", "A", "F"),
            "lambda1": angle("B", "G", "K"),
            "lambda2": angle("G", "K", "M"),
            "height": np.einsum("ni,ni->n", top - base, normal),
            "rotation": _angle_about(p["F"] - base, p["K"] - top, normal),
            "AE": np.linalg.norm(p["A"] - p["E"], axis=-1),
            "BK": np.linalg.norm(p["B"] - p["K"], axis=-1),
            "theta_G": _angle_about(p["B"] - p["G"], p["K"] - p["G"], self._theta_g_axis),
        }

    @property
    def end_gap(self) -> float:
        """|BK| (m) at the end of the path (no monotone input needed): 0 when the tetrahedron is reached."""
        M = self._motions(self.trace[1][-1:])
        return float(np.linalg.norm(_apply(M["KLM"], VERTICES["K"]) - _apply(M["ABG"], VERTICES["B"])))

    def events(self) -> tuple[Event, ...]:
        """The two ends of the path (the deployed truncated tetrahedron and the Bricard fold)."""
        lo, hi = self.domain
        start, end = (lo, hi) if self._monotone > 0 else (hi, lo)
        reach = self.end_gap
        fold = (
            "the tetrahedron: A = C = E and B, H, K; D, J, L; F, G, M merge"
            if reach < 1e-9
            else f"the Bricard fold A = C = E short of the tetrahedron (|BK| = {reach:.4g} m): going on would "
            "pass the Bricard's links through each other"
        )
        return (
            Event("end", start, ("deployed",), "the truncated tetrahedron (6-1)"),
            Event("lock", end, ("deployed",), fold),
        )


class SchemeI(Transformation):
    """
    Scheme I (Yang 2017, §6.3): R joints at G, H, J (triangle -> bar), S joints at K, L, M (bar -> KLM).

    Input theta_G (rad): the thesis's angle of K about s_G, theta_G0 + q_G, falling from its deployed value
    (146.4427 deg for delta1 = 0) to the end of the path. `delta` = delta1 (rad), sign chosen here (thumb along B - K).
    """

    input_name = "theta_G"
    REVOLUTE = REVOLUTE_I
    _input = 1
    _symbol = "delta1"
    _reach = "(-62.02, 56.95)"  # `_heads_for_bdf`

    def _setup_axes(self) -> None:
        self.s_g = axis_g(self.delta)
        self._theta_g_axis = self.s_g
        G, B, K = VERTICES["G"], VERTICES["B"], VERTICES["K"]
        self._offset = float(_angle_about(B - G, K - G, self.s_g))  # theta_G0

    def _bar(self, u: NDArray[np.float64], abg: NDArray[np.float64]) -> NDArray[np.float64]:
        return abg @ _about_line(VERTICES["G"], self.s_g, u[:, 1])

    def _top_angle(self, abg: NDArray[np.float64], klm: NDArray[np.float64]) -> float:
        return -self._offset  # theta_G = 0: the bar GK lies on GB

    def _bar_k(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """K carried by the bar GK turned by q (n,) (rad) about s_G, in ABG's D-H frame (3, n) (m)."""
        G, K = (_apply(self._to_abg, VERTICES[v]) for v in "GK")
        s = self._to_abg[:3, :3] @ self.s_g
        w = K - G
        along = (w @ s) * s
        return (G + along)[:, None] + np.outer(w - along, np.cos(q)) + np.outer(np.cross(s, w), np.sin(q))

    def _columns(self, path: NDArray[np.float64]) -> NDArray[np.float64]:
        """(theta, q, d residual / d theta (m^2/rad), central differences with step 1e-6) (N, 3): chord steps."""
        theta, bar_k = path[:, 0], self._bar_k(path[:, 1])
        slope = (self._radius2(theta + 1e-6, bar_k) - self._radius2(theta - 1e-6, bar_k)) / 2e-6
        return np.column_stack([path, slope])

    def _solve(self, x: NDArray[np.float64], table: PathTable) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """
        q = theta_G - theta_G0; theta closes |K of the bar - Bricard axis|^2 = |K of KLM - KLM's axis|^2 (KLM
        turns and slides on that axis), by chord steps with the table's slopes.
        """
        q = x - self._offset
        bar_k, radius2 = self._bar_k(q), float(VERTICES["K"][:2] @ VERTICES["K"][:2])
        where = table.locate(x)

        def residual(theta: NDArray[np.float64], rows: NDArray[np.intp]) -> NDArray[np.float64]:
            return self._radius2(theta, bar_k[:, rows]) - radius2

        def correction(theta: NDArray[np.float64], rows: NDArray[np.intp], r: NDArray[np.float64]) -> NDArray:
            return r / table.at(where, 2, rows)

        theta = polish(table.at(where, 0), residual, correction, f"theta at {self.input_name}", RESIDUAL_FLOOR)
        return theta, q

    def equations(self, u: ArrayLike) -> NDArray[np.float64]:
        u = np.atleast_2d(np.asarray(u, dtype=float))
        abg = self.bricard_motion(u[:, 0])[:, 0]
        return _apply(self._bar(u, abg), VERTICES["K"]) - _apply(_screw(u[:, 2], u[:, 3]), VERTICES["K"])


class SchemeII(Transformation):
    """
    Scheme II (Yang 2017, §6.4): S joints at G, H, J (triangle -> bar), R joints at K, L, M (bar -> KLM).

    Input theta (rad): the Bricard's D-H angle at A, rising from theta_d = 40.4591 deg to theta_f = 186.9018 deg.
    `delta` = delta2 (rad), sign chosen here (thumb along G - M); delta2 < 0 makes theta turn back (ParameterError).
    """

    input_name = "theta"
    REVOLUTE = REVOLUTE_II
    _input = 0
    _symbol = "delta2"
    _reach = "(-27.56, 58.52)"  # `_heads_for_bdf`

    def _setup_axes(self) -> None:
        self.s_k = axis_k(self.delta)
        self._theta_g_axis = axis_g(0.0)  # fixed in ABG, the root: the thesis's theta_G as a monitor

    def _bar(self, u: NDArray[np.float64], abg: NDArray[np.float64]) -> NDArray[np.float64]:
        return _screw(u[:, 2], u[:, 3]) @ _about_line(VERTICES["K"], self.s_k, -u[:, 1])

    def _top_angle(self, abg: NDArray[np.float64], klm: NDArray[np.float64]) -> float:
        g = _apply(invert(klm), _apply(abg, VERTICES["G"]))  # G (on F) seen from KLM's deployed pose
        return -float(_angle_about(VERTICES["G"] - VERTICES["K"], g - VERTICES["K"], self.s_k))

    def _solve(self, x: NDArray[np.float64], table: PathTable) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """
        theta = x; q closes |G of the bar - KLM's axis|^2 = |G of ABG - the Bricard's axis|^2, the bar turned by q
        about s_K (deployed frame: KLM's axis is z), by Newton's method (exact slope; it vanishes where theta turns
        back, e.g. deployed for delta2 = 0, and q goes as sqrt(theta - theta_d)).
        """
        K, G = VERTICES["K"], VERTICES["G"]
        w = G - K
        along = (w @ self.s_k) * self.s_k
        (cx, cy), (ax, ay), (bx, by) = (K + along)[:2], (w - along)[:2], -np.cross(self.s_k, w)[:2]
        radius2 = self._radius2(x, _apply(self._to_abg, G))

        def residual(q: NDArray[np.float64], rows: NDArray[np.intp]) -> NDArray[np.float64]:
            cq, sq = np.cos(q), np.sin(q)
            vx, vy = cx + ax * cq + bx * sq, cy + ay * cq + by * sq
            return vx * vx + vy * vy - radius2[rows]

        def correction(q: NDArray[np.float64], rows: NDArray[np.intp], r: NDArray[np.float64]) -> NDArray:
            cq, sq = np.cos(q), np.sin(q)
            vx, vy = cx + ax * cq + bx * sq, cy + ay * cq + by * sq
            slope = 2.0 * (vx * (bx * cq - ax * sq) + vy * (by * cq - ay * sq))
            return np.divide(r, slope, out=np.zeros_like(r), where=slope != 0.0)

        return x, polish(table.at(table.locate(x), 1), residual, correction, "q at theta", RESIDUAL_FLOOR)

    def equations(self, u: ArrayLike) -> NDArray[np.float64]:
        u = np.atleast_2d(np.asarray(u, dtype=float))
        abg = self.bricard_motion(u[:, 0])[:, 0]
        return _apply(self._bar(u, abg), VERTICES["G"]) - _apply(abg, VERTICES["G"])
