"""Thick square twist (`kinematics.thick_square_twist`, scene `thick-square-twist`) against Peng 2018, Fig 4-4
(with §3.3 and §4.2): height rule, kinematic equivalence with the zero-thickness twist, mobility at
flat, MuJoCo paths and panel contact."""

import numpy as np
import pytest

import sim_origami.scenes.square_twist  # registers `square-twist`
import sim_origami.scenes.thick_square_twist  # noqa: F401  (registers `thick-square-twist`)
from sim_origami import scenes
from sim_origami.checks.branches import classify
from sim_origami.checks.paths import compare
from sim_origami.errors import ParameterError
from sim_origami.geometry import wrap
from sim_origami.kinematics.square_twist import CLASS_OF, CREASES, EDGES, RIGID, VERTICES, SquareTwist, mode_classes
from sim_origami.kinematics.thick_square_twist import (
    LAYOUT,
    ThickSquareTwist,
    crease_heights,
    layouts,
    square_levels,
    thick_pattern,
)
from sim_origami.kinematics.thick_vertex4 import ThickVertex4
from sim_origami.origami import hinge_gap
from sim_origami.presets import FAST
from sim_origami.simulate import contact_distance, contact_input, mujoco_mobility, simulate
from sim_origami.tolerances import TOLERANCES
from sim_origami.validation import validate

ALPHA = 5 * np.pi / 6  # Fig 3-15
B = 0.05
SIGN_CONSISTENT = tuple(m for members in mode_classes().values() for m in members)


def thick(modes: str = "CSCS", **params: float):
    """The registered scene on `modes` (index into RIGID) with other parameters as given (API units)."""
    return scenes.get("thick-square-twist").build(modes=float(RIGID.index(modes) + 1), **params)


def vertex_folds(q: np.ndarray, k: int) -> np.ndarray:
    """Fold angles (n, 4) of vertex k's creases 1..4 from joint angles (n, 12) in CREASES order."""
    v = VERTICES[k]
    names = (f"{v}1", EDGES[k], EDGES[(k - 1) % 4], f"{v}4")
    return q[:, [CREASES.index(n) for n in names]]


@pytest.mark.parametrize("modes", SIGN_CONSISTENT)
def test_height_rule_in_the_thesis_frame(modes):
    """Derived here: heights close round the square iff #S = #C (the six rigid strings); single slab iff opposite."""
    if modes in RIGID:
        heights = crease_heights(ALPHA, B, modes)
        assert square_levels(heights) == (2 if CLASS_OF[modes] == "opposite" else 3)
        steps = sorted(
            {round(abs(heights[e] - heights[f]), 12) for e, f in zip(EDGES, EDGES[1:] + EDGES[:1], strict=True)}
        )
        assert steps == [B]  # each vertex lifts its crease 3 by b; adjacent: b, 2b, b, 0 round it
    else:
        with pytest.raises(ParameterError, match=f"modes '{modes}'.*#S = #C"):
            crease_heights(ALPHA, B, modes)


@pytest.mark.parametrize("modes", SIGN_CONSISTENT)
def test_mirrored_vertices_make_every_string_height_consistent_and_kinematics_locks_the_others(modes):
    """Derived here: mirrored layouts reverse a vertex's lift: three layouts per string (one single-slab), so heights do
    not select the rigid strings; a non-rigid thick sheet is immobile even at flat (zero thickness: 4)."""
    found = layouts(ALPHA, B, modes)
    assert len(found) == 3
    assert sorted(square_levels(crease_heights(ALPHA, B, modes, f)) for f in found) == [2, 3, 3]
    if modes in RIGID:
        return
    for flips in found:
        assert thick_pattern(ALPHA, B, modes, flips=flips).loop_system().mobility(np.zeros(12)) == 0
    with pytest.raises(ParameterError, match=f"modes '{modes}': loop gain K = .* != 1"):
        ThickSquareTwist(ALPHA, B, modes, flips=found[0])


@pytest.mark.parametrize("modes", RIGID)
def test_each_vertex_is_the_bennett_vertex_of_its_mode(modes):
    """Independent of the pattern's loops: each vertex's heights are thick_vertex4's layout up to an offset,
    and `ThickVertex4` closes on that vertex's folds of the zero-thickness closed form."""
    model = ThickSquareTwist(ALPHA, B, modes)
    q = SquareTwist(ALPHA).joint_angles(modes, np.linspace(-3.1, 3.1, 63))
    for k, v in enumerate(VERTICES):
        vertex = ThickVertex4([ALPHA, np.pi / 2, np.pi - ALPHA, np.pi / 2], B, LAYOUT[modes[k]])
        h = np.array([model.heights[n] for n in (f"{v}1", EDGES[k], EDGES[(k - 1) % 4], f"{v}4")])
        np.testing.assert_allclose(h - h[0], vertex.heights, atol=1e-15, rtol=0)
        assert np.max(vertex.loop_system().residual_norm(vertex_folds(q, k))) <= 1e-12  # measured <= 1e-15


@pytest.mark.parametrize("modes", RIGID)
def test_thick_sheet_folds_exactly_like_its_zero_thickness_mode_string(modes):
    model, zero = ThickSquareTwist(ALPHA, B, modes), SquareTwist(ALPHA)
    loops = model.loop_system()
    q = zero.joint_angles(modes, np.linspace(-np.pi, np.pi, 1001))
    assert np.max(loops.residual_norm(q)) <= TOLERANCES.closed_form_residual  # measured <= 1.3e-15
    for sign in (1.0, -1.0):
        x = sign * np.linspace(0.1, 3.0, 30)
        exact = model.joint_angles(modes, x)
        numeric = loops.follow(exact[0], CREASES.index("AB"), x)
        assert np.max(np.abs(wrap(numeric - exact))) <= TOLERANCES.closed_form_rad  # measured <= 6.9e-14
    for other in RIGID:
        if other != modes:  # the hinge heights block the other five strings: measured >= 1.4e-3 at x = 0.05
            assert loops.residual_norm(zero.joint_angles(other, 0.05))[0] >= 1e-3


def test_thickness_removes_the_flat_bifurcation():
    """Zero thickness: six strings cross at flat (mobility 4). Thick: one branch through flat, mobility 1."""
    model, zero = ThickSquareTwist(ALPHA, B), SquareTwist(ALPHA)
    loops = model.loop_system()
    assert zero.loop_system().mobility(np.zeros(12)) == 4
    assert loops.mobility(np.zeros(12)) == 1  # smallest kept singular value 2.0e-2, next 1.3e-16
    for x in (1e-3, 1e-2, 0.5):
        assert loops.mobility(model.joint_angles("CSCS", x)[0]) == 1
    assert [b.name for b in model.branches()] == ["CSCS"]
    assert [(e.kind, e.input) for e in model.events()] == [("lock", -np.pi), ("lock", np.pi)]
    assert model.gruebler() == -12
    scene, flat = thick(), scenes.get("square-twist").build()
    assert (mujoco_mobility(scene, scene.pose("CSCS", 0.0)), mujoco_mobility(flat, flat.pose("CSCS", 0.0))) == (1, 4)


def test_mujoco_from_flat_and_from_every_zero_thickness_branch_takes_the_layouts_string():
    """Unforced choice at flat: started at the flat pose, or snapped from a pose of each zero-thickness branch at
    x = 0.05 (0.11 to 0.19 rad off the thick sheet's), driven to 1 rad, MuJoCo ends on CSCS."""
    scene, zero = thick(), scenes.get("square-twist").build()
    drive = scene.mechanism.joint_index(scene.drive_joint)
    starts = [zero.pose("CSCS", 0.0)] + [zero.pose(b, 0.05) for b in RIGID if b != "CSCS"]
    for initial in starts:
        run = simulate(scene, "CSCS", initial=initial, stop=1.0, duration=8.0)
        labels = classify(zero.kinematics, run.q[:, drive], scene.outputs(run.q))
        assert (labels.followed, labels.flips) == ("CSCS", 0)
        error = compare(scene, "CSCS", run.q).error
        assert np.max(np.abs(error[len(error) // 2 :])) <= FAST.angle_rad  # measured 1.3e-8


def test_validate_default_scene_with_blockage_at_panel_contact():
    report = validate(thick())
    failed = [v.name for v in report.verdicts + report.runs[0].verdicts if not v.passed]
    assert not failed
    run = report.runs[0]
    assert run.dynamic_path.max_error() <= FAST.angle_rad  # measured 3.8e-8 (fast, 4x), 0.03 s CPU
    assert run.projection_path.max_error() <= TOLERANCES.projection_rad  # measured 2.2e-15
    assert [run.mobility["start"][k] for k in ("numeric", "mujoco", "truss")] == [1, 1, 1]
    # the servo, driven to the zero-thickness lock at pi, stops where the panels touch: 2.884709 vs 2.884709
    blockage = report.blockage
    assert blockage.stopped and blockage.contact_input == pytest.approx(2.8847085, abs=1e-6)
    assert blockage.error <= 1e-5  # measured 4.4e-7


@pytest.mark.parametrize("modes", [m for m in RIGID if m != "CSCS"])
def test_mujoco_fast_path_on_the_other_rigid_strings(modes):
    scene = thick(modes)
    # the path's sweep time (sweep_rate) is timed for 2e-7: measured <= 1.07e-7 (CSSC)
    assert compare(scene, modes, simulate(scene, modes).q).max_error() <= 2.5e-7


def test_panels_are_slabs_carrying_their_hinge_lines():
    """Corners b thick, sides a = b sin(alpha), the opposite-class square b; every hinge on both its panels."""
    scene = thick()
    pattern, bodies = scene.pattern, {b.name: b for b in scene.mechanism.bodies}
    assert hinge_gap(pattern, scene.mechanism) <= 1e-12
    depth = {name: np.ptp(body.solid.vertices[:, 2]) for name, body in bodies.items()}
    volume = {name: body.solid.volume for name, body in bodies.items()}
    a = B * np.sin(ALPHA)
    for name in pattern.face_names:
        t = B if name.startswith(("corner", "square")) else a
        assert depth[name] == pytest.approx(t, abs=1e-15)
        face = pattern.faces[pattern.face_names.index(name)]
        x, y = pattern.vertices[list(face)].T
        area = 0.5 * abs(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))
        assert volume[name] == pytest.approx(area * t, rel=1e-12)  # a full slab, not a hull of the hinges alone


def test_panels_touch_only_near_the_flat_folded_end():
    """Faces sharing no vertex: clear over the default sweep of every string (closest 0.11 m, SSCC) and over
    -2.4..2.4 on CSCS (0.145 m); CSCS touches first at |x| = 2.8847085 (side_BC and corner_D, side_DA and
    corner_B), earlier with thicker panels: b 0.02 -> 3.0379, 0.1 -> 2.6432 (zero thickness: pi)."""
    for modes in RIGID:
        scene = thick(modes)
        assert np.min(contact_distance(scene, modes, np.linspace(*scene.path, 96))) >= 0.1  # measured >= 0.1086
    scene = thick()
    assert np.min(contact_distance(scene, "CSCS", np.linspace(-2.4, 2.4, 97))) >= 0.1  # measured 0.1453
    onset = contact_input(scene, "CSCS", 0.5, np.pi)
    assert onset == pytest.approx(2.8847085, abs=1e-6)
    assert contact_input(scene, "CSCS", -0.5, -np.pi) == pytest.approx(-onset, abs=1e-9)
    assert contact_input(thick(b=0.02), "CSCS", 0.5, np.pi) == pytest.approx(3.037870, abs=1e-6)
    assert contact_input(thick(b=0.1), "CSCS", 0.5, np.pi) == pytest.approx(2.643202, abs=1e-6)


@pytest.mark.parametrize(
    ("params", "match"),
    [
        ({"modes": 0.0}, "modes = 0; it must be a whole number from 1 to 6"),
        ({"modes": 2.5}, "modes = 2.5; it must be a whole number"),
        ({"b": 0.0}, "b = 0 m; it must be a number"),
        ({"alpha": np.pi / 2}, "alpha = 90 deg"),
    ],
)
def test_bad_parameters_are_refused(params, match):
    with pytest.raises(ParameterError, match=match):
        scenes.get("thick-square-twist").build(**params)


def test_bad_modes_and_flips_are_refused():
    with pytest.raises(ParameterError, match="modes 'CCCS' put 1 vertices in mode S"):
        ThickSquareTwist(ALPHA, B, "CCCS")
    with pytest.raises(ParameterError, match=r"modes 'CCCC' with layout flips \(1, 1, 1, 1\).*#S = #C"):
        ThickSquareTwist(ALPHA, B, "CCCC")
    with pytest.raises(ParameterError, match=r"flips \(1, 2, 1, 1\)"):
        ThickSquareTwist(ALPHA, B, "CSCS", flips=(1, 2, 1, 1))
