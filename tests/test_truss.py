"""The truss method (`sim_origami.truss`, command `mobility`) against Yang 2017, ch. 2-3, the numeric loop
closure's Jacobian rank, MuJoCo's constraint Jacobian and the closed forms."""

import numpy as np
import pytest

from sim_origami import cli, scenes, truss
from sim_origami.cli import mobility
from sim_origami.errors import AssemblyError, ParameterError
from sim_origami.geometry import rotation, wrap
from sim_origami.path import BIFURCATION_RTOL
from sim_origami.simulate import mujoco_mobility
from sim_origami.truss import (
    GRAM_FROM,
    RANK_RTOL,
    analyse,
    constraints,
    follow,
    follow_scene,
    removable_bars,
    truss_mobility,
    truss_of,
)

DEG = np.pi / 180
# Truss path vs closed form (issue 6 target 1e-9 rad). Measured 3.6e-14 (along) and 1.4e-14 (against) on the
# default Bricard path, <= 6.3e-12 on every branch after the bifurcations crossed below, 1.0e-13 on the closed path.
PATH_RAD = 1e-9
# A double point is located to about sqrt(corrector tolerance): measured input errors <= 5.5e-7 rad (plane
# Bricard at 0), <= 2.7e-8 rad on the Bricard bundle; closed form there <= 2.7e-8 rad from the located point.
LOCATED_RAD = 5e-6


def poses(scene) -> list[tuple[str, float]]:
    """The first branch's start pose and every bifurcation event (on its first branch)."""
    kin = scene.kinematics
    first = kin.branches()[0].name
    events = [(e.branches[0], e.input) for e in kin.events() if e.kind == "bifurcation"]
    return [(first, scene.branch_path(first)[0]), *events]


@pytest.mark.slow
@pytest.mark.parametrize("name", scenes.names())
def test_truss_mobility_equals_jacobian_mobility(name):
    # Issue 6 item 5: at the start pose and at every bifurcation, truss m = numeric rank = MuJoCo rank; the ranks
    # also count the idle spin of each bar held by two spherical joints (truncated octahedron: 3), the truss not.
    scene = scenes.get(name).build()
    loops = scene.kinematics.loop_system()
    idle = scene.mechanism.idle_spins
    for branch, x in poses(scene):
        q = scene.pose(branch, x)
        counts = truss_mobility(scene, q)
        numeric = loops.mobility(scene.mechanism_to_loop(q)[0])
        assert counts.mobility == numeric - idle == mujoco_mobility(scene, q) - idle, (branch, x)
        assert counts.mobility - counts.self_stress == counts.maxwell
        # The rank decision is clear-cut: measured kept >= 1.5e-4 (triangle-twist-6r), dropped <= 1e-15 of the
        # largest singular value over every scene's poses here.
        assert counts.kept > 1e3 * RANK_RTOL and counts.dropped < 1e-3 * RANK_RTOL


def test_large_truss_counts_from_the_gram_matrix_equal_the_svd_counts(monkeypatch):
    # The waterbomb tube's truss (446 x 306) is over GRAM_FROM coordinates: counts only come from the Gram matrix
    # and M on its near-null eigenvectors, the same rank as the full SVD's, its smallest kept singular value to 1e-9.
    scene = scenes.get("waterbomb-tube").build()
    for branch, x in poses(scene):
        t = truss_of(scene.mechanism, scene.pose(branch, x))
        assert constraints(t).shape[1] > GRAM_FROM
        fast, full = analyse(t, stresses=False), analyse(t)
        assert (fast.rank, fast.mobility, fast.self_stress) == (full.rank, full.mobility, full.self_stress)
        assert fast.kept == pytest.approx(full.kept, rel=1e-9) and fast.dropped < 1e-3 * RANK_RTOL
    # too few eigenpairs to reach past the near-null singular values (6 rigid motions at least): the SVD decides
    monkeypatch.setattr(truss, "GRAM_LOW", 4)
    assert truss._gram_counts(constraints(t), RANK_RTOL) is None
    assert analyse(t, stresses=False).rank == full.rank


def test_yang2017_bennett_counts_tilt_and_release():
    # Yang 2017, Sec. 3.3, Fig. 3-1: j = 8, b = 20, r = 17, m = 1, s = 3; an axis tilted by 1.5 deg (derived here):
    # r = 18, m = 0; minus CD', C'D, C'D' of one link (the common normal CD stays): b = 17, r = 17, m = 1, s = 0
    # (Sec. 3.3, the RSSR form).
    scene = scenes.get("bennett").build()
    truss = truss_of(scene.mechanism, scene.pose("bennett", 1.0))
    c = analyse(truss)
    assert (c.nodes, c.bars, c.rank, c.mobility, c.self_stress, c.maxwell) == (8, 20, 17, 1, 3, -2)
    x = truss.nodes.copy()
    a, a2 = truss.node_names.index("joint_1"), truss.node_names.index("joint_1'")
    axis = x[a2] - x[a]
    normal = np.cross(axis, [1.0, 0.0, 0.0])
    x[a2] = x[a] + rotation(normal / np.linalg.norm(normal), 1.5 * DEG) @ axis
    tilted = analyse(truss, x)
    assert (tilted.rank, tilted.mobility, tilted.self_stress) == (18, 0, 2)
    removed = removable_bars(truss)
    names = {truss.bar_names()[k] for k in removed}
    assert names == {"joint_1-joint_2'", "joint_1'-joint_2", "joint_1'-joint_2'"}
    assert len({truss.bar_body[k] for k in removed}) == 1
    released = analyse(truss.without(removed))
    assert (released.bars, released.rank, released.mobility, released.self_stress) == (17, 17, 1, 0)


def test_yang2017_rssr_truss():
    # Yang 2017, Sec. 3.3: Bennett with S joints at C and D (joints 3, 4): j = 6, b = 11, r = 11, m = 1, s = 0.
    scene = scenes.get("bennett").build()
    c = analyse(truss_of(scene.mechanism, scene.pose("bennett", 1.0), spherical=("joint_3", "joint_4")))
    assert (c.nodes, c.bars, c.rank, c.mobility, c.self_stress) == (6, 11, 11, 1, 0)


@pytest.mark.parametrize("ball", ["joint_1", "joint_2"])
def test_yang2017_myard_counts_and_non_overconstrained_forms(ball):
    # Yang 2017, Sec. 3.4, Fig. 3-7: Myard j = 9, b = 22, r = 20, m = 1, s = 2 (joints 3, 4 meet: link 34 is a
    # triangle); RRSRR (S at A = joint 1) and RSRRR (S at B = joint 2): j = 8, b = 17, r = 17, m = 1, s = 0.
    scene = scenes.get("myard").build()
    q = scene.pose("plane_symmetric", 40 * DEG)
    truss = truss_of(scene.mechanism, q)
    c = analyse(truss)
    assert (c.nodes, c.bars, c.rank, c.mobility, c.self_stress) == (9, 22, 20, 1, 2)
    s = analyse(truss_of(scene.mechanism, q, spherical=(ball,)))
    assert (s.nodes, s.bars, s.rank, s.mobility, s.self_stress) == (8, 17, 17, 1, 0)
    # Sec. 3.4: two body bars of one link that share A' (the RRSRR of Fig. 3-9)
    removed = removable_bars(truss)
    assert len(removed) == 2 and all("joint_1'" in truss.bar_names()[k] for k in removed)
    assert analyse(truss.without(removed)).self_stress == 0


def test_yang2017_threefold_bricard_counts():
    # Yang 2017, Sec. 2.3, Fig. 2-3: j = 12, b = 30; at theta = 129.31 deg, phi = -19.990 (a pose chosen here):
    # r = 29, m = 1, s = 1; at the bundle (theta = phi = 180 deg, Sec. 2.4, Fig. 2-5b) the mobility is 2.
    scene = scenes.get("bricard-threefold").build()
    q = scene.pose("even-axes-along", 129.31 * DEG)
    assert q[1] == pytest.approx(-19.990 * DEG, abs=5e-4 * DEG)
    c = truss_mobility(scene, q)
    assert (c.nodes, c.bars, c.rank, c.mobility, c.self_stress) == (12, 30, 29, 1, 1)
    assert truss_mobility(scene, scene.pose("even-axes-along", np.pi)).mobility == 2


@pytest.mark.parametrize("branch", ["even-axes-along", "even-axes-against"])
def test_bricard_threefold_path_follower_matches_closed_form(branch):
    # Issue 6 target: the truss path follower agrees with the closed form to <= 1e-9 rad on the default path.
    scene = scenes.get("bricard-threefold").build()
    start, stop = scene.branch_path(branch)
    run = follow_scene(scene, branch, start, stop)
    assert run.path.reached and not run.path.bifurcations
    assert run.input[0] == pytest.approx(start, abs=1e-15) and run.input[-1] == pytest.approx(stop, abs=1e-14)
    error = np.abs(wrap(scene.outputs(run.q) - scene.kinematics.joint_angles(branch, run.input)))
    assert error.max() <= PATH_RAD
    # Yang 2017, Sec. 2.3 (threefold symmetry): theta1 = theta3 = theta5 on the path (< 1e-11); measured 6e-15
    assert np.abs(wrap(run.q[:, 0] - run.q[:, 2])).max() < 1e-11
    assert np.abs(wrap(run.q[:, 0] - run.q[:, 4])).max() < 1e-11


def test_path_follower_keeps_joint_couplings():
    # The waterbomb cell's 6 symmetry/periodic couplings enter the corrector as coupling rows; measured 2.7e-13
    # rad against the closed form and 4.9e-14 rad on the couplings over the default path.
    scene = scenes.get("waterbomb-vertex").build()
    start, stop = scene.branch_path("line-symmetric")
    run = follow_scene(scene, "line-symmetric", start, stop)
    assert run.path.reached
    error = np.abs(wrap(scene.outputs(run.q) - scene.kinematics.joint_angles("line-symmetric", run.input)))
    assert error.max() <= PATH_RAD
    index = scene.mechanism.joint_index
    for a, b, c in scene.mechanism.couplings:
        assert np.abs(run.q[:, index(a)] - c * run.q[:, index(b)]).max() < 1e-12


@pytest.mark.slow
def test_bricard_threefold_closed_path_crosses_the_bundle_twice():
    # Yang 2017, Sec. 2.4, Fig. 2-5: the motion is closed (from theta = 129.31 deg theta1 grows by 720 deg) and
    # passes the bundle twice, at theta1 = pi and 3 pi, where the mobility is 2; 'keep' goes straight through.
    scene = scenes.get("bricard-threefold").build()
    x0 = 129.31 * DEG
    run = follow_scene(scene, "even-axes-along", x0, x0 + 4 * np.pi)
    events = run.path.bifurcations
    assert [e.input for e in events] == pytest.approx([np.pi, 3 * np.pi], abs=LOCATED_RAD)
    assert all(e.mobility == 2 and e.directions == 2 and e.sigma2 < BIFURCATION_RTOL for e in events)
    # back at the start: measured 9e-15
    assert np.abs(run.path.nodes[-1] - run.path.nodes[0]).max() < 1e-12
    kin = scene.kinematics
    error = np.min([np.abs(wrap(scene.outputs(run.q) - kin.evaluate(b.name, wrap(run.input))[0])).max(axis=1)
                    for b in kin.branches()], axis=0)
    at_events = [e.index for e in events]
    assert np.delete(error, at_events).max() <= PATH_RAD
    assert error[at_events].max() <= LOCATED_RAD


@pytest.mark.parametrize(
    ("name", "branch", "start", "stop", "kept", "switched"),
    [
        # Bricard bundle: the smooth crossing changes the name (kinematics/bricard_threefold.py docstring)
        ("bricard-threefold", "even-axes-along", 2.6, 2 * np.pi - 2.6, "even-axes-against", "even-axes-along"),
        ("bricard-plane", "theta1_eq_theta4", 0.3, -0.3, "theta1_eq_theta4", "theta1_plus_theta4_eq_2theta2"),
        ("miura", "straight", -0.3, 0.3, "straight", "miura"),
        ("thick-diamond", "diamond", 0.3, -0.3, "diamond", "counter23"),
    ],
)
@pytest.mark.slow
def test_branch_choice_at_a_bifurcation(name, branch, start, stop, kept, switched):
    scene = scenes.get(name).build()
    kin = scene.kinematics
    for choice, expected in (("keep", kept), ("switch", switched)):
        run = follow_scene(scene, branch, start, stop, choice=choice)
        (event,) = run.path.bifurcations
        assert (event.mobility, event.directions, event.choice) == (2, 2, choice)
        assert run.path.reached
        after = slice(event.index + 1, None)
        x = wrap(run.input[after])
        error = np.abs(wrap(scene.outputs(run.q[after]) - kin.evaluate(expected, x)[0])).max()
        other = next(b for b in (kept, switched) if b != expected)
        assert error <= PATH_RAD
        assert np.abs(wrap(scene.outputs(run.q[after]) - kin.evaluate(other, x)[0])).max() > 0.1


@pytest.mark.slow
def test_truss_rejects_bad_input():
    scene = scenes.get("bennett").build()
    q = scene.pose("bennett", 1.0)
    with pytest.raises(ParameterError, match="4 finite joint angles"):
        truss_of(scene.mechanism, q[:3])
    with pytest.raises(ParameterError, match="finite"):
        truss_of(scene.mechanism, np.array([np.nan, *q[1:]]))
    with pytest.raises(ParameterError, match="joint_9"):
        truss_of(scene.mechanism, q, spherical=("joint_9",))
    with pytest.raises(AssemblyError, match="not closed"):
        truss_of(scene.mechanism, q + np.array([0.0, 1e-3, 0.0, 0.0]))
    truss = truss_of(scene.mechanism, q)
    with pytest.raises(ParameterError, match="bars \\[20\\]"):
        truss.without([20])
    with pytest.raises(ParameterError, match="'sideways'"):
        follow(truss, "joint_1", 2.0, choice="sideways")
    with pytest.raises(ParameterError, match="joint_7"):
        follow(truss, "joint_7", 2.0)
    with pytest.raises(ParameterError, match="positive"):
        follow(truss, "joint_1", 2.0, step=-0.1)
    flat = scenes.get("vertex4").build()
    with pytest.raises(ParameterError, match="mobility 1 at the start"):
        follow(truss_of(flat.mechanism, flat.pose("odd1", 0.0)), "crease_1", 0.3)
    with pytest.raises(AssemblyError, match="no single body"):
        sheet = scenes.get("miura-sheet").build()
        removable_bars(truss_of(sheet.mechanism, sheet.pose("miura", 0.5)))


def run_cli(capsys, monkeypatch, *argv: str) -> tuple[int, str, str]:
    """`sim-origami mobility ...` in process, with the command registered as cli/__init__.py will."""
    if mobility not in cli.COMMANDS:
        monkeypatch.setattr(cli, "COMMANDS", (*cli.COMMANDS, mobility))
    code = cli.main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_mobility_table(capsys, monkeypatch):
    code, out, _ = run_cli(capsys, monkeypatch, "mobility", "bricard-threefold", "--at", "129.31")
    assert code == 0
    lines = out.splitlines()
    at = next(line.split() for line in lines if line.strip().startswith("at "))
    assert at == ["at", "129.3100", "12", "30", "0", "29", "1", "1", "0", "1", "1"]
    bundle = [line.split() for line in lines if line.strip().startswith("bifurcation")]
    assert [row[6] for row in bundle] == ["2", "2"] and [row[1] for row in bundle] == ["-180.0000", "180.0000"]
    assert "redundant bars at at 129.3100 deg (24)" in out and "mobilities agree" in out


def test_cli_mobility_takes_the_idle_spin_off_as_validation_does(capsys, monkeypatch):
    """The RSSR's coupler CD spins freely between its balls: the loop ranks and MuJoCo count 2, the truss 1. The
    command used to print 'MOBILITIES DIFFER' and exit 1 on this built-in scene."""
    code, out, _ = run_cli(capsys, monkeypatch, "mobility", "rssr")
    start = next(line.split() for line in out.splitlines() if line.strip().startswith("start"))
    assert code == 0 and start[6] == start[9] == start[10] == "1", out
    assert "1 idle spin(s)" in out and "mobilities agree" in out


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (("mobility", "nosuch"), "nosuch"),
        (("mobility", "vertex4", "--branch", "Q"), "'Q'"),
        (("mobility", "vertex4", "--at", "ten"), "ten"),
        (("mobility", "vertex4", "--at", "nan"), "finite"),
        (("mobility", "vertex4", "--at", "300"), "outside"),
        (("mobility", "vertex4", "-p", "alpha1"), "NAME=VALUE"),
        (("mobility", "vertex4", "-p", "beta=70"), "beta"),
    ],
)
def test_cli_mobility_bad_input_exits_2_with_one_line(capsys, monkeypatch, argv, needle):
    code, out, err = run_cli(capsys, monkeypatch, *argv)
    assert code == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and needle in err
