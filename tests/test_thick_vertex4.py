"""Thick four-crease vertex (Peng 2018, §4.2): the closed form closes its lifted loop at every input, ends included,
and layouts whose hinges fall on one line (no Bennett linkage) are refused."""

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.errors import ParameterError
from sim_origami.kinematics.thick_vertex4 import ThickVertex4
from sim_origami.kinematics.vertex4 import Vertex4
from sim_origami.simulate import contact_distance, contact_input


def thick(alpha1_deg: float, alpha2_deg: float, layout: str) -> ThickVertex4:
    a1, a2 = np.deg2rad([alpha1_deg, alpha2_deg])
    return ThickVertex4([a1, a2, np.pi - a1, np.pi - a2], 0.05, layout)


# 60/120 staircase: creases 1 and 3 collinear, so eqn 2-5's coefficients vanish at rho1 = +/- pi; the old closed form
# (Vertex4's roots) missed the loop by 0.027 there and 0.1 within 1e-8 rad of it; 90.001/90: 5.3e-7 at the ends.
@pytest.mark.parametrize("alpha1, alpha2, layout", [(60, 120, "staircase"), (90.001, 90, "staircase"),
                                                    (45, 90, "staircase"), (100, 80, "staircase"),
                                                    (60, 60, "zigzag"), (89.9, 90, "zigzag")])
def test_closed_form_closes_the_lifted_loop_everywhere_ends_included(alpha1, alpha2, layout):
    kin = thick(alpha1, alpha2, layout)
    (branch,) = kin.branches()
    lo, hi = branch.domain
    ends = np.array([0.0, 1e-14, 1e-10, 1e-8, 1e-6])
    x = np.concatenate([lo + ends, hi - ends, np.linspace(lo, hi, 201), [1e-12, -1e-9]])
    values, valid = kin.evaluate(branch.name, x)
    assert valid.all()
    assert np.max(kin.loop_system().residual_norm(kin.loop_angles(values))) < 2e-15


@pytest.mark.parametrize("alpha1, alpha2, layout", [(60, 90, "staircase"), (60, 120, "staircase"),
                                                    (45, 90, "zigzag")])
def test_hinge_angles_are_the_zero_thickness_fold_angles_of_the_mode(alpha1, alpha2, layout):
    kin = thick(alpha1, alpha2, layout)
    x = np.linspace(-3.1, 3.1, 125)
    ours, _ = kin.evaluate(kin.mode, x)
    zero, _ = Vertex4(kin.alpha).evaluate(kin.mode, x)
    assert np.max(np.abs(ours - zero)) < 1e-10


@pytest.mark.parametrize("params, match", [
    ({"alpha1": 90.0}, r"^alpha1 = 90 deg, alpha2 = 90 deg: staircase hinges 2 and 4 lie on one line .*"
                       r"alpha1 must differ from alpha2$"),
    ({"alpha1": 60.0, "alpha2": 60.0 + 1e-5}, "staircase hinges 2 and 4 lie on one line"),
    ({"alpha1": 60.0, "alpha2": 120.0, "zigzag": 1.0}, r"^alpha1 = 60 deg, alpha2 = 120 deg: zigzag hinges 1 and 3 "
                                                       r"lie on one line .*alpha1 \+ alpha2 must differ from 180 deg$"),
    ({"alpha1": 90.0, "zigzag": 1.0}, "zigzag hinges 1 and 3 lie on one line"),
])
def test_coaxial_hinges_are_refused(params, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("thick-vertex4").build_from_user(params)


def test_cli_refuses_alpha1_90_in_one_line_with_exit_2(capsys):
    code = main(["validate", "thick-vertex4", "-p", "alpha1=90", "--preset", "fast"])
    err = capsys.readouterr().err
    assert code == 2
    assert err.count("\n") == 1 and "alpha1 must differ from alpha2" in err


@pytest.mark.parametrize("zigzag", [0.0, 1.0])
def test_both_layouts_sweep_the_way_their_slabs_leave_room(zigzag):
    """The validation sweep and the blockage run start apart and meet where the slabs block the fold: the zigzag
    layout swept rho1 > 0, where its slabs overlap from the start (blockage stopped at 0.017 rad, contact at 0.4)."""
    scene = scenes.get("thick-vertex4").build(zigzag=zigzag)
    branch = scene.kinematics.branches()[0].name
    start = scene.branch_path(branch)[0]
    assert contact_distance(scene, branch, np.array([start]))[0] > 0
    touch = contact_input(scene, branch, start, scene.kinematics.branch(branch).domain[0])
    assert touch == pytest.approx({0.0: -0.5246, 1.0: -1.5728}[zigzag], abs=2e-4)
