"""Poisson's ratios of the square-twist metamaterial (Peng 2018, §3.3, eqns 3-30 to 3-32) measured on the
geometry of scene `square-twist` (closed-form poses and MuJoCo) by `checks.poisson`."""

import numpy as np
import pytest

import sim_origami.scenes.square_twist  # noqa: F401  (registers `square-twist`)
from sim_origami import scenes
from sim_origami.errors import ParameterError
from sim_origami.kinematics.square_twist import metamaterial_unit
from sim_origami.simulate import simulate
from sim_origami.studies.poisson import (
    check_square_twist,
    poisson_ratio,
    square_twist_dimensions,
    thin,
    vertex_positions,
)

# a = pleat = 1, b = c = side / 2 = 1: the tables below
GEOMETRY = {"side": 2.0, "pleat": 1.0}
# Rigid mode strings with vertex A in mode C (eqn 3-31 is A's C branch); the first letter is A's mode.
A_IN_C = ("CCSS", "CSCS", "CSSC")
# The tables hold eqns 3-30 to 3-32 evaluated independently here to 6 decimals: half a unit of the last digit.
PRINTED = 5e-7


def scene(alpha: float):
    return scenes.get("square-twist").build(alpha=alpha, **GEOMETRY)


def measured(sc, q):
    """Vertex positions, their face-to-face gap, theta = rho_AB and phi = rho_DA from mechanism angles q (n, 12)."""
    positions, gap = vertex_positions(sc.pattern, sc.mechanism.body_poses(q))
    m = sc.mechanism
    return positions, gap, q[:, m.joint_index("AB")], q[:, m.joint_index("DA")]


@pytest.mark.parametrize(
    ("alpha", "rows"),
    [  # theta, L, S, H, nu_SL, nu_HL (eqns 3-30 to 3-32, a = b = c = 1)
        (5 * np.pi / 6, ((np.pi / 6, 1.566987, 1.456756, 0.631854, -0.398480, 9.186190),
                         (np.pi / 3, 1.383975, 1.133975, 0.933013, -0.614521, 0.856406),
                         (np.pi / 2, 1.133975, 0.883975, 0.933013, -1.039382, -0.526279),
                         (2 * np.pi / 3, 0.883975, 0.733975, 0.733013, -1.729816, -1.468060),
                         (5 * np.pi / 6, 0.700962, 0.657347, 0.401085, -2.567671, -5.040666))),
        (3 * np.pi / 4, ((np.pi / 6, 1.905266, 1.582791, 0.998502, -0.249648, 6.159052),
                         (np.pi / 2, 1.292893, 0.792893, 1.207107, -1.226541, -0.535534),
                         (5 * np.pi / 6, 0.680521, 0.602995, 0.508604, -4.607159, -3.462525))),
        (2 * np.pi / 3, ((np.pi / 6, 2.250000, 1.500000, 1.299038, -0.166667, 3.000000),
                         (np.pi / 2, 1.500000, 0.750000, 1.299038, -2.000000, -0.500000),
                         (5 * np.pi / 6, 0.750000, 0.642857, 0.556731, -10.500000, -3.095238))),
    ],
)
def test_closed_form_geometry_reproduces_the_poisson_tables(alpha, rows):
    rows = np.array(rows)
    sc = scene(alpha)
    for branch in A_IN_C:
        q = sc.loop_to_mechanism(sc.kinematics.joint_angles(branch, rows[:, 0]))
        positions, gap, theta, phi = measured(sc, q)
        assert gap <= 1e-14  # faces agree on shared vertices: measured <= 1.3e-15
        dims = square_twist_dimensions(sc.pattern, positions, theta, phi)
        # tables vs ours: the tabled L, S, H from pattern vertices, measured within 7.8e-16 of eqn 3-30
        np.testing.assert_allclose(np.stack([dims.L, dims.S, dims.H], -1), rows[:, 1:4], atol=PRINTED, rtol=0)
    # the ratios as central differences of the measured geometry, 5e-4 rad either side of each table theta
    nu = []
    for t in rows[:, 0]:
        x = t + 5e-4 * np.arange(-1.0, 2.0)
        q = sc.loop_to_mechanism(sc.kinematics.joint_angles("CCSS", x))
        positions, _, _, phi = measured(sc, q)
        dims = square_twist_dimensions(sc.pattern, positions, x, phi)
        nu.append((poisson_ratio(dims.L, dims.S, x)[1], poisson_ratio(dims.H, dims.L, x)[1]))
    # truncation only, against eqn 3-32 at the same theta: measured relative <= 1.0e-6 (nu_HL, alpha 120, theta 30)
    np.testing.assert_allclose(nu, rows[:, 4:], rtol=3e-6, atol=PRINTED)


@pytest.mark.parametrize("branch", A_IN_C)
def test_mujoco_motion_has_peng2018_poisson_ratios(branch):
    sc = scene(5 * np.pi / 6)
    run = simulate(sc, branch)  # fast preset (RK4, 8 ms), 4x sweep over 0.5..2.4 rad (the H peak at 1.2995 inside)
    positions, gap, theta, phi = measured(sc, run.q)
    assert gap <= 1e-7  # soft closures: the faces' placements of a vertex differ by at most 3.7e-8 m
    check = check_square_twist(sc.pattern, positions, theta, phi, sc.kinematics.alpha)
    assert check.dimension_error <= 1e-7  # L, S, H against eqn 3-30: measured <= 2.9e-8 m (CSSC)
    assert check.phi_error <= 2e-7  # rho_DA against eqn 3-31: measured <= 3.9e-8 rad (CSSC)
    # finite differences over 0.002 rad: measured <= 9.7e-6 (nu_SL) and 4.0e-5 (nu_HL = 10.3 at the sweep's start)
    assert check.nu_sl_error <= 1e-4 and check.nu_hl_error <= 2e-4
    assert len(check.samples) >= 500  # 1000 samples (8 ms steps) thinned to 642
    # the text's signs on the path: nu_SL < 0 throughout, nu_HL changes sign once (where H peaks)
    assert np.all(check.nu_sl < 0)
    assert np.count_nonzero(np.diff(np.sign(check.nu_hl))) == 1


def test_vertex_a_in_mode_s_does_not_follow_the_formulas():
    """On SCCS vertex A folds in mode S: rho_DA = 2 atan(m_S tan(theta/2)) < 0, not eqn 3-31's C branch."""
    sc = scene(5 * np.pi / 6)
    x = np.linspace(0.5, 2.4, 200)
    q = sc.loop_to_mechanism(sc.kinematics.joint_angles("SCCS", x))
    positions, _, theta, phi = measured(sc, q)
    check = check_square_twist(sc.pattern, positions, theta, phi, sc.kinematics.alpha)
    assert check.phi_error >= 1.0 and check.dimension_error >= 0.1  # measured 4.7 rad and 0.87 m


def test_poisson_ratio_is_exact_on_quadratics():
    x = np.linspace(0.5, 2.0, 7)  # second-order differences, one-sided at the ends: exact for quadratics
    nu = poisson_ratio(x**2 + 1.0, 3.0 - x, x)
    np.testing.assert_allclose(nu, (3.0 - x) / (x**2 + 1.0) * 2 * x, rtol=1e-12, atol=0)


def test_thin_keeps_samples_a_minimum_step_apart():
    x = np.array([0.0, 0.001, 0.002, 0.01, 0.0105, 0.02, 0.05])
    assert thin(x, 0.01).tolist() == [0, 3, 5, 6]


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: thin(np.linspace(0, 1, 5), 0.0), "min_step = 0; it must be positive"),
        (lambda: thin(np.linspace(0, 0.01, 50), 0.01), "only 2 samples are 0.01 apart"),
        (lambda: poisson_ratio([1.0, 2, 3], [1.0, 2, 3], [0.0, 1, 1]), "strictly monotonic"),
        (lambda: poisson_ratio([1.0, 2, 3], [1.0, 1, 1], [0.0, 1, 2]), "load dimension is stationary"),
        (lambda: metamaterial_unit(5 * np.pi / 6, [0.0]), "theta = 0 rad; eqn 3-32 needs 0 < theta < pi"),
    ],
)
def test_bad_input_is_refused(call, match):
    with pytest.raises(ParameterError, match=match):
        call()


def test_missing_face_pose_is_refused():
    sc = scene(5 * np.pi / 6)
    poses = sc.mechanism.body_poses(np.zeros((1, 12)))
    del poses["corner_B"]
    with pytest.raises(ParameterError, match="no pose for face 'corner_B'"):
        vertex_positions(sc.pattern, poses)
