"""FOLD 1.2 import and export of crease patterns (the FOLD 1.2 specification, Demaine, Ku, Lang et al.).

Reading (`read_fold`, table in docs/fold_files.md). A file becomes a flat `CreasePattern` in the XY plane
(metres, counter-clockwise faces) with fold angles; what is refused raises one ParameterError naming the field,
the value and the rule. `FoldPattern.notes` says, one sentence each, what the reader did to the file.

Which geometry. The key frame (top level) is the crease pattern when its vertices_coords lie in one plane with
no face overlapping another. Otherwise the file_frames entry of frame_classes "creasePattern" is, else the key
frame's vertices_flatUnfoldCoords (Crease Pattern Editor), and the key frame's coordinates give the fold angles;
when the top level has no coordinates (Origami Simulator's exports) the first frame with coordinates is; a key
frame in 3-D with neither is a folded form and is unfolded (below).

Planes and sizes. Coordinates are 2-D or 3-D. A 3-D sheet is flat when no vertex lies further than
`fold_mesh.PLANE_RTOL` of its size (bounding-box diagonal) from its best plane (SVD); it is turned into XY by the
smallest rotation carrying the plane's normal (taken with z > 0, else y > 0, else x > 0) to +z, and its offset
dropped. Every tolerance is relative to the size, so a 1 mm and a 1000-unit sheet read alike.

Units. Lengths are in the geometry frame's `frame_unit` and converted to metres (`FoldPattern.unit_scale`);
"unit" (or none) has no physical meaning in FOLD and is read as metres. Files are written with `frame_unit` "m".
`edges_foldAngle` is in degrees in FOLD and in radians here (rho of `sim_origami.creases`).

Signs and sides. FOLD's counter-clockwise face order gives each face its normal and a valley folds the normals
into each other, so for faces counter-clockwise seen from +z FOLD's M/V and fold-angle signs are those of
`sim_origami.creases` (rho > 0 valley seen from +z). Faces are first given one orientation over the whole
sheet (each shared side run both ways); when the file's faces run clockwise (most of the area, seen from +z)
the paper is seen from -z, so M and V swap and fold angles change sign. Angles measured from coordinates follow
the faces' loops; when most M/V creases measured clearly folded have the other letter's sign, the file's loops run
for the other side of the paper than its letters (the FOLD examples' box.fold), so M and V are read swapped.

Faces. `faces_vertices`, else `faces_edges`, else the faces of the planar edge graph (`fold_mesh.planar_faces`).
Faces must be simple polygons of non-zero area; they may be non-convex. Every face side must be an edge, a "B"
edge borders one face and every other edge two. Each interior vertex must be developable (sector angles summing
to 360 deg); Kawasaki and rigid foldability are checked elsewhere.

Assignments (any case). M, V, U and F edges are creases of that assignment (U free, F meant to stay flat); B edges
are the boundary; a cut C splits the paper (vertices along it are doubled, each side becomes a B edge); a join J
merges its two faces into one polygon. Without edges_assignment, edges of one face are B and of two faces U.
Creases are named e<FOLD edge index>.

Fold angles. `edges_foldAngle` (deg, in [-180, 180]; null on a crease = unknown, NaN; entries on B edges are not
read). A folded form (3-D vertices_coords) gives the dihedral angles between its faces' normals; within
`fold_mesh.FLAT_FOLD_TOL` of +-180 deg the M/V letter gives the sign. Folded forms are unfolded breadth-first over
the faces by their own edge lengths and angles (`fold_mesh.unfold`). Flat-folded forms (faces overlapping in one
plane) need a crease-pattern frame.

Precision (docs/fold_files.md, "Precision"). Numbers keep the digits they were printed with (`precision.Typed`): a
folded form is read as its nearest rigid state in units of its coordinates' precision (developable, and on a rigid
motion of its own pattern where that needs special geometry), a frame of coordinates as its nearest state with the
crease pattern's faces, and a complete edges_foldAngle state as its nearest state closing every loop when within its
precision. `FoldPattern.fit` says how far the file's numbers were from it and which moved the most; a form beyond its
precision is read all the same (its check fails), and only one with no such state near it is refused.

Frames. Each entry of `file_frames` gives one row of fold angles: its own edges_foldAngle, else the dihedral angles
of its own vertices_coords (Origami Simulator's exports), else what it inherits (`frame_inherit`; without
`frame_parent` the parent is the key frame). Frames must keep the crease pattern's edges_vertices.

Writing (`fold_dict`). Creases first (FOLD edge k = crease k), then the boundary as "B"; angles in degrees as
given (continuous along the frames, in [-180, 180]). With fold angles, the letters come from the motion, never
"U" with an angle (FOLD's unassigned creases are unfolded by viewers): "F" at 0 deg for a crease within
`flat_tol` of flat in every state, else V/M by the sign of its largest excursion, a state where it has the
other sign carrying its own edges_assignment; `frame_description` names those and any declared M/V the
motion contradicts. docs/fold_motion.md.

Thick panels. The custom per-edge field `edges_sim_origami:hingeHeight` (FOLD's `edges_<namespace>:...`
form for custom edge data, lengths in `frame_unit`) gives Crease.height along +z; absent means 0. On border
("B") edges it is the height of a neighbouring cell's hinge there (`CreasePattern.border_heights`, which shape
thick panels), or null where there is none.
"""

import json
import os
import reprlib
import sys
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy import sparse as sp

from . import fold_mesh
from .closure import Coupling, LoopSystem
from .creases import Crease, CreasePattern
from .errors import ParameterError
from .files import write_text
from .fold_mesh import Face, key, reverse
from .path import correct
from .precision import EXACT_ULPS, Adjustment, Typed

FILE_SPEC = 1.2
HEIGHT_KEY = "edges_sim_origami:hingeHeight"
# The precision (frame_unit) of a frame's vertices_coords, as the user states it; otherwise read from the numbers' text.
PRECISION_KEY = "frame_sim_origami:precision"
# A folded form's nearest rigid state reports this many of its coordinates' moves (the largest against their
# precision) as adjustments; the verdict counts them all.
ADJUSTMENTS_SHOWN = 4
# A folded form whose pattern has no freedom without special geometry is fitted with this many further states on its
# rigid motion (`_on_a_motion`): a 3 x 3 Miura sheet printed to 4 decimals then folds to its lock, as does Hull's
# square twist (6 decimals) through its state. Up to this many vertices: a 10 x 10 sheet's fit (121 vertices, 1815
# coordinates with its further states) took 7.6 s CPU and its unfolding still placed vertices 1.4e-9 of the size
# apart (the developable state stood).
MOTION_STATES = 4
FREE_STATES = 1e6
MOTION_VERTICES = 50
# ... unless the developable state's closure Jacobian already has a null direction, its smallest singular value at
# most this fraction of its largest.
MOBILE_RTOL = 1e-13
# Their guesses close the loops as far as the rounded pattern lets them (a least-squares minimum, 3e-9 to 2e-8 on the
# 4-decimal Miura sheet): the fit closes them.
GUESS_TOL = 1e-14
# Fold angles printed to every digit are held to this (rad): exact states (closed forms, the numeric closure, the
# motions this tool writes) close to it (tolerances.closed_form_rad), not to their last printed digit.
EXACT_ANGLE = 1e-12
# Crease angles (rad) within this of flat or of +-pi do not mark a state along a motion.
FOLDED = 1e-3
# Metres per FOLD frame_unit; "unit" (no physical meaning) is read as metres.
UNITS = {
    "unit": 1.0, "km": 1e3, "m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "nm": 1e-9, "in": 0.0254, "pt": 0.0254 / 72,
}
# FOLD assignment -> crease assignment, seen from +z (UP) or from -z (DOWN: every face clockwise).
UP = {"M": "M", "V": "V", "U": "U", "F": "F"}
DOWN = {"M": "V", "V": "M", "U": "U", "F": "F"}
LETTERS = ("B", "M", "V", "F", "U", "C", "J")
# Sector-angle sum at an interior vertex vs 2 pi (rad).
DEVELOPABLE_TOL = 1e-9
# A face is degenerate when |area| <= AREA_RTOL * (its longest side)^2; an edge when its length <= this * size.
AREA_RTOL = 1e-12
# A written crease whose |rho| (rad) never exceeds this is F (flat). Exact states (closed form, numeric closure)
# hold to 1e-12 rad (tolerances.closed_form_rad), so 1e-9 stays 1000x above their noise and far below any
# visible fold; simulated motions pass their own preset's angle tolerance instead (report.motion_fold).
FLAT_TOL = 1e-9


@dataclass(frozen=True)
class FileNumbering:
    """
    How a FOLD file numbered and measured what its pattern renumbers and rescales, so that a file written from the
    pattern (`fold_dict`) can keep them: `unit` its frame_unit, `per_unit` pattern lengths per file unit (the
    pattern's vertices over the file's), `vertex_of` the file vertex of each pattern vertex (cuts double some),
    `edges` the file's edges_vertices in its order.
    """

    unit: str
    per_unit: float
    vertex_of: tuple[int, ...]
    edges: tuple[tuple[int, int], ...]

    def scaled(self, factor: float) -> "FileNumbering":
        """The same numbering for the pattern's vertices times `factor` (e.g. scaled to a unit size)."""
        return replace(self, per_unit=self.per_unit * factor)


@dataclass(frozen=True)
class FoldPattern:
    """
    A FOLD file read as a crease pattern. `fold_angles` (n_creases,) rad: the key frame's fold state (its
    edges_foldAngle, or the dihedral angles of a folded form), NaN where unknown, or None; `frames`
    (n_frames, n_creases) rad: one row per `file_frames` entry, or None; both in `pattern.creases` order.
    `edge_of_crease`: the FOLD edge index of each crease. `frames_from_coords`: some frame's angles were
    measured from its 3-D vertices_coords (whose panels may bend). `notes`: one sentence per thing the reader
    did. `unit_scale`: metres per file unit. `numbering`: the file's unit and numbering, for writing files that keep
    them.
    """

    pattern: CreasePattern
    fold_angles: NDArray[np.float64] | None
    edge_of_crease: tuple[int, ...]
    frames: NDArray[np.float64] | None
    frames_from_coords: bool = False
    notes: tuple[str, ...] = ()
    unit_scale: float = 1.0
    fit: "FormFit | AngleFit | None" = None
    numbering: FileNumbering | None = None


@dataclass(frozen=True)
class StateFit:
    """
    A folded state in the file against the nearest rigid one: `ratio` the largest move over the moved value's precision
    (<= 1: within what its printing allows), `distance` the largest move and `precision` the precision of the value
    moved the most against it (in the fit's unit); `compared` says what was compared with what, `values` how many
    numbers; `adjustments` the values moved the most.
    """

    ratio: float
    distance: float
    precision: float
    compared: str
    adjustments: tuple[Adjustment, ...]
    values: int

    @property
    def within(self) -> bool:
        """The file's state is rigid within its precision."""
        return self.ratio <= 1.0


@dataclass(frozen=True)
class FormFit(StateFit):
    """
    A folded form (`StateFit`), which is what is read (its unfolding, its dihedral angles): lengths in the file's
    `unit`; the largest vertex move at file vertex `vertex` (on creases `creases`), `size` the form's bounding-box
    diagonal.
    """

    field: str
    unit: str
    size: float
    vertex: int
    creases: tuple[str, ...]

    def text(self) -> str:
        """The distance in words: absolute, against the size and the precision, and where it is largest."""
        unit = f" {self.unit}" if self.unit else ""
        at = f" (creases {', '.join(self.creases[:6])})" if self.creases else ""
        return (f"{self.field} are {self.distance:.3g}{unit} ({self.distance / self.size:.3g} of the form's size "
                f"{self.size:.4g}{unit}) from the nearest rigid folded state, {self.ratio:.3g} x the precision "
                f"{self.precision:.3g}{unit} of the coordinate moved most, largest at vertex {self.vertex}{at}; "
                f"{self.compared}")


@dataclass
class _Sheet:
    """A crease pattern read from one frame, with what is needed to measure other frames' fold angles."""

    pattern: CreasePattern
    edge_of_crease: tuple[int, ...]
    source: NDArray[np.int_]  # file vertex of each pattern vertex
    hinges: list[tuple[int, int, int, int]]  # per crease: start, end, left face, right face
    signs: NDArray[np.float64]  # per crease: +1 V, -1 M, 0 otherwise (pattern's view)
    sign: float  # -1 when the file is seen from -z
    n_file_vertices: int
    edges_vertices: Any
    unit_scale: float
    unit: str  # the frame_unit its lengths were given in
    folded_xyz: NDArray[np.float64] | None  # a folded form's nearest rigid state, per pattern vertex (file units)
    notes: list[str] = field(default_factory=list)
    fit: FormFit | None = None
    measured: list[NDArray[np.float64]] = field(default_factory=list)  # fold angles measured from coordinates
    # other frames' coordinates against their nearest rigid states of this pattern: (field, unit, fit)
    frame_fits: list[tuple[str, str, fold_mesh.Fit]] = field(default_factory=list)


class _FoldedFormError(ParameterError):
    """A folded form that a crease-pattern frame, when the file has one, replaces; `short`: why, in a few words."""

    def __init__(self, message: str, short: str):
        super().__init__(message)
        self.short = short


def read_fold(source: str | os.PathLike | Mapping[str, Any]) -> FoldPattern:
    """Read a FOLD file (path) or its parsed JSON (mapping); the module docstring states the rules."""
    doc = _load(source)
    key = {name: value for name, value in doc.items() if not name.startswith("file_")}
    raw = _list(doc.get("file_frames", []), "file_frames")
    for k, frame in enumerate(raw):
        if not isinstance(frame, dict):
            raise ParameterError(f"file_frames[{k}] is a {type(frame).__name__}; a frame is a JSON object")
    frames = _resolve_all(raw, key)
    crease_frame = next((k for k, f in enumerate(frames) if _is_crease_pattern(f)), None)
    if crease_frame is not None:
        other, label = frames[crease_frame], f"frame {crease_frame + 1} vertices_coords"
        where = f"frame {crease_frame + 1} (frame_classes creasePattern)"
    elif "vertices_flatUnfoldCoords" in key:  # Crease Pattern Editor's flat folds carry their unfolding
        other = {**key, "vertices_coords": key["vertices_flatUnfoldCoords"]}
        label = where = "vertices_flatUnfoldCoords"
    else:
        other, label, where = None, "", ""
    if "vertices_coords" in key:
        try:
            sheet = _read_sheet(key, "vertices_coords", prefer_frame=other is not None)
            geometry = key
        except _FoldedFormError as why:
            if other is None:
                raise
            geometry = other
            sheet = _read_sheet(geometry, label, prefer_frame=False)
            sheet.notes.insert(0, f"the key frame is a folded form ({why.short}); the crease pattern is {where}")
    else:
        pick = crease_frame if crease_frame is not None else next(
            (k for k, f in enumerate(frames) if "vertices_coords" in f), None)
        if pick is None:
            raise ParameterError("FOLD field 'vertices_coords' is missing from the key frame and every file_frames "
                                 "entry; a crease pattern needs vertex coordinates")
        geometry = frames[pick]
        sheet = _read_sheet(geometry, f"frame {pick + 1} vertices_coords", prefer_frame=False)
        why = "frame_classes creasePattern" if pick == crease_frame else "the first frame with vertices_coords"
        sheet.notes.insert(0, f"the top level has no vertices_coords; the crease pattern is frame {pick + 1} ({why})")
    n_notes = len(sheet.notes)
    fold_angles, rows, from_coords = _angles(key, geometry, raw, frames, sheet)
    agree, disagree = _letter_agreement(sheet)
    if disagree > agree:  # the faces' loops are oriented for the other side of the paper than its letters
        del sheet.notes[n_notes:]
        sheet = _swap_letters(sheet)
        sheet.notes.append(f"the M/V letters disagree with the measured fold directions at {disagree} of "
                           f"{agree + disagree} creases: the file's faces run for the other side of the paper, "
                           "so M and V are read swapped")
        fold_angles, rows, from_coords = _angles(key, geometry, raw, frames, sheet)
    _say_sign_conflicts(sheet, fold_angles, rows)
    fit: FormFit | AngleFit | None = _worst(sheet)
    complete = fold_angles is not None and bool(np.all(np.abs(fold_angles) < np.pi - FOLDED))  # NaN: free
    if fit is None and "edges_foldAngle" in key and complete and np.any(fold_angles != 0):
        fold_angles, fit = _nearest_closed(key, sheet, fold_angles, sheet.notes)
    numbering = FileNumbering(sheet.unit, sheet.unit_scale, tuple(int(v) for v in sheet.source),
                              tuple((int(a), int(b)) for a, b in sheet.edges_vertices))
    return FoldPattern(sheet.pattern, fold_angles, sheet.edge_of_crease, rows, from_coords, tuple(sheet.notes),
                       sheet.unit_scale, fit, numbering)


def fold_dict(
    pattern: CreasePattern,
    fold_angles: ArrayLike | None = None,
    frames: ArrayLike | None = None,
    *,
    title: str = "sim_origami crease pattern",
    creator: str = "sim_origami",
    flat_tol: float = FLAT_TOL,
    notes: tuple[str, ...] = (),
    numbering: FileNumbering | None = None,
) -> dict[str, Any]:
    """
    FOLD 1.2 data of a pattern: edges are its creases (in order, FOLD edge k = crease k) then the
    boundary, lengths in metres; with the `numbering` of the file the pattern was read from, in that file's unit
    and its vertex and edge numbers (`_renumbered`). The key frame holds `fold_angles` (n_creases,) rad, or 0;
    each row of `frames` (n_frames, n_creases) rad becomes a `file_frames` entry inheriting from the key frame.
    Fold angles are written in degrees, as given (continuous along the frames), and must lie in [-pi, pi].

    Assignments (`assign_creases`): without any fold angle given, each crease keeps the pattern's M/V/U.
    With angles, they come from the motion: `F` (written as 0 deg) for a crease whose |rho| stays within
    `flat_tol` rad in every state, otherwise V or M by the sign of its largest excursion. A state (key frame
    or frame) in which a crease has the other sign carries its own edges_assignment, so that every written
    angle has the sign of its letter and no crease is `U` with an angle. `frame_description` lists such
    sign changes, any declared M/V that the motion contradicts, and `notes`.
    """
    boundary = _boundary_edges(pattern)
    n, pad = len(pattern.creases), [0.0] * len(boundary)
    rows = np.empty((0, n)) if frames is None else _frame_rows(frames, n)
    key = np.zeros(n) if fold_angles is None else np.asarray(fold_angles, dtype=float)
    states = np.vstack([_fold_radians(key, n, "fold_angles"), *(_fold_radians(r, n, f"frames[{k}]")
                        for k, r in enumerate(rows))])
    if fold_angles is None and not len(rows):
        letters, said = np.array([[c.assignment for c in pattern.creases]]), []
    else:
        letters, said = assign_creases(pattern, states, flat_tol)
        states = np.where(letters == "F", 0.0, states)
    doc = {
        "file_spec": FILE_SPEC,
        "file_creator": creator,
        "file_classes": ["singleModel", "animation"] if len(rows) else ["singleModel"],
        "frame_title": title,
        "frame_classes": ["creasePattern"],
        "frame_attributes": ["2D"],
        "frame_unit": "m",
        "vertices_coords": np.asarray(pattern.vertices, dtype=float).tolist(),
        "edges_vertices": [[int(c.start), int(c.end)] for c in pattern.creases] + [list(e) for e in boundary],
        "edges_assignment": letters[0].tolist() + ["B"] * len(boundary),
        "edges_foldAngle": np.rad2deg(states[0]).tolist() + pad,
        "faces_vertices": [[int(v) for v in face] for face in pattern.faces],
    }
    if said or notes:
        doc["frame_description"] = " ".join([*said, *notes])
    if any(c.height != 0.0 for c in pattern.creases) or any(h != 0.0 for *_, h in pattern.border_heights):
        known = {frozenset((a, b)): float(h) for a, b, h in pattern.border_heights}
        doc[HEIGHT_KEY] = [float(c.height) for c in pattern.creases] + [known.get(frozenset(e)) for e in boundary]
    if len(rows):
        doc["file_frames"] = []
        for rho, own in zip(states[1:], letters[1:], strict=True):
            frame = {"frame_inherit": True, "frame_parent": 0, "frame_classes": ["creasePattern"],
                     "edges_foldAngle": np.rad2deg(rho).tolist() + pad}
            if np.any(own != letters[0]):
                frame["edges_assignment"] = own.tolist() + ["B"] * len(boundary)
            doc["file_frames"].append(frame)
    return doc if numbering is None else _renumbered(doc, numbering)


def _renumbered(doc: dict[str, Any], numbering: FileNumbering) -> dict[str, Any]:
    """
    `fold_dict`'s data in the unit and numbering of the file read: coordinates in its frame_unit, and where the
    pattern kept its vertices (no cut doubled one) and every edge is one of the file's, its edges in the file's
    order; otherwise `vertices_sim_origami:fileVertex` and `edges_sim_origami:fileEdge` give each written vertex's and
    edge's number in the file (null: none there).
    """
    coords = np.asarray(doc["vertices_coords"]) / numbering.per_unit  # 15 digits: 100 mm, not 100.00000000000001
    doc = doc | {"frame_unit": numbering.unit, "vertices_coords": [[float(f"{x:.15g}") for x in v] for v in coords]}
    vertex_of = numbering.vertex_of
    index = {key(a, b): k for k, (a, b) in enumerate(numbering.edges)}
    file_edge = [index.get(key(vertex_of[a], vertex_of[b])) for a, b in doc["edges_vertices"]]
    kept = list(vertex_of) == list(range(len(vertex_of))) and sorted(e for e in file_edge if e is not None) == list(
        range(len(numbering.edges))) and None not in file_edge
    if not kept:
        return doc | {"vertices_sim_origami:fileVertex": list(vertex_of), "edges_sim_origami:fileEdge": file_edge}
    order = np.argsort(file_edge)

    def reorder(frame: dict[str, Any]) -> dict[str, Any]:
        return frame | {name: [value[k] for k in order] for name, value in frame.items()
                        if name.startswith("edges_") and isinstance(value, list)}

    out = reorder(doc)
    if "file_frames" in doc:
        out["file_frames"] = [reorder(frame) for frame in doc["file_frames"]]
    return out


def assign_creases(
    pattern: CreasePattern, states: ArrayLike, flat_tol: float = FLAT_TOL
) -> tuple[NDArray[np.str_], list[str]]:
    """
    FOLD letters (n_states, n_creases) for fold angles `states` (n_states, n_creases) rad, and sentences
    saying where they depart from one letter per crease or from the pattern's declared M/V.

    A crease is `F` in every state when max |rho| <= flat_tol; otherwise its letter is V (rho > 0, valley
    seen from +z) or M by the sign of its largest |rho|, and a state where rho has the other sign gets the
    letter of that sign (rho = 0 keeps the crease's letter).
    """
    rho = np.asarray(states, dtype=float)
    names = [c.name for c in pattern.creases]
    peak = rho[np.argmax(np.abs(rho), axis=0), np.arange(rho.shape[1])]
    flat = np.abs(peak) <= flat_tol
    overall = np.where(flat, "F", np.where(peak > 0, "V", "M"))
    letters = np.where(rho > 0, "V", np.where(rho < 0, "M", overall))
    letters = np.where(flat, "F", letters)
    said = []
    flips = [k for k in range(len(names)) if np.any(letters[:, k] != overall[k])]
    if flips:
        said.append(
            f"Creases {', '.join(names[k] for k in flips)} change sign along the motion: each is assigned by its "
            "largest excursion, and the frames where it has the other sign carry their own edges_assignment."
        )
    contradicted = [
        f"{c.name} ({c.assignment} declared, {overall[k]} in the motion)"
        for k, c in enumerate(pattern.creases)
        if c.assignment in ("M", "V") and overall[k] != c.assignment
    ]
    if contradicted:
        said.append(f"The motion contradicts the pattern's declared assignment at {', '.join(contradicted)}.")
    return letters, said


def write_fold(
    path: str | os.PathLike,
    pattern: CreasePattern,
    frames: ArrayLike | None = None,
    *,
    fold_angles: ArrayLike | None = None,
    title: str = "sim_origami crease pattern",
    creator: str = "sim_origami",
    flat_tol: float = FLAT_TOL,
    notes: tuple[str, ...] = (),
    numbering: FileNumbering | None = None,
) -> Path:
    """Write `fold_dict(pattern, fold_angles, frames, ...)` as a .fold JSON file, atomically; returns the path."""
    doc = fold_dict(pattern, fold_angles, frames, title=title, creator=creator, flat_tol=flat_tol, notes=notes,
                    numbering=numbering)
    return write_text(path, json.dumps(doc, indent=1) + "\n")


def _load(source: str | os.PathLike | Mapping[str, Any]) -> Mapping[str, Any]:
    """The FOLD JSON object of a path or an already parsed mapping."""
    if isinstance(source, Mapping):
        return source
    try:  # each float keeps the precision of its text (`precision.Typed`); NaN and Infinity are no JSON numbers
        doc = json.loads(Path(source).read_text(), parse_float=Typed, parse_int=_integer, parse_constant=_constant)
    except json.JSONDecodeError as err:
        raise ParameterError(f"{source} is not JSON ({err}); a FOLD file is a JSON object") from err
    except OSError as err:
        raise ParameterError(f"cannot read FOLD file {source}: {err.strerror}") from err
    except UnicodeDecodeError as err:
        raise ParameterError(f"{source} is not UTF-8 text ({err.reason}); a FOLD file is JSON text") from err
    except RecursionError:  # the reader recurses once per array or object level
        raise ParameterError(f"{source} nests its JSON arrays or objects thousands of levels deep; a FOLD file's "
                             "fields are at most three levels deep") from None
    if not isinstance(doc, dict):
        raise ParameterError(f"{source} holds a JSON {type(doc).__name__}; a FOLD file is a JSON object")
    return doc


class _LongInteger:
    """An integer whose text is longer than Python converts (4300 digits): kept as its length, refused where read."""

    def __init__(self, text: str):
        self.digits = len(text.lstrip("-"))

    def __repr__(self) -> str:
        return f"an integer of {self.digits} digits"


def _integer(text: str) -> "int | _LongInteger":
    """A JSON integer; one too long for int() is read as a _LongInteger, refused only in a field that is read (a
    custom or metadata field may hold anything)."""
    try:
        return int(text)
    except ValueError:
        return _LongInteger(text)


def _constant(text: str) -> float:
    """JSON has no NaN or Infinity, though Python's reader takes them: refused (null is FOLD's unknown value)."""
    raise ParameterError(f"the FOLD file holds {text}, which is no JSON number; give finite numbers (null where a fold "
                         "angle is unknown)")


def _shown(value: Any) -> str:
    """A value of the file as a refusal quotes it: short whatever its size or depth."""
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 1024:
        return f"an integer of about {int(value.bit_length() * np.log10(2)) + 1} digits"
    return reprlib.repr(value)


def _number(value: Any, where: str, allow_null: bool) -> float:
    """One number of a FOLD number field, named `where` in a refusal: finite, within a double's range, and not a
    boolean or a string (which numpy would read as 1.0 or parse); null is NaN where allowed."""
    if value is None and allow_null:
        return np.nan
    if isinstance(value, _LongInteger) or (isinstance(value, int) and not isinstance(value, bool)
                                           and abs(value) > sys.float_info.max):
        raise ParameterError(f"{where} = {_shown(value)}; numbers must lie within a double's range (+-1.8e308)")
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        null = " or null" if allow_null else ""
        raise ParameterError(f"{where} = {_shown(value)} ({_json_type(value)}); it must be a number{null}")
    if not np.isfinite(value):
        raise ParameterError(f"{where} = {value}; numbers must be finite" + ("; null is an unknown value" if allow_null
                                                                             else ""))
    return float(value)


def _json_type(value: Any) -> str:
    """The JSON name of a Python value's type, with its article."""
    names = {bool: "a boolean", str: "a string", list: "an array", dict: "an object", type(None): "null"}
    return names.get(type(value), f"a {type(value).__name__}")


def _unit_scale(unit: Any) -> float:
    """Metres per FOLD frame_unit."""
    if not isinstance(unit, str) or unit not in UNITS:
        raise ParameterError(f"frame_unit = {unit!r}; sim_origami reads {', '.join(UNITS)}")
    return UNITS[unit]


def _numbers(values: list, field: str, allow_null: bool = False) -> NDArray[np.float64]:
    """A FOLD list of numbers as floats, each checked by `_number` and named by its index; null is NaN where
    allowed."""
    return np.array([_number(x, f"{field}[{i}]", allow_null) for i, x in enumerate(values)], dtype=float)


def _per_edge(value: Any, n_edges: int, field: str, allow_null: bool = False) -> NDArray[np.float64]:
    """A per-edge number field (n_edges,); null entries are NaN when allowed."""
    rows = _list(value, field)
    if len(rows) != n_edges:
        raise ParameterError(f"{field} has {len(rows)} entries; it needs one number per edge ({n_edges})")
    return _numbers(rows, field, allow_null=allow_null)


def _heights(value: Any, letters: list[str]) -> NDArray[np.float64]:
    """The hinge-height field (n_edges,): numbers, null (NaN) allowed on border and cut edges only."""
    if not isinstance(value, list) or len(value) != len(letters):
        raise ParameterError(f"{HEIGHT_KEY} needs one entry per edge ({len(letters)})")
    for k, (entry, letter) in enumerate(zip(value, letters, strict=True)):
        if entry is None and letter not in ("B", "C", "J"):
            raise ParameterError(f"{HEIGHT_KEY}[{k}] is null on a {letter!r} edge; only border edges may have no hinge")
    return _numbers(value, HEIGHT_KEY, allow_null=True)


def _degrees(value: Any, creases: tuple[int, ...], n_edges: int, field: str) -> NDArray[np.float64]:
    """
    A FOLD edges_foldAngle (deg) as radians of the crease edges `creases`: null is NaN (unknown); crease entries
    must lie in [-180, 180]; entries of other edges (borders, cuts) are not read.
    """
    deg = _per_edge(value, n_edges, field, allow_null=True)[list(creases)]
    bad = np.flatnonzero(np.abs(deg) > 180.0)
    if bad.size:
        raise ParameterError(
            f"{field}[{creases[bad[0]]}] = {deg[bad[0]]:g} deg; FOLD fold angles lie in [-180, 180] deg"
        )
    return np.deg2rad(deg)


def _list(value: Any, field: str) -> list:
    if not isinstance(value, list):
        raise ParameterError(f"{field} is a {type(value).__name__}; FOLD stores it as a JSON array")
    return value


def _coords(value: Any, field: str) -> tuple[NDArray[np.float64], int]:
    """Vertex coordinates as (n, 3) (2-D ones get z = 0) and their dimension (2 or 3)."""
    rows, dim = [], 2
    for v, c in enumerate(_list(value, field)):
        if not isinstance(c, list) or len(c) not in (2, 3):
            raise ParameterError(f"{field}[{v}] = {c!r}; a vertex has 2 or 3 coordinates")
        dim = max(dim, len(c))
        rows.append([*(_number(x, f"{field}[{v}][{j}]", False) for j, x in enumerate(c)), 0.0][:3])
    if not rows:
        raise ParameterError(f"{field} is empty; a crease pattern needs vertices")
    return np.array(rows, dtype=float), dim


def _vertex_lists(value: Any, field: str, n_vertices: int) -> list[tuple[int, ...]]:
    """Lists of vertex indices, each in [0, n_vertices)."""
    out = []
    for k, item in enumerate(_list(value, field)):
        ok = isinstance(item, list) and all(type(i) is int and 0 <= i < n_vertices for i in item)
        if not ok:
            raise ParameterError(f"{field}[{k}] = {item!r}; it must list vertex indices in [0, {n_vertices})")
        out.append(tuple(item))
    return out


def _edges(value: Any, n_vertices: int) -> list[tuple[int, int]]:
    """Edges as (u, v) of two distinct vertices; no two edges join the same pair."""
    edges = _vertex_lists(value, "edges_vertices", n_vertices)
    first: dict[tuple[int, int], int] = {}
    for k, e in enumerate(edges):
        if len(e) != 2 or e[0] == e[1]:
            raise ParameterError(f"edges_vertices[{k}] = {list(e)}; an edge joins two distinct vertices")
        other = first.setdefault(key(*e), k)
        if other != k:
            raise ParameterError(f"edges {other} and {k} both join vertices {e[0]} and {e[1]}; edges must differ")
    return edges


def _assignments(value: Any, n_edges: int) -> list[str] | None:
    """FOLD assignment letters, one per edge, in upper case: B, M, V, F, U, C or J (None when absent)."""
    if value is None:
        return None
    letters = _list(value, "edges_assignment")
    if len(letters) != n_edges:
        raise ParameterError(f"edges_assignment has {len(letters)} entries; it needs one per edge ({n_edges})")
    out = []
    for k, letter in enumerate(letters):
        if not isinstance(letter, str) or letter.upper() not in LETTERS:
            raise ParameterError(
                f"edge {k} has assignment {letter!r}; FOLD assignments are {', '.join(LETTERS)} (either case)"
            )
        out.append(letter.upper())
    return out


def _file_faces(frame: Mapping[str, Any], edges: list[tuple[int, int]], n_vertices: int) -> list[Face] | None:
    """faces_vertices, or faces_edges turned into vertex loops; None when the file has neither (or empty)."""
    if frame.get("faces_vertices"):
        faces = _vertex_lists(frame["faces_vertices"], "faces_vertices", n_vertices)
    elif frame.get("faces_edges"):
        loops = _vertex_lists(frame["faces_edges"], "faces_edges", len(edges))
        faces = fold_mesh.faces_from_edges(loops, edges)
    else:
        return None
    for k, face in enumerate(faces):
        if len(face) < 3 or len(set(face)) != len(face):
            raise ParameterError(f"face {k} {list(face)} must list 3 or more distinct vertices")
    return faces


def _cross(a: tuple[float, float], b: tuple[float, float]) -> float:
    """z of the cross product of 2-D vectors."""
    return a[0] * b[1] - a[1] * b[0]


def _segments_meet(p: tuple, q: tuple, r: tuple, s: tuple) -> bool:
    """Whether the closed segments pq and rs (points as float pairs) share a point."""

    def sub(a: tuple, b: tuple) -> tuple[float, float]:
        return a[0] - b[0], a[1] - b[1]

    d = (_cross(sub(q, p), sub(r, p)), _cross(sub(q, p), sub(s, p)), _cross(sub(s, r), sub(p, r)),
         _cross(sub(s, r), sub(q, r)))
    if d[0] * d[1] < 0 and d[2] * d[3] < 0:
        return True
    ends = ((d[0], r, p, q), (d[1], s, p, q), (d[2], p, r, s), (d[3], q, r, s))
    return any(o == 0 and all(min(a[i], b[i]) <= x[i] <= max(a[i], b[i]) for i in (0, 1)) for o, x, a, b in ends)


def _check_areas(faces: list[Face], xy: NDArray[np.float64], unit: str = "m^2") -> NDArray[np.float64]:
    """Signed areas of the faces, each non-zero relative to its longest side squared."""
    areas = fold_mesh.signed_areas(xy, faces)
    f_of, v, nxt, _ = fold_mesh.corners(faces)
    longest = np.zeros(len(faces))
    np.maximum.at(longest, f_of, np.sum((xy[nxt] - xy[v]) ** 2, axis=1))
    bad = np.flatnonzero(np.abs(areas) <= AREA_RTOL * longest)
    if bad.size:
        k = int(bad[0])
        raise ParameterError(f"face {k} {list(faces[k])} has area {areas[k]:.3g} {unit}; faces must not be degenerate")
    return areas


def _check_faces(faces: list[Face], xy: NDArray[np.float64]) -> None:
    """Counter-clockwise faces must have non-zero area and be simple polygons (no spike, no meeting sides)."""
    _check_areas(faces, xy)
    _, angles = fold_mesh.corner_angles(xy, faces)
    spikes = np.flatnonzero(angles == 0.0)
    if spikes.size:
        f_of, v, _, _ = fold_mesh.corners(faces)
        k = int(f_of[spikes[0]])
        raise ParameterError(f"face {k} doubles back at vertex {v[spikes[0]]}; faces must be simple polygons")
    for k, face in enumerate(faces):
        if len(face) > 3:  # a triangle of non-zero area is simple
            _check_simple(k, face, [tuple(p) for p in xy[list(face)].tolist()])


def _check_simple(k: int, face: Face, p: list[tuple[float, float]]) -> None:
    """A counter-clockwise face (vertices p) must not have two sides that meet."""
    n = len(face)
    for i in range(n):
        for j in range(i + 2, n - (i == 0)):
            if _segments_meet(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n]):
                raise ParameterError(
                    f"face {k}: sides {face[i]}-{face[(i + 1) % n]} and {face[j]}-{face[(j + 1) % n]} meet; "
                    "faces must be simple polygons"
                )


def _sides(face: tuple[int, ...]) -> Iterator[tuple[int, int]]:
    """The directed sides (a, b) of a face."""
    return zip(face, face[1:] + face[:1], strict=True)


def _split_cuts_as_borders(edges: list[tuple[int, int]], letters: list[str], faces: list[Face],
                           notes: list[str]) -> list[str]:
    """
    `letters` with each C edge that borders one face read as B: a cut written already split (its vertices doubled,
    each side an edge of its own, as some writers give a slit) is a border on each side. A note counts them.
    """
    count = Counter(key(*side) for face in faces for side in _sides(face))
    split = {k for k, (e, letter) in enumerate(zip(edges, letters, strict=True))
             if letter == "C" and count[key(*e)] == 1}
    if not split:
        return letters
    notes.append(f"{len(split)} cut edge(s) C bordering one face each (a cut written with its vertices already "
                 "doubled) read as borders")
    return ["B" if k in split else letter for k, letter in enumerate(letters)]


def _check_incidence(edges: list[tuple[int, int]], letters: list[str], faces: list[Face]) -> None:
    """Every face side is an edge; a boundary edge borders one face, every other edge two."""
    index = {key(*e) for e in edges}
    count = Counter(key(*side) for face in faces for side in _sides(face))
    for f, face in enumerate(faces):
        for a, b in _sides(face):
            if key(a, b) not in index:
                raise ParameterError(f"side {a}-{b} of face {f} is not in edges_vertices; every face side is an edge")
    for k, (e, letter) in enumerate(zip(edges, letters, strict=True)):
        n, need = count[key(*e)], 1 if letter == "B" else 2
        if n != need:
            rule = {"B": "a boundary edge borders one face", "C": "a cut runs between two faces",
                    "J": "a join merges two faces"}.get(letter, "a crease joins two faces")
            raise ParameterError(f"edge {k} ({e[0]}-{e[1]}, {letter!r}) borders {n} face(s); {rule}")


def _check_developable(pattern: CreasePattern, tol: float = DEVELOPABLE_TOL) -> None:
    """
    Sector angles round each interior vertex must sum to 2 pi within `tol` (rad). A flat fan closes
    at a multiple of 2 pi, so this catches a sheet wrapping round a vertex more than once.
    """
    v, angles = fold_mesh.corner_angles(pattern.vertices, list(pattern.faces))
    total = np.bincount(v, weights=angles, minlength=len(pattern.vertices))
    for v in pattern.interior_vertices():
        if abs(total[v] - 2 * np.pi) > tol:
            raise ParameterError(
                f"interior vertex {v}: sector angles sum to {np.rad2deg(total[v]):.12g} deg; a developable "
                f"vertex needs 360 deg (within {tol:.3g} rad)"
            )


def _resolve_all(frames: list[dict], key: Mapping[str, Any]) -> list[Mapping[str, Any]]:
    """Every file_frames entry with the properties it inherits (frame_inherit; no frame_parent: the key frame)."""
    done: dict[int, Mapping[str, Any]] = {0: key}
    for start in range(1, len(frames) + 1):
        chain, k, seen = [], start, set()
        while k not in done:
            frame = frames[k - 1]
            chain.append((k, frame))
            if frame.get("frame_inherit") is not True:
                done[k] = frame
                chain.pop()
                break
            parent = frame.get("frame_parent", 0)
            if type(parent) is not int or not 0 <= parent <= len(frames) or parent in seen or parent == k:
                raise ParameterError(
                    f"frame {k} inherits from frame_parent = {parent!r}; it must name a frame in [0, "
                    f"{len(frames)}] without an inheritance cycle"
                )
            seen.add(k)
            k = parent
        for j, frame in reversed(chain):
            done[j] = {**done[k], **frame}
            k = j
    return [done[k] for k in range(1, len(frames) + 1)]


def _is_crease_pattern(frame: Mapping[str, Any]) -> bool:
    classes = frame.get("frame_classes")
    return isinstance(classes, list) and "creasePattern" in classes and "vertices_coords" in frame


def _read_sheet(frame: Mapping[str, Any], label: str, prefer_frame: bool) -> _Sheet:
    """
    The crease pattern of one frame (resolved). `prefer_frame`: a folded form raises _FoldedFormError (the caller
    has a crease-pattern frame) instead of being unfolded; a flat-folded form always does.
    """
    notes: list[str] = []
    scale = _unit_scale(frame.get("frame_unit", "unit"))
    xyz, dim = _coords(frame["vertices_coords"], "vertices_coords")
    n = len(xyz)
    if "edges_vertices" not in frame:
        raise ParameterError("FOLD field 'edges_vertices' is missing; a crease pattern needs its edges")
    edges = _edges(frame["edges_vertices"], n)
    letters = _assignments(frame.get("edges_assignment"), len(edges))
    faces = _file_faces(frame, edges, n)
    extent = fold_mesh.size(xyz)
    if extent == 0.0:
        raise ParameterError("vertices_coords are all one point; a crease pattern needs a sheet of non-zero size")
    ends = np.asarray(edges, dtype=int).reshape(-1, 2)
    lengths = np.linalg.norm(xyz[ends[:, 1]] - xyz[ends[:, 0]], axis=1)
    short = np.flatnonzero(lengths <= AREA_RTOL * extent)
    if short.size:
        a, b = edges[short[0]]
        raise ParameterError(f"edge {short[0]} joins vertices {a} and {b} at one point (length "
                             f"{lengths[short[0]]:.3g}); edges must have length")
    flat = dim == 2 or bool(np.all(xyz[:, 2] == xyz[0, 2]))
    xy = xyz[:, :2].copy()
    if not flat:
        rotation, worst, rms = fold_mesh.plane_fit(xyz)
        if worst <= fold_mesh.PLANE_RTOL * extent:
            flat, xy = True, (xyz @ rotation.T)[:, :2]
            normal = np.round(rotation.T @ [0.0, 0.0, 1.0], 12) + 0.0
            n0, n1, n2 = normal
            notes.append(
                f"the sheet ({label}) lies in the plane of normal ({n0:.6g}, {n1:.6g}, {n2:.6g}) (rms "
                f"{rms / extent:.2g}, largest {worst / extent:.2g} of the sheet's size off it), turned into XY"
            )
    if faces is None:
        if not flat:
            raise ParameterError(
                f"{label} are 3-D (a folded form) and there is no faces_vertices or faces_edges; faces are found "
                "from the edge graph of a flat pattern only: add faces_vertices"
            )
        faces = fold_mesh.planar_faces(xy, edges)
        notes.append(f"{len(faces)} faces built from the planar edge graph (no faces_vertices in the file)")
    if letters is None:
        count = Counter(key(*side) for face in faces for side in _sides(face))
        letters = ["B" if count[key(*e)] == 1 else "U" for e in edges]
        notes.append("no edges_assignment: edges of one face read as B, of two faces as U")
    letters = _split_cuts_as_borders(edges, letters, faces, notes)
    _check_incidence(edges, letters, faces)
    if not flat and prefer_frame:
        raise _FoldedFormError(f"{label} are 3-D", "3-D")
    file_faces = faces
    below = flat and _check_areas(faces, xy, "file unit^2").sum() < 0  # the file's faces clockwise (by area)
    by_side = fold_mesh.side_faces(faces)  # undirected side -> faces on it, the same after orienting
    faces = fold_mesh.orient(faces, by_side)
    if flat:
        positive = (fold_mesh.signed_areas(xy, faces) > 0).tolist()
        if not all(positive) and any(positive):
            f, g = positive.index(True), positive.index(False)
            raise _FoldedFormError(
                f"{label} lie in one plane but faces {f} and {g}, given one normal, face opposite ways: a flat-folded "
                "form, whose +-180 deg folds and their order cannot be read without a crease pattern; add the crease "
                "pattern as a file_frames entry with frame_classes creasePattern",
                "folded flat, faces overlapping",
            )
        if not positive[0]:
            faces = [reverse(face) for face in faces]
    turned = sum(a != b for a, b in zip(faces, file_faces, strict=True))
    if 0 < turned < len(faces):
        notes.append(f"{min(turned, len(faces) - turned)} face(s) reversed to give the sheet one normal")
    cuts = {key(*edges[k]) for k, letter in enumerate(letters) if letter == "C"}
    source, new_of = np.arange(n), None
    if cuts:
        faces, source, new_of = fold_mesh.split_cuts(n, faces, cuts)
        notes.append(f"{len(cuts)} cut edge(s) split the paper: {len(source) - n} vertices doubled along them")

    # Edges on the new vertices: a cut becomes one border edge per side, a join disappears.
    def renamed(f: int, a: int, b: int) -> tuple[int, int]:
        return (a, b) if new_of is None else (new_of[f, a], new_of[f, b])

    fit = folded = None
    if flat:
        xy = xy[source]
    else:
        flat_sides = [renamed(by_side[key(*e)][0][0], *e) for e, letter in zip(edges, letters, strict=True)
                      if letter == "F"]
        folded, fit = _nearest_rigid(frame, label, xyz, _panels(faces, flat_sides), source, notes)
        xy, more = fold_mesh.unfold(folded, faces)
        notes.extend(more)
    xy = xy * scale

    new_edges, new_letters, fold_index = edges, letters, list(range(len(edges)))
    if cuts or "J" in letters:
        new_edges, new_letters, fold_index = [], [], []
        for k, (a, b) in enumerate(edges):
            users = by_side.get(key(a, b), [])
            if letters[k] == "J":
                continue
            if letters[k] == "C":
                pieces = [renamed(f, a, b) for f, _ in users]
            else:
                pieces = [renamed(users[0][0], a, b) if users else (a, b)]
            for piece in pieces:
                new_edges.append(piece)
                new_letters.append("B" if letters[k] == "C" else letters[k])
                fold_index.append(k)
    joins = [(k, renamed(by_side[key(*e)][0][0], *e)) for k, e in enumerate(edges) if letters[k] == "J"]
    if joins:
        faces = fold_mesh.merge_joins(faces, joins)
        notes.append(f"{len(joins)} join edge(s) merged their faces: {len(file_faces)} faces became {len(faces)}")
    if cuts or joins:
        _check_incidence(new_edges, new_letters, faces)
    _check_faces(faces, xy)
    faces = _drop_loose(faces, notes)
    heights = np.zeros(len(edges))
    if HEIGHT_KEY in frame:
        heights = scale * _heights(frame[HEIGHT_KEY], letters)
    sign = -1.0 if below else 1.0
    if below:
        notes.append("the faces run clockwise seen from +z: the paper is seen from -z, so M/V and angle signs swap")
    table = DOWN if below else UP
    crease_edges = [j for j, letter in enumerate(new_letters) if letter in table]
    creases = tuple(
        Crease(f"e{fold_index[j]}", *new_edges[j], table[new_letters[j]], float(heights[fold_index[j]]))
        for j in crease_edges
    )
    kept = {key(*side) for face in faces for side in _sides(face)}
    border = tuple((*new_edges[j], float(heights[fold_index[j]])) for j, letter in enumerate(new_letters)
                   if letter == "B" and np.isfinite(heights[fold_index[j]]) and key(*new_edges[j]) in kept)
    pattern = CreasePattern(xy, tuple(faces), creases, tuple(f"f{k}" for k in range(len(faces))), border)
    _check_developable(pattern)
    left = {side: f for f, face in enumerate(faces) for side in _sides(face)}
    hinges = [(c.start, c.end, left[c.start, c.end], left[c.end, c.start]) for c in creases]
    signs = np.array([{"V": 1.0, "M": -1.0}.get(c.assignment, 0.0) for c in creases])
    if fit is not None and (moving := _on_a_motion(fit, pattern, scale, hinges, signs, label, notes)) is not None:
        try:
            xy, _ = fold_mesh.unfold(moving.xyz, faces)
            _check_developable(replace(pattern, vertices=xy * scale))
        except ParameterError as why:  # closed less well than the developable state: that one stands
            notes.append(f"{label}: the state on a rigid motion found does not unfold ({why}); its nearest "
                         "developable state is read")
        else:
            fit, folded, pattern = moving, moving.xyz, replace(pattern, vertices=xy * scale)
    if fit is not None:
        fit = _form_fit(fit, pattern, source, label, frame.get("frame_unit", "unit"))
    return _Sheet(
        pattern, tuple(fold_index[j] for j in crease_edges), source, hinges, signs, sign, n,
        frame["edges_vertices"], scale, frame.get("frame_unit", "unit"), folded, notes, fit,
    )


def _nearest_rigid(
    frame: Mapping[str, Any], label: str, xyz: NDArray[np.float64], faces: list[Face], source: NDArray[np.int_],
    notes: list[str],
) -> tuple[NDArray[np.float64], fold_mesh.Fit]:
    """
    A folded form's nearest developable state (`fold_mesh.nearest_developable`) in units of its coordinates'
    precision (`_coords_precision`), per pattern vertex (file units), with the fit. ParameterError when none is
    found near it (the projection leaves a residual: the faces cannot be made to fit one flat sheet).
    """
    precision = _coords_precision(frame, xyz)[source]
    fit = fold_mesh.nearest_developable(xyz[source], faces, precision)
    extent = fold_mesh.size(xyz)
    if not fit.residual <= fold_mesh.DEVELOP_RTOL * extent:
        raise ParameterError(
            f"folded form not developable: {label} has no developable folded state near it (the nearest found still "
            f"misses its {fit.conditions} by {fit.residual:.3g}, {fit.residual / extent:.3g} of its size): the faces "
            "do not fit one flat sheet"
        )
    if fit.distance > 0:
        notes.append(f"{label}: the nearest developable folded state (planar faces, 360 deg round every interior "
                     f"vertex) is {fit.distance:.3g} file units away, {fit.ratio:.3g} x the coordinates' "
                     "precision")
    return fit.xyz, fit


def _panels(faces: list[Face], flat: list[tuple[int, int]]) -> list[Face]:
    """
    The rigid panels of a sheet whose F creases (vertex pairs `flat`) stay flat, as its model holds them
    (`kinematics.numeric_pattern.lock_flat`): the faces on either side of each merged into one polygon, which the fits
    hold planar. A file written by a simulator or mesher (triangles, their diagonals F) is thereby fitted as its
    quadrilaterals; otherwise each triangle pair could bend a little across its F crease within the precision, and the
    model, holding it flat, would not close. The faces as they are where merging leaves no simple polygons (F creases
    round a loop).
    """
    try:
        return fold_mesh.merge_joins(faces, list(enumerate(flat))) if flat else faces
    except ParameterError:
        return faces


def _pattern_panels(pattern: CreasePattern) -> list[Face]:
    """`_panels` of a crease pattern: its faces merged across its F creases."""
    return _panels(list(pattern.faces), [(c.start, c.end) for c in pattern.creases if c.assignment == "F"])


def _worst(sheet: _Sheet) -> FormFit | None:
    """The folded forms read (the crease pattern's frame unfolded, other frames' coordinates) farthest from their
    nearest rigid states against their precision, and how many were compared; None without any."""
    fits = [sheet.fit] if sheet.fit is not None else []
    fits += [_form_fit(fit, sheet.pattern, sheet.source, label, unit) for label, unit, fit in sheet.frame_fits]
    if len(fits) < 2:
        return fits[0] if fits else None
    worst = max(fits, key=lambda f: f.ratio)
    return replace(worst, compared=f"{worst.compared}; the farthest of {len(fits)} folded states read",
                   values=sum(f.values for f in fits))


def _on_a_motion(
    fit: fold_mesh.Fit, pattern: CreasePattern, scale: float, hinges: list[tuple[int, int, int, int]],
    signs: NDArray[np.float64], label: str, notes: list[str],
) -> fold_mesh.Fit | None:
    """
    For a folded form whose pattern has no freedom unless its geometry is special (creases <= 3 x interior vertices +
    F creases: a Miura or square-twist sheet, which rounding makes rigid), the nearest form that lies on a rigid
    motion of its own pattern: up to MOTION_VERTICES, `fold_mesh.MotionConditions` (MOTION_STATES more states of the
    same faces, guessed by closing the loops at fractions of the most folded crease's angle); where that is not
    found or too large, the nearest flat-foldable state of a quadrilateral mesh (`_flat_foldable`). Used when it is
    found, and within the coordinates' precision or the developable state (`fit`) is not; None otherwise (a note
    says why).
    """
    n_f = sum(c.assignment == "F" for c in pattern.creases)
    if len(pattern.creases) > 3 * len(pattern.interior_vertices()) + n_f:
        return None
    rho = fold_mesh.dihedral_angles(fit.xyz, list(pattern.faces), hinges, signs, label)
    k = int(np.argmax(np.where([c.assignment != "F" for c in pattern.creases], np.abs(rho), -1.0)))
    if not FOLDED < abs(rho[k]) < np.pi - FOLDED:
        return None
    locks = tuple(Coupling(j, j, 0.0) for j, c in enumerate(pattern.creases) if c.assignment == "F")
    loops = pattern.loop_system(locks)
    sigma = np.linalg.svd(loops.jacobian(rho), compute_uv=False)
    if len(sigma) < len(rho) or sigma[-1] <= MOBILE_RTOL * sigma[0]:
        return None  # its state already moves (an exact Miura sheet: 1e-15 of the largest; 6 decimals 1e-11)
    missed = []
    panels = _pattern_panels(pattern)
    if len(fit.xyz) <= MOTION_VERTICES:
        moving = _further_states(fit, pattern, panels, scale, hinges, loops, rho, k, label, missed)
        if moving is not None:
            notes += missed
            return moving
    flat = _flat_foldable(fit, panels, label, notes)
    notes += missed if flat is None else []
    return flat


def _further_states(
    fit: fold_mesh.Fit, pattern: CreasePattern, panels: list[Face], scale: float,
    hinges: list[tuple[int, int, int, int]], loops: LoopSystem, rho: NDArray[np.float64], k: int, label: str,
    notes: list[str],
) -> fold_mesh.Fit | None:
    """`_on_a_motion`'s fit with MOTION_STATES further states of the same panels (`_panels`; crease k the most folded
    of rho)."""
    fixed = np.zeros(len(rho), dtype=bool)
    fixed[k] = True
    faces = list(pattern.faces)
    flat = pattern.vertices / scale  # file units, as fit.xyz
    root = hinges[k][3]
    states = []
    for t in np.linspace(0.0, 1.0, MOTION_STATES + 2)[1:-1]:
        q = correct(loops, t * rho, fixed, GUESS_TOL, max_iter=100)[0]
        xyz = fold_mesh.place(flat, faces, hinges, q, root)
        rotation, shift = fold_mesh.superpose(xyz[list(faces[root])], fit.xyz[list(faces[root])])
        states.append(np.where(np.isnan(xyz), fit.xyz, xyz @ rotation.T + shift))
    a, b, left, right = hinges[k]
    marker = tuple(max((v for v in faces[f] if v not in (a, b)),
                       key=lambda v: np.linalg.norm(np.cross(fit.xyz[b] - fit.xyz[a], fit.xyz[v] - fit.xyz[a])))
                   for f in (left, right))
    conditions = fold_mesh.MotionConditions(fit.xyz, panels, states, faces[root], marker)
    # the further states are free to move: 1e6 x the form's precision (as free as the least squares can tell)
    cheap = np.full(fit.given.shape, FREE_STATES * float(np.max(fit.precision)))
    n = len(fit.given)
    found = fold_mesh.nearest_rigid(np.vstack([fit.given, *states]), np.vstack([fit.precision, *[cheap] * len(states)]),
                                    conditions, bounded=n)
    moving = fold_mesh.Fit(fit.given, found.xyz[:n], fit.precision, found.residual, conditions.describe())
    if not found.residual <= fold_mesh.DEVELOP_RTOL * fold_mesh.size(fit.given):
        notes.append(f"{label}: no state on a rigid motion of its pattern found near it (its conditions missed by "
                     f"{found.residual:.3g}); its nearest developable state is read")
        return None
    if moving.ratio > 1.0 >= fit.ratio:
        notes.append(f"{label}: the nearest state on a rigid motion of its pattern is {moving.ratio:.3g} x the "
                     "coordinates' precision away; its nearest developable state, within it, is read")
        return None
    notes.append(f"{label}: its pattern moves only with special geometry (as many closure conditions as creases), so "
                 f"the nearest state on a rigid motion of it is read: {moving.distance:.3g} file units away, "
                 f"{moving.ratio:.3g} x the coordinates' precision")
    return moving


def _flat_foldable(fit: fold_mesh.Fit, panels: list[Face], label: str, notes: list[str]) -> fold_mesh.Fit | None:
    """
    For a pattern whose interior vertices all have four corners of its panels (`_panels`: faces joined by F creases are
    one), the nearest developable form whose
    vertices are also flat-foldable (Kawasaki: opposite sectors sum to pi). A developable, flat-foldable
    quadrilateral mesh with one rigidly folded state folds rigidly (Tachi 2009, "Generalization of rigid-foldable
    quadrilateral-mesh origami"), so this is a state on a rigid motion of its pattern, found by one sparse projection
    at any size (the fit of further states costs 7.6 s at 121 vertices). Used when within the coordinates' precision
    or the developable state (`fit`) is not; None otherwise.
    """
    conditions = fold_mesh.RigidConditions(fit.given, panels, flat_foldable=True)
    if conditions.n_sectors != 2 * len(conditions.interior) or not len(conditions.interior):
        return None
    found = fold_mesh.nearest_rigid(fit.given, fit.precision, conditions)
    flat = fold_mesh.Fit(fit.given, found.xyz, fit.precision, found.residual, conditions.describe())
    if not found.residual <= fold_mesh.DEVELOP_RTOL * fold_mesh.size(fit.given) or flat.ratio > 1.0 >= fit.ratio:
        return None
    notes.append(f"{label}: its pattern moves only with special geometry, and its vertices are flat-foldable within "
                 f"the precision: the nearest developable, flat-foldable state is read (such a quadrilateral mesh "
                 f"with one folded state folds rigidly): {flat.distance:.3g} file units away, {flat.ratio:.3g} x the "
                 "coordinates' precision")
    return flat


def _form_fit(fit: fold_mesh.Fit, pattern: CreasePattern, source: NDArray[np.int_], label: str, unit: str) -> FormFit:
    """The fit in the file's terms: file vertices, crease names, the coordinates moved the most as adjustments."""
    v = fit.vertex
    creases = tuple(c.name for c in pattern.creases if v in (c.start, c.end))
    against = np.abs(fit.moved) / fit.precision
    order = np.argsort(against, axis=None)[::-1][:ADJUSTMENTS_SHOWN]
    shown = [np.unravel_index(k, against.shape) for k in order if against.flat[k] > 0]
    adjustments = tuple(
        Adjustment(f"{label}[{source[i]}][{j}]", float(fit.given[i, j]), float(fit.xyz[i, j]),
                   float(fit.precision[i, j]), "" if unit == "unit" else unit)
        for i, j in shown
    )
    worst = np.unravel_index(int(np.argmax(against)), against.shape)
    moved = int(np.count_nonzero(fit.moved))
    compared = (f"{fit.given.size} coordinates of {len(fit.given)} vertices held to {fit.conditions}; {moved} moved, "
                f"rms {np.sqrt(np.mean(fit.moved**2)):.3g}")
    return FormFit(ratio=fit.ratio, distance=fit.distance, precision=float(fit.precision[worst]), compared=compared,
                   adjustments=adjustments, values=fit.given.size, field=label, unit="" if unit == "unit" else unit,
                   size=fold_mesh.size(fit.given), vertex=int(source[v]), creases=creases)


def _coords_precision(frame: Mapping[str, Any], xyz: NDArray[np.float64]) -> NDArray[np.float64]:
    """
    The precision (n, 3) of each coordinate, in file units: the frame's PRECISION_KEY when it states one; else half a
    unit in the last digit printed. Writers drop trailing zeros ('0.25' or '1' for 0.250000 or 1.000000), so an
    integer, or a number printed with fewer significant digits than the field's longest, is taken to the field's
    finest printed digit. A field without decimals (integers typed by hand), or given as floats (a parsed mapping, not
    text), is exact: EXACT_ULPS units in the last place of the size.
    """
    floor = EXACT_ULPS * np.spacing(fold_mesh.size(xyz))
    if PRECISION_KEY in frame:
        stated = _number(frame[PRECISION_KEY], PRECISION_KEY, False)
        if not stated > 0:
            raise ParameterError(f"{PRECISION_KEY} = {_shown(frame[PRECISION_KEY])}; it must be a positive number "
                                 "(frame_unit)")
        return np.full(xyz.shape, max(stated, floor))
    rows = [[*c, 0][:3] for c in frame["vertices_coords"]]
    return _printed_precision([x for row in rows for x in row], xyz.ravel(), floor).reshape(xyz.shape)


def _printed_precision(numbers: list[Any], values: NDArray[np.float64], floor: float) -> NDArray[np.float64]:
    """
    Half a unit in the last printed digit of each of a field's `numbers` (as read: `Typed` from text), the field's
    finest for integers and numbers printed with fewer significant digits than its longest, at least `floor`; all
    `floor` when none was printed with decimals. `values` (same length) are the numbers as floats.
    """
    half = np.array([x.precision if isinstance(x, Typed) else 0.0 for x in numbers], dtype=float)
    printed = half > 0
    if not np.any(printed):
        return np.full(len(values), floor)
    with np.errstate(divide="ignore"):
        digits = np.floor(np.log10(np.abs(values))) - np.log10(2 * np.where(printed, half, 1.0))
    short = ~printed | ~(digits >= np.max(digits[printed]))
    return np.maximum(np.where(short, np.min(half[printed]), half), floor)


def _nearest_closed(
    key: Mapping[str, Any], sheet: _Sheet, rho: NDArray[np.float64], notes: list[str]
) -> tuple[NDArray[np.float64], "AngleFit | None"]:
    """
    The key frame's edges_foldAngle `rho` (rad, the pattern's signs) against the nearest state closing every loop
    (F creases flat): least-norm Gauss-Newton in units of each angle's printed precision (`_printed_precision`).
    Within the precision, that state replaces `rho`, with the fit; beyond it `rho` is kept and traced towards (a note
    gives the distance; the trace's distance from it is a check, `PatternPath.target_check`), with the fit (nothing
    adjusted) when the angles were printed with decimals, so that their precision judges the state.
    """
    numbers = [key["edges_foldAngle"][e] for e in sheet.edge_of_crease]
    precision = np.deg2rad(_printed_precision(numbers, np.rad2deg(sheet.sign * rho), np.rad2deg(EXACT_ANGLE)))
    locks = tuple(Coupling(j, j, 0.0) for j, c in enumerate(sheet.pattern.creases) if c.assignment == "F")
    loops = sheet.pattern.loop_system(locks)
    closed = fold_mesh.nearest_rigid(rho, precision, _Closing(loops), tol=fold_mesh.RIGID_RTOL).xyz
    moved = np.abs(closed - rho) / precision
    names = [c.name for c in sheet.pattern.creases]
    shown = [k for k in np.argsort(moved)[::-1][:ADJUSTMENTS_SHOWN] if moved[k] > 0]
    adjustments = tuple(
        Adjustment(f"edges_foldAngle[{sheet.edge_of_crease[k]}]", float(numbers[k]),
                   float(numbers[k]) + float(np.rad2deg(sheet.sign * (closed[k] - rho[k]))),
                   float(np.rad2deg(precision[k])), "deg")
        for k in shown
    )
    worst = int(np.argmax(moved))
    compared = f"{len(rho)} fold angles held to {loops.n_residuals} closure conditions; {np.count_nonzero(moved)} moved"
    fit = AngleFit(ratio=float(np.max(moved, initial=0.0)),
                   distance=float(np.rad2deg(np.max(np.abs(closed - rho), initial=0.0))),
                   precision=float(np.rad2deg(precision[worst])), compared=compared, adjustments=adjustments,
                   values=len(rho), crease=names[worst])
    if not fit.within:
        # printed with decimals, the angles state their precision, and a state beyond it is not a rigid state as
        # typed: kept (traced towards) and judged by that precision (`PatternPath.state_check`). Angles without
        # decimals (integers, parsed floats) state none: judged by the trace's distance from them (TARGET_TOL)
        printed = bool(np.any(precision > EXACT_ANGLE * (1 + 1e-9)))
        notes.append(f"edges_foldAngle: {fit.distance:.3g} deg from the nearest state closing every loop, "
                     f"{fit.ratio:.3g} x the angles' precision: a direction to trace towards")
        return rho, replace(fit, adjustments=()) if printed else None
    if fit.distance > 0:
        notes.append(f"edges_foldAngle: the nearest state closing every loop is {fit.distance:.3g} deg away, "
                     f"{fit.ratio:.3g} x the angles' precision; it is what is read")
    return closed, fit


class _Closing:
    """The loops' closure as `fold_mesh.Conditions` on fold angles (rad; residuals in rad and lengths)."""

    def __init__(self, loops: LoopSystem):
        self.loops = loops

    def residual(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        return self.loops.residual(q)

    def jacobian(self, q: NDArray[np.float64]) -> sp.csr_matrix:
        return sp.csr_matrix(self.loops.jacobian(q))

    def describe(self) -> str:
        return f"{self.loops.n_residuals} closure conditions"


@dataclass(frozen=True)
class AngleFit(StateFit):
    """A folded state given as fold angles (`StateFit`, in deg) against the nearest one closing every loop, its
    largest move at crease `crease`."""

    crease: str

    def text(self) -> str:
        """The distance in words."""
        return (f"edges_foldAngle are {self.distance:.3g} deg from the nearest state closing every loop, "
                f"{self.ratio:.3g} x the precision {self.precision:.3g} deg of the angle moved most, largest at crease "
                f"{self.crease}; {self.compared}")


def _drop_loose(faces: list[Face], notes: list[str]) -> list[Face]:
    """
    `faces` without the loose ones: a face that shares no side with another (cut free all round, as the square
    inside a loop of C edges that cuts a hole) takes no part in any motion, and would be a body joined to nothing.
    Kept when no face has a neighbour (a pattern without creases: said elsewhere). A note names what was dropped.
    """
    count = Counter(key(*side) for face in faces for side in _sides(face))
    loose = [f for f, face in enumerate(faces) if all(count[key(*side)] == 1 for side in _sides(face))]
    if not loose or len(loose) == len(faces):
        return faces
    notes.append(f"{len(loose)} face(s) cut free all round (face(s) {', '.join(map(str, loose[:5]))} of the built "
                 "or given faces: a hole's cut-out) left out: they share no crease with the rest")
    dropped = set(loose)
    return [face for f, face in enumerate(faces) if f not in dropped]


def _measured(sheet: _Sheet, frame: Mapping[str, Any], field: str) -> NDArray[np.float64]:
    """
    Fold angles (n_creases,) rad of a frame's vertices_coords: the dihedral angles of its nearest rigid state, each
    face congruent to the crease pattern's (its sides and fan diagonals as long, and planar), in units of the
    coordinates' precision (`fold_mesh.nearest_rigid`); the fit is kept (`_Sheet.frame_fits`). Where none is found
    (a frame far from any), of the coordinates as given.
    """
    xyz, _ = _coords(frame["vertices_coords"], field)
    if len(xyz) != sheet.n_file_vertices:
        raise ParameterError(f"{field} has {len(xyz)} vertices; the crease pattern has {sheet.n_file_vertices}")
    given = xyz[sheet.source]
    fold_mesh.dihedral_angles(given, list(sheet.pattern.faces), sheet.hinges, sheet.signs, field)  # faces with area
    faces = _pattern_panels(sheet.pattern)
    bars = fold_mesh.face_bars(faces)
    unit = frame.get("frame_unit", "unit")
    rest = np.linalg.norm(sheet.pattern.vertices[bars[:, 0]] - sheet.pattern.vertices[bars[:, 1]], axis=1)
    # in the frame's unit; "unit" (no physical meaning) in either frame compares the numbers as they are
    rest /= sheet.unit_scale if "unit" in (unit, sheet.unit) else _unit_scale(unit)
    conditions = fold_mesh.RigidConditions(given, faces, bars, rest)
    fit = fold_mesh.nearest_rigid(given, _coords_precision(frame, xyz)[sheet.source], conditions)
    if not fit.residual <= fold_mesh.DEVELOP_RTOL * fold_mesh.size(given):
        sheet.notes.append(f"{field}: no rigid state of the crease pattern found near it (its faces' lengths missed by "
                           f"{fit.residual:.3g}); its fold angles are measured as given")
        return _dihedral(sheet, given, field)
    sheet.frame_fits.append((field, unit, fit))
    return _dihedral(sheet, fit.xyz, field)


def _dihedral(sheet: _Sheet, xyz: NDArray[np.float64], field: str) -> NDArray[np.float64]:
    """Fold angles (n_creases,) rad of 3-D coordinates (one row per pattern vertex)."""
    rho = fold_mesh.dihedral_angles(xyz, list(sheet.pattern.faces), sheet.hinges, sheet.signs, field)
    sheet.measured.append(rho)
    return rho


def _angles(
    key: Mapping[str, Any], geometry: Mapping[str, Any], raw: list[dict], frames: list[Mapping[str, Any]], sheet: _Sheet
) -> tuple[NDArray[np.float64] | None, NDArray[np.float64] | None, bool]:
    """The key frame's fold angles, the frames' and whether some were measured from coordinates."""
    sheet.measured.clear()
    sheet.frame_fits.clear()
    return (_key_angles(key, geometry, sheet), *_frame_angles(raw, frames, sheet, geometry))


def _letter_agreement(sheet: _Sheet) -> tuple[int, int]:
    """How many measured fold angles of M/V creases, clearly folded (neither flat nor +-pi), have their letter's
    sign and how many the other."""
    agree = disagree = 0
    for rho in sheet.measured:
        clear = (np.abs(rho) > fold_mesh.FLAT_FOLD_TOL) & (np.pi - np.abs(rho) > fold_mesh.FLAT_FOLD_TOL)
        clear &= sheet.signs != 0
        same = np.sign(rho[clear]) == sheet.signs[clear]
        agree, disagree = agree + int(same.sum()), disagree + int((~same).sum())
    return agree, disagree


def _say_sign_conflicts(sheet: _Sheet, key: NDArray[np.float64] | None, rows: NDArray[np.float64] | None) -> None:
    """A note naming the M/V creases whose fold angle has the other letter's sign in some state (beyond FOLDED of
    flat): the letters bound the trace to their side, so such a state cannot be reached as written."""
    states = [s for s in (key, *(() if rows is None else rows)) if s is not None]
    if not states:
        return
    rho = np.stack(states)
    against = (np.sign(rho) == -sheet.signs) & (np.abs(rho) > FOLDED) & (sheet.signs != 0)
    creases = np.flatnonzero(against.any(axis=0))
    if not len(creases):
        return
    shown = []
    for j in creases[:ADJUSTMENTS_SHOWN]:
        row = int(np.flatnonzero(against[:, j])[0])
        where = "" if row == 0 and key is not None else f" in frame {row + (key is None)}"
        letter = sheet.pattern.creases[j].assignment  # as the file has it (the pattern's are swapped when seen from -z)
        letter = {"M": "V", "V": "M"}[letter] if sheet.sign < 0 else letter
        angle = np.rad2deg(sheet.sign * rho[row, j])
        shown.append(f"{sheet.pattern.creases[j].name} {letter} at {angle:+.4g} deg{where}")
    more = f" and {len(creases) - len(shown)} more" if len(creases) > len(shown) else ""
    sheet.notes.append(
        f"the fold angles contradict the M/V letters at {len(creases)} of {int(np.count_nonzero(sheet.signs))} "
        f"lettered creases ({'; '.join(shown)}{more}): FOLD's positive angle is a valley; a crease folds only to its "
        "letter's side, so such a state cannot be reached as written"
    )


def _swap_letters(sheet: _Sheet) -> _Sheet:
    """The sheet with M and V swapped (the paper read from the other side of its letters)."""
    swap = {"M": "V", "V": "M"}
    creases = tuple(replace(c, assignment=swap.get(c.assignment, c.assignment)) for c in sheet.pattern.creases)
    return replace(sheet, pattern=replace(sheet.pattern, creases=creases), signs=-sheet.signs)


def _key_angles(key: Mapping[str, Any], geometry: Mapping[str, Any], sheet: _Sheet) -> NDArray[np.float64] | None:
    """The key frame's fold angles: its edges_foldAngle, else its folded form's dihedral angles, else None."""
    n_edges = len(sheet.edges_vertices)
    if "edges_foldAngle" in key:
        if key.get("edges_vertices") != sheet.edges_vertices:
            raise ParameterError("the key frame's edges_vertices differ from the crease pattern's; its "
                                 "edges_foldAngle cannot be read on the crease pattern")
        return sheet.sign * _degrees(key["edges_foldAngle"], sheet.edge_of_crease, n_edges, "edges_foldAngle")
    if sheet.folded_xyz is not None:
        sheet.notes.append("fold angles measured as the dihedral angles of the folded form")
        return _dihedral(sheet, sheet.folded_xyz, "vertices_coords")
    if key is not geometry and "vertices_coords" in key:
        sheet.notes.append("fold angles measured as the dihedral angles of the key frame's vertices_coords")
        return _measured(sheet, key, "vertices_coords")
    return None


def _frame_angles(
    raw: list[dict], frames: list[Mapping[str, Any]], sheet: _Sheet, geometry: Mapping[str, Any]
) -> tuple[NDArray[np.float64] | None, bool]:
    """Fold angles (n_frames, n_creases) rad of the file_frames entries (None without any), and whether some
    were measured from vertices_coords (the crease pattern's own frame, when a folded form, from the state read)."""
    if not frames:
        return None, False
    rows, measured = [], 0
    for k, (own, frame) in enumerate(zip(raw, frames, strict=True), start=1):
        if frame.get("edges_vertices") != sheet.edges_vertices:
            raise ParameterError(f"frame {k} changes edges_vertices; frames are read as fold angles of the crease "
                                 "pattern")
        angles_first = "edges_foldAngle" in own or ("vertices_coords" not in own and "edges_foldAngle" in frame)
        if angles_first:
            field = f"frame {k} edges_foldAngle"
            n_edges = len(sheet.edges_vertices)
            rows.append(sheet.sign * _degrees(frame["edges_foldAngle"], sheet.edge_of_crease, n_edges, field))
        elif frame is geometry and sheet.folded_xyz is not None:
            rows.append(_dihedral(sheet, sheet.folded_xyz, f"frame {k} vertices_coords"))
            measured += 1
        elif "vertices_coords" in frame:
            rows.append(_measured(sheet, frame, f"frame {k} vertices_coords"))
            measured += 1
        else:
            raise ParameterError(f"frame {k} has no edges_foldAngle or vertices_coords (own or inherited); "
                                 "a frame needs one of them to give fold angles")
    if measured:
        sheet.notes.append(f"{measured} frame(s) without edges_foldAngle: fold angles measured as the dihedral "
                           "angles of their vertices_coords")
    return np.stack(rows).reshape(len(rows), len(sheet.pattern.creases)), measured > 0


def _boundary_edges(pattern: CreasePattern) -> list[tuple[int, int]]:
    """Face sides that are not creases, counter-clockwise; each must border exactly one face."""
    creases = {frozenset((c.start, c.end)) for c in pattern.creases}
    sides = [side for face in pattern.faces for side in _sides(face)]
    directed = set(sides)
    out = []
    for a, b in sides:
        if frozenset((a, b)) in creases:
            continue
        if (b, a) in directed:
            raise ParameterError(f"edge {a}-{b} joins two faces but is not a crease; FOLD export needs it as a crease")
        out.append((int(a), int(b)))
    return out


def _frame_rows(frames: ArrayLike, n_creases: int) -> NDArray[np.float64]:
    """Frames' fold angles as an (n_frames, n_creases) array (rad)."""
    rows = np.asarray(frames, dtype=float)
    if rows.ndim != 2 or rows.shape[1] != n_creases:
        raise ParameterError(f"frames have shape {rows.shape}; they need (n_frames, {n_creases}) fold angles (rad)")
    return rows


def _fold_radians(angles: ArrayLike, n_creases: int, what: str) -> NDArray[np.float64]:
    """Fold angles (n_creases,) rad, checked to lie in [-pi, pi]."""
    rho = np.asarray(angles, dtype=float)
    if rho.shape != (n_creases,):
        raise ParameterError(f"{what} has shape {rho.shape}; it needs one fold angle per crease ({n_creases})")
    bad = np.flatnonzero(~(np.abs(rho) <= np.pi))
    if bad.size:
        raise ParameterError(f"{what}[{bad[0]}] = {rho[bad[0]]:g} rad; FOLD fold angles lie in [-pi, pi]")
    return rho
