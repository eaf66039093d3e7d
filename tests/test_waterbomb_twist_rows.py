"""Twist of a row other than the middle one (`WaterbombTwist(row=...)`, scene `waterbomb-twist -p row=...`) against
Feng, Ma and Chen 2020 (§3, "Bifurcation", Fig 16), the loop solver and MuJoCo. The paper gives no numbers for paths
I and III beyond their common start (configuration iii)."""

import numpy as np
import pytest

import sim_origami.scenes.waterbomb_twist  # noqa: F401  (registers the scene)
from sim_origami import scenes
from sim_origami.checks.branches import classify
from sim_origami.checks.paths import compare
from sim_origami.errors import ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.waterbomb_tube import WaterbombTube, beta_max, tube_layout
from sim_origami.kinematics.waterbomb_twist import CCW, CW, WaterbombTwist, twist_folds, unwrapped
from sim_origami.presets import FAST
from sim_origami.simulate import simulate
from sim_origami.tolerances import TOLERANCES

DEG = np.pi / 180
ALPHA = 40 * DEG
BETA = beta_max(ALPHA, 6)  # 42.0105238 deg (eqn 40 solved here; Fig 16 prints 42.01)
PATH_I = WaterbombTwist(6, 3, ALPHA, BETA, row=1)  # top row twisting
PATH_III = WaterbombTwist(6, 3, ALPHA, BETA, row=-1)  # bottom row twisting


def inputs(model: WaterbombTwist, branch: str, k: int = 21) -> np.ndarray:
    return np.linspace(*model.branch(branch).domain, k)


@pytest.mark.slow
@pytest.mark.parametrize("model", [PATH_I, PATH_III], ids=["I", "III"])
def test_closed_form_closes_the_tube(model):
    """Every vertex loop and the ring round the middle row, free and with the couplings, on both senses; every edge
    rigid."""
    free, coupled = model.free_loop_system(), model.loop_system()
    layout = model.layout
    for branch in (CCW, CW):
        x = inputs(model, branch)
        q = model.joint_angles(branch, x)
        assert np.max(free.residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured <= 5.4e-15
        assert np.max(coupled.residual_norm(q)) <= TOLERANCES.closed_form_residual
        X = model.vertices(branch, x)
        for _, s, e, _ in layout.creases:
            d = layout.flat[e] - layout.flat[s]
            d[0] -= 2 * 6 * np.round(d[0] / (2 * 6))
            assert np.max(np.abs(np.linalg.norm(X[:, e] - X[:, s], axis=-1) - np.linalg.norm(d))) <= 1e-13


def test_rows_do_not_depend_on_the_rows_farther_out():
    """The idea behind the model: the rows of the m-row tube twisting in row 1 are those of a taller tube twisting in
    its row 1 (here 3 against 5 rows, names shifted by one row): the chain builds outward from the twisting row."""
    zeta = np.linspace(60 * DEG, 120 * DEG, 7)
    small, tall = tube_layout(6, 3, ALPHA, BETA, 1.0), tube_layout(6, 5, ALPHA, BETA, 1.0)
    q3, q5 = twist_folds(small, zeta, row=1), twist_folds(tall, zeta, row=1)

    def shifted(name: str) -> str:
        return name[0] + str(int(name[1]) + 1) + name[2:]

    pick = [tall.index(shifted(name)) for name in small.names]
    assert np.max(np.abs(q3 - q5[:, pick])) <= 1e-12  # measured 0 rad: the same arithmetic


@pytest.mark.slow
def test_start_is_the_equal_diameter_cylinder():
    """Paths I, II, III and the contraction meet at configuration iii: the contraction's end (theta = 360/n), every
    row's A's on the axis, every vertical edge folded flat (kappa_Bi,4 = kappa_Ci,4 = 0)."""
    tube = WaterbombTube(6, 3, ALPHA, BETA)
    end = unwrapped(tube.layout, tube.folds(np.array([2 * np.pi / 6 - np.pi])))[0]
    vertical = [tube.layout.index(f"V{r}_{k}") for r in range(3) for k in range(6)]
    assert np.max(np.abs(end[vertical] + np.pi)) <= 1e-14  # measured 0
    for row in (1, 0, -1):
        model = PATH_I if row == 1 else PATH_III if row == -1 else WaterbombTwist(6, 3, ALPHA, BETA)
        assert model.start == pytest.approx(np.pi - 47.7173 * DEG, abs=5e-5 * DEG)  # eqn 39a
        for branch in (CCW, CW):
            q = model.joint_angles(branch, model.start)[0]
            assert np.max(np.abs(wrap(q - end))) <= 1e-14  # measured 8.9e-16 rad
            assert np.max(np.abs(model.radii(branch, model.start))) <= 1e-15  # measured 6.7e-16 m


def test_ranges_and_events():
    """Paths I and III (no numbers in the paper): eta02 from 0 (counter-clockwise end) to 100.8002 deg (clockwise),
    the end-ring twist +-72.3493 deg, as path II: the twisting row's own limits (a), (b) end them. The other rows
    touch the axis at the start (no crossing events)."""
    for model in (PATH_I, PATH_III):
        eta02 = np.rad2deg(np.pi - np.array(model.domain))
        np.testing.assert_allclose(eta02, [100.8002, 0.0], atol=5e-5, rtol=0)  # measured 100.800215, 5.3e-12
        assert model.end_twist(CW, model.domain[0])[0] / DEG == pytest.approx(-72.3493, abs=5e-5)
        kinds = sorted((e.kind, e.branches) for e in model.events())
        assert kinds == [("bifurcation", (CCW,)), ("bifurcation", (CW,)), ("lock", (CCW,)), ("lock", (CW,))]
        assert [b.name for b in model.branches()] == [CCW, CW]


def test_mirror_relation():
    """Path III is the half-turn image of path I at the same input: the strip's point reflection A_i <-> A_-i, B_i
    <-> C_(-i-1), slot p <-> 2 - p maps the creases, and the end-ring twist is the same (not reversed)."""
    layout = PATH_I.layout
    keys = {key: v for v, key in enumerate(layout.keys)}
    image = {"A": lambda i: ("A", -i), "B": lambda i: ("C", -i - 1), "C": lambda i: ("B", -i - 1)}

    def mapped(v: int) -> int:
        kind, i, p = layout.keys[v]
        return keys[(*image[kind](i), (2 - p) % 12)]

    ends = {frozenset(c[1:3]): k for k, c in enumerate(layout.creases)}
    perm = [ends[frozenset((mapped(s), mapped(e)))] for _, s, e, _ in layout.creases]
    assert layout.names[perm[layout.index(PATH_I.input_crease)]] == "A0_0_5"
    for branch in (CCW, CW):
        x = inputs(PATH_I, branch, 9)
        q1, q3 = PATH_I.joint_angles(branch, x), PATH_III.joint_angles(branch, x)
        assert np.max(np.abs(q3[:, perm] - q1)) <= 1e-13  # measured 0 rad
        assert np.max(np.abs(PATH_III.end_twist(branch, x) - PATH_I.end_twist(branch, x))) <= 1e-15


@pytest.mark.slow
def test_couplings_leave_one_degree_of_freedom():
    """The couplings found from the closed form (91 on the 6 x 3 tube) leave mobility 1 on each sense and 2 at the
    start; the radial contraction breaks them (the twisting row's A is line-symmetric), so it is no branch here."""
    model = PATH_I
    coupled, free = model.loop_system(), model.free_loop_system()
    assert len(model.couplings) == 91
    for branch in (CCW, CW):
        assert coupled.mobility(model.joint_angles(branch, np.mean(model.branch(branch).domain))[0]) == 1
    at_start = model.joint_angles(CW, model.start)[0]
    assert (free.mobility(at_start), coupled.mobility(at_start)) == (21, 2)
    tube = WaterbombTube(6, 3, ALPHA, BETA)
    contraction = unwrapped(tube.layout, tube.folds(np.linspace(*tube.domain, 7)[1:-1]))
    assert np.max(coupled.residual_norm(contraction)) > 0.1  # measured 0.80


@pytest.mark.slow
def test_closed_form_matches_the_numeric_continuation():
    loops, joint = PATH_I.loop_system(), PATH_I.loop_input()[0]
    for branch in (CCW, CW):
        lo, hi = PATH_I.branch(branch).domain
        x = np.linspace(lo + 0.2 * (hi - lo), hi - 0.2 * (hi - lo), 5)
        q = PATH_I.joint_angles(branch, x)
        numeric = loops.follow(q[0], joint, x)
        assert np.max(np.abs(wrap(numeric - q))) <= TOLERANCES.closed_form_rad  # measured 9.6e-14 rad


@pytest.mark.slow
@pytest.mark.parametrize(("row", "branch"), [(1, CCW), (-1, CW)])
def test_mujoco_follows_the_twist_of_an_end_row(row, branch):
    """The 6 x 3 tube at beta_max twisting in its top (path I) or bottom row (III), scene preset fast 8x: every
    crease's path error, the branch followed and the closure residual."""
    scene = scenes.get("waterbomb-twist").build(beta=BETA, row=row)
    run = simulate(scene, branch)
    path = compare(scene, branch, run.q)
    labels = classify(scene.kinematics, path.input, path.simulated)
    assert (labels.followed, labels.flips) == (branch, 0)
    assert path.max_error() <= FAST.angle_rad  # measured 1.3e-8 (I ccw), 9.7e-9 rad (III cw)
    assert np.max(run.closure_residual) <= FAST.residual_per_m  # measured 2.6e-9, 3.6e-9 m


@pytest.mark.parametrize(
    ("values", "match"),
    [
        ({"row": 2}, r"row = 2; the 3-row tube twists in one of its rows -1, 0, 1"),
        ({"row": 0.5}, r"row = 0.5; it must be a whole number"),
        ({"row": 1}, r"beta = 40 deg is not beta_max = 42.0105238 deg .*row 1 has r_A = 0.0581 a"),
        ({"row": -1, "beta": 42.01}, r"beta = 42.01 deg is not beta_max .*r_A = 1.48e-05 a"),  # Fig 16's rounding
        ({"row": -2}, r"row = -2; the 3-row tube twists in one of its rows -1, 0, 1"),
    ],
)
def test_bad_row_or_beta_is_refused(values, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("waterbomb-twist").build_from_user(values)


@pytest.mark.slow
def test_beta_window():
    """The twisting row must be fully folded where the contraction ends, |r_A| <= 1e-9 a: r_A = -1.615 a (beta -
    beta_max), so beta_max +- 5e-10 rad passes and +- 1e-9 rad does not; 42.0105238 deg (typed) passes."""
    for d in (5e-10, -5e-10):
        WaterbombTwist(6, 3, ALPHA, BETA + d, row=1)
    for d in (1e-9, -1e-9):
        with pytest.raises(ParameterError, match="not fully folded"):
            WaterbombTwist(6, 3, ALPHA, BETA + d, row=-1)
    scene = scenes.get("waterbomb-twist").build_from_user({"row": 1, "beta": 42.0105238})
    assert scene.kinematics.input_crease == "A2_0_2" and scene.params["row"] == 1
