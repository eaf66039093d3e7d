"""Mechanism + templates -> MJCF. The one place where MJCF names are made.

Names: bodies as in the mechanism (`panel_<i>`, `link_<i>` or a crease pattern's faces; the root's
geoms sit on the world body), hinges as the mechanism's joints, meshes `<body>_solid` /
`<body>_collision`, closure sites `<joint>_parent_<k>` / `<joint>_child_<k>`, connects
`close_<joint>_<k>`, joint couplings `couple_<joint>_<other>`, the drive `drive_<joint>`, keyframes
`start_<branch>`.

A hinge's qpos equals the mechanism's joint angle: a joint traversed from its child to its parent
in the spanning tree gets the reversed axis. Each cut joint is closed by one site-based `connect`
per anchor on its axis (sites need not coincide at qpos0, spec mujoco.md §2.1). Contact, gravity
and render assets enter only the models that use them.
"""

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from importlib import resources

import numpy as np

from . import __version__
from .errors import ParameterError
from .geometry import invert
from .mechanism import Mechanism
from .scenes.base import Scene

ORDER = (
    "compiler", "option", "size", "custom", "visual", "default", "asset", "worldbody",
    "contact", "equality", "actuator", "sensor", "keyframe",
)  # fmt: skip
PRESETS = ("fast", "stiff", "accurate")


@dataclass(frozen=True)
class ModelOptions:
    """What one compiled model needs: preset, drive kind, contact, render assets, keyframes."""

    preset: str = "fast"
    drive: str = "equality"  # "equality": kinematic tracking; "servo": force-limited actuator; "none"
    contact: bool = False
    render: bool = False
    gravity: bool = False  # the scene's gravity (m/s^2, its root frame) and the energy flag


def template(name: str) -> ET.Element:
    """A fragment of `mjcf_templates/`, parsed with its comments."""
    text = resources.files("sim_origami.mjcf_templates").joinpath(name).read_text()
    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    return ET.fromstring(text, parser=parser)


def preset_duration(preset: str) -> float:
    """Sweep duration (s) stated by a preset template."""
    for numeric in template(f"options/{preset}.xml").iter("numeric"):
        if numeric.get("name") == "sweep_duration":
            return float(numeric.get("data"))
    raise KeyError(f"preset {preset} has no sweep_duration")


def _fmt(values) -> str:
    return " ".join(repr(float(v)) for v in np.ravel(values))  # shortest exact round-trip


def _quat(R: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation matrix."""
    w = np.sqrt(max(0.0, 1.0 + np.trace(R))) / 2
    if w > 1e-6:
        return np.array(
            [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
        )
    i = int(np.argmax(np.diag(R)))
    j, k = (i + 1) % 3, (i + 2) % 3
    q = np.zeros(4)
    q[i + 1] = np.sqrt(max(0.0, 1.0 + R[i, i] - R[j, j] - R[k, k])) / 2
    q[0] = (R[k, j] - R[j, k]) / (4 * q[i + 1])
    q[j + 1] = (R[j, i] + R[i, j]) / (4 * q[i + 1])
    q[k + 1] = (R[k, i] + R[i, k]) / (4 * q[i + 1])
    return q


def _section(root: ET.Element, tag: str) -> ET.Element:
    found = root.find(tag)
    return found if found is not None else ET.SubElement(root, tag)


def _merge(root: ET.Element, fragment: ET.Element) -> None:
    """Append the children of each top-level section of `fragment` into `root`."""
    for child in fragment:
        if child.tag is ET.Comment:
            root.append(child)
            continue
        if child.tag in ("compiler", "option", "size"):
            root.append(child)
            continue
        _section(root, child.tag).extend(list(child))


def _add_meshes(asset: ET.Element, mechanism: Mechanism) -> None:
    for body in mechanism.bodies:
        for suffix, mesh in (("solid", body.solid), ("collision", body.collision)):
            if mesh is None:
                continue
            ET.SubElement(
                asset, "mesh", name=f"{body.name}_{suffix}",
                vertex=_fmt(mesh.vertices), face=" ".join(str(int(i)) for i in np.ravel(mesh.faces)),
            )  # fmt: skip


def _add_bodies(world: ET.Element, mechanism: Mechanism, contact: bool) -> dict[str, ET.Element]:
    ref = mechanism.reference_poses()
    elements = {mechanism.root: world}
    by_name = {b.name: b for b in mechanism.bodies}

    def add_geoms(parent: ET.Element, name: str) -> None:
        body = by_name[name]
        ET.SubElement(parent, "geom", name=f"{name}_solid", mesh=f"{name}_solid", rgba=_fmt(body.rgba))
        parent[-1].set("class", "panel")
        if contact and body.collision is not None:
            ET.SubElement(parent, "geom", name=f"{name}_collision", mesh=f"{name}_collision")
            parent[-1].set("class", "collision")

    world.append(ET.Comment(f" {mechanism.root}: fixed to the world "))
    add_geoms(world, mechanism.root)
    for edge in mechanism.tree:
        joint = mechanism.joints[edge.joint]
        rel = invert(ref[edge.parent]) @ ref[edge.child]
        attrs = {"name": edge.child}
        if not np.allclose(rel, np.eye(4), atol=1e-14):
            attrs |= {"pos": _fmt(rel[:3, 3]), "quat": _fmt(_quat(rel[:3, :3]))}
        body = ET.SubElement(elements[edge.parent], "body", attrs)
        frame = joint.frame_child if edge.sign > 0 else joint.frame_parent
        axis = frame[:3, 2] * edge.sign
        hinge = ET.SubElement(body, "joint", name=joint.name, pos=_fmt(frame[:3, 3]), axis=_fmt(axis))
        hinge.set("class", "crease")
        add_geoms(body, edge.child)
        elements[edge.child] = body
    return elements


def _add_self_contact(root: ET.Element, scene: Scene) -> None:
    """Collision solids collide by contype/conaffinity; bodies that share a vertex are excluded."""
    for geom in root.iter("geom"):
        if geom.get("class") == "collision":
            geom.set("contype", "1")
            geom.set("conaffinity", "1")
    section = _section(root, "contact")
    section.append(ET.Comment(" panels that share a vertex touch in every pose: excluded "))
    body = {name: ("world" if name == scene.mechanism.root else name) for name in scene.pattern.face_names}
    for a, b in scene.pattern.touching_faces():
        ET.SubElement(section, "exclude", body1=body[a], body2=body[b])


def qpos_order(mechanism: Mechanism) -> list[str]:
    """Hinge names in MuJoCo's qpos order: depth-first over the nested bodies."""
    children: dict[str, list] = {}
    for edge in mechanism.tree:
        children.setdefault(edge.parent, []).append(edge)
    order: list[str] = []

    def visit(body: str) -> None:
        for edge in children.get(body, []):
            order.append(mechanism.joints[edge.joint].name)
            visit(edge.child)

    visit(mechanism.root)
    return order


def build_xml(scene: Scene, options: ModelOptions, keyframes: dict[str, np.ndarray] | None = None) -> str:
    """
    MJCF text of a scene.

    Parameters
    ----------
    scene : Scene
    options : ModelOptions
    keyframes : {name: (n_joints,) float}, optional
      Mechanism joint angles stored as keyframes `start_<name>`.
    """
    if options.preset not in PRESETS:
        raise ParameterError(f"unknown preset {options.preset!r}; presets are {', '.join(PRESETS)}")
    mechanism = scene.mechanism
    contact = options.contact and (bool(scene.contact_pairs) or scene.self_contact)
    root = ET.Element("mujoco", model=scene.name)
    root.append(ET.Comment(f" sim_origami {__version__}, scene {scene.name}; {scene.notes} "))
    fragments = ["base.xml", f"options/{options.preset}.xml", "defaults.xml"]
    if options.render:
        fragments += ["visual.xml", "render_scene.xml"]
    for name in fragments:
        _merge(root, template(name))
    if contact:
        root.find("option/flag").set("contact", "enable")
    if options.gravity:
        # free motion under gravity (e.g. the IFToMM A04 benchmark): energy reported, not dissipated
        root.find("option").set("gravity", _fmt(scene.gravity))
        root.find("option/flag").set("gravity", "enable")
        root.find("option/flag").set("energy", "enable")
    _add_meshes(_section(root, "asset"), mechanism)
    elements = _add_bodies(_section(root, "worldbody"), mechanism, contact)

    equality = _section(root, "equality")
    for i in mechanism.cut_joints:
        joint = mechanism.joints[i]
        equality.append(ET.Comment(f" loop cut at {joint.name}: anchors on its axis, away from shared vertices "))
        on_parent, on_child = mechanism.anchor_points(i)
        for k, (p, c) in enumerate(zip(on_parent, on_child, strict=True)):
            ET.SubElement(elements[joint.parent], "site", name=f"{joint.name}_parent_{k}", pos=_fmt(p))
            ET.SubElement(elements[joint.child], "site", name=f"{joint.name}_child_{k}", pos=_fmt(c))
            for side in ("parent", "child"):
                elements[getattr(joint, side)].findall("site")[-1].set("class", "closure_site")
            ET.SubElement(
                equality, "connect", name=f"close_{joint.name}_{k}",
                site1=f"{joint.name}_child_{k}", site2=f"{joint.name}_parent_{k}",
            ).set("class", "closure")  # fmt: skip

    if mechanism.couplings:
        equality.append(ET.Comment(" couplings q1 = c q2: symmetry the model assumes, or periodic copies of creases "))
    for joint, other, scale in mechanism.couplings:
        ET.SubElement(
            equality, "joint", name=f"couple_{joint}_{other}", joint1=joint, joint2=other,
            polycoef=_fmt([0.0, scale, 0.0, 0.0, 0.0]),
        ).set("class", "closure")  # fmt: skip

    drive = f"drive_{scene.drive_joint}"
    if options.drive == "equality":
        equality.append(ET.Comment(" input: the harness writes the target angle into eq_data[drive, 0] each step "))
        ET.SubElement(equality, "joint", name=drive, joint1=scene.drive_joint, polycoef="0 0 0 0 0").set(
            "class", "drive"
        )
    elif options.drive == "servo":
        actuator = _section(root, "actuator")
        actuator.append(ET.Comment(" input: force-limited servo, so that contact can stop the motion "))
        ET.SubElement(actuator, "position", name=drive, joint=scene.drive_joint).set("class", "servo")

    if contact and scene.self_contact:
        _add_self_contact(root, scene)
    if contact and scene.contact_pairs:
        pairs = _section(root, "contact")
        pairs.append(ET.Comment(" only panels that fold onto each other may touch; all others share a vertex "))
        for a, b in scene.contact_pairs:
            ET.SubElement(pairs, "pair", geom1=f"{a}_collision", geom2=f"{b}_collision").set("class", "contact")

    if keyframes:
        frames = _section(root, "keyframe")
        order = qpos_order(mechanism)
        for name, q in keyframes.items():
            qpos = [q[mechanism.joint_index(j)] for j in order]
            ET.SubElement(frames, "key", name=f"start_{name}", qpos=_fmt(qpos))

    root[:] = sorted(root, key=lambda e: ORDER.index(e.tag) if e.tag in ORDER else -1)
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="unicode")
