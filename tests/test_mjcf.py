"""MJCF generation (`sim_origami.mjcf`): structure, names, options and keyframes of compiled models."""

import dataclasses
import xml.etree.ElementTree as ET

import mujoco
import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.errors import ParameterError
from sim_origami.mjcf import ModelOptions, closures, mujoco_joints, qpos_order
from sim_origami.presets import ACCURATE, FAST, STIFF, as_preset
from sim_origami.scenes import Tuning
from sim_origami.simulate import scene_xml
from sim_origami.studies import pareto

# Menagerie's top-level order; `visual` appears only in rendered models.
MENAGERIE_ORDER = (
    "compiler", "option", "custom", "visual", "default", "asset", "worldbody",
    "contact", "equality", "actuator", "keyframe",
)
# MJCF numbers are written with 12 significant digits (mjcf._fmt): |rounding| <= 5e-12 for angles
# and positions below 10; measured keyframe qpos error 2e-12 rad, closure-site gap 3e-12 m.
MJCF_DIGITS_ATOL = 1e-11
# Force range of the servo that validation.run_blockage assumes (20 N m at the drive joint).
SERVO_FORCE_LIMIT = 20.0


def thick_miura():
    return scenes.get("miura").build(thickness=0.02)


def compiled(scene, keyframes=None, **options) -> tuple[mujoco.MjModel, str]:
    """Compiled model and its MJCF text."""
    xml = scene_xml(scene, ModelOptions(**options), keyframes)
    return mujoco.MjModel.from_xml_string(xml), xml


def names_of(model: mujoco.MjModel, obj: mujoco.mjtObj, count: int) -> set[str]:
    return {mujoco.mj_id2name(model, obj, i) for i in range(count)}


def all_scenes():
    return [scenes.get(name).build() for name in scenes.names()]


@pytest.mark.parametrize("name", scenes.names())
@pytest.mark.parametrize("preset", [FAST, STIFF, ACCURATE], ids=lambda p: p.name)
@pytest.mark.parametrize("drive", ["equality", "servo"])
@pytest.mark.parametrize("render", [False, True])
def test_generated_xml_compiles(name, preset, drive, render):
    model, _ = compiled(scenes.get(name).build(), preset=preset, drive=drive, render=render)
    assert model.njnt == len(mujoco_joints(scenes.get(name).build().mechanism))


def test_top_level_elements_follow_menagerie_order():
    scene = thick_miura()
    _, xml = compiled(
        scene, {"miura": scene.pose("miura", 0.5)}, drive="servo", contact=True, render=True
    )  # every section present
    tags = [e.tag for e in ET.fromstring(xml) if isinstance(e.tag, str)]
    assert tags == list(MENAGERIE_ORDER)


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_top_level_elements_of_a_plain_model_are_unique_and_ordered(scene):
    _, xml = compiled(scene)
    tags = [e.tag for e in ET.fromstring(xml) if isinstance(e.tag, str)]
    assert tags == [t for t in MENAGERIE_ORDER if t in tags]
    assert "visual" not in tags and "actuator" not in tags and "keyframe" not in tags


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_names_follow_the_scheme(scene):
    model, _ = compiled(scene)
    mech = scene.mechanism
    panels = {b.name for b in mech.bodies if not b.spacer}  # spacers carry a ball's axes, not MuJoCo bodies
    assert names_of(model, mujoco.mjtObj.mjOBJ_BODY, model.nbody) == {"world"} | (panels - {mech.root})
    assert len({b.name for b in mech.bodies}) == len(mech.bodies)  # panels, links or faces, unique
    assert names_of(model, mujoco.mjtObj.mjOBJ_GEOM, model.ngeom) == {f"{p}_solid" for p in panels}
    # hinges by their joint's name, balls by their spherical joint's name
    hinges = {mech.joints[e.joint].name for e in mech.tree if not mech.joints[e.joint].ball}
    balls = {name for name, (_, _, iz) in mech.balls.items() if iz not in mech.cut_joints}
    assert names_of(model, mujoco.mjtObj.mjOBJ_JOINT, model.njnt) == hinges | balls
    closed = {f"close_{c.joint}_{c.k}" for c in closures(mech)}
    couplings = {f"couple_{a}_{b}" for a, b, _ in mech.couplings}
    assert names_of(model, mujoco.mjtObj.mjOBJ_EQUALITY, model.neq) == closed | couplings | {
        f"drive_{scene.drive_joint}"
    }


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_closure_connects_join_parent_and_child_sites_on_the_cut_joint_bodies(scene):
    model, _ = compiled(scene)
    mech = scene.mechanism

    def body_of(panel: str) -> int:
        return 0 if panel == mech.root else model.body(panel).id

    for c in closures(mech):
        eq = model.equality(f"close_{c.joint}_{c.k}")
        assert eq.type == mujoco.mjtEq.mjEQ_CONNECT and model.eq_objtype[eq.id] == mujoco.mjtObj.mjOBJ_SITE
        child, parent = model.site(f"{c.joint}_child_{c.k}"), model.site(f"{c.joint}_parent_{c.k}")
        assert (eq.obj1id, eq.obj2id) == (child.id, parent.id)
        assert (parent.bodyid, child.bodyid) == (body_of(c.parent), body_of(c.child))
        # Body frames are the flat sheet's (or deployed) frame, so sites sit at the anchors as given.
        np.testing.assert_allclose(parent.pos, c.on_parent, atol=MJCF_DIGITS_ATOL, rtol=0)
        np.testing.assert_allclose(child.pos, c.on_child, atol=MJCF_DIGITS_ATOL, rtol=0)
    # a hinge cut closes at each of its anchors, a spherical joint cut at its centre only
    cut = [mech.joints[i] for i in mech.cut_joints]
    assert len(closures(mech)) == sum(len(j.anchors) for j in cut if not j.ball) + sum(1 for j in cut if j.ball)


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_equality_drive_is_a_joint_equality_on_the_drive_joint(scene):
    model, _ = compiled(scene)
    eq = model.equality(f"drive_{scene.drive_joint}")
    assert eq.type == mujoco.mjtEq.mjEQ_JOINT
    assert eq.obj1id == model.joint(scene.drive_joint).id and eq.obj2id == -1
    assert model.nu == 0


@pytest.mark.parametrize(
    "scene", [s for s in all_scenes() if not s.contact_pairs and not s.self_contact], ids=lambda s: s.name
)
def test_zero_thickness_scene_has_contact_disabled_no_pairs_and_no_render_assets(scene):
    assert scene.contact_pairs == ()
    model, xml = compiled(scene, contact=True)  # asking for contact changes nothing without pairs
    assert model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    assert model.npair == 0 and model.nexclude == 0
    assert model.nlight == 0 and model.ntex == 0
    assert "<light" not in xml and "<texture" not in xml and "<contact" not in xml


@pytest.mark.parametrize("scene", [s for s in all_scenes() if s.self_contact], ids=lambda s: s.name)
def test_self_contact_collides_every_panel_pair_that_shares_no_vertex(scene):
    model, _ = compiled(scene, contact=True)
    assert not model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    collision = [g for g in range(model.ngeom) if model.geom(g).name.endswith("_collision")]
    assert len(collision) == len(scene.mechanism.bodies)
    assert all(model.geom_contype[g] == 1 and model.geom_conaffinity[g] == 1 for g in collision)
    assert model.nexclude == len(scene.pattern.touching_faces())
    plain, _ = compiled(scene)
    assert plain.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT and plain.nexclude == 0


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_render_option_adds_light_and_skybox_texture(scene):
    model, _ = compiled(scene, render=True)
    assert model.nlight >= 1 and model.ntex >= 1


@pytest.mark.parametrize("scene", [*all_scenes(), thick_miura()], ids=[*scenes.names(), "thick"])
@pytest.mark.parametrize("preset", [FAST, STIFF, ACCURATE], ids=lambda p: p.name)
def test_gravity_is_disabled(scene, preset):
    model, _ = compiled(scene, preset=preset, contact=True)
    assert model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_GRAVITY


def test_thick_miura_with_contact_has_exactly_the_scene_pairs_and_contact_enabled():
    scene = thick_miura()
    model, _ = compiled(scene, contact=True)
    assert not model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    geom = {i: mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, i) for i in range(model.ngeom)}
    # MuJoCo may store a pair's geoms in either order.
    pairs = {frozenset((geom[g1], geom[g2])) for g1, g2 in zip(model.pair_geom1, model.pair_geom2, strict=True)}
    assert model.npair == len(scene.contact_pairs)
    assert pairs == {frozenset((f"{a}_collision", f"{b}_collision")) for a, b in scene.contact_pairs}
    # Only explicit pairs collide: every geom is out of the contype/conaffinity filter.
    assert not np.any(model.geom_contype) and not np.any(model.geom_conaffinity)


def test_thick_miura_without_contact_has_contact_disabled_and_no_collision_geoms():
    model, _ = compiled(thick_miura(), contact=False)
    assert model.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_CONTACT
    assert model.npair == 0
    assert not any(n.endswith("_collision") for n in names_of(model, mujoco.mjtObj.mjOBJ_GEOM, model.ngeom))


@pytest.mark.parametrize("scene", [*all_scenes(), thick_miura()], ids=[*scenes.names(), "thick"])
def test_servo_drive_is_a_force_limited_position_actuator_on_the_drive_joint(scene):
    model, _ = compiled(scene, drive="servo", contact=True)
    act = model.actuator(f"drive_{scene.drive_joint}")
    assert model.nu == 1
    assert act.trntype == mujoco.mjtTrn.mjTRN_JOINT and act.trnid[0] == model.joint(scene.drive_joint).id
    # Position actuator: force = kp * (ctrl - qpos) - kv * qdot.
    assert act.gaintype == mujoco.mjtGain.mjGAIN_FIXED and act.biastype == mujoco.mjtBias.mjBIAS_AFFINE
    assert act.gainprm[0] > 0 and act.biasprm[1] == -act.gainprm[0] and act.biasprm[2] < 0
    assert act.forcelimited
    np.testing.assert_allclose(act.forcerange, [-SERVO_FORCE_LIMIT, SERVO_FORCE_LIMIT], atol=0, rtol=0)
    with pytest.raises(KeyError):
        model.equality(f"drive_{scene.drive_joint}")


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_keyframes_hold_the_closed_form_pose_of_each_branch(scene):
    branches = [b.name for b in scene.kinematics.branches()]
    poses = {b: scene.pose(b, 0.5 * sum(scene.branch_path(b))) for b in branches}
    model, _ = compiled(scene, poses)
    data = mujoco.MjData(model)
    mech = scene.mechanism
    for branch, pose in poses.items():
        mujoco.mj_resetDataKeyframe(model, data, model.key(f"start_{branch}").id)
        for joint in mujoco_joints(mech):
            adr = model.jnt_qposadr[model.joint(joint.name).id]
            qpos = data.qpos[adr : adr + joint.width]
            np.testing.assert_allclose(qpos, joint.qpos(pose), atol=MJCF_DIGITS_ATOL, rtol=0, err_msg=joint.name)
            # and back: the mechanism angles it stands for (a ball's three from its quaternion)
            np.testing.assert_allclose(joint.angles(qpos[None])[0], pose[list(joint.joints)], atol=1e-12, rtol=0)
        # The joints at the closed form's angles close the loops in MuJoCo too.
        mujoco.mj_kinematics(model, data)
        for c in closures(mech):
            gap = data.site(f"{c.joint}_child_{c.k}").xpos - data.site(f"{c.joint}_parent_{c.k}").xpos
            np.testing.assert_allclose(gap, 0.0, atol=MJCF_DIGITS_ATOL, rtol=0)


@pytest.mark.parametrize("scene", all_scenes(), ids=scenes.names())
def test_qpos_order_matches_the_compiled_hinge_addresses(scene):
    model, _ = compiled(scene)
    order = qpos_order(scene.mechanism)
    widths = [j.width for j in mujoco_joints(scene.mechanism)]  # 1 per hinge, 4 per ball (a quaternion)
    assert [model.jnt_qposadr[model.joint(j).id] for j in order] == list(np.cumsum([0, *widths[:-1]]))
    assert sum(widths) == model.nq


@pytest.mark.parametrize("preset", [FAST, STIFF, ACCURATE], ids=lambda p: p.name)
def test_preset_sweep_duration_is_the_compiled_custom_numeric(preset):
    model, _ = compiled(all_scenes()[0], preset=preset)
    assert model.numeric("sweep_duration").data[0] == preset.sweep_duration > 0


def test_unknown_preset_raises_naming_it_and_the_presets():
    with pytest.raises(ParameterError, match="'turbo'; presets are fast, stiff, accurate, fast-projected"):
        as_preset("turbo")


def test_stiff_preset_is_semi_implicit_euler_with_closures_at_twice_its_step():
    model, _ = compiled(scenes.get("waterbomb-vertex").build(), preset=STIFF)
    assert model.opt.integrator == mujoco.mjtIntegrator.mjINT_EULER and model.opt.timestep == 0.00125
    closures = [i for i in range(model.neq) if model.equality(i).name.startswith(("close_", "couple_"))]
    assert closures and all(model.eq_solref[i, 0] == 2 * model.opt.timestep for i in closures)


def test_a_scenes_fast_step_scale_lengthens_fast_only_and_keeps_tau_over_h():
    """The twist tuned to 1.25x fast's step runs at 10 ms, closures and drive at 25 ms; stiff and other scenes as
    written."""
    scene = dataclasses.replace(scenes.get("waterbomb-twist").build(), tuning=Tuning(fast_step_scale=1.25))
    fast, _ = compiled(scene, preset=FAST)
    stiff, _ = compiled(scene, preset=STIFF)
    plain, _ = compiled(scenes.get("waterbomb-vertex").build(), preset=FAST)
    assert (fast.opt.timestep, stiff.opt.timestep, plain.opt.timestep) == (0.01, 0.00125, 0.008)
    rows = [i for i in range(fast.neq) if fast.equality(i).name.startswith(("close_", "couple_", "drive_"))]
    assert rows and np.allclose(fast.eq_solref[rows, 0], 0.025, rtol=0, atol=1e-15)
    assert pareto.scene_presets(scene)[FAST].h == fast.opt.timestep


def test_a_scenes_fast_timeconst_scale_softens_the_closures_and_drive_not_the_step():
    """A large FOLD pattern's closures and drive run at 1.2x fast's time constant (3 steps, not 2.5), its step 8 ms;
    its regulariser scale reaches model.xml and the pareto study's fast setting."""
    scene = dataclasses.replace(scenes.get("waterbomb-vertex").build(),
                                tuning=Tuning(fast_timeconst_scale=1.2, fast_regularization_scale=0.01))
    fast, _ = compiled(scene, preset=FAST)
    stiff, _ = compiled(scene, preset=STIFF)
    plain, _ = compiled(scenes.get("waterbomb-vertex").build(), preset=STIFF)
    assert fast.opt.timestep == 0.008
    rows = [i for i in range(fast.neq) if fast.equality(i).name.startswith(("close_", "couple_", "drive_"))]
    assert rows and np.allclose(fast.eq_solref[rows, 0], 0.024, rtol=0, atol=1e-15)
    assert np.array_equal(stiff.eq_solref, plain.eq_solref)
    assert pareto.scene_presets(scene)[FAST].tau == pytest.approx(0.024)
    # the pareto study's "fast as the scene runs it" carries the scene's regulariser, as model.xml does
    regularization = float(fast.numeric("regularization_scale").data[0])
    assert regularization == pytest.approx(1e-4) == pareto.scene_presets(scene)[FAST].regularization
