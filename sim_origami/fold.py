"""FOLD 1.2 import and export of flat crease patterns (https://github.com/edemaine/fold, doc/spec.md).

Units. Lengths are read in the key frame's `frame_unit` and converted to metres; "unit" (or no unit)
has no physical meaning in FOLD and is read as metres. Files are written with `frame_unit` "m".
`edges_foldAngle` is in degrees in FOLD and in radians here (rho of `sim_origami.creases`).

Signs and sides. FOLD's counter-clockwise face order gives each face its normal and a valley folds
the normals into each other, so for faces counter-clockwise seen from +z FOLD's M/V and fold-angle
signs are those of `sim_origami.creases` (rho > 0 valley seen from +z). Clockwise faces are reversed;
when every face is clockwise the file's paper is seen from -z, so M and V swap and fold angles change
sign. A file mixing both orientations is read as seen from +z.

Geometry read. vertices_coords must be flat (2-D, or 3-D with one z; the sheet is moved to z = 0).
Faces must be simple polygons of non-zero area; they may be non-convex. Every face side must be an
edge, a "B" edge borders one face and a crease two. Each interior vertex must be developable (sector
angles summing to 360 deg); Kawasaki and rigid foldability are checked elsewhere.

Assignments. M, V and U edges are creases of that assignment; F (a crease present but unfolded)
becomes a "U" crease that is expected to stay flat (not enforced); B edges are the boundary.
FOLD 1.2 cuts "C" and joins "J" are refused. Creases are named e<FOLD edge index>.

Frames. The key frame (top level) is the pattern; each entry of `file_frames` gives one row of fold
angles from its own or inherited (`frame_inherit`, `frame_parent`) `edges_foldAngle`, and must keep the
key frame's `edges_vertices`; other frame fields are not read.

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
from collections import Counter
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from .creases import Crease, CreasePattern
from .errors import ParameterError
from .files import write_text

FILE_SPEC = 1.2
HEIGHT_KEY = "edges_sim_origami:hingeHeight"
REQUIRED = ("vertices_coords", "edges_vertices", "edges_assignment", "faces_vertices")
# Metres per FOLD frame_unit; "unit" (no physical meaning) is read as metres.
UNITS = {"unit": 1.0, "m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "nm": 1e-9, "in": 0.0254, "pt": 0.0254 / 72}
# FOLD assignment -> crease assignment, seen from +z (UP) or from -z (DOWN: every face clockwise).
UP = {"M": "M", "V": "V", "U": "U", "F": "U"}
DOWN = {"M": "V", "V": "M", "U": "U", "F": "U"}
REFUSED = {"C": "a cut (FOLD 1.2): split it into 'B' edges", "J": "a join (FOLD 1.2): merge the joined faces"}
# Sector-angle sum at an interior vertex vs 2 pi (rad).
DEVELOPABLE_TOL = 1e-9
# A face is degenerate when |area| <= AREA_RTOL * (its longest side)^2.
AREA_RTOL = 1e-12
# z spread allowed in 3-D vertices_coords, relative to the sheet's extent in x and y.
FLAT_RTOL = 1e-12
# A written crease whose |rho| (rad) never exceeds this is F (flat). Exact states (closed form, numeric closure)
# hold to 1e-12 rad (tolerances.closed_form_rad), so 1e-9 stays 1000x above their noise and far below any
# visible fold; simulated motions pass their own preset's angle tolerance instead (report.motion_fold).
FLAT_TOL = 1e-9


@dataclass(frozen=True)
class FoldPattern:
    """
    A FOLD file read as a crease pattern. `fold_angles` (n_creases,) rad: the key frame's
    edges_foldAngle, or None; `frames` (n_frames, n_creases) rad: one row per `file_frames` entry, or
    None; both in `pattern.creases` order. `edge_of_crease`: the FOLD edge index of each crease.
    """

    pattern: CreasePattern
    fold_angles: NDArray[np.float64] | None
    edge_of_crease: tuple[int, ...]
    frames: NDArray[np.float64] | None


def read_fold(source: str | os.PathLike | Mapping[str, Any]) -> FoldPattern:
    """Read a FOLD file (path) or its parsed JSON (mapping); the module docstring states the rules."""
    doc = _load(source)
    for field in REQUIRED:
        if field not in doc:
            raise ParameterError(f"FOLD field {field!r} is missing; sim_origami needs {', '.join(REQUIRED)}")
    scale = _unit_scale(doc.get("frame_unit", "unit"))
    xy = _flat_coords(doc["vertices_coords"]) * scale
    edges = _edges(doc["edges_vertices"], len(xy))
    letters = _assignments(doc["edges_assignment"], len(edges))
    faces, seen_from_below = _faces(doc["faces_vertices"], xy)
    _check_incidence(edges, letters, faces)
    heights = scale * _heights(doc[HEIGHT_KEY], letters) if HEIGHT_KEY in doc else np.zeros(len(edges))
    table = DOWN if seen_from_below else UP
    crease_edges = tuple(k for k, letter in enumerate(letters) if letter in table)
    creases = tuple(Crease(f"e{k}", *edges[k], table[letters[k]], float(heights[k])) for k in crease_edges)
    border = tuple((*edges[k], float(heights[k])) for k, letter in enumerate(letters)
                   if letter == "B" and np.isfinite(heights[k]))  # fmt: skip
    pattern = CreasePattern(xy, tuple(faces), creases, tuple(f"f{k}" for k in range(len(faces))), border)
    _check_developable(pattern)
    sign = -1.0 if seen_from_below else 1.0
    angles = _degrees(doc["edges_foldAngle"], len(edges), "edges_foldAngle") if "edges_foldAngle" in doc else None
    return FoldPattern(
        pattern,
        None if angles is None else sign * angles[list(crease_edges)],
        crease_edges,
        _frame_angles(doc, crease_edges, sign),
    )


def fold_dict(
    pattern: CreasePattern,
    fold_angles: ArrayLike | None = None,
    frames: ArrayLike | None = None,
    *,
    title: str = "sim_origami crease pattern",
    creator: str = "sim_origami",
    flat_tol: float = FLAT_TOL,
    notes: tuple[str, ...] = (),
) -> dict[str, Any]:
    """
    FOLD 1.2 data of a pattern: edges are its creases (in order, FOLD edge k = crease k) then the
    boundary. The key frame holds `fold_angles` (n_creases,) rad, or 0; each row of `frames`
    (n_frames, n_creases) rad becomes a `file_frames` entry inheriting from the key frame. Fold angles
    are written in degrees, as given (continuous along the frames), and must lie in [-pi, pi].

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
                        for k, r in enumerate(rows))])  # fmt: skip
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
                     "edges_foldAngle": np.rad2deg(rho).tolist() + pad}  # fmt: skip
            if np.any(own != letters[0]):
                frame["edges_assignment"] = own.tolist() + ["B"] * len(boundary)
            doc["file_frames"].append(frame)
    return doc


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
) -> Path:
    """Write `fold_dict(pattern, fold_angles, frames, ...)` as a .fold JSON file, atomically; returns the path."""
    doc = fold_dict(pattern, fold_angles, frames, title=title, creator=creator, flat_tol=flat_tol, notes=notes)
    return write_text(path, json.dumps(doc, indent=1) + "\n")


def _load(source: str | os.PathLike | Mapping[str, Any]) -> Mapping[str, Any]:
    """The FOLD JSON object of a path or an already parsed mapping."""
    if isinstance(source, Mapping):
        return source
    try:
        doc = json.loads(Path(source).read_text())
    except json.JSONDecodeError as err:
        raise ParameterError(f"{source} is not JSON ({err}); a FOLD file is a JSON object") from err
    except OSError as err:
        raise ParameterError(f"cannot read FOLD file {source}: {err.strerror}") from err
    if not isinstance(doc, dict):
        raise ParameterError(f"{source} holds a JSON {type(doc).__name__}; a FOLD file is a JSON object")
    return doc


def _unit_scale(unit: Any) -> float:
    """Metres per FOLD frame_unit."""
    if unit not in UNITS:
        raise ParameterError(f"frame_unit = {unit!r}; sim_origami reads {', '.join(UNITS)}")
    return UNITS[unit]


def _numbers(value: Any, field: str, allow_nan: bool = False) -> NDArray[np.float64]:
    """A FOLD number array as floats; every entry must be a finite number (or NaN, if allowed)."""
    try:
        out = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as err:
        raise ParameterError(f"{field} must hold numbers only ({err})") from err
    bad = np.argwhere(~np.isfinite(out) & ~(allow_nan & np.isnan(out)))
    if len(bad):
        at = tuple(int(i) for i in bad[0])
        raise ParameterError(f"{field}{list(at)} = {out[at]}; numbers must be finite")
    return out


def _per_edge(value: Any, n_edges: int, field: str) -> NDArray[np.float64]:
    """A per-edge number field (n_edges,)."""
    out = _numbers(value, field)
    if out.shape != (n_edges,):
        raise ParameterError(f"{field} has shape {out.shape}; it needs one number per edge ({n_edges})")
    return out


def _heights(value: Any, letters: list[str]) -> NDArray[np.float64]:
    """The hinge-height field (n_edges,): numbers, null (NaN) allowed on border edges only."""
    if not isinstance(value, list) or len(value) != len(letters):
        raise ParameterError(f"{HEIGHT_KEY} needs one entry per edge ({len(letters)})")
    for k, (entry, letter) in enumerate(zip(value, letters, strict=True)):
        if entry is None and letter != "B":
            raise ParameterError(f"{HEIGHT_KEY}[{k}] is null on a {letter!r} edge; only border edges may have no hinge")
    return _numbers([np.nan if entry is None else entry for entry in value], HEIGHT_KEY, allow_nan=True)


def _degrees(value: Any, n_edges: int, field: str) -> NDArray[np.float64]:
    """A FOLD edges_foldAngle (deg, in [-180, 180]) as radians (n_edges,)."""
    deg = _per_edge(value, n_edges, field)
    bad = np.flatnonzero(np.abs(deg) > 180.0)
    if bad.size:
        raise ParameterError(f"{field}[{bad[0]}] = {deg[bad[0]]:g} deg; FOLD fold angles lie in [-180, 180] deg")
    return np.deg2rad(deg)


def _list(value: Any, field: str) -> list:
    if not isinstance(value, list):
        raise ParameterError(f"{field} is a {type(value).__name__}; FOLD stores it as a JSON array")
    return value


def _flat_coords(value: Any) -> NDArray[np.float64]:
    """Vertex coordinates (n, 2) of a flat sheet: 2-D, or 3-D with every z equal (dropped)."""
    rows = []
    for v, c in enumerate(_list(value, "vertices_coords")):
        if not isinstance(c, list) or len(c) not in (2, 3):
            raise ParameterError(f"vertices_coords[{v}] = {c!r}; a vertex has 2 or 3 coordinates")
        rows.append([*c, 0.0][:3])
    xyz = _numbers(rows, "vertices_coords").reshape(-1, 3)
    if len(xyz):
        z, extent = xyz[:, 2], np.ptp(xyz[:, :2], axis=0).max()
        off = np.flatnonzero(np.abs(z - z[0]) > FLAT_RTOL * extent)
        if off.size:
            v = off[0]
            raise ParameterError(
                f"vertex {v} has z = {z[v]:g} but vertex 0 has z = {z[0]:g}: vertices_coords must be flat "
                "(2-D, or 3-D with all z equal)"
            )
    return xyz[:, :2].copy()


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
    first: dict[frozenset, int] = {}
    for k, e in enumerate(edges):
        if len(e) != 2 or e[0] == e[1]:
            raise ParameterError(f"edges_vertices[{k}] = {list(e)}; an edge joins two distinct vertices")
        other = first.setdefault(frozenset(e), k)
        if other != k:
            raise ParameterError(f"edges {other} and {k} both join vertices {e[0]} and {e[1]}; edges must differ")
    return edges


def _assignments(value: Any, n_edges: int) -> list[str]:
    """FOLD assignment letters, one per edge: B, M, V, F or U."""
    letters = _list(value, "edges_assignment")
    if len(letters) != n_edges:
        raise ParameterError(f"edges_assignment has {len(letters)} entries; it needs one per edge ({n_edges})")
    for k, letter in enumerate(letters):
        if isinstance(letter, str) and letter in REFUSED:
            raise ParameterError(f"edge {k} has assignment {letter!r}, {REFUSED[letter]}; sim_origami does not read it")
        if letter not in ("B", *UP):
            raise ParameterError(f"edge {k} has assignment {letter!r}; FOLD assignments are B, M, V, F, U (uppercase)")
    return letters


def _cross(a: NDArray, b: NDArray) -> NDArray:
    """z of the cross product of 2-D vectors (..., 2)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _corner_angles(p: NDArray[np.float64]) -> NDArray[np.float64]:
    """Interior angles (rad, in [0, 2 pi)) at the corners of a counter-clockwise polygon (n, 2)."""
    to_next, to_prev = np.roll(p, -1, axis=0) - p, np.roll(p, 1, axis=0) - p
    return np.mod(np.arctan2(_cross(to_next, to_prev), np.sum(to_next * to_prev, axis=-1)), 2 * np.pi)


def _segments_meet(p: NDArray, q: NDArray, r: NDArray, s: NDArray) -> bool:
    """Whether the closed segments pq and rs share a point."""
    d = (_cross(q - p, r - p), _cross(q - p, s - p), _cross(s - r, p - r), _cross(s - r, q - r))
    if d[0] * d[1] < 0 and d[2] * d[3] < 0:
        return True
    ends = ((d[0], r, p, q), (d[1], s, p, q), (d[2], p, r, s), (d[3], q, r, s))
    return any(o == 0 and np.all(np.minimum(a, b) <= x) and np.all(x <= np.maximum(a, b)) for o, x, a, b in ends)


def _faces(value: Any, xy: NDArray[np.float64]) -> tuple[list[tuple[int, ...]], bool]:
    """
    Counter-clockwise simple faces, and whether every face was given clockwise (the file's paper
    then seen from -z). Each clockwise face is reversed, keeping its first vertex.
    """
    faces = _vertex_lists(value, "faces_vertices", len(xy))
    if not faces:
        raise ParameterError("faces_vertices is empty; a crease pattern needs at least one face")
    out, clockwise = [], 0
    for k, face in enumerate(faces):
        if len(face) < 3 or len(set(face)) != len(face):
            raise ParameterError(f"face {k} {list(face)} must list 3 or more distinct vertices")
        p = xy[list(face)]
        area = 0.5 * float(np.sum(_cross(p, np.roll(p, -1, axis=0))))
        longest = float(np.max(np.sum((np.roll(p, -1, axis=0) - p) ** 2, axis=-1)))
        if abs(area) <= AREA_RTOL * longest:
            raise ParameterError(f"face {k} {list(face)} has area {area:.3g} m^2; faces must not be degenerate")
        if area < 0:
            face, clockwise = (face[0], *face[:0:-1]), clockwise + 1
        _check_simple(k, face, xy[list(face)])
        out.append(face)
    return out, clockwise == len(faces)


def _check_simple(k: int, face: tuple[int, ...], p: NDArray[np.float64]) -> None:
    """A counter-clockwise face (vertices p) must be a simple polygon: no spike, no meeting sides."""
    spikes = np.flatnonzero(_corner_angles(p) == 0.0)
    if spikes.size:
        raise ParameterError(f"face {k} doubles back at vertex {face[spikes[0]]}; faces must be simple polygons")
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


def _check_incidence(edges: list[tuple[int, int]], letters: list[str], faces: list[tuple[int, ...]]) -> None:
    """Every face side is an edge; a boundary edge borders one face, a crease two."""
    index = {frozenset(e) for e in edges}
    count = Counter(frozenset(side) for face in faces for side in _sides(face))
    for f, face in enumerate(faces):
        for a, b in _sides(face):
            if frozenset((a, b)) not in index:
                raise ParameterError(f"side {a}-{b} of face {f} is not in edges_vertices; every face side is an edge")
    for k, (e, letter) in enumerate(zip(edges, letters, strict=True)):
        n, need = count[frozenset(e)], 1 if letter == "B" else 2
        if n != need:
            rule = "a boundary edge borders one face" if letter == "B" else "a crease joins two faces"
            raise ParameterError(f"edge {k} ({e[0]}-{e[1]}, {letter!r}) borders {n} face(s); {rule}")


def _check_developable(pattern: CreasePattern) -> None:
    """
    Sector angles round each interior vertex must sum to 2 pi within DEVELOPABLE_TOL. A flat fan closes
    at a multiple of 2 pi, so this catches a sheet wrapping round a vertex more than once.
    """
    total = np.zeros(len(pattern.vertices))
    for face in pattern.faces:
        total[list(face)] += _corner_angles(pattern.vertices[list(face)])
    for v in pattern.interior_vertices():
        if abs(total[v] - 2 * np.pi) > DEVELOPABLE_TOL:
            raise ParameterError(
                f"interior vertex {v}: sector angles sum to {np.rad2deg(total[v]):.12g} deg; a developable "
                f"vertex needs 360 deg (within {DEVELOPABLE_TOL:g} rad)"
            )


def _resolve(frames: list[dict], k: int, key: Mapping[str, Any], seen: tuple[int, ...] = ()) -> Mapping[str, Any]:
    """Frame k (0: the key frame, k > 0: file_frames[k - 1]) with the properties it inherits."""
    if k == 0:
        return key
    frame = frames[k - 1]
    if frame.get("frame_inherit") is not True:
        return frame
    parent = frame.get("frame_parent")
    if type(parent) is not int or not 0 <= parent <= len(frames) or parent in (*seen, k):
        raise ParameterError(
            f"frame {k} inherits from frame_parent = {parent!r}; it must name a frame in [0, {len(frames)}] "
            "without an inheritance cycle"
        )
    return {**_resolve(frames, parent, key, (*seen, k)), **frame}


def _frame_angles(doc: Mapping[str, Any], crease_edges: tuple[int, ...], sign: float) -> NDArray[np.float64] | None:
    """Fold angles (n_frames, n_creases) rad of the file_frames entries, or None without file_frames."""
    frames = _list(doc.get("file_frames", []), "file_frames")
    if not frames:
        return None
    for k, frame in enumerate(frames):
        if not isinstance(frame, dict):
            raise ParameterError(f"file_frames[{k}] is a {type(frame).__name__}; a frame is a JSON object")
    key = {name: value for name, value in doc.items() if not name.startswith("file_")}
    rows = []
    for k in range(1, len(frames) + 1):
        frame = _resolve(frames, k, key)
        if frame.get("edges_vertices") != doc["edges_vertices"]:
            raise ParameterError(f"frame {k} changes edges_vertices; frames are read as fold angles of the key frame")
        if "edges_foldAngle" not in frame:
            raise ParameterError(f"frame {k} has no edges_foldAngle (own or inherited); frames are read as fold angles")
        rows.append(_degrees(frame["edges_foldAngle"], len(doc["edges_vertices"]), f"frame {k} edges_foldAngle"))
    return sign * np.stack(rows)[:, list(crease_edges)]


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
