"""Rotations and rigid transforms, batched on leading axes.

Rotation matrices are (..., 3, 3) float arrays, homogeneous transforms (..., 4, 4). Angles are
radians and right-handed about the given axis.
"""

import numpy as np
from numpy.typing import ArrayLike, NDArray


def rotation(axis: ArrayLike, angle: ArrayLike) -> NDArray[np.float64]:
    """
    Rotation matrices about unit axes (Rodrigues).

    Parameters
    ----------
    axis : (..., 3) float
      Unit rotation axes.
    angle : (...) float
      Angles in radians, broadcast against the leading axes of `axis`.

    Returns
    -------
    R : (..., 3, 3) float
    """
    axis = np.asarray(axis, dtype=float)
    angle = np.asarray(angle, dtype=float)
    shape = np.broadcast_shapes(axis.shape[:-1], angle.shape)
    k = np.broadcast_to(axis, (*shape, 3))
    c = np.cos(angle)[..., None, None]
    s = np.sin(angle)[..., None, None]
    kx, ky, kz = k[..., 0], k[..., 1], k[..., 2]
    zero = np.zeros_like(kx)
    skew = np.stack(
        [
            np.stack([zero, -kz, ky], -1),
            np.stack([kz, zero, -kx], -1),
            np.stack([-ky, kx, zero], -1),
        ],
        -2,
    )
    outer = k[..., :, None] * k[..., None, :]
    return c * np.eye(3) + s * skew + (1.0 - c) * outer


def rot_x(angle: ArrayLike) -> NDArray[np.float64]:
    """Rotation about +x, (..., 3, 3)."""
    return rotation(np.array([1.0, 0.0, 0.0]), angle)


def rot_z(angle: ArrayLike) -> NDArray[np.float64]:
    """Rotation about +z, (..., 3, 3)."""
    return rotation(np.array([0.0, 0.0, 1.0]), angle)


def xyz_rotation(a: ArrayLike, b: ArrayLike, c: ArrayLike) -> NDArray[np.float64]:
    """Rx(a) @ Ry(b) @ Rz(c), (..., 3, 3): intrinsic x-y-z angles (rad), the order of `mechanism.ball_joint`."""
    return rot_x(a) @ rotation([0.0, 1.0, 0.0], b) @ rot_z(c)


def xyz_angles(R: ArrayLike) -> NDArray[np.float64]:
    """The intrinsic x-y-z angles (..., 3) (rad) of rotations (..., 3, 3); y in [-pi/2, pi/2], singular at its ends."""
    R = np.asarray(R, dtype=float)
    b = np.arcsin(np.clip(R[..., 0, 2], -1.0, 1.0))
    return np.stack([np.arctan2(-R[..., 1, 2], R[..., 2, 2]), b, np.arctan2(-R[..., 0, 1], R[..., 0, 0])], -1)


def quaternion(R: ArrayLike) -> NDArray[np.float64]:
    """Unit quaternion (w, x, y, z) with w >= 0 of one rotation matrix (3, 3) (Shepperd's method)."""
    R = np.asarray(R, dtype=float)
    w = np.sqrt(max(0.0, 1.0 + np.trace(R))) / 2
    if w > 0.5:
        return np.array(
            [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
        )
    i = int(np.argmax(np.diag(R)))
    j, k = (i + 1) % 3, (i + 2) % 3
    q = np.zeros(4)
    q[i + 1] = np.sqrt(max(0.0, 1.0 + R[i, i] - R[j, j] - R[k, k])) / 2
    q[0] = (R[k, j] - R[j, k]) / (4 * q[i + 1])
    q[j + 1] = (R[j, i] + R[i, j]) / (4 * q[i + 1])
    q[k + 1] = (R[k, i] + R[i, k]) / (4 * q[i + 1])
    return q if q[0] >= 0 else -q


def quaternion_matrix(q: ArrayLike) -> NDArray[np.float64]:
    """Rotation matrices (..., 3, 3) of quaternions (..., 4) (w, x, y, z), normalised first."""
    q = np.asarray(q, dtype=float)
    w, x, y, z = np.moveaxis(q / np.linalg.norm(q, axis=-1, keepdims=True), -1, 0)
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
        ],
        -2,
    )


def rotation_vector(R: ArrayLike) -> NDArray[np.float64]:
    """
    Axis times angle of rotation matrices (the vee of the matrix logarithm).

    Exact for angles in [0, pi); used as the rotational closure residual.

    Parameters
    ----------
    R : (..., 3, 3) float

    Returns
    -------
    w : (..., 3) float
      Rotation vector in radians.
    """
    R = np.asarray(R, dtype=float)
    v = 0.5 * np.stack([R[..., 2, 1] - R[..., 1, 2], R[..., 0, 2] - R[..., 2, 0], R[..., 1, 0] - R[..., 0, 1]], -1)
    s = np.linalg.norm(v, axis=-1)
    c = 0.5 * (np.trace(R, axis1=-2, axis2=-1) - 1.0)
    angle = np.arctan2(s, c)
    # angle / sin(angle) -> 1 as the angle -> 0
    scale = np.where(s > 1e-12, angle / np.where(s > 1e-12, s, 1.0), 1.0 + angle**2 / 6.0)
    return v * scale[..., None]


def left_jacobian_inverse(phi: ArrayLike) -> NDArray[np.float64]:
    """
    Inverse left Jacobian (..., 3, 3) of SO(3) at rotation vectors phi (..., 3): d phi = Jl^-1(phi) w when the
    rotation exp(phi) is turned by the small spatial rotation w. I - [phi]/2 + (1/t^2 - (1 + cos t)/(2 t sin t))
    [phi]^2, t = |phi|; the last coefficient tends to 1/12 as t -> 0.
    """
    phi = np.asarray(phi, dtype=float)
    t = np.linalg.norm(phi, axis=-1)
    zero = np.zeros_like(t)
    P = np.stack([np.stack([zero, -phi[..., 2], phi[..., 1]], -1), np.stack([phi[..., 2], zero, -phi[..., 0]], -1),
                  np.stack([-phi[..., 1], phi[..., 0], zero], -1)], -2)
    small = t < 1e-4
    safe = np.where(small, 1.0, t)
    exact = 1.0 / safe**2 - (1.0 + np.cos(safe)) / (2.0 * safe * np.sin(safe))
    coef = np.where(small, 1.0 / 12.0 + t**2 / 720.0, exact)
    return np.eye(3) - 0.5 * P + coef[..., None, None] * P @ P


def transform(R: ArrayLike | None = None, p: ArrayLike | None = None) -> NDArray[np.float64]:
    """Homogeneous transform (4, 4) from a rotation (3, 3) and a translation (3,)."""
    T = np.eye(4)
    if R is not None:
        T[:3, :3] = R
    if p is not None:
        T[:3, 3] = p
    return T


def transform_z(angle: ArrayLike) -> NDArray[np.float64]:
    """Homogeneous rotations about +z, (..., 4, 4) (written directly: the loop products' inner step)."""
    angle = np.asarray(angle, dtype=float)
    c, s = np.cos(angle), np.sin(angle)
    T = np.zeros((*angle.shape, 4, 4))
    T[..., 0, 0] = c
    T[..., 0, 1] = -s
    T[..., 1, 0] = s
    T[..., 1, 1] = c
    T[..., 2, 2] = 1.0
    T[..., 3, 3] = 1.0
    return T


def invert(T: ArrayLike) -> NDArray[np.float64]:
    """Inverse of rigid transforms (..., 4, 4)."""
    T = np.asarray(T, dtype=float)
    Ti = np.zeros_like(T)
    Rt = np.swapaxes(T[..., :3, :3], -1, -2)
    Ti[..., :3, :3] = Rt
    Ti[..., :3, 3] = -np.einsum("...ij,...j->...i", Rt, T[..., :3, 3])
    Ti[..., 3, 3] = 1.0
    return Ti


def frame_along(axis: ArrayLike, point: ArrayLike = (0.0, 0.0, 0.0)) -> NDArray[np.float64]:
    """
    A right-handed frame (4, 4) whose z axis is `axis` and whose origin is `point`.

    The x axis is the component of +z (or of +x when `axis` is near z) orthogonal to `axis`;
    only the z axis and origin matter to a revolute joint.
    """
    z = np.asarray(axis, dtype=float)
    z = z / np.linalg.norm(z)
    helper = np.array([0.0, 0.0, 1.0]) if abs(z[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    x = helper - z * (helper @ z)
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    return transform(np.stack([x, y, z], axis=1), point)


def common_normal_foot(p0: ArrayLike, s0: ArrayLike, p1: ArrayLike, s1: ArrayLike) -> NDArray[np.float64]:
    """Foot on line (p1, s1) of the common normal of lines (p0, s0) and (p1, s1); unit directions, not parallel."""
    p0, s0, p1, s1 = (np.asarray(v, dtype=float) for v in (p0, s0, p1, s1))
    w, b = p0 - p1, s0 @ s1
    return p1 + ((s1 @ w) - b * (s0 @ w)) / (1.0 - b * b) * s1


def frames_along(axes: ArrayLike, points: ArrayLike) -> NDArray[np.float64]:
    """`frame_along` for many axes (n, 3) and points (n, 3) at once: frames (n, 4, 4), the same ones."""
    z = np.asarray(axes, dtype=float)
    z = z / np.sqrt(_dots(z, z))[:, None]
    helper = np.where((np.abs(z[:, 2]) < 0.9)[:, None], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    x = helper - z * _dots(helper, z)[:, None]
    x /= np.sqrt(_dots(x, x))[:, None]
    T = np.zeros((len(z), 4, 4))
    T[:, :3, 0], T[:, :3, 1], T[:, :3, 2], T[:, :3, 3], T[:, 3, 3] = x, np.cross(z, x), z, points, 1.0
    return T


def _dots(a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[np.float64]:
    """Row dot products of (n, 3) arrays, rounded as `a[i] @ b[i]` rounds them (a batched matmul)."""
    return (a[:, None, :] @ b[:, :, None])[:, 0, 0]


def signed_angle(u: ArrayLike, v: ArrayLike, axis: ArrayLike) -> NDArray[np.float64]:
    """Right-handed angle (...) from vectors u to v about `axis`; all (..., 3)."""
    u, v, axis = (np.asarray(x, dtype=float) for x in (u, v, axis))
    return np.arctan2(np.einsum("...i,...i", np.cross(u, v), axis), np.einsum("...i,...i", u, v))


def unit(v: ArrayLike) -> NDArray[np.float64]:
    """Vectors (..., 3) scaled to unit length."""
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def wrap(angle: ArrayLike) -> NDArray[np.float64]:
    """Angles wrapped to (-pi, pi]."""
    out = -np.remainder(-np.asarray(angle, dtype=float) + np.pi, 2.0 * np.pi) + np.pi
    # pi + 1 ulp rounds to exactly -pi above; the range is half-open at -pi
    return np.where(out <= -np.pi, out + 2.0 * np.pi, out)


def rigid_fit(reference: ArrayLike, points: ArrayLike) -> NDArray[np.float64]:
    """
    The rigid motions (..., 4, 4) that best carry `reference` (k, 3) onto `points` (..., k, 3) in least
    squares (Kabsch); exact for a rigid body's points, which must not all lie on one line.
    """
    P0 = np.asarray(reference, dtype=float)
    P = np.asarray(points, dtype=float)
    c0, c = P0.mean(axis=0), P.mean(axis=-2)
    H = np.swapaxes(P - c[..., None, :], -1, -2) @ (P0 - c0)
    U, _, Vt = np.linalg.svd(H)
    d = np.sign(np.linalg.det(U @ Vt))
    D = np.zeros((*d.shape, 3, 3))
    D[..., 0, 0], D[..., 1, 1], D[..., 2, 2] = 1.0, 1.0, d
    R = U @ D @ Vt
    T = np.zeros((*R.shape[:-2], 4, 4))
    T[..., :3, :3], T[..., :3, 3], T[..., 3, 3] = R, c - np.einsum("...ij,j->...i", R, c0), 1.0
    return T


def minimal_rotation(u: ArrayLike, v: ArrayLike) -> NDArray[np.float64]:
    """The rotations (..., 3, 3) by the smallest angle carrying unit u (3,) onto unit v (..., 3) (not antiparallel)."""
    u, v = np.asarray(u, dtype=float), np.asarray(v, dtype=float)
    w = np.cross(u, v)
    c = np.einsum("...i,...i", np.broadcast_to(u, v.shape), v)
    zero = np.zeros_like(c)
    K = np.stack([np.stack([zero, -w[..., 2], w[..., 1]], -1), np.stack([w[..., 2], zero, -w[..., 0]], -1),
                  np.stack([-w[..., 1], w[..., 0], zero], -1)], -2)
    return np.eye(3) + K + K @ K / (1.0 + c)[..., None, None]


def enclosed_volume(points: ArrayLike, faces: list[list[int]]) -> NDArray[np.float64]:
    """
    Volume (..., ) enclosed by faces (vertex index cycles, counter-clockwise seen from outside) of vertex
    positions (..., V, 3), by the divergence theorem over the triangles from each face's centroid: exact for
    planar faces and for merged vertices, the symmetric choice for a skew face.
    """
    P = np.asarray(points, dtype=float)
    total = np.zeros(P.shape[:-2])
    for k in faces:
        centre = P[..., k, :].mean(-2)
        for a, b in zip(k, k[1:] + k[:1], strict=True):
            total = total + np.einsum("...i,...i", centre, np.cross(P[..., a, :], P[..., b, :]))
    return total / 6.0


def triangles_cross(
    first: ArrayLike, second: ArrayLike, graze: float = 1e-12, parallel: float = 1e-15
) -> NDArray[np.bool_]:
    """
    Whether each pair of triangles (..., 3, 3) (vertices in m) crosses: an edge of one passes through the other's
    interior (Moller-Trumbore, both ways). An edge must reach `graze` (barycentric, and along the edge) inside, so
    edges that only end on each other to rounding do not count; edges closer to parallel to the other's plane than
    `parallel` (m^3) are skipped. The zero-thickness panels' collision test (Feng, Ma and Chen 2020's "physical
    interference").
    """
    first, second = np.asarray(first, dtype=float), np.asarray(second, dtype=float)
    hit = np.zeros(np.broadcast_shapes(first.shape, second.shape)[:-2], dtype=bool)
    for one, other in ((first, second), (second, first)):
        e1, e2 = other[..., 1, :] - other[..., 0, :], other[..., 2, :] - other[..., 0, :]
        for k in range(3):
            p0, d = one[..., k, :], one[..., (k + 1) % 3, :] - one[..., k, :]
            h = np.cross(d, e2)
            det = np.sum(e1 * h, axis=-1)
            s = p0 - other[..., 0, :]
            q = np.cross(s, e1)
            with np.errstate(invalid="ignore", divide="ignore"):
                det = np.where(np.abs(det) > parallel, det, np.nan)
                u, v, t = (np.sum(s * h, -1) / det, np.sum(d * q, -1) / det, np.sum(e2 * q, -1) / det)
                hit |= (u > graze) & (v > graze) & (u + v < 1 - graze) & (t > graze) & (t < 1 - graze)
    return hit
