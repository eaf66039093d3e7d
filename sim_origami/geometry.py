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
    Inverse left Jacobian (3, 3) of SO(3) at rotation vector phi (3,): d phi = Jl^-1(phi) w when the rotation
    exp(phi) is turned by the small spatial rotation w. I - [phi]/2 + (1/t^2 - (1 + cos t)/(2 t sin t)) [phi]^2,
    t = |phi|; the last coefficient tends to 1/12 as t -> 0.
    """
    phi = np.asarray(phi, dtype=float)
    t = float(np.linalg.norm(phi))
    P = np.array([[0.0, -phi[2], phi[1]], [phi[2], 0.0, -phi[0]], [-phi[1], phi[0], 0.0]])
    coef = 1.0 / 12.0 + t**2 / 720.0 if t < 1e-4 else 1.0 / t**2 - (1.0 + np.cos(t)) / (2.0 * t * np.sin(t))
    return np.eye(3) - 0.5 * P + coef * P @ P


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
