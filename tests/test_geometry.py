"""Rotations, rigid transforms and angle helpers of `sim_origami.geometry`."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim_origami.geometry import (
    frame_along,
    invert,
    rot_x,
    rot_z,
    rotation,
    rotation_vector,
    signed_angle,
    transform,
    transform_z,
    unit,
    wrap,
)

# Deterministic and database-free: the suite must not write into the repository.
HYPOTHESIS = settings(max_examples=60, deadline=None, derandomize=True, database=None)


def random_axes(rng: np.random.Generator, n: int) -> np.ndarray:
    """n unit vectors (n, 3), isotropic."""
    return unit(rng.normal(size=(n, 3)))


def random_transforms(rng: np.random.Generator, n: int) -> np.ndarray:
    """n rigid transforms (n, 4, 4) with translations up to 10 length units."""
    T = np.zeros((n, 4, 4))
    T[:, :3, :3] = rotation(random_axes(rng, n), rng.uniform(-np.pi, np.pi, n))
    T[:, :3, 3] = rng.uniform(-10.0, 10.0, (n, 3))
    T[:, 3, 3] = 1.0
    return T


def assert_proper_rotations(R: np.ndarray) -> None:
    """R (..., 3, 3) is orthonormal with determinant +1."""
    eye = np.broadcast_to(np.eye(3), R.shape)
    # Rodrigues with unit axes: measured 1.1e-15 (angles up to 10 rad); 1e-14 leaves 9x margin.
    np.testing.assert_allclose(np.swapaxes(R, -1, -2) @ R, eye, atol=1e-14, rtol=0)
    np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-14, rtol=0)


def test_rotation_is_orthonormal_with_unit_determinant_batched():
    rng = np.random.default_rng(0)
    R = rotation(random_axes(rng, 500), rng.uniform(-10.0, 10.0, 500))
    assert R.shape == (500, 3, 3)
    assert_proper_rotations(R)


def test_rotation_broadcasts_axes_against_angles():
    rng = np.random.default_rng(1)
    axes = random_axes(rng, 4)[:, None, :]  # (4, 1, 3)
    angles = np.linspace(-3.0, 3.0, 5)  # (5,)
    R = rotation(axes, angles)
    assert R.shape == (4, 5, 3, 3)
    assert_proper_rotations(R)
    # Each broadcast entry equals the unbatched rotation; same arithmetic, so exact to rounding.
    np.testing.assert_allclose(R[2, 3], rotation(axes[2, 0], angles[3]), atol=1e-15, rtol=0)


def test_rotations_are_right_handed():
    x, y, z = np.eye(3)
    # Exact quarter turns; cos(pi/2) ~ 6e-17 is the only error.
    np.testing.assert_allclose(rot_z(np.pi / 2) @ x, y, atol=1e-15, rtol=0)
    np.testing.assert_allclose(rot_x(np.pi / 2) @ y, z, atol=1e-15, rtol=0)
    np.testing.assert_allclose(rotation(y, np.pi / 2) @ z, x, atol=1e-15, rtol=0)


def test_rotation_leaves_its_axis_fixed():
    rng = np.random.default_rng(2)
    axes = random_axes(rng, 100)
    R = rotation(axes, rng.uniform(-np.pi, np.pi, 100))
    # Measured 5.6e-16 for unit axes; 1e-14 leaves 18x margin.
    np.testing.assert_allclose(np.einsum("nij,nj->ni", R, axes), axes, atol=1e-14, rtol=0)


def test_rotation_vector_inverts_rotation_for_angles_in_zero_to_pi():
    rng = np.random.default_rng(3)
    axes = random_axes(rng, 400)
    # Include the exact zero, the small-angle series branch and angles close to pi.
    angles = np.concatenate([[0.0, 1e-14, 1e-9, 1e-6], rng.uniform(0.0, np.pi - 0.01, 396)])
    w = rotation_vector(rotation(axes, angles))
    # Error grows like 1e-16 / sin(angle); measured 2e-14 at pi - 0.01, so 1e-12 leaves 50x margin.
    np.testing.assert_allclose(w, axes * angles[:, None], atol=1e-12, rtol=0)


def test_rotation_vector_of_identity_is_zero():
    assert np.array_equal(rotation_vector(np.eye(3)), np.zeros(3))


def test_invert_composes_to_identity_on_both_sides():
    T = random_transforms(np.random.default_rng(4), 300)
    Ti = invert(T)
    eye = np.broadcast_to(np.eye(4), T.shape)
    # Translations up to 10 units: measured 8.9e-15; 1e-13 leaves 11x margin.
    np.testing.assert_allclose(Ti @ T, eye, atol=1e-13, rtol=0)
    np.testing.assert_allclose(T @ Ti, eye, atol=1e-13, rtol=0)


def test_transform_z_is_homogeneous_rotation_about_z():
    angles = np.linspace(-3.0, 3.0, 7)
    T = transform_z(angles)
    assert T.shape == (7, 4, 4)
    assert np.array_equal(T[:, :3, :3], rot_z(angles))
    assert np.array_equal(T[:, 3], np.broadcast_to([0.0, 0.0, 0.0, 1.0], (7, 4)))
    assert np.array_equal(T[:, :3, 3], np.zeros((7, 3)))


def test_transform_places_rotation_and_translation():
    R = rot_x(0.3)
    T = transform(R, [1.0, 2.0, 3.0])
    assert np.array_equal(T[:3, :3], R)
    assert np.array_equal(T[:3, 3], [1.0, 2.0, 3.0])
    assert np.array_equal(T[3], [0.0, 0.0, 0.0, 1.0])


@pytest.mark.parametrize("axis", [(0.0, 0.0, 1.0), (0.0, 0.0, -2.0), (1.0, 2.0, 0.5), (3.0, 0.0, 0.0)])
def test_frame_along_is_right_handed_with_z_on_axis_and_origin_at_point(axis):
    point = np.array([0.5, -1.0, 2.0])
    T = frame_along(axis, point)
    assert_proper_rotations(T[:3, :3])
    # z is the normalised axis itself: measured exact; 1e-15 allows a rounding of the norm.
    np.testing.assert_allclose(T[:3, 2], unit(np.array(axis)), atol=1e-15, rtol=0)
    assert np.array_equal(T[:3, 3], point)


def test_signed_angle_is_positive_counter_clockwise_about_axis():
    x, y, z = np.eye(3)
    # atan2 of exact unit vectors: exact quarter turns.
    np.testing.assert_allclose(signed_angle(x, y, z), np.pi / 2, atol=1e-15, rtol=0)
    np.testing.assert_allclose(signed_angle(x, y, -z), -np.pi / 2, atol=1e-15, rtol=0)
    np.testing.assert_allclose(signed_angle(y, x, z), -np.pi / 2, atol=1e-15, rtol=0)
    np.testing.assert_allclose(signed_angle(x, -x, z), np.pi, atol=1e-15, rtol=0)


def test_signed_angle_recovers_rotation_angle_batched():
    rng = np.random.default_rng(5)
    axes = random_axes(rng, 200)
    u = unit(np.cross(axes, rng.normal(size=(200, 3))))  # perpendicular to the axes
    angles = rng.uniform(-np.pi + 1e-6, np.pi - 1e-6, 200)
    v = np.einsum("nij,nj->ni", rotation(axes, angles), u)
    # atan2 of rotated unit vectors: measured 2.2e-16; 1e-14 leaves 45x margin.
    np.testing.assert_allclose(signed_angle(u, v, axes), angles, atol=1e-14, rtol=0)


@HYPOTHESIS
@given(st.floats(-1e3, 1e3))
def test_wrap_returns_congruent_angle_in_half_open_range(x):
    w = float(wrap(x))
    assert -np.pi < w <= np.pi
    turns = (x - w) / (2 * np.pi)
    # |x| <= 1e3 loses at most ~1e-13 rad in the remainder; 1e-12 turns is 60x that.
    assert abs(turns - round(turns)) < 1e-12


@pytest.mark.parametrize("x", [np.pi, -np.pi, 3 * np.pi, -3 * np.pi])
def test_wrap_maps_odd_multiples_of_pi_to_plus_pi(x):
    assert float(wrap(x)) == np.pi


def test_wrap_keeps_pi_plus_one_ulp_inside_half_open_range():
    # pi + 1 ulp is congruent to about -pi + 4e-16; the only admissible float answers are the
    # neighbours of pi and -pi that lie in (-pi, pi], never -pi itself.
    x = np.nextafter(np.pi, 4.0)
    w = float(wrap(x))
    assert -np.pi < w <= np.pi, f"wrap({x!r}) = {w!r} is outside (-pi, pi]"


def test_wrap_is_batched_and_keeps_shape():
    x = np.linspace(-20.0, 20.0, 24).reshape(2, 3, 4)
    w = wrap(x)
    assert w.shape == x.shape
    assert np.all((w > -np.pi) & (w <= np.pi))
