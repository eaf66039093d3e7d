"""Mechanism + templates -> MJCF. The one place where MJCF names are made.

Names: bodies as in the mechanism (`panel_<i>`, `link_<i>` or a crease pattern's faces; the root's
geoms sit on the world body), hinges as the mechanism's joints, meshes `<body>_solid` /
`<body>_collision`, closure sites `<joint>_parent_<k>` / `<joint>_child_<k>`, connects
`close_<joint>_<k>`, joint couplings `couple_<joint>_<other>`, the drive `drive_<joint>`, keyframes
`start_<branch>`; model.xml adds a position servo `drive_<joint>` per driven joint and materials named by colour.

A hinge's qpos equals the mechanism's joint angle: a joint traversed from its child to its parent
in the spanning tree gets the reversed axis. Each cut joint is closed by one site-based `connect`
per anchor on its axis (sites need not coincide at qpos0: MuJoCo documentation, equality/connect), unless the
mechanism marks it implied (closed by its couplings and the other loops): then only its sites are written.
Contact, gravity and render assets enter only the models that use them.

`build_model` compiles the text once into a `CompiledModel`: the text, MuJoCo's model and the ids this builder's
names resolve to, by role; code outside this module reaches MuJoCo's elements through those ids, not by name.
"""

import colorsys
import copy
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from importlib import resources

import mujoco
import numpy as np
from numpy.typing import NDArray

from . import __version__
from .geometry import invert, quaternion, quaternion_matrix, xyz_angles, xyz_rotation
from .mechanism import Body, Mechanism
from .mjcf_tidy import attach_comments, box_of, short, tidy
from .presets import FAST, Preset

ORDER = (
    "compiler", "option", "size", "custom", "visual", "default", "asset", "worldbody",
    "contact", "equality", "actuator", "sensor", "keyframe",
)
# The templates' one-line comments name this package's code or notes; model.xml is read by people without them, so
# those words are replaced as the comments enter a model (better reworded in mjcf_templates/ itself).
OUTSIDER_WORDS = {
    "the biggest accuracy lever (section 4.1)": "the biggest accuracy lever measured",
    "times 0.01 (simulate.compile_model)": "times 0.01 (regularization_scale below)",
    "(sim_origami.stabilize)": "after each step (the validation run's projection onto the closures, not MuJoCo's)",
}
# model.xml: colour names of its materials, by hue (degrees: the upper end of each name's range), for colours with
# some saturation; the others are white, grey or black by lightness.
HUES = ((15, "red"), (45, "orange"), (70, "yellow"), (165, "green"), (200, "cyan"), (255, "blue"), (290, "violet"),
        (335, "magenta"), (360, "red"))


@dataclass(frozen=True)
class ModelOptions:
    """What one compiled model needs: preset, drive kind, contact, render assets, keyframes."""

    preset: Preset = FAST
    drive: str = "equality"  # "equality": kinematic tracking; "servo": force-limited actuator; "none"
    contact: bool = False
    render: bool = False
    gravity: bool = False  # the setup's gravity (m/s^2, its root frame) and the energy flag


@dataclass(frozen=True)
class ModelSetup:
    """
    What a model holds beyond its mechanism, whatever the run: its name and note, the driven joints, which collision
    solids may touch, gravity, which hinges are creases of paper (drawn as paper and crease lines) and the fast
    preset's step and regulariser scales. `scenes.base.Scene.model_setup` fills it from a scene.

    Contact: `contact_pairs` (body, body) may touch; with `self_contact_exclude` not None, every collision solid
    may touch every other except those pairs (bodies that touch in every pose, e.g. faces sharing a vertex).
    """

    name: str
    drives: tuple[str, ...]
    notes: str = ""
    contact_pairs: tuple[tuple[str, str], ...] = ()
    self_contact_exclude: tuple[tuple[str, str], ...] | None = None
    gravity: tuple[float, float, float] | None = None
    creases: frozenset[str] = frozenset()
    fast_step_scale: float = 1.0
    fast_timeconst_scale: float = 1.0
    fast_regularization_scale: float = 1.0

    @property
    def has_contact(self) -> bool:
        """Whether any collision solids may touch."""
        return bool(self.contact_pairs) or self.self_contact_exclude is not None



def drive_name(joint: str) -> str:
    """The MJCF name of the drive (equality or actuator) of mechanism joint `joint`."""
    return f"drive_{joint}"


def site_name(joint: str, side: str, k: int) -> str:
    """The MJCF name of closure site k of cut joint `joint` on its "parent" or "child" side."""
    return f"{joint}_{side}_{k}"


def collision_name(body: str) -> str:
    """The MJCF name of body `body`'s collision solid (geom and mesh)."""
    return f"{body}_collision"


def keyframe_name(branch: str) -> str:
    """The MJCF name of the keyframe at branch `branch`'s start pose."""
    return f"start_{branch}"


def template(name: str) -> ET.Element:
    """A fragment of `mjcf_templates/`, parsed with its comments."""
    text = resources.files("sim_origami.mjcf_templates").joinpath(name).read_text()
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    return ET.fromstring(text, parser=parser)


def _fmt(values) -> str:
    return " ".join(repr(float(v)) for v in np.ravel(values))  # shortest exact round-trip


def _section(root: ET.Element, tag: str) -> ET.Element:
    found = root.find(tag)
    return found if found is not None else ET.SubElement(root, tag)


def _merge(root: ET.Element, fragment: ET.Element) -> None:
    """
    Append the children of each top-level section of `fragment` into `root`. Comments of one line come along;
    longer ones (the templates' measurement notes) stay in the template files.
    """
    for child in [c for c in fragment.iter() if c.tag is ET.Comment and "\n" in (c.text or "")]:
        _drop(fragment, child)
    for child in [c for c in fragment.iter() if c.tag is ET.Comment]:
        for code, words in OUTSIDER_WORDS.items():
            child.text = (child.text or "").replace(code, words)
    for child in fragment:
        if child.tag is ET.Comment:
            root.append(child)
            continue
        if child.tag in ("compiler", "option", "size"):
            root.append(child)
            continue
        _section(root, child.tag).extend(list(child))


def _drop(tree: ET.Element, comment: ET.Element) -> None:
    """Remove `comment` from wherever it sits in `tree`."""
    for parent in tree.iter():
        if comment in list(parent):
            parent.remove(comment)
            return


def _scale_step(root: ET.Element, step: float, timeconst: float) -> None:
    """The merged preset's timestep times `step`, its closure and drive solref time constants times `step` and
    `timeconst`."""
    option = root.find("option")
    option.set("timestep", _fmt(float(option.get("timestep")) * step))
    for cls in ("closure", "drive"):
        equality = root.find(f".//default[@class='{cls}']/equality")
        tau, *rest = (float(v) for v in equality.get("solref").split())
        equality.set("solref", _fmt([tau * step * timeconst, *rest]))


def _add_meshes(asset: ET.Element, mechanism: Mechanism) -> None:
    for body in mechanism.bodies:
        for suffix, mesh in (("solid", body.solid), ("collision", body.collision)):
            if mesh is None or body.spacer or (suffix == "solid" and box_of(mesh) is not None):
                continue
            ET.SubElement(
                asset, "mesh", name=f"{body.name}_{suffix}",
                vertex=_fmt(mesh.vertices), face=" ".join(str(int(i)) for i in np.ravel(mesh.faces)),
            )


def _solid_geom(parent: ET.Element, body: Body) -> None:
    """The body's visual solid (it carries the mass): a box primitive when it is a box, else its mesh."""
    box = box_of(body.solid)
    if box is None:
        ET.SubElement(parent, "geom", name=f"{body.name}_solid", mesh=f"{body.name}_solid", rgba=_fmt(body.rgba))
    else:
        centre, quat, half = box
        ET.SubElement(parent, "geom", name=f"{body.name}_solid", type="box", pos=_fmt(centre), quat=_fmt(quat),
                      size=_fmt(half), rgba=_fmt(body.rgba))
    parent[-1].set("class", "panel")


def _add_bodies(
    world: ET.Element, mechanism: Mechanism, contact: bool, creases: frozenset[str] = frozenset()
) -> dict[str, ET.Element]:
    """
    Nested bodies along the spanning tree; a spherical joint's spacers are skipped (its hinges become one ball).
    Hinges named in `creases` are in class `crease` (origami), the others in class `revolute` (linkages).
    """
    ref = mechanism.reference_poses()
    elements = {mechanism.root: world}
    by_name = {b.name: b for b in mechanism.bodies}

    def add_geoms(parent: ET.Element, name: str) -> None:
        body = by_name[name]
        _solid_geom(parent, body)
        if contact and body.collision is not None:
            ET.SubElement(parent, "geom", name=collision_name(name), mesh=collision_name(name))
            parent[-1].set("class", "collision")

    world.append(ET.Comment(f" {mechanism.root}: fixed to the world "))
    add_geoms(world, mechanism.root)
    real = {mechanism.root: mechanism.root}  # the MuJoCo body each mechanism body hangs from
    for edge in mechanism.tree:
        joint = mechanism.joints[edge.joint]
        parent = real[edge.parent]
        if by_name[edge.child].spacer:
            real[edge.child] = parent
            continue
        real[edge.child] = edge.child
        rel = invert(ref[parent]) @ ref[edge.child]
        attrs = {"name": edge.child}
        if not np.allclose(rel, np.eye(4), atol=1e-14):
            attrs |= {"pos": _fmt(rel[:3, 3]), "quat": _fmt(quaternion(rel[:3, :3]))}
        body = ET.SubElement(elements[parent], "body", attrs)
        if joint.ball:
            frames = mechanism.ball_frames(joint.ball)
            centre = frames[1 if edge.sign > 0 else 0][:3, 3]
            ET.SubElement(body, "joint", name=joint.ball, pos=_fmt(centre)).set("class", "ball")
        else:
            frame = joint.frame_child if edge.sign > 0 else joint.frame_parent
            axis = frame[:3, 2] * edge.sign
            hinge = ET.SubElement(body, "joint", name=joint.name, pos=_fmt(frame[:3, 3]), axis=_fmt(axis))
            hinge.set("class", "crease" if joint.name in creases else "revolute")
        add_geoms(body, edge.child)
        elements[edge.child] = body
    return elements


def _add_paper(root: ET.Element, mechanism: Mechanism, elements: dict[str, ET.Element], creases: frozenset[str]):
    """
    Render models: each panel joined by a crease shows a front (+z of the flat sheet, every panel's frame) and a
    back colour: its solid split by face normal into `<body>_front` (top and sides) / `<body>_back` (bottom)
    surfaces (massless, shell inertia), the solid itself moved to hidden group 3.
    """
    panels = {name for j in mechanism.joints if j.name in creases for name in (j.parent, j.child)}
    asset = _section(root, "asset")
    for body in mechanism.bodies:
        if body.name not in panels or body.spacer:
            continue
        nz = np.asarray(body.solid.face_normals)[:, 2]
        elements[body.name].find(f"geom[@name='{body.name}_solid']").set("group", "3")
        # faces that look up or sideways (the paper's edge) are the front, faces that look down the back
        for side, faces in (("front", body.solid.faces[nz >= -1e-9]), ("back", body.solid.faces[nz < -1e-9])):
            used, index = np.unique(faces, return_inverse=True)
            vertices = body.solid.vertices[used]
            if len(vertices) < 4:  # MuJoCo needs 4 vertices a mesh: add the centre of a lone triangle, unused
                vertices = np.vstack([vertices, vertices.mean(axis=0)])
            ET.SubElement(asset, "mesh", name=f"{body.name}_{side}", inertia="shell", vertex=_fmt(vertices),
                          face=" ".join(str(int(i)) for i in index.ravel()))
            ET.SubElement(elements[body.name], "geom", name=f"{body.name}_{side}", mesh=f"{body.name}_{side}").set(
                "class", f"paper_{side}"
            )


def _add_self_contact(root: ET.Element, mechanism: Mechanism, exclude: tuple[tuple[str, str], ...]) -> None:
    """Collision solids collide by contype/conaffinity; the `exclude` pairs of bodies (sharing a vertex) do not."""
    for geom in root.iter("geom"):
        if geom.get("class") == "collision":
            geom.set("contype", "1")
            geom.set("conaffinity", "1")
    section = _section(root, "contact")
    section.append(ET.Comment(" panels that share a vertex touch in every pose: excluded "))
    for a, b in exclude:
        ET.SubElement(section, "exclude", body1="world" if a == mechanism.root else a,
                      body2="world" if b == mechanism.root else b)


@dataclass(frozen=True)
class MjJoint:
    """
    One joint of the compiled model and the mechanism joints it stands for.

    A hinge stands for one mechanism joint (qpos = its angle). A ball stands for the three hinges of a
    spherical joint in the spanning tree (`mechanism.ball_joint`): qpos is the quaternion Q of the MuJoCo child
    relative to its reference, in its body frame. With R the triad's rotation in that body's frame and
    E = xyz_rotation(angles): Q = R E R^T, or R E^T R^T when the MuJoCo child is the mechanism's parent.
    """

    name: str
    joints: tuple[int, ...]
    triad: NDArray[np.float64] | None = None
    reverse: bool = False

    @property
    def width(self) -> int:
        """Entries in qpos."""
        return 1 if self.triad is None else 4

    def qpos(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """qpos entries (width,) from mechanism angles (n_joints,)."""
        if self.triad is None:
            return q[list(self.joints)]
        E = xyz_rotation(*q[list(self.joints)])
        return quaternion(self.triad @ (E.T if self.reverse else E) @ self.triad.T)

    def angles(self, qpos: NDArray[np.float64]) -> NDArray[np.float64]:
        """Mechanism angles (n, len(joints)) from this joint's qpos entries (n, width)."""
        if self.triad is None:
            return qpos
        E = self.triad.T @ quaternion_matrix(qpos) @ self.triad
        return xyz_angles(np.swapaxes(E, -1, -2) if self.reverse else E)


def mujoco_joints(mechanism: Mechanism) -> list[MjJoint]:
    """The model's joints in MuJoCo's qpos order: depth-first over the nested bodies, spacers collapsed."""
    children: dict[str, list] = {}
    for edge in mechanism.tree:
        children.setdefault(edge.parent, []).append(edge)
    spacer = {b.name for b in mechanism.bodies if b.spacer}
    order: list[MjJoint] = []

    def visit(body: str) -> None:
        for edge in children.get(body, []):
            joint = mechanism.joints[edge.joint]
            if not joint.ball:
                order.append(MjJoint(joint.name, (edge.joint,)))
            elif edge.child not in spacer:
                reverse = edge.sign < 0
                triad = mechanism.ball_frames(joint.ball)[0 if reverse else 1][:3, :3]
                order.append(MjJoint(joint.ball, mechanism.balls[joint.ball], triad, reverse))
            visit(edge.child)

    visit(mechanism.root)
    return order


@dataclass(frozen=True)
class Closure:
    """
    One connect `close_<joint>_<k>` between sites `<joint>_parent_<k>` and `<joint>_child_<k>`, at `on_parent`
    and `on_child` (m) in the frames of the bodies `parent` and `child`.
    """

    joint: str
    k: int
    parent: str
    child: str
    on_parent: NDArray[np.float64]
    on_child: NDArray[np.float64]


def closures(mechanism: Mechanism) -> list[Closure]:
    """
    The connects that close the loops: one per anchor of each cut hinge (points on its axis), one at the centre
    of each spherical joint whose last hinge is cut (between its two end bodies).
    """
    out = []
    for i in mechanism.cut_joints:
        joint = mechanism.joints[i]
        if joint.ball:
            ix, _, iz = mechanism.balls[joint.ball]
            Fp, Fc = mechanism.ball_frames(joint.ball)
            ends = mechanism.joints[ix].parent, mechanism.joints[iz].child
            out.append(Closure(joint.ball, 0, *ends, Fp[:3, 3], Fc[:3, 3]))
        else:
            for k, (p, c) in enumerate(zip(*mechanism.anchor_points(i), strict=True)):
                out.append(Closure(joint.name, k, joint.parent, joint.child, p, c))
    return out


def qpos_order(mechanism: Mechanism) -> list[str]:
    """MuJoCo joint names in qpos order (hinges as the mechanism's joints, balls as spherical joints)."""
    return [j.name for j in mujoco_joints(mechanism)]


def keyframe_qpos(mechanism: Mechanism, q: NDArray[np.float64]) -> NDArray[np.float64]:
    """The model's qpos (nq,) for mechanism angles q (n_joints,)."""
    return np.concatenate([j.qpos(np.asarray(q, dtype=float)) for j in mujoco_joints(mechanism)])


def model_size(mechanism: Mechanism) -> float:
    """Largest coordinate (m) of any body's solid or joint frame, in its own body frame: the scale of float noise."""
    extents = [np.max(np.abs(b.solid.vertices)) for b in mechanism.bodies if len(b.solid.vertices)]
    extents += [np.max(np.abs(j.frame_parent[:3, 3])) for j in mechanism.joints]
    return float(max(extents, default=1.0))


def _note_preset(root: ET.Element, preset: Preset) -> None:
    """One-line comments on the preset's option and the regulariser scale a plain MuJoCo load must apply."""
    option = root.find("option")
    root.insert(list(root).index(option), ET.Comment(
        f" preset {preset.name}: constraints at MuJoCo's largest impedance (solimp 0.9999); measured in "
        "docs/performance.md "))
    custom = root.find("custom")
    scale = next(i for i, e in enumerate(custom) if e.get("name") == "regularization_scale")
    custom.insert(scale, ET.Comment(
        " regularization_scale: the validation run multiplied the compiled model's body_invweight0 and dof_invweight0 "
        "by it (as impedance 0.999999: MuJoCo caps solimp at 0.9999, so no attribute states it); do the same to repeat "
        "its numbers, holding and folding do not need it "
    ))


def _keyframes(mechanism: Mechanism, keyframes: dict[str, np.ndarray], drives: tuple[str, ...] = ()) -> ET.Element:
    """Keys `start_<name>` at mechanism angles, exact (state, not geometry); with `drives`, ctrl at their angles."""
    frames = ET.Element("keyframe")
    for name, q in keyframes.items():
        key = ET.SubElement(frames, "key", name=keyframe_name(name), qpos=_fmt(keyframe_qpos(mechanism, q)))
        if drives:
            key.set("ctrl", _fmt([q[mechanism.joint_index(j)] for j in drives]))
    return frames


def with_keyframes(xml: str, mechanism: Mechanism, keyframes: dict[str, np.ndarray]) -> str:
    """`build_xml`'s text without keyframes, with them added: the same text as building with them (the keyframe
    section comes last and is not tidied), without building the model again."""
    frames = _keyframes(mechanism, keyframes)
    ET.indent(frames, space="  ", level=1)
    head, tail = xml.rsplit("</mujoco>", 1)
    return f"{head}  {ET.tostring(frames, encoding='unicode')}\n</mujoco>{tail}"


@dataclass(frozen=True)
class Replay:
    """
    What model.xml adds to the MJCF a run stepped so that plain MuJoCo plays it alone: keyframes `start_<branch>` at
    mechanism angles `poses` with ctrl at each driven joint's angle there, and per driven joint a position servo
    (`kp` N m/rad, `kv` N m s/rad, `ctrlrange` rad: the viewer's slider) critically damped with time constant
    `timeconst` (s).
    """

    poses: dict[str, NDArray[np.float64]]
    kp: tuple[float, ...]
    kv: tuple[float, ...]
    ctrlrange: tuple[tuple[float, float], ...]
    timeconst: float


def replay_xml(xml: str, mechanism: Mechanism, drives: tuple[str, ...], replay: Replay) -> str:
    """
    model.xml: `xml`, the text of a run's model (joint-equality drive, no keyframes), with what plain MuJoCo needs
    to play it alone, each addition under a comment starting 'replay': a header, named materials for the colours,
    the drive equalities off and a position servo per driven joint instead, keyframes with ctrl. The run's text is
    otherwise kept as it is: options, masses, constraints and qpos0 (where MuJoCo reads the regulariser's weights).
    """
    root = ET.fromstring(xml, parser=ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))
    root.insert(1, ET.Comment(
        " replay: the model the validation run stepped (its options, masses and constraints), with what plain MuJoCo "
        "needs to play it alone under comments starting 'replay'; reset to a keyframe and step: the start pose holds; "
        "move ctrl to fold "))
    _name_materials(root)
    _add_servos(root, drives, replay)
    root.append(ET.Comment(
        " replay: the validation runs' start poses (closures closed), ctrl holding the input; the default pose qpos0 "
        "stays the run's reference, where MuJoCo reads the regulariser's weights "))
    root.append(_keyframes(mechanism, replay.poses, drives))
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode")


def colour_name(rgba: str) -> str:
    """A colour's name (model.xml's materials): white, grey or black when nearly unsaturated, else its hue's."""
    r, g, b = (float(v) for v in rgba.split()[:3])
    hue, light, _ = colorsys.rgb_to_hls(r, g, b)
    if max(r, g, b) - min(r, g, b) < 0.1:
        return "white" if light > 0.85 else "black" if light < 0.15 else "grey"
    return next(name for top, name in HUES if hue * 360 < top)


def _name_materials(root: ET.Element) -> None:
    """Each body colour (a geom's rgba) as a named material in the asset section, the geoms using it by name."""
    geoms = [g for g in root.find("worldbody").iter("geom") if g.get("rgba")]
    names: dict[str, str] = {}
    uses: dict[str, int] = {}
    for rgba in dict.fromkeys(g.get("rgba") for g in geoms):
        name = colour_name(rgba)
        uses[name] = uses.get(name, 0) + 1
        names[rgba] = name if uses[name] == 1 else f"{name}_{uses[name]}"  # two blues: blue, blue_2
    asset = root.find("asset")
    if asset is None:
        asset = ET.Element("asset")
        root.insert(list(root).index(root.find("worldbody")), asset)
    materials = [ET.Element("material", name=name, rgba=rgba) for rgba, name in names.items()]
    asset[:0] = [ET.Comment(" replay: the bodies' colours, named (drawing only) "), *materials]
    for geom in geoms:
        items = list(geom.items())
        geom.attrib.clear()
        for attr, value in items:  # in place of rgba, keeping the attributes' order
            geom.set(*(("material", names[value]) if attr == "rgba" else (attr, value)))


def _add_servos(root: ET.Element, drives: tuple[str, ...], replay: Replay) -> None:
    """The drive equalities off (active false) and, after the equality section, a position servo per driven joint."""
    equality = root.find("equality")
    held = [e for e in equality.iter("joint") if e.get("name") in {drive_name(j) for j in drives}]
    for element in held:
        element.set("active", "false")
    equality.insert(list(equality).index(held[-1]) + 1, ET.Comment(
        " replay: the input's equality is off here (active false): the position servo below drives it "))
    actuator = ET.Element("actuator")
    actuator.append(ET.Comment(
        f" replay: ctrl = the driven joint's angle (rad); critically damped with time constant {replay.timeconst:g} s "
        "on the mechanism's inertia at that joint in its lightest start pose "))
    for joint, kp, kv, (lo, hi) in zip(drives, replay.kp, replay.kv, replay.ctrlrange, strict=True):
        ET.SubElement(actuator, "position", name=drive_name(joint), joint=joint, kp=f"{kp:.4g}", kv=f"{kv:.4g}",
                      ctrlrange=f"{short(lo, 0.0)} {short(hi, 0.0)}")
    root.insert(list(root).index(equality) + 1, actuator)


def build_xml(
    mechanism: Mechanism, setup: ModelSetup, options: ModelOptions, keyframes: dict[str, np.ndarray] | None = None
) -> str:
    """
    MJCF text of a mechanism.

    Parameters
    ----------
    mechanism : Mechanism
    setup : ModelSetup
      Name, drives, contact, gravity and crease hinges (`Scene.model_setup` for a scene).
    options : ModelOptions
    keyframes : {name: (n_joints,) float}, optional
      Mechanism joint angles stored as keyframes `start_<name>`.
    """
    contact = options.contact and setup.has_contact
    root = ET.Element("mujoco", model=setup.name)
    root.append(ET.Comment(f" sim_origami {__version__}, {setup.name}; {setup.notes} "))
    fragments = ["base.xml", options.preset.template, "defaults.xml"]
    if options.render:
        fragments += ["visual.xml", "render_scene.xml"]
    for name in fragments:
        _merge(root, template(name))
    if options.preset == FAST and (setup.fast_step_scale, setup.fast_timeconst_scale) != (1.0, 1.0):
        _scale_step(root, setup.fast_step_scale, setup.fast_timeconst_scale)
    if options.preset == FAST and setup.fast_regularization_scale != 1.0:
        numeric = root.find("custom/numeric[@name='regularization_scale']")
        numeric.set("data", _fmt(float(numeric.get("data")) * setup.fast_regularization_scale))
    if contact:
        root.find("option/flag").set("contact", "enable")
    if options.gravity:
        # free motion under gravity (e.g. the IFToMM A04 benchmark): energy reported, not dissipated
        root.find("option").set("gravity", _fmt(setup.gravity))
        root.find("option/flag").set("gravity", "enable")
        root.find("option/flag").set("energy", "enable")
    _note_preset(root, options.preset)
    _add_meshes(_section(root, "asset"), mechanism)
    elements = _add_bodies(_section(root, "worldbody"), mechanism, contact, setup.creases)
    if options.render:
        _add_paper(root, mechanism, elements, setup.creases)

    equality = _section(root, "equality")
    if mechanism.cut_joints:
        equality.append(ET.Comment(" loops cut at hinges (anchors on the axis, away from shared vertices) or at "
                                   "spherical joints (one connect at the centre) "))
    if mechanism.implied:
        equality.append(ET.Comment(f" {len(mechanism.implied)} cut hinges closed by the couplings and the other "
                                   "loops: their sites are measured, not connected "))
    for c in closures(mechanism):
        for side, body, pos in (("parent", c.parent, c.on_parent), ("child", c.child, c.on_child)):
            ET.SubElement(elements[body], "site", name=site_name(c.joint, side, c.k), pos=_fmt(pos)).set(
                "class", "closure_site"
            )
        if c.joint in mechanism.implied:
            continue
        ET.SubElement(
            equality, "connect", name=f"close_{c.joint}_{c.k}", site1=site_name(c.joint, "child", c.k),
            site2=site_name(c.joint, "parent", c.k),
        ).set("class", "closure")

    if mechanism.couplings:
        equality.append(ET.Comment(" couplings q1 = c q2: symmetry the model assumes, or periodic copies of creases "))
    for joint, other, scale in mechanism.couplings:
        if joint == other:  # a lock q = scale q, i.e. q = 0 (a crease kept flat)
            ET.SubElement(equality, "joint", name=f"lock_{joint}", joint1=joint, polycoef="0 0 0 0 0").set(
                "class", "closure"
            )
            continue
        ET.SubElement(
            equality, "joint", name=f"couple_{joint}_{other}", joint1=joint, joint2=other,
            polycoef=_fmt([0.0, scale, 0.0, 0.0, 0.0]),
        ).set("class", "closure")

    if options.drive == "equality":
        equality.append(ET.Comment(" input: a joint equality whose target angle (eq_data[0]) the validation run "
                                   "rewrote every step "))
        for joint in setup.drives:
            ET.SubElement(equality, "joint", name=drive_name(joint), joint1=joint, polycoef="0 0 0 0 0").set(
                "class", "drive"
            )
    elif options.drive == "servo":
        actuator = _section(root, "actuator")
        actuator.append(ET.Comment(" input: force-limited servo, so that contact can stop the motion "))
        for joint in setup.drives:
            ET.SubElement(actuator, "position", name=drive_name(joint), joint=joint).set("class", "servo")

    if contact and setup.self_contact_exclude is not None:
        _add_self_contact(root, mechanism, setup.self_contact_exclude)
    if contact and setup.contact_pairs:
        pairs = _section(root, "contact")
        pairs.append(ET.Comment(" only panels that fold onto each other may touch; all others share a vertex "))
        for a, b in setup.contact_pairs:
            ET.SubElement(pairs, "pair", geom1=collision_name(a), geom2=collision_name(b)).set("class", "contact")

    if keyframes:
        root.append(_keyframes(mechanism, keyframes))

    groups = sorted(attach_comments(root), key=lambda g: ORDER.index(g[-1].tag) if g[-1].tag in ORDER else -1)
    root[:] = [e for g in groups for e in g]
    tidy(root, model_size(mechanism))
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode")


def scale_regularization(model: mujoco.MjModel, scale: float) -> None:
    """
    Multiply every constraint row's regulariser R = (1 - d) / d x diagApprox by `scale`, through the inverse
    weights diagApprox is read from (body_invweight0: connects and contacts; dof_invweight0: joint equalities).
    MuJoCo caps the impedance d at 0.9999; scale 0.01 acts as d = 0.999999 (mjcf_templates/options/).
    """
    model.body_invweight0[:] *= scale
    model.dof_invweight0[:] *= scale


@dataclass(frozen=True)
class ModelIds:
    """
    The MuJoCo ids of what `build_xml` named, by role. Drives follow the setup's driven joints: the equality of each
    (drive "equality") or its actuator ("servo"), its joint's dof and qpos address. `site_pairs` holds the (parent,
    child) closure sites of each of `closures`; `collision` each body's collision geom (contact models);
    `joints` the qpos map: each MuJoCo joint (`mujoco_joints`, qpos order) with its first qpos address.
    """

    drive_equalities: tuple[int, ...]
    drive_actuators: tuple[int, ...]
    drive_dofs: tuple[int, ...]
    drive_qpos: tuple[int, ...]
    site_pairs: tuple[tuple[int, int], ...]
    collision: dict[str, int]
    joints: tuple[tuple[MjJoint, int], ...]

    @property
    def held(self) -> tuple[int, ...]:
        """The dofs a stabilised step holds: the driven joints' of a driven model, none of an undriven one."""
        return self.drive_dofs if self.drive_equalities or self.drive_actuators else ()


@dataclass(frozen=True, eq=False)
class CompiledModel:
    """
    One model as built and compiled: its MJCF text (what model.xml starts from), MuJoCo's model of it with the
    regulariser scale the text states applied (`scale_regularization`), the options it was built with (its preset
    among them) and the ids of its named elements by role. Runs step a copy each (`fresh`): MuJoCo's model holds
    state a run writes (a drive's eq_data).
    """

    xml: str
    model: mujoco.MjModel
    options: ModelOptions
    ids: ModelIds

    @property
    def preset(self) -> Preset:
        """The preset it was built with."""
        return self.options.preset

    def fresh(self) -> tuple[mujoco.MjModel, mujoco.MjData]:
        """A copy of the compiled model (0.8 ms on the 16 x 16 Miura FOLD sheet; compiling took 32 ms) and its data."""
        model = copy.copy(self.model)
        return model, mujoco.MjData(model)


def build_model(mechanism: Mechanism, setup: ModelSetup, options: ModelOptions) -> CompiledModel:
    """`build_xml`'s text (no keyframes) compiled, its regulariser scale applied, with the ids of its named elements."""
    xml = build_xml(mechanism, setup, options)
    model = mujoco.MjModel.from_xml_string(xml)
    scale_regularization(model, float(model.numeric("regularization_scale").data[0]))
    return CompiledModel(xml, model, options, _ids(model, mechanism, setup, options))


def _ids(model: mujoco.MjModel, mechanism: Mechanism, setup: ModelSetup, options: ModelOptions) -> ModelIds:
    """The ids of the elements `build_xml` named in `model`."""
    drives = setup.drives
    contact = options.contact and setup.has_contact
    return ModelIds(
        drive_equalities=tuple(model.equality(drive_name(j)).id for j in drives) if options.drive == "equality"
        else (),
        drive_actuators=tuple(model.actuator(drive_name(j)).id for j in drives) if options.drive == "servo" else (),
        drive_dofs=tuple(int(model.jnt_dofadr[model.joint(j).id]) for j in drives),
        drive_qpos=tuple(int(model.jnt_qposadr[model.joint(j).id]) for j in drives),
        site_pairs=tuple(tuple(model.site(site_name(c.joint, side, c.k)).id for side in ("parent", "child"))
                         for c in closures(mechanism)),
        collision={b.name: model.geom(collision_name(b.name)).id for b in mechanism.bodies
                   if contact and not b.spacer and b.collision is not None},
        joints=tuple((j, int(model.jnt_qposadr[model.joint(j.name).id])) for j in mujoco_joints(mechanism)),
    )
