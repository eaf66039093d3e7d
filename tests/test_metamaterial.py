"""Double-corrugated metamaterial elements 1 and 2 (seed 003 §3.2.3, digest M8 eqns 3-24, 3-25, 3-28) measured on
the geometry of scene `corrugated-sheet` (2 x 2 P units; closed-form poses and MuJoCo) by `checks.metamaterial`."""

import numpy as np
import pytest

import sim_origami.scenes.corrugated_sheet  # noqa: F401  (registers `corrugated-sheet`)
from sim_origami import scenes
from sim_origami.checks.metamaterial import (
    ELEMENTS,
    check_element,
    element_dimensions,
    element_formulas,
    element_vertices,
    formula_poisson,
    max_height_angle,
)
from sim_origami.checks.poisson import vertex_positions
from sim_origami.errors import ParameterError
from sim_origami.simulate import simulate

ALPHA, BETA = 3 * np.pi / 4, np.pi / 3  # the digest's sample values = the scene's defaults (Fig 3-2)
# The digest prints 6 decimals: half a unit of the last digit.
PRINTED = 5e-7
# Another flat-foldable design (gamma = 60 deg the smallest sector), in radians.
OTHER = {"alpha": np.deg2rad(120.0), "beta": np.deg2rad(70.0), "gamma": np.deg2rad(60.0), "delta": np.deg2rad(110.0)}


def sheet(**angles: float):
    return scenes.get("corrugated-sheet").build(unit=0.0, rows=2, cols=2, **angles)


def measured(sc, q):
    """Vertex positions, their face-to-face gap, phi = pi - |rho_u1_2| and the input x = rho_u1_1 from q (n, J)."""
    positions, gap = vertex_positions(sc.pattern, sc.mechanism.body_poses(q))
    m = sc.mechanism
    return positions, gap, np.pi - np.abs(q[:, m.joint_index("u1_2")]), q[:, m.joint_index("u1_1")]


@pytest.mark.parametrize(
    ("element", "rows"),
    [  # phi, W, H, L (digest M8 table; the printed phi 1.0472, 1.5708, 2.0944 are pi/3, pi/2, 2 pi/3: at the
        # rounded phi W differs by up to 1.2e-6)
        (1, ((np.pi / 3, 0.824937, 0.705701, 1.325076),
             (np.pi / 2, 1.137055, 0.654654, 1.467314),
             (2 * np.pi / 3, 1.380314, 0.530926, 1.668058))),
        (2, ((np.pi / 3, 0.824937, 1.411402, 2.650152),
             (np.pi / 2, 1.137055, 1.309307, 2.934628),
             (2 * np.pi / 3, 1.380314, 1.061852, 3.336116))),
    ],
)  # fmt: skip
def test_formulas_reproduce_the_digest_table(element, rows):
    rows = np.array(rows)
    d = element_formulas(rows[:, 0], ALPHA, BETA, element)
    np.testing.assert_allclose(np.stack([d.W, d.H, d.L], axis=1), rows[:, 1:], rtol=0, atol=PRINTED)


@pytest.mark.parametrize("angles", [{}, OTHER])
@pytest.mark.parametrize("element", sorted(ELEMENTS))
def test_sheet_geometry_is_the_element_at_every_phi(element, angles):
    sc = sheet(**angles)
    alpha, beta = sc.kinematics.model.sectors[:2]
    x = np.linspace(0.01, np.pi - 0.01, 1001)
    q = sc.loop_to_mechanism(sc.kinematics.joint_angles(ELEMENTS[element][0], x))
    positions, gap, phi, _ = measured(sc, q)
    assert gap <= 1e-13  # closed-form poses: measured <= 7.2e-15 m
    assert np.max(np.abs(phi - (np.pi - x))) <= 1e-14  # every u crease folds with |rho| = x: measured 4.4e-16
    dims = element_dimensions(sc.pattern, positions, phi, element)
    seed = element_formulas(phi, alpha, beta, element)
    for m, f in ((dims.W, seed.W), (dims.H, seed.H), (dims.L, seed.L)):
        assert np.max(np.abs(m - f)) <= 1e-12  # measured <= 1.5e-13 m (H of element 2, OTHER, near phi = 0.01)


@pytest.mark.parametrize(
    ("element", "branch"),
    [(1, "CSCS"), (1, "SCCS"), (1, "SSCC"), (2, "CCSS"), (2, "CSCS"), (2, "CSSC"), (2, "SCSC"), (2, "SSCC")],
)
def test_other_mode_strings_are_not_the_element(element, branch):
    """
    The element's vertices on the other rigid strings miss eqn 3-24/3-25 (element 1 also holds on CCSS and CSSC:
    the row (1..3, 2) is the same zig-zag there, on CCSS with the u row folding 0.101 as fast as the input).
    """
    sc = sheet()
    x = np.linspace(0.3, 2.0, 50)
    positions, _, phi, _ = measured(sc, sc.loop_to_mechanism(sc.kinematics.joint_angles(branch, x)))
    dims = element_dimensions(sc.pattern, positions, phi, element)
    seed = element_formulas(phi, ALPHA, BETA, element)
    miss = max(np.max(np.abs(dims.H - seed.H)), np.max(np.abs(dims.L - seed.L)))
    assert miss >= 0.3  # measured >= 0.39 m (element 2's H on CCSS)


def test_closed_form_ratios_and_the_texts_claims():
    phi = np.linspace(0.02, np.pi - 0.02, 3001)
    phi_ii = max_height_angle(ALPHA, BETA)
    assert abs(phi_ii - 0.955317) <= PRINTED  # ours; the seed gives no number (Fig 3-12 is lost)
    one, two = (element_formulas(phi, ALPHA, BETA, e) for e in (1, 2))
    # "maximum heights of (b)-(d) equal and twice that of (a)", "(a)-(c) peak at the same phi": elements 1, 2 only
    np.testing.assert_allclose(two.H, 2 * one.H, rtol=1e-15, atol=0)
    assert np.argmax(one.H) == np.argmax(two.H) and abs(phi[np.argmax(one.H)] - phi_ii) <= phi[1] - phi[0]
    for element, d in ((1, one), (2, two)):
        nu_in, nu_out = formula_poisson(phi, ALPHA, BETA, element)
        # complex step against second-order differences on the 1e-3 rad grid (interior): measured 1.3e-6 absolute
        # on nu_in, 1.1e-3 relative on nu_out (truncation where H -> 0 near flat and nu_out grows to 1.0e4)
        fd_in = -(d.W / d.L) * np.gradient(d.L, phi) / np.gradient(d.W, phi)
        fd_out = -(d.W / d.H) * np.gradient(d.H, phi) / np.gradient(d.W, phi)
        assert np.max(np.abs(nu_in - fd_in)[1:-1]) <= 1e-5
        assert np.max(np.abs((nu_out - fd_out) / nu_out)[1:-1]) <= 3e-3
        # 0 < phi < phi_II: negative in 3-D; phi_II < phi < pi: negative in-plane, positive out-of-plane
        assert np.all(nu_in < 0)
        assert np.all(nu_out[phi < phi_ii] < 0) and np.all(nu_out[phi > phi_ii] > 0)


@pytest.mark.parametrize("element", sorted(ELEMENTS))
def test_mujoco_motion_has_the_seed_dimensions_and_ratios(element):
    sc = sheet()
    branch = ELEMENTS[element][0]
    # fast preset, 32x sweep, x from 0.3 to 2.4 rad: phi from 2.84 down to 0.74, past phi_II = 0.955; 1.2-1.4 s CPU
    run = simulate(sc, branch, stop=2.4)
    positions, gap, phi, x = measured(sc, run.q)
    exact = sc.loop_to_mechanism(sc.kinematics.joint_angles(branch, x))
    assert np.max(np.abs(run.q - exact)) <= 1e-8  # every fold angle on the closed form: measured 6.9e-10 rad
    assert gap <= 1e-8  # soft closures: measured 1.4e-9 m
    check = check_element(sc.pattern, positions, phi, ALPHA, BETA, element)
    assert check.dimension_error <= 5e-9  # W, H, L against eqns 3-24/3-25: measured 2.6e-10 (1), 5.2e-10 m (2)
    # differences over 0.002 rad; the same on both elements, so truncation, not MuJoCo: measured 8.5e-6 (nu_in,
    # |nu_in| <= 1.6) and 5.1e-5 (nu_out, up to 43 at the sweep's start near flat)
    assert check.nu_in_error <= 5e-5 and check.nu_out_error <= 2e-4
    assert len(check.samples) >= 800  # 8000 samples thinned to 942
    # the text's signs on the path: nu_in < 0 throughout, nu_out changes sign once, at phi_II (samples 0.002 apart)
    assert np.all(check.nu_in < 0)
    flips = np.nonzero(np.diff(np.sign(check.nu_out)))[0]
    assert len(flips) == 1
    assert abs(check.measured.phi[check.samples][flips[0]] - max_height_angle(ALPHA, BETA)) <= 0.004  # 2.1e-4


@pytest.mark.parametrize(
    ("call", "match"),
    [
        (lambda: element_formulas([1.0], ALPHA, BETA, 3), "element = 3; elements 1 and 2"),
        (lambda: element_formulas([0.0, 1.0], ALPHA, BETA, 1), r"phi in \[0, 1\] rad; the dihedral angle"),
        (lambda: element_formulas([1.0], ALPHA, 2.0, 1), "beta = 2 rad; the seed's arctan"),
        (lambda: element_formulas([1.0], 3.5, BETA, 1), "alpha = 3.5 rad; a sector angle"),
        (lambda: element_vertices(scenes.get("corrugated-sheet").build(rows=1, cols=1).pattern, 1), r"no vertex"),
    ],
)
def test_bad_input_is_refused(call, match):
    with pytest.raises(ParameterError, match=match):
        call()
