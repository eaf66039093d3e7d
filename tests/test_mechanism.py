"""The mechanism graph (`sim_origami.mechanism`) and the panel solids it carries into MuJoCo."""

import dataclasses

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.errors import ParameterError
from sim_origami.geometry import wrap
from sim_origami.mechanism import Mechanism
from sim_origami.mjcf import ModelOptions, template
from sim_origami.origami import vertex_mechanism
from sim_origami.simulate import compile_model
from sim_origami.tolerances import TOLERANCES

SCENE_BRANCHES = [
    (name, branch.name) for name in scenes.names() for branch in scenes.get(name).build().kinematics.branches()
]
# A general (neither flat-foldable nor collinear) developable vertex, radians.
ALPHA = np.deg2rad([60.0, 100.0, 90.0, 110.0])
# MuJoCo stores mesh vertices in float32 and integrates mass properties from them: measured mass and
# principal-moment differences against trimesh (float64) up to 1e-8 for ~1 kg panels of ~1 m.
FLOAT32_MESH_ATOL = 1e-6


def closed_form_mechanism_angles(name: str, branch: str, samples: int = 41):
    """A default scene and mechanism angles (samples, n_joints) of its closed form along the branch's path."""
    scene = scenes.get(name).build()
    x = np.linspace(*scene.branch_path(branch), samples)
    values = scene.kinematics.joint_angles(branch, x)
    return scene, scene.loop_to_mechanism(scene.kinematics.loop_angles(values))


def panel_density() -> float:
    """Density (kg/m^3) of the `panel` default class, the one that carries the mass."""
    for default in template("defaults.xml").iter("default"):
        if default.get("class") == "panel":
            return float(default.find("geom").get("density"))
    raise AssertionError("defaults.xml has no panel class")


@pytest.mark.slow
@pytest.mark.parametrize(("name", "branch"), SCENE_BRANCHES)
def test_mechanism_loop_system_closes_on_closed_form_angles(name, branch):
    scene, q = closed_form_mechanism_angles(name, branch)
    residual = scene.mechanism.loop_system().residual_norm(q)
    assert np.max(residual) <= TOLERANCES.closed_form_residual


@pytest.mark.slow
@pytest.mark.parametrize("name", scenes.names())
def test_mechanism_loop_system_is_open_when_one_angle_is_off(name):
    scene = scenes.get(name).build()
    branch = scene.kinematics.branches()[0].name
    _, q = closed_form_mechanism_angles(name, branch)
    for joint in range(len(scene.mechanism.joints)):
        bent = q.copy()
        bent[:, joint] += 0.1
        # 0.1 rad off one crease of a 1 m vertex: measured residual >= 0.067 on every sample.
        assert np.min(scene.mechanism.loop_system().residual_norm(bent)) > 0.01


@pytest.mark.parametrize(("name", "branch"), SCENE_BRANCHES)
def test_complete_recovers_cut_joint_angles_from_tree_angles(name, branch):
    scene, q = closed_form_mechanism_angles(name, branch)
    cut = list(scene.mechanism.cut_joints)
    assert cut, "a single-vertex mechanism has one loop, so one cut joint"
    tree_only = q.copy()
    tree_only[:, cut] = 0.0
    # modulo 2 pi: a crease folded flat onto itself (the twisting tube's middle row) is pi and -pi at once
    difference = wrap(scene.mechanism.complete(tree_only) - q)
    np.testing.assert_allclose(difference, 0.0, atol=TOLERANCES.closed_form_rad, rtol=0)


@pytest.mark.parametrize(("name", "branch"), SCENE_BRANCHES)
def test_cut_joint_anchors_coincide_on_a_closed_pose(name, branch):
    scene, q = closed_form_mechanism_angles(name, branch, samples=5)
    mech = scene.mechanism
    poses = mech.body_poses(q)
    for i in mech.cut_joints:
        joint = mech.joints[i]
        on_parent, on_child = mech.anchor_points(i)
        for p, c in zip(on_parent, on_child, strict=True):
            world_p = poses[joint.parent][:, :3, :3] @ p + poses[joint.parent][:, :3, 3]
            world_c = poses[joint.child][:, :3, :3] @ c + poses[joint.child][:, :3, 3]
            np.testing.assert_allclose(world_c, world_p, atol=TOLERANCES.closed_form_residual, rtol=0)


@pytest.mark.parametrize(
    ("root", "keep"),
    [(r, k) for r in range(1, 5) for k in range(1, 5)],
    ids=[f"root{r}-keep{k}" for r in range(1, 5) for k in range(1, 5)],
)
def test_spanning_tree_keeps_the_kept_joint(root, keep):
    mech = vertex_mechanism(ALPHA, root=root, keep=(keep,))
    kept = mech.joint_index(f"crease_{keep}")
    assert kept in {e.joint for e in mech.tree}
    assert kept not in mech.cut_joints


@pytest.mark.parametrize("root", [1, 2, 3, 4])
def test_spanning_tree_reaches_every_body_once_and_cuts_one_joint_per_loop(root):
    mech = vertex_mechanism(ALPHA, root=root)
    children = [e.child for e in mech.tree]
    assert sorted([*children, mech.root]) == sorted(b.name for b in mech.bodies)
    assert len(mech.cut_joints) == len(mech.joints) - len(mech.tree) == 1


def test_tree_with_a_disconnected_body_raises_parameter_error():
    full = vertex_mechanism(ALPHA)
    # Only crease_2 (panel_1 - panel_2) and crease_3 (panel_2 - panel_3): panel_4 hangs free.
    mech = Mechanism(full.bodies, full.joints[1:3], root="panel_1")
    with pytest.raises(ParameterError, match="panel_4"):
        _ = mech.tree


def test_unknown_root_raises_parameter_error():
    full = vertex_mechanism(ALPHA)
    with pytest.raises(ParameterError, match="panel_9"):
        Mechanism(full.bodies, full.joints, root="panel_9")


def test_joint_naming_an_unknown_body_raises_parameter_error():
    full = vertex_mechanism(ALPHA)
    stray = dataclasses.replace(full.joints[0], parent="panel_7")
    with pytest.raises(ParameterError, match="panel_7"):
        Mechanism(full.bodies, (stray, *full.joints[1:]), root="panel_1")


def test_unknown_joint_name_raises_parameter_error():
    with pytest.raises(ParameterError, match="crease_9"):
        vertex_mechanism(ALPHA).joint_index("crease_9")


@pytest.mark.parametrize(
    ("name", "values"),
    [("vertex4", {}), ("miura", {}), ("miura", {"thickness": 0.02})],
    ids=["vertex4", "miura", "thick"],
)
def test_panel_solids_and_collision_solids_are_watertight_volumes(name, values):
    scene = scenes.get(name).build(**values)
    for body in scene.mechanism.bodies:
        for mesh in (body.solid, body.collision):
            if mesh is not None:
                assert mesh.is_watertight and mesh.is_winding_consistent
                assert mesh.volume > 0.0  # outward-facing triangles


@pytest.mark.parametrize(
    ("name", "values"), [("vertex4", {}), ("miura", {"thickness": 0.02})], ids=["vertex4", "thick"]
)
def test_mujoco_body_mass_and_inertia_equal_trimesh_at_panel_density(name, values):
    scene = scenes.get(name).build(**values)
    model = compile_model(scene, ModelOptions(contact=True)).model  # collision solids compiled too: massless
    density = panel_density()
    checked = 0
    for body in scene.mechanism.bodies:
        if body.name == scene.mechanism.root:
            continue  # the root's geoms belong to the world body
        solid = body.solid.copy()
        solid.density = density
        b = model.body(body.name).id
        np.testing.assert_allclose(model.body_mass[b], solid.volume * density, atol=FLOAT32_MESH_ATOL, rtol=0)
        # MuJoCo: about the centre of mass, in principal axes; trimesh: about the centre of mass, body axes.
        principal = np.linalg.eigvalsh(solid.moment_inertia)
        np.testing.assert_allclose(np.sort(model.body_inertia[b]), principal, atol=FLOAT32_MESH_ATOL, rtol=0)
        np.testing.assert_allclose(model.body_ipos[b], solid.center_mass, atol=FLOAT32_MESH_ATOL, rtol=0)
        checked += 1
    assert checked == len(scene.mechanism.bodies) - 1


def test_hinge_mismatch_is_zero_on_a_closed_pose_and_sees_a_wrong_cut_angle():
    scene = scenes.get("vertex4").build()
    q = scene.pose("odd2", 0.8)
    cut = [scene.mechanism.joints[i].name for i in scene.mechanism.cut_joints]
    assert scene.mechanism.hinge_mismatch(q, cut) <= 1e-14  # measured ~1e-16: the loop closes
    q[scene.mechanism.cut_joints[0]] += 1e-3
    # an angle off by d moves Rz's entries by d max(|sin q|, |cos q|): between d / sqrt 2 and d (measured 9.9e-4)
    assert 0.7e-3 < scene.mechanism.hinge_mismatch(q, cut) <= 1.0001e-3
