"""Linkage files (JSON or TOML, schema version 1, docs/linkage_files.md): a mechanism without a closed form.

Two forms of the same information:

- `form = "dh"`: one closed loop as Denavit-Hartenberg rows in the convention of `kinematics.dh` (joint k: offset
  R_k along its axis, then length a and twist alpha to joint k+1; the last row leads back to joint 1). Link k
  joins joint k to joint k+1 and is body `link_<k>`; the last link is the ground. An optional `theta0` per joint
  is the start configuration.
- `form = "axes"`: named bodies and joints, each joint a line (a point and a direction) between two bodies, drawn
  in one assembled pose; any body graph, one loop or several. `theta0` is a joint's angle in that pose (default 0).

Joints are `revolute` (a hinge, its angle the right-handed turn of the second body relative to the first about
the direction, or the D-H theta) or `spherical` (a ball: three hinge angles `<name>_x`, `_y`, `_z` about its triad,
intrinsic x-y-z, `mechanism.ball_joint`). Angles in the file are in `units.angle` (deg by default, as people write
them), lengths in `units.length` (m by default); everything read is returned in radians and metres.

Every geometry number (D-H a, alpha, offset; axis points and directions) is read with its precision: half a unit in
its last printed digit (`precision.Typed`; an integer +-0.5), or the file's `precision` table for every length and
angle. `LinkageSpec.values` lists them, and `read_linkage(path, values)` reads the file with some replaced: the
nearest mobile linkage (`scenes.linkage_file.nearest_mobile`).

Every refusal is one ParameterError naming the field by its path, e.g. `joints[3].alpha: ...`.
"""

import json
import math
import re
import sys
import unicodedata
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from .conventions import LENGTH_RANGE, LENGTH_RATIO_MAX
from .errors import ParameterError
from .fold import UNITS as LENGTH_UNITS
from .geometry import transform, transform_z
from .kinematics.dh import DHRow
from .linkage import bar
from .linkage_forms import reduced_form
from .mechanism import Body, Joint, Mechanism, ball_joint
from .origami import PALETTE
from .precision import Typed
from .solids import MESH_FORMATS, mujoco_mesh_problem

if sys.version_info >= (3, 11):
    import tomllib
else:  # Python 3.10: the same parser, as a package
    import tomli as tomllib

VERSION = 1
VERSION_KEY = "sim_origami_linkage"
ANGLE_UNITS = {"deg": math.pi / 180.0, "rad": 1.0}
JOINT_TYPES = ("revolute", "spherical")
FORMS = ("dh", "axes")
# Default bar side and closure anchor distance, as fractions of the linkage's longest link (the built-in D-H scenes
# use 0.05 m bars and anchors of half their longest link on links of about 1 m).
WIDTH_SHARE = 0.05
ANCHOR_SHARE = 0.5
# A file's sweep lasts this many times what the path's rule asks (`sweep_rate`, which keeps MuJoCo's lag near 0.2 of
# the tolerance for any path): 1 by default; a file may ask for slower.
SWEEP_TIME_SCALE = 1.0
# Lengths beyond this (m) are refused as they are read, before any solid is built (1e308 overflowed trimesh); the
# scene then holds the linkage's size to the simulated range (`conventions.LENGTH_RANGE`, 1e-4 .. 1e4 m).
LENGTH_LIMIT = 1e9
# The input range lies within +-RANGE_LIMIT (rad): a turn either way (the trace steps at most 0.05 rad, so a range
# of 1e308 deg would never end); the sweep lasts at most SWEEP_SCALE_LIMIT times the preset's duration.
RANGE_LIMIT = 2 * math.pi
SWEEP_SCALE_LIMIT = 100.0
# The input range spans at least RANGE_MIN (rad): the trace's first step (`linkage_path.FIRST_STEP`); below it the
# trace takes no step and the bifurcation study's poses (+-2e-3 rad about a meeting) leave the range.
RANGE_MIN = 0.01
# Documents nested deeper than this are refused as they are read: the schema's deepest value is a number in a vector
# in a joint's table in the joints list (depth 4), and the parsers recurse once a level (thousands of levels gave a
# RecursionError in json and tomllib alike; so did repr of the values).
DEPTH_LIMIT = 32
# A TOML key of more dotted parts than that is refused before tomllib reads it: it walks each part's prefix, a cost
# quadratic in their number (4000 parts: 0.3 s; a file of a megabyte would take an hour).
DOTTED = re.compile(rf"(?<![\w-])(?:[\w-]++\s*+\.\s*+){{{DEPTH_LIMIT},}}")

TOP_FIELDS = {VERSION_KEY, "form", "name", "units", "precision", "joints", "bodies", "ground", "input", "shapes",
              "contact", "anchor", "sweep_time_scale", "notes"}
DH_FIELDS = {"name", "type", "a", "alpha", "offset", "theta0"}
AXIS_FIELDS = {"name", "type", "bodies", "point", "direction", "theta0"}
# The fields that fix a linkage's geometry, whose values the nearest exact linkage may move (docs/linkage_files.md).
GEOMETRY = re.compile(r"joints\[\d+\]\.(a|alpha|offset|point\[\d\]|direction\[\d\])")
# An integer in a file (TOML gives no hook for its text) stands for +-0.5 of its unit, as printed.
INTEGER_PRECISION = 0.5


@dataclass(frozen=True)
class Value:
    """One geometry number of a file: its field path, the value as typed and its precision (file units: `unit`)."""

    field: str
    given: float
    precision: float
    unit: str


@dataclass(frozen=True)
class LinkageSpec:
    """
    A linkage file read and checked: the mechanism, and how to drive and start it.

    Attributes
    ----------
    joint_names : one name per mechanism joint, in order (a ball's three hinges `<name>_x`, `_y`, `_z`).
    input_joint : the driven mechanism joint.
    input_range : (lo, hi) of its angle (rad).
    start : every joint's start angle (rad), or None to assemble at `start_input` (rad, None: the range's middle).
    length_m : metres per length unit of the file.
    values : the geometry numbers as typed, with their precision (`Value`, file units).
    """

    name: str
    form: str
    mechanism: Mechanism
    joint_names: tuple[str, ...]
    input_joint: str
    input_range: tuple[float, float]
    start: NDArray[np.float64] | None
    start_input: float | None
    contact_pairs: tuple[tuple[str, str], ...]
    sweep_time_scale: float
    length_m: float
    notes: str
    values: tuple[Value, ...] = ()


def read_linkage(source: str | Path, values: Mapping[str, float] | None = None) -> LinkageSpec:
    """
    Read a linkage file (`.json` or `.toml`); the module docstring and docs/linkage_files.md give the rules.

    `values` replaces geometry numbers by field path (`Value.field`, file units): the nearest exact linkage.

    Raises
    ------
    ParameterError
      For a source that is no path, `values` that are no table of geometry fields and numbers, and any field of the
      file that breaks the schema (named by its path).
    """
    if not isinstance(source, (str, Path)) or (isinstance(source, str) and not source) or "\0" in str(source):
        raise ParameterError(f"source = {_shown(source)}: give the linkage file's path (a str or Path)")
    path = Path(source)
    doc = _load(path)
    if values is not None and not isinstance(values, Mapping):
        raise ParameterError(f"values = {_shown(values)}: give a table of field paths and numbers")
    if values:
        doc = _replaced(doc, values)
    _known(doc, TOP_FIELDS, "")
    version = doc.get(VERSION_KEY)
    if version is None:
        raise ParameterError(f"{VERSION_KEY}: missing; a linkage file starts with {VERSION_KEY} = {VERSION} (the "
                             "schema version it is written for)")
    if isinstance(version, bool) or version != VERSION:
        raise ParameterError(f"{VERSION_KEY} = {_shown(version)}: this sim_origami reads schema version {VERSION}")
    form = doc.get("form")
    if form not in FORMS:
        raise ParameterError(f"form = {_shown(form)}: it must be one of {', '.join(map(repr, FORMS))} (D-H rows of one "
                             "loop, or axis lines between named bodies)")
    units = _table(doc.get("units", {}), "units")
    _known(units, {"length", "angle"}, "units")
    length_unit, angle_unit = units.get("length", "m"), units.get("angle", "deg")
    if not isinstance(length_unit, str) or length_unit not in LENGTH_UNITS:
        raise ParameterError(f"units.length = {_shown(length_unit)}: it must be one of {', '.join(LENGTH_UNITS)}")
    if not isinstance(angle_unit, str) or angle_unit not in ANGLE_UNITS:
        raise ParameterError(f"units.angle = {_shown(angle_unit)}: it must be one of {', '.join(ANGLE_UNITS)}")
    stated = _table(doc.get("precision", {}), "precision")
    _known(stated, {"length", "angle"}, "precision")
    read = _Reader(LENGTH_UNITS[length_unit], ANGLE_UNITS[angle_unit], path.parent)
    read.stated = {kind: read.positive(v, f"precision.{kind}", length=False) for kind, v in stated.items()}
    read.units = {"length": length_unit, "angle": angle_unit, "": ""}
    joints = doc.get("joints")
    if not isinstance(joints, list) or not joints:
        raise ParameterError("joints: missing or empty; give a list of joints (a table each)")
    build = _dh if form == "dh" else _axes
    mechanism, names, starts, input_names, meshes = build(doc, [_table(j, f"joints[{k}]")
                                                                for k, j in enumerate(joints)], read)
    given = _table(doc.get("input"), "input")
    _known(given, {"joint", "range", "start"}, "input")
    joint = given.get("joint")
    if not isinstance(joint, str) or joint not in input_names:
        raise ParameterError(f"input.joint = {_shown(joint)}: it must name a revolute joint, one of "
                             f"{', '.join(input_names)}")
    mech_input = input_names[joint]
    span = read.angles(given.get("range"), "input.range", 2)
    if not span[0] < span[1]:
        raise ParameterError("input.range: give [low, high] with low < high")
    if span[1] - span[0] < RANGE_MIN:
        raise ParameterError(f"input.range = {_shown(given['range'])}: it must span at least "
                             f"{RANGE_MIN / read.rad:.3g} {angle_unit} (the trace's first step)")
    if max(abs(span[0]), abs(span[1])) > RANGE_LIMIT + 1e-12:
        raise ParameterError(f"input.range = {_shown(given['range'])}: it must lie within one turn either way "
                             f"(+-{RANGE_LIMIT / read.rad:g} {angle_unit})")
    start_input = read.angle(given["start"], "input.start") if "start" in given else None
    if start_input is not None and not span[0] <= start_input <= span[1]:
        raise ParameterError("input.start: it must lie inside input.range")
    start = None
    if starts is not None:
        start = np.zeros(len(mechanism.joints))
        for name, value in starts.items():
            start[mechanism.joint_index(name)] = value
        if start_input is not None:
            raise ParameterError("input.start: the start configuration (theta0) already fixes the start input")
    contact = tuple(_pair(p, f"contact[{k}]", {b.name for b in mechanism.bodies if not b.spacer})
                    for k, p in enumerate(_list(doc.get("contact", []), "contact")))
    mechanism = _with_solids(mechanism, meshes, {b for pair in contact for b in pair})
    scale = read.positive(doc.get("sweep_time_scale", SWEEP_TIME_SCALE), "sweep_time_scale", length=False)
    if scale > SWEEP_SCALE_LIMIT:
        raise ParameterError(f"sweep_time_scale = {scale:g}: it must be at most {SWEEP_SCALE_LIMIT:g}")
    notes = _text(doc.get("notes", ""), "notes", "a string")
    name = _text(doc.get("name", path.stem), "name", "a non-empty word (no spaces or slashes)")
    if not name.strip() or any(c.isspace() or c in "/\\" for c in name):
        raise ParameterError(f"name = {_shown(name)}: it must be a non-empty word (no spaces or slashes)")
    geometry = tuple(v for v in read.seen.values() if GEOMETRY.fullmatch(v.field))
    return LinkageSpec(name, form, mechanism, names, mech_input, (span[0], span[1]), start, start_input, contact,
                       scale, read.length_m, notes, geometry)


def _replaced(doc: dict, values: Mapping[str, float]) -> dict:
    """The document with geometry numbers replaced by field path ('joints[1].alpha', 'joints[0].point[2]')."""
    joints = doc.get("joints")
    # the joints copied a level deep (their vectors too), the file's own values left as read
    doc = {**doc, "joints": [{k: list(v) if isinstance(v, list) else v for k, v in j.items()}
                             if isinstance(j, dict) else j for j in joints] if isinstance(joints, list) else joints}
    for field, value in values.items():
        match = re.fullmatch(r"joints\[(\d+)\]\.(\w+)(?:\[(\d)\])?", field) if isinstance(field, str) else None
        if match is None or not GEOMETRY.fullmatch(field):
            raise ParameterError(f"{_shown(field)}: not a geometry field of a linkage file")
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ParameterError(f"values[{field!r}] = {_shown(value)}: it must be a number")
        k, key, i = int(match[1]), match[2], match[3]
        try:
            if i is None:
                doc["joints"][k][key] = value
            else:
                doc["joints"][k][key][int(i)] = value
        except (IndexError, KeyError, TypeError) as err:  # a field the file does not hold
            raise ParameterError(f"{field}: the file has no such number to replace") from err
    return doc


class _Reader:
    """Numbers of the file in its units, checked, as radians and metres; each one read is kept in `seen` with its
    precision (the `precision` table's for its kind, else half a unit in its last printed digit)."""

    def __init__(self, length_m: float, rad: float, folder: Path):
        self.length_m, self.rad, self.folder = length_m, rad, folder
        self.stated: dict[str, float] = {}
        self.units = {"length": "m", "angle": "deg", "": ""}
        self.seen: dict[str, Value] = {}

    def number(self, value: Any, field: str, kind: str = "") -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ParameterError(f"{field} = {_shown(value)}: it must be a number")
        if isinstance(value, int) and abs(value) > sys.float_info.max:  # beyond a float: math.isfinite overflows
            raise ParameterError(f"{field} = {_shown(value)}: it must be a finite number (within a float's range)")
        if not math.isfinite(value):
            raise ParameterError(f"{field} = {_shown(value)}: it must be a finite number")
        if kind in self.stated:
            precision = self.stated[kind]
        elif isinstance(value, Typed):
            precision = value.precision
        else:  # an integer as printed, or a float given in the API (exact: held)
            precision = INTEGER_PRECISION if isinstance(value, int) else 0.0
        self.seen[field] = Value(field, float(value), precision, self.units[kind])
        return float(value)

    def length(self, value: Any, field: str) -> float:
        out = self.number(value, field, "length") * self.length_m
        if abs(out) > LENGTH_LIMIT:
            raise ParameterError(f"{field} = {_shown(value)}: lengths beyond {LENGTH_LIMIT:g} m are not simulated")
        return out

    def angle(self, value: Any, field: str) -> float:
        return self.number(value, field, "angle") * self.rad

    def sized(self, value: Any, field: str, size: float) -> float:
        """A positive length within the simulated range and within LENGTH_RATIO_MAX of the linkage's size (m), as
        every scene's lengths: a bar 1e-300 wide gave MuJoCo a body of no mass, found only after the trace."""
        out = self.positive(value, field)
        low, high = max(LENGTH_RANGE[0], size / LENGTH_RATIO_MAX), min(LENGTH_RANGE[1], size * LENGTH_RATIO_MAX)
        if not low <= out <= high:
            raise ParameterError(f"{field} = {_shown(value)}: it must lie within {low / self.length_m:.3g} .. "
                                 f"{high / self.length_m:.3g} {self.units['length']} ({LENGTH_RANGE[0]:g} .. "
                                 f"{LENGTH_RANGE[1]:g} m and within {LENGTH_RATIO_MAX:g} times the linkage's size, "
                                 f"{size:.3g} m)")
        return out

    def positive(self, value: Any, field: str, length: bool = True) -> float:
        out = self.length(value, field) if length else self.number(value, field)
        if not out > 0:
            raise ParameterError(f"{field} = {_shown(value)}: it must be > 0")
        return out

    def vector(self, value: Any, field: str, length: bool = False) -> NDArray[np.float64]:
        """Three numbers: lengths (in metres) or unitless (a direction)."""
        if not isinstance(value, list) or len(value) != 3:
            raise ParameterError(f"{field} = {_shown(value)}: give three numbers [x, y, z]")
        read = self.length if length else self.number
        return np.array([read(v, f"{field}[{k}]") for k, v in enumerate(value)])

    def angles(self, value: Any, field: str, n: int) -> list[float]:
        if not isinstance(value, list) or len(value) != n:
            raise ParameterError(f"{field} = {_shown(value)}: give {n} angles")
        return [self.angle(v, f"{field}[{k}]") for k, v in enumerate(value)]


def _load(path: Path) -> dict:
    """The file's top-level table: TOML for `.toml`, JSON otherwise."""
    try:
        text = path.read_text()
    except OSError as err:
        raise ParameterError(f"cannot read linkage file {path}: {err.strerror}") from err
    except UnicodeDecodeError as err:
        raise ParameterError(f"{path} is not UTF-8 text ({err.reason}); a linkage file is JSON or TOML") from err
    deep = ParameterError(f"{path}: lists or tables nested more than {DEPTH_LIMIT} deep; a linkage file's numbers "
                          "lie 4 deep")
    toml = path.suffix.lower() == ".toml"
    if toml and DOTTED.search(text):
        raise deep
    try:
        # each float keeps the precision it was printed with (`precision.Typed`)
        doc = tomllib.loads(text, parse_float=Typed) if toml else json.loads(text, parse_float=Typed)
    except RecursionError:  # both parsers recurse once a level
        raise deep from None
    except tomllib.TOMLDecodeError as err:
        raise ParameterError(f"{path} is not TOML ({err})") from err
    except json.JSONDecodeError as err:
        raise ParameterError(f"{path} is not JSON ({err}); a linkage file is JSON (or TOML, named .toml)") from err
    except ValueError as err:  # Python's int-from-text limit: an integer of over 4,300 digits
        raise ParameterError(f"{path}: an integer of over {sys.get_int_max_str_digits()} digits; a linkage file's "
                             "numbers lie within a float's range") from err
    if not isinstance(doc, dict):
        raise ParameterError(f"{path} holds a JSON {type(doc).__name__}; a linkage file is an object")
    if _depth(doc) > DEPTH_LIMIT:  # repr, copies and checks of the values recurse as well
        raise deep
    return doc


def _depth(doc: Any) -> int:
    """The deepest nesting of lists and tables in a parsed document (counted without recursion: TOML's dotted keys
    nest tables any depth without a bracket)."""
    deepest, stack = 0, [(doc, 0)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, (list, dict)):
            deepest = max(deepest, depth + 1)
            stack += [(v, depth + 1) for v in (value.values() if isinstance(value, dict) else value)]
    return deepest


# How many characters of a value a message quotes: a refusal stays one short line whatever the value.
SHOWN = 60


def _shown(value: Any) -> str:
    """A value as a message quotes it: its repr, cut to SHOWN characters (an integer by its digit count)."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value).bit_length() > 200:
        # repr of an integer over 4,300 digits raises; the count is what matters
        return f"<an integer of {int(abs(value).bit_length() * math.log10(2)) + 1} digits>"
    if isinstance(value, (list, dict)) and len(value) > SHOWN:  # repr of a long list costs its length
        return f"<a {type(value).__name__} of {len(value)} items>"
    text = repr(value)
    return text if len(text) <= SHOWN else f"{text[:SHOWN - 20]}...{text[-12:]} ({len(text)} characters)"


def _text(value: Any, field: str, rule: str) -> str:
    """A string without control characters (NUL, line breaks) or lone surrogates: names and notes end up in file
    names, XML and one-line messages."""
    if not isinstance(value, str):
        raise ParameterError(f"{field} = {_shown(value)}: it must be {rule}")
    bad = next((c for c in value if unicodedata.category(c) in ("Cc", "Cs")), None)
    if bad is not None:
        raise ParameterError(f"{field} = {_shown(value)}: it holds the control character {bad!r}; it must be {rule}")
    return value


def _table(value: Any, field: str) -> dict:
    if not isinstance(value, dict):
        raise ParameterError(f"{field}: {'missing' if value is None else _shown(value)}; it must be a table of fields")
    return value


def _list(value: Any, field: str) -> list:
    if not isinstance(value, list):
        raise ParameterError(f"{field} = {_shown(value)}: it must be a list")
    return value


def _known(table: dict, fields: set[str], where: str) -> None:
    """Refuse a field the schema does not have (a typo would otherwise be ignored)."""
    for key in table:
        if key not in fields:
            field = f"{where}.{key}" if where else key
            raise ParameterError(f"{field}: unknown field; fields here are {', '.join(sorted(fields))}")


def _pair(value: Any, field: str, bodies: set[str]) -> tuple[str, str]:
    if not isinstance(value, list) or len(value) != 2 or not all(isinstance(v, str) for v in value) or \
            value[0] == value[1]:
        raise ParameterError(f"{field} = {_shown(value)}: give two different body names")
    for name in value:
        if name not in bodies:
            raise ParameterError(f"{field}: unknown body {_shown(name)}; bodies are {', '.join(sorted(bodies))}")
    return value[0], value[1]


def _joint_type(joint: dict, field: str) -> str:
    kind = joint.get("type", "revolute")
    if kind not in JOINT_TYPES:
        raise ParameterError(f"{field}.type = {_shown(kind)}: unknown joint type; types are {', '.join(JOINT_TYPES)}")
    return kind


def _names(joints: list[dict], default: str) -> list[str]:
    names = []
    for k, j in enumerate(joints):
        name = _text(j.get("name", default.format(k + 1)), f"joints[{k}].name", "a non-empty word")
        if not name or any(c.isspace() for c in name):
            raise ParameterError(f"joints[{k}].name = {_shown(name)}: it must be a non-empty word")
        if name in names:
            raise ParameterError(f"joints[{k}].name = {_shown(name)}: joints[{names.index(name)}] has that name too")
        names.append(name)
    return names


def _starts(joints: list[dict], read: _Reader, required: bool) -> list[float] | None:
    """Each joint's theta0 (rad): all or none (the D-H form), or 0 where absent (the axes form)."""
    given = ["theta0" in j for j in joints]
    if not any(given) and not required:
        return None
    if not required and not all(given):
        missing = given.index(False)
        raise ParameterError(f"joints[{missing}].theta0: missing; give theta0 for every joint (a start "
                             "configuration) or for none (the loop is then assembled numerically)")
    return [read.angle(j.get("theta0", 0.0), f"joints[{k}].theta0") for k, j in enumerate(joints)]


def _shapes(doc: dict, read: _Reader, size: float, bodies: set[str]) -> tuple[float, dict[str, trimesh.Trimesh]]:
    """Bar side (m) and mesh solids per body (in the body's frame, metres) from the `shapes` table."""
    shapes = _table(doc.get("shapes", {}), "shapes")
    _known(shapes, {"width", "meshes"}, "shapes")
    width = read.sized(shapes["width"], "shapes.width", size) if "width" in shapes else WIDTH_SHARE * size
    meshes = {}
    for body, file in _table(shapes.get("meshes", {}), "shapes.meshes").items():
        if body not in bodies:
            raise ParameterError(f"shapes.meshes: unknown body {_shown(body)}; bodies are {', '.join(sorted(bodies))}")
        field = f"shapes.meshes.{body}"
        file = _text(file, field, "a mesh file name (STL, OBJ, PLY), relative to the file")
        if Path(file).suffix.lower().lstrip(".") not in MESH_FORMATS:
            raise ParameterError(f"{field} = {_shown(file)}: a mesh file ends in "
                                 f"{', '.join('.' + f for f in MESH_FORMATS)}")
        try:
            mesh = trimesh.load_mesh(read.folder / file)
        except OSError as err:
            raise ParameterError(f"{field}: cannot read mesh {_shown(file)} ({err.strerror})") from err
        except Exception as err:  # trimesh's parsers raise anything on a damaged file: it is the file's fault
            raise ParameterError(f"{field}: cannot read mesh {_shown(file)} ({type(err).__name__}: "
                                 f"{_shown(str(err))})") from err
        if not isinstance(mesh, trimesh.Trimesh) or not len(mesh.faces):
            raise ParameterError(f"{field}: {_shown(file)} holds no single triangle mesh")
        if not np.all(np.isfinite(mesh.vertices)) or np.max(np.abs(mesh.vertices)) * read.length_m > LENGTH_LIMIT:
            raise ParameterError(f"{field}: {_shown(file)} has a vertex that is not finite or lies beyond "
                                 f"{LENGTH_LIMIT:g} m")
        mesh.apply_scale(read.length_m)
        problem = mujoco_mesh_problem(mesh)  # MuJoCo would otherwise refuse it only after the trace
        if problem:
            raise ParameterError(f"{field}: {_shown(file)} is no solid MuJoCo can simulate ({problem})")
        meshes[body] = mesh
    return width, meshes


def _dh(doc: dict, joints: list[dict], read: _Reader):
    """The D-H form: one loop, bodies link_1..link_n (link n the ground)."""
    for key in ("bodies", "ground"):
        if key in doc:
            raise ParameterError(f"{key}: a form = 'dh' file has links link_1 .. link_n (the last is the ground); "
                                 f"{key} belongs to form = 'axes'")
    n = len(joints)
    if n < 4:
        raise ParameterError(f"joints: {n} D-H rows; a movable closed loop needs at least 4 joints")
    rows, spherical = [], []
    for k, j in enumerate(joints):
        field = f"joints[{k}]"
        _known(j, DH_FIELDS, field)
        if _joint_type(j, field) == "spherical":
            spherical.append(k + 1)
        for key in ("a", "alpha"):
            if key not in j:
                raise ParameterError(f"{field}.{key}: missing; a D-H row needs a (length to the next joint) and "
                                     "alpha (twist to the next joint)")
        a = read.length(j["a"], f"{field}.a")
        if a < 0:
            raise ParameterError(f"{field}.a = {_shown(j['a'])}: a length to the next joint must be >= 0")
        rows.append(DHRow(read.length(j.get("offset", 0.0), f"{field}.offset"), a, read.angle(j["alpha"],
                                                                                            f"{field}.alpha")))
    names = _names(joints, "theta{}")
    size = max(max(abs(r.a), abs(r.R)) for r in rows)
    if size == 0:
        # a spherical linkage (an origami vertex): every axis through one point, so no length to scale by. The
        # anchor, when stated, is its size (the connects sit there), else one length unit of the file
        if all(min(abs(math.sin(r.alpha)), abs(math.cos(r.alpha) - 1)) < 1e-12 for r in rows):
            raise ParameterError("joints: every a and offset is 0 and every alpha 0 or 180 deg; the axes are one "
                                 "line, which is no linkage")
        size = read.positive(doc["anchor"], "anchor") / ANCHOR_SHARE if "anchor" in doc else read.length_m
    anchor = read.sized(doc["anchor"], "anchor", size) if "anchor" in doc else ANCHOR_SHARE * size
    width, meshes = _shapes(doc, read, size, {f"link_{k + 1}" for k in range(n)})
    hinges = [k + 1 for k in range(n) if k + 1 not in spherical]
    if not hinges:
        raise ParameterError("joints: every joint is spherical; the input must be a revolute joint")
    inputs = {names[k - 1]: f"joint_{k}" for k in hinges}
    given = _table(doc.get("input"), "input")
    joint = given.get("joint")
    driven = int(inputs.get(joint, f"joint_{hinges[0]}").split("_")[1]) if isinstance(joint, str) else hinges[0]
    mechanism = reduced_form(tuple(rows), tuple(spherical), width=width, anchor=anchor, input_joint=driven)
    joint_names = []
    for j in mechanism.joints:
        k = int(j.name.split("_")[1])
        joint_names.append(names[k - 1] if not j.ball else f"{names[k - 1]}_{j.name[-1]}")
    theta0 = _starts(joints, read, required=False)
    starts = None
    if theta0 is not None:  # a ball turns about its former axis only: angles (0, 0, theta0) in its D-H triad
        starts = {(f"joint_{k + 1}" if k + 1 not in spherical else f"ball_{k + 1}_z"): t for k, t in enumerate(theta0)}
    return mechanism, tuple(joint_names), starts, inputs, meshes


def _axes(doc: dict, joints: list[dict], read: _Reader):
    """The axes form: named bodies (frames = the world frame of the drawn pose) and joint lines between them."""
    names = _names(joints, "joint_{}")
    ground = doc.get("ground")
    pairs = []
    for k, j in enumerate(joints):
        field = f"joints[{k}]"
        _known(j, AXIS_FIELDS, field)
        pair = j.get("bodies")
        if not isinstance(pair, list) or len(pair) != 2 or not all(isinstance(b, str) and b for b in pair):
            raise ParameterError(f"{field}.bodies = {_shown(pair)}: give the two bodies it joins, [first, second]")
        for i, body in enumerate(pair):
            _text(body, f"{field}.bodies[{i}]", "a body name")
        if pair[0] == pair[1]:
            raise ParameterError(f"{field}.bodies: {_shown(pair[0])} twice; a joint joins two different bodies")
        pairs.append(tuple(pair))
    bodies = list(dict.fromkeys(b for p in pairs for b in p))
    listed = doc.get("bodies")
    if listed is not None:
        listed = _list(listed, "bodies")
        for k, b in enumerate(listed):
            if b not in bodies:
                raise ParameterError(f"bodies[{k}] = {_shown(b)}: no joint names it")
        bodies = list(dict.fromkeys([*listed, *bodies]))
    if ground not in bodies:
        raise ParameterError(f"ground = {_shown(ground)}: it must name a body, one of {', '.join(bodies)}")
    if len(joints) < len(bodies):  # a spanning tree has len(bodies) - 1 joints: one more closes a loop
        raise ParameterError(f"joints: the axes form no closed loop ({len(joints)} joints between {len(bodies)} "
                             "bodies make a tree or less); a linkage file needs at least one loop")
    points, frames, kinds = [], [], []
    for k, j in enumerate(joints):
        field = f"joints[{k}]"
        kind = _joint_type(j, field)
        if "point" not in j:
            raise ParameterError(f"{field}.point: missing; a joint is a line through a point (its centre for a "
                                 "spherical joint)")
        p = read.vector(j["point"], f"{field}.point", length=True)
        if kind == "revolute" and "direction" not in j:
            raise ParameterError(f"{field}.direction: missing; a revolute joint turns about a direction")
        d = read.vector(j.get("direction", [0.0, 0.0, 1.0]), f"{field}.direction")
        if not np.max(np.abs(d)) > 0:
            raise ParameterError(f"{field}.direction = {_shown(j['direction'])}: it must be a nonzero vector")
        d = d / np.max(np.abs(d))  # any length is read, 1e308 included, without overflowing its norm
        if kind == "spherical" and "theta0" in j:
            raise ParameterError(f"{field}.theta0: a spherical joint's angles are 0 in the drawn pose")
        points.append(p)
        frames.append(_frame(p, d))
        kinds.append(kind)
    # The mechanism is built about the first joint's point: its loops hold differences of the file's coordinates, not
    # products of far-off frames. A spherical 4R of size 1.4 drawn 70 units from the origin, rotated: polished poses
    # closed to 4.2e-15 (median) built about the origin, 7.6e-16 about its first point (1.4 units off: 2.1e-16)
    centre = points[0].copy()
    points = [p - centre for p in points]
    frames = [transform(F[:3, :3], F[:3, 3] - centre) for F in frames]
    size = _size(points, pairs)
    width, meshes = _shapes(doc, read, size, set(bodies))
    for mesh in meshes.values():
        mesh.apply_translation(-centre)
    anchor = read.sized(doc["anchor"], "anchor", size) if "anchor" in doc else ANCHOR_SHARE * size
    theta0 = _starts(joints, read, required=True)
    body_list = []
    for k, b in enumerate(bodies):
        ends = [points[i] for i, p in enumerate(pairs) if b in p]
        body_list.append(Body(b, _solid(ends, width), None, PALETTE[k % len(PALETTE)]))
    mech_joints, starts, inputs = [], {}, {}
    for k, name in enumerate(names):
        if kinds[k] == "spherical":
            spacers, hinges = ball_joint(name, *pairs[k], frames[k], frames[k])
            body_list += spacers
            mech_joints += hinges
        else:
            # the child's frame turned by -theta0 about the axis: the hinge reads theta0 in the drawn pose
            mech_joints.append(Joint(name, *pairs[k], frames[k], frames[k] @ transform_z(theta0[k]),
                                     anchors=(-anchor, anchor)))
            starts[name] = theta0[k]
            inputs[name] = name
    given = _table(doc.get("input"), "input")
    keep = (given["joint"],) if isinstance(given.get("joint"), str) and given["joint"] in inputs else ()
    try:
        mechanism = Mechanism(tuple(body_list), tuple(mech_joints), root=ground, keep=keep)
        mechanism.tree  # noqa: B018  (a body left out of the graph is found here, before anything is traced)
    except ParameterError as err:
        raise ParameterError(f"joints: {err}") from err
    return mechanism, tuple(j.name for j in mech_joints), starts, inputs, meshes


def _frame(point: NDArray[np.float64], direction: NDArray[np.float64]) -> NDArray[np.float64]:
    """A frame (4, 4) at `point` whose z is `direction` (x: the world axis least along it, made normal)."""
    z = direction / np.linalg.norm(direction)
    helper = np.eye(3)[int(np.argmin(np.abs(z)))]
    x = helper - (helper @ z) * z
    x /= np.linalg.norm(x)
    return transform(np.stack([x, np.cross(z, x), z], axis=1), point)


def _size(points: list[NDArray[np.float64]], pairs: list[tuple[str, str]]) -> float:
    """The longest distance between two joints of one body (the linkage's size), at least the spread of all."""
    longest = 0.0
    for b in {b for p in pairs for b in p}:
        ends = [points[i] for i, p in enumerate(pairs) if b in p]
        longest = max([longest, *(float(np.linalg.norm(u - v)) for u in ends for v in ends)])
    if longest == 0.0:
        raise ParameterError("joints: every joint passes through one point; the linkage has no size")
    return longest


def _solid(ends: list[NDArray[np.float64]], width: float) -> trimesh.Trimesh:
    """A body's default solid: a bar between its two joints, the hull of the bars between its joints otherwise."""
    if len(ends) <= 2:
        return bar(ends[0], ends[-1], width)
    bars = [bar(ends[i], ends[(i + 1) % len(ends)], width) for i in range(len(ends))]
    return trimesh.convex.convex_hull(np.vstack([b.vertices for b in bars]))


def _with_solids(mechanism: Mechanism, meshes: dict[str, trimesh.Trimesh], colliding: set[str]) -> Mechanism:
    """The mechanism with the named bodies' solids replaced by mesh solids, and the colliding bodies' solids as their
    collision solids too (MuJoCo collides only what has one)."""
    if not meshes and not colliding:
        return mechanism
    bodies = []
    for b in mechanism.bodies:
        solid = meshes.get(b.name, b.solid)
        bodies.append(Body(b.name, solid, solid if b.name in colliding else None, b.rgba, b.spacer))
    return Mechanism(tuple(bodies), mechanism.joints, mechanism.root, mechanism.keep)
