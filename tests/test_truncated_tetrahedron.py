"""Truncated tetrahedron -> tetrahedron, schemes I and II (`kinematics.truncated_tetrahedron`, assemblies in
`scenes.truncated_tetrahedron`) against Yang 2017, ch. 6 and the numeric loop closure of the whole assembly (9 R
hinges, 3 spherical joints, 3 loops) and MuJoCo (ball joints)."""

import re

import numpy as np
import pytest
from published import check_every, checked_by, yang2017

from sim_origami import scenes
from sim_origami.checks.paths import compare
from sim_origami.errors import DomainError, ParameterError
from sim_origami.geometry import invert, transform_z, wrap
from sim_origami.kinematics.truncated_tetrahedron import (
    BARS,
    NAMES,
    TETRAHEDRON,
    TRIANGLES,
    VERTICES,
    VOLUME_RATIO,
    SchemeI,
    SchemeII,
    axis_g,
    axis_k,
    volume,
)
from sim_origami.mechanism import Mechanism, ball_joint
from sim_origami.scenes.truncated_tetrahedron import (
    BALLS,
    INPUT_JOINT,
    _bodies,
    _hinge,
    assembly_of,
    model,
    revolute_axes,
)
from sim_origami.simulate import simulate
from sim_origami.validation import MUJOCO_VERTEX_ERROR, _conditioning, validate

DEG = np.pi / 180
INDEX = {v: k for k, v in enumerate(NAMES)}
EDGES = [(t[i], t[(i + 1) % 3]) for t in TRIANGLES for i in range(3)] + [(b[0], b[1]) for b in BARS]
OWNER = {v: body for body in TRIANGLES for v in body}


@pytest.fixture(scope="module")
def one() -> SchemeI:
    return SchemeI()


@pytest.fixture(scope="module")
def one_reaching() -> SchemeI:
    return SchemeI(-5 * DEG)


@pytest.fixture(scope="module")
def two() -> SchemeII:
    return SchemeII()


@pytest.fixture(scope="module", params=["I", "II", "I-5"])
def case(request, one, two, one_reaching):
    kinematics = {"I": one, "II": two, "I-5": one_reaching}[request.param]
    return request.param[:2].rstrip("-"), kinematics, assembly_of(kinematics)


def kabsch_error(P: np.ndarray, target: dict[str, np.ndarray]) -> float:
    """Largest distance (m) of vertices P (12, 3) from `target` after the best proper rigid fit."""
    T = np.array([target[v] for v in NAMES])
    U, _, Vt = np.linalg.svd((P - P.mean(0)).T @ (T - T.mean(0)))
    R = (U @ Vt).T
    assert np.linalg.det(R) > 0
    return float(np.max(np.linalg.norm((P - P.mean(0)) @ R.T + T.mean(0) - T, axis=1)))


# --- Yang 2017, chapter 6 (tests/published/yang2017.py) --------------------------------------------------


def test_truncated_tetrahedron_bricard_parameters(two):
    """a = 2√69/23, alpha 231.0378/128.9622 deg, R = 0, c = 17√22/92, d = 5√166/92; deployed and folded angles."""
    for k, row in enumerate(two.rows):
        assert row.a == pytest.approx(2 * np.sqrt(69) / 23, abs=1e-14)  # measured 2.2e-16
        assert abs(row.R) < 1e-14  # measured 5.7e-16
        expected = np.pi + np.arccos(19 / np.sqrt(913)) if k % 2 == 0 else np.pi - np.arccos(19 / np.sqrt(913))
        assert row.alpha % (2 * np.pi) == pytest.approx(expected, abs=1e-12)
    frame_2 = two._frame @ transform_z(two.theta_d) @ two.rows[0].link()  # joint B's D-H frame (6-26)
    assert (invert(two._frame) @ np.append(VERTICES["A"], 1))[2] == pytest.approx(17 * np.sqrt(22) / 92, abs=1e-14)
    assert (invert(frame_2) @ np.append(VERTICES["B"], 1))[2] == pytest.approx(-5 * np.sqrt(166) / 92, abs=1e-14)
    # alpha12; (6-28) 2G and corrected (6-33) 2s_G to 5-6 digits; deployed and folded angles and theta -> phi
    # samples to 1e-4 deg (measured 3e-5)
    check_every(yang2017.NUMBERS, "test_truncated_tetrahedron_bricard_parameters")


def test_corrected_axes():
    """Misprints 28, 29: s_G = unit(G - Q) (printed OG), s_M = (√22/11, -√66/33, 5√33/33); s_K printed right."""
    assert axis_g(0.0) == pytest.approx([0, 4 * np.sqrt(66) / 33, np.sqrt(33) / 33], abs=1e-15)
    assert axis_k(0.0) == pytest.approx([0, 2 * np.sqrt(66) / 33, 5 * np.sqrt(33) / 33], abs=1e-15)
    axes = revolute_axes(SchemeI())
    assert axes["H"] == pytest.approx([-2 * np.sqrt(22) / 11, -2 * np.sqrt(66) / 33, np.sqrt(33) / 33], abs=1e-15)
    assert axes["J"] == pytest.approx([2 * np.sqrt(22) / 11, -2 * np.sqrt(66) / 33, np.sqrt(33) / 33], abs=1e-15)
    # s_G lies in the bisecting plane of angle BGK: equal angles to GB and GK (the printed OG direction does not)
    G, B, K = VERTICES["G"], VERTICES["B"], VERTICES["K"]
    assert (B - G) @ axis_g(0.0) == pytest.approx((K - G) @ axis_g(0.0), abs=1e-15)
    check_every(yang2017.CORRECTIONS, "test_corrected_axes")  # the printed OG: 0.71 m apart


@pytest.mark.slow
def test_delta_peak_of_the_bricard(two):
    """delta = angle BAF rises from 120 to its peak 129.52 deg (at rho ≈ 102.4 deg) then falls to 60 deg."""
    x = np.linspace(*two.domain, 301)
    m = two.monitors(x)
    k = int(np.argmax(m["delta"]))
    assert m["delta"][k] / DEG == pytest.approx(129.52, abs=0.02)  # sampled peak, measured 129.52
    assert m["rho"][k] / DEG == pytest.approx(102.4, abs=1.0)  # worked here to 0.1 deg; sampling 0.5 deg
    assert (m["delta"][0] / DEG, m["delta"][-1] / DEG) == pytest.approx((120.0, 60.0), abs=1e-9)


def test_deployed_state_is_the_truncated_tetrahedron(case):
    _, kinematics, _ = case
    start = kinematics.events()[0].input
    P = kinematics.vertices(start)[0]
    assert np.max(np.abs(P - np.array([VERTICES[v] for v in NAMES]))) < 1e-14  # measured 5.6e-16 m
    for pose in kinematics.body_poses(start).values():
        assert np.max(np.abs(pose[0] - np.eye(4))) < 1e-14
    assert np.max(np.abs(kinematics.revolute_angles(start))) < 1e-14


def test_scheme_ii_reaches_the_tetrahedron(two):
    """Scheme II (s_K ∥ QK, delta2 = 0): |AE|, |BK|, |FG|, |FM| -> 0, KLM height 1.633 -> 0, net rotation 30 deg;
    the end is (6-3)."""
    end = two.domain[1]
    assert end == pytest.approx(two.theta_f, abs=1e-15)
    assert kabsch_error(two.vertices(end)[0], TETRAHEDRON) < 1e-12  # measured 1.5e-15 m
    m = two.monitors(np.array(two.domain))
    assert m["height"] == pytest.approx([2 * np.sqrt(6) / 3, 0.0], abs=1e-12)
    assert (m["rotation"][1] - m["rotation"][0]) / DEG == pytest.approx(30.0, abs=1e-9)


@pytest.mark.slow
def test_scheme_i_misses_the_tetrahedron(one):
    """Scheme I (derived here): with s_G ∥ QG (Sec. 6.3.2 says it reaches 0) the path ends at the Bricard fold with
    theta_G = 3.708 deg, |BK| = 0.0585, KLM height 0.0586 m, KLM rotation 29.66 deg; theta_G starts at the printed
    146.44 deg."""
    lo = one.domain[0]
    # theta_G from 146.44269 to 3.70837 deg; |BK| 0.058534, height 0.058435, rotation 29.6617 (measured)
    check_every(yang2017.NUMBERS, "test_scheme_i_misses_the_tetrahedron")
    m = one.monitors(lo)
    assert m["AE"][0] < 1e-13  # A = C = E (measured 2.2e-15 m)
    assert "short of the tetrahedron" in one.events()[1].detail


def test_scheme_i_turned_axis_reaches_the_tetrahedron(one_reaching):
    """Scheme I with delta1 = -5 deg reaches the tetrahedron after rho over-opens to 120.08 deg."""
    lo, _ = one_reaching.domain
    assert kabsch_error(one_reaching.vertices(lo)[0], TETRAHEDRON) < 1e-11  # measured 1.5e-15 m
    assert abs(lo) < 1e-9  # theta_G -> 0 (measured exactly 0: the path ends on the tetrahedron state)
    rho = one_reaching.monitors(np.linspace(*one_reaching.domain, 401))["rho"]
    assert rho.max() / DEG == pytest.approx(120.08, abs=0.01)  # measured 120.075 (sampled)
    assert "the tetrahedron" in one_reaching.events()[1].detail


@pytest.mark.slow
def test_scheme_i_threshold_near_minus_3_5_deg():
    """Found here: the tetrahedron is reached for delta1 <~ -3.5 deg and missed above (Sec. 6.5: "delta1 >= 0")."""
    assert SchemeI(-3.5 * DEG).end_gap < 1e-12  # measured 9.6e-16 m
    assert SchemeI(-3 * DEG).end_gap > 1e-3  # measured 0.0084 m


@pytest.mark.slow
def test_scheme_ii_negative_delta_over_opens():
    """delta2 = -5 deg: rho first rises to 122.03 deg (a first truss trace here), so theta turns back and cannot
    drive it."""
    kinematics = SchemeII(-5 * DEG)
    P = kinematics.bricard_motion(kinematics.trace[1][:, 0])
    A, E, F = (P[:, k, :3, :3] @ VERTICES[v] + P[:, k, :3, 3] for k, v in ((0, "A"), (4, "E"), (4, "F")))
    cos = np.einsum("ni,ni->n", A - F, E - F) / (np.linalg.norm(A - F, axis=1) * np.linalg.norm(E - F, axis=1))
    assert np.rad2deg(np.arccos(cos.min())) == pytest.approx(122.03, abs=0.05)  # trace step 0.02: measured 122.02
    with pytest.raises(ParameterError, match="turns back"):
        _ = kinematics.domain


@pytest.mark.slow
def test_a_path_toward_the_other_fold_is_refused():
    """delta2 = -40 deg: the direction d psi > 0 runs theta down to the fold B = D = F (-106.0 deg), where the trace
    stalled (ConvergenceError at residual 3.2e-14 m); it is a ParameterError naming delta2 and its measured limits."""
    with pytest.raises(ParameterError, match=r"delta2 = -40 deg: .* B = D = F .*\(-27.56, 58.52\)"):
        _ = SchemeII(-40 * DEG).trace


@pytest.mark.slow
@pytest.mark.parametrize(
    ("scheme", "inside", "outside"),
    [(SchemeI, -62.01, -62.03), (SchemeI, 56.94, 56.96), (SchemeII, -27.55, -27.57), (SchemeII, 58.51, 58.53)],
)
def test_the_limits_of_the_path_toward_the_fold(scheme, inside, outside):
    """Either side of the limits in `_reach`: just inside the path rises to theta_f (A = C = E, or turns back in
    theta_G: another ParameterError), just outside it heads for B = D = F."""
    kinematics = scheme(inside * DEG)
    assert kinematics.trace[1][-1, 0] == pytest.approx(kinematics.theta_f, abs=1e-3)  # the fold or the tetrahedron
    with pytest.raises(ParameterError, match="B = D = F"):
        _ = scheme(outside * DEG).trace


@pytest.mark.slow
@pytest.mark.parametrize("entry", checked_by(yang2017.NUMBERS, "test_scheme_ii_path_matches_the_worked_table"), ids=str)
def test_scheme_ii_path_matches_the_worked_table(entry):
    # measured agreement <= 0.0051 deg and <= 5e-5 m
    entry.check()


@pytest.mark.slow
@pytest.mark.parametrize("entry", checked_by(yang2017.NUMBERS, "test_scheme_i_path_matches_the_worked_table"), ids=str)
def test_scheme_i_path_matches_the_worked_table(entry):
    # measured agreement <= 0.0050 deg and <= 1e-4 m
    entry.check()


def test_volume_ratio(two):
    """Ch. 6: 23; exactly 23 √2/12 against √2/12 for unit edges."""
    deployed, folded = volume(two.vertices(np.array(two.domain)))
    assert deployed == pytest.approx(23 * np.sqrt(2) / 12, abs=1e-14)  # measured 0
    assert folded == pytest.approx(np.sqrt(2) / 12, abs=1e-13)  # measured 4e-16
    assert deployed / folded == pytest.approx(VOLUME_RATIO, rel=1e-12)


# --- closure: closed form and the numeric loop system --------------------------------------------------------


def test_closed_form_keeps_every_edge_and_the_symmetry(case):
    _, kinematics, _ = case
    x = np.linspace(*kinematics.domain, 25)
    P = kinematics.vertices(x)
    lengths = np.stack([np.linalg.norm(P[:, INDEX[a]] - P[:, INDEX[b]], axis=-1) for a, b in EDGES], -1)
    assert np.max(np.abs(lengths - 1.0)) < 1e-12  # 12 triangle edges and 6 bars (measured 1.4e-15 m)
    assert np.max(np.abs(kinematics.equations(kinematics.state(x)))) < 1e-14  # measured 8.9e-16 m


def test_mechanism_closes_at_the_closed_form(case):
    """Loop residual at angles_from_poses(body_poses) <= 1e-12 along the path; hinge angles = revolute_angles."""
    scheme, kinematics, mechanism = case
    loops = mechanism.loop_system()
    assert len(loops.loops) == 3 and len(mechanism.joints) == 18  # 9 R + 3 balls x 3 hinges
    x = np.linspace(*kinematics.domain, 31)
    q = mechanism.angles_from_poses(kinematics.body_poses(x))
    assert np.max(loops.residual_norm(q)) < 1e-12  # measured 2.8e-15
    hinges = [mechanism.joint_index(n) for n in kinematics.REVOLUTE]
    assert np.max(np.abs(wrap(q[:, hinges] - kinematics.revolute_angles(x)))) < 1e-12  # measured 1.3e-15 rad
    # ball triads clear of the middle-angle singularity: measured max |b| 12.3 deg (I), 3.5 deg (II), 14.1 (I, -5)
    middle = [mechanism.balls[name][1] for name in BALLS[scheme]]
    assert np.max(np.abs(q[:, middle])) < 20 * DEG
    # mobility 1 at a generic pose: rank 17 of 18 joint angles (truss m = 1, s = 1; no idle spin)
    assert loops.mobility(q[10]) == 1
    assert (
        np.linalg.matrix_rank(loops.jacobian(q[10]), tol=1e-9) == 17
    )  # 2nd smallest sigma >= 0.18, smallest <= 1.8e-16


def test_closed_form_matches_numeric_continuation(case):
    """The whole assembly driven at its input hinge (numeric LM continuation) against the closed form."""
    scheme, kinematics, mechanism = case
    lo, hi = kinematics.domain
    # scheme II's input theta has a turning point at deployment: start 2 deg inside (the numeric solve is singular
    # exactly there); scheme I's theta_G falls from its deployed value
    x = np.linspace(lo + 2 * DEG, hi, 41) if scheme == "II" else np.linspace(hi, lo, 41)
    loops = mechanism.loop_system()
    i = mechanism.joint_index(INPUT_JOINT[scheme])
    q0 = mechanism.angles_from_poses(kinematics.body_poses(x[0]))[0]
    q = loops.follow(q0, i, q0[i] + (x - x[0]), tol=1e-13)
    hinges = [mechanism.joint_index(n) for n in kinematics.REVOLUTE]
    assert (
        np.max(np.abs(wrap(q[:, hinges] - kinematics.revolute_angles(x)))) < 1e-9
    )  # measured 9.7e-12 rad (I, -5), 7.8e-13 (I)
    poses = mechanism.body_poses(q)
    P = np.stack([poses[OWNER[v]][:, :3, :3] @ VERTICES[v] + poses[OWNER[v]][:, :3, 3] for v in NAMES], axis=1)
    assert np.max(np.linalg.norm(P - kinematics.vertices(x), axis=-1)) < 1e-9  # measured 8.9e-12 m (I, -5), 7.1e-13 (I)


def test_bricard_with_balls_at_g_to_m_has_four_dof(two):
    """Sec. 6.2.3: S joints at G..M give 4 DOF; each S-S bar adds its idle spin, so the loop mobility is 4 + 3."""
    axes = revolute_axes(two)
    hinges = [_hinge(name, axes[name]) for name in "ABCDEF"]
    spacers, balls = [], []
    for name, parent, child in [("G", "ABG", "GK"), ("H", "CDH", "HL"), ("J", "EFJ", "JM"),
                                ("K", "GK", "KLM"), ("L", "HL", "KLM"), ("M", "JM", "KLM")]:
        frame = np.eye(4)
        frame[:3, 3] = VERTICES[name]
        bodies, joints = ball_joint(name, parent, child, frame, frame)
        spacers += bodies
        balls += joints
    mechanism = Mechanism(tuple(_bodies() + spacers), tuple(hinges + balls), root="ABG", keep=("A",))
    q = mechanism.angles_from_poses(two.body_poses(100 * DEG))
    assert mechanism.loop_system().residual_norm(q)[0] < 1e-14
    assert mechanism.loop_system().mobility(q[0]) == 7


# --- bad input -----------------------------------------------------------------------------------------------


@pytest.mark.parametrize("delta", [np.pi / 2, -2.0, np.nan, np.inf])
def test_bad_delta(delta):
    with pytest.raises(ParameterError, match="delta1"):
        SchemeI(delta)
    with pytest.raises(ParameterError, match="delta2"):
        SchemeII(delta)


def test_bad_scheme():
    with pytest.raises(ParameterError, match="scheme 'III'"):
        model("III")


@pytest.mark.parametrize("theta_deg", [30.0, 190.0, np.nan])
def test_input_outside_the_transformation(two, theta_deg):
    with pytest.raises(DomainError, match="outside the transformation"):
        two.vertices(theta_deg * DEG)


def test_theta_g_outside_the_transformation(one):
    with pytest.raises(DomainError, match="theta_G = 150"):
        one.body_poses(150 * DEG)


# --- MuJoCo (scenes `truncated-tetrahedron-i`, `-ii`: S joints as ball joints) -------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("name", ["truncated-tetrahedron-i", "truncated-tetrahedron-ii"])
def test_mujoco_follows_the_transformation(name):
    report = validate(scenes.get(name).build())
    assert report.passed
    run = report.runs[0]
    vertex = next(v for v in run.verdicts if v.id == MUJOCO_VERTEX_ERROR)
    assert vertex.measured < 1e-6  # issue 6 target, unit edges (measured 9.4e-8 (I), 4.8e-8 (II); stiff 16x)
    start = run.mobility["start"]
    assert (start["numeric"], start["mujoco"], start["truss"]) == (1, 1, 1)


@pytest.mark.slow
def test_a_path_error_near_the_critical_delta_names_the_ill_conditioned_pose():
    """0.02 deg inside the refused limit the path passes near the Bricard's other fold: fast misses by 1.2e-5 rad over
    the 130 s its path's rates ask for (4.7e-4 at the former 16 s; measured), and the failing check says where and how
    ill-conditioned the closure is there, against the start."""
    scene = scenes.get("truncated-tetrahedron-i").build_from_user({"delta": -62.0})
    branch = scene.kinematics.branches()[0].name
    path = compare(scene, branch, simulate(scene, branch).q)
    clause = _conditioning(scene, path, 1e-6)
    worst, start = (float(v) for v in re.findall(r"condition number is (\S+) \((\S+) at", clause)[0])
    assert path.max_error() > 1e-5 and worst > 10 * start
    assert _conditioning(scene, path, 1.0) == ""
