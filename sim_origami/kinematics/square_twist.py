"""Square-twist pattern: 4 flat-foldable vertices round a central square (Peng 2018, §3.3; §3.2).

Pattern (Peng 2018, §3.3: the Q unit of §3.2.2 with beta = delta = pi/2, eqn 3-29). A central square of side `side` with
corners A, B, C, D counter-clockwise, centred at the origin of the flat sheet (normal +z). Every corner is a degree-4
vertex with sectors (alpha, pi/2, pi - alpha, pi/2), pi/2 < alpha < pi; the twist angle, between each pleat and the
square edge next to it, is gamma = pi - alpha. Vertex-local creases, counter-clockwise, at vertex k = 0..3 (A..D;
directions from +x):

* crease 2: the square edge to the next corner, at 90k deg (A2 = AB, B2 = BC, C2 = CD, D2 = DA);
* crease 3: the square edge to the previous corner, at 90k + 90 deg (A3 = DA, B3 = AB, ...);
* crease 4: a pleat at 90k + 90 + (180 - alpha) deg; crease 1: a pleat at 90k - alpha deg.

Pleats have length `pleat`. A's crease 1 and B's crease 4 are parallel and bound the parallelogram
`side_AB` beyond edge AB (angles alpha at A, gamma at B); each corner face `corner_<v>` is the
pleat x pleat square between the two pleats of vertex v. Nine faces, twelve creases, four loops.

Angles are fold angles rho (`sim_origami.creases`: 0 flat, > 0 a valley seen from +z), a crease's rho
the same at both its vertices. The input is x = rho_AB in [-pi, pi].

Closed form (Peng 2018, eqns 3-3 and 3-29 to 3-31). Each vertex folds in mode S (rho3 = -rho1, rho4 = rho2) or mode
C (rho3 = rho1, rho4 = -rho2), linear in t = tan(rho/2) with the multipliers of
`vertex4.flat_foldable_multipliers`. Round the square, t(crease 3) = m23 t(crease 2) with

    m_C = -cos((pi/2 - alpha)/2) / cos((pi/2 + alpha)/2),   m_S = sin((pi/2 - alpha)/2) / sin((pi/2 + alpha)/2),

and m_C m_S = -1 identically. Chaining t(AB) -> A -> DA -> D -> CD -> C -> BC -> B -> t(AB) multiplies
by the loop gain K = m_C^#C m_S^#S: the modes (A, B, C, D) fold rigidly iff K = 1, i.e. two vertices in
each mode; then tan(rho_i/2) = k_i tan(x/2) with constant k_i on every crease. M/V signs close round the
square only with an even number of S vertices (sign K = (-1)^#S); the 8 such mode strings fall into 4
classes under the pattern's 90 deg rotation (thesis T1-T4, which of ours is T1 is not in the text):

* ``adjacent``: two S vertices sharing an edge (CCSS and rotations, 4 members), rigid;
* ``opposite``: S vertices diagonally opposite (CSCS, SCSC), rigid;
* ``all-C`` (K = m_C^4 = 9 at alpha = 150 deg) and ``all-S`` (K = 1/9): locked at the flat state (the
  classic 4-fold-symmetric twist).

Branches of `SquareTwist` are the six rigid mode strings, named by the mode of each vertex A, B, C, D:
all cross at the flat state (a bifurcation) and end where every crease folds flat at once (x = +-pi).

Metamaterial unit (Peng 2018, eqns 3-30 to 3-32): theta and phi are the fold angles of creases 2 and 3
of one mode-C vertex (tan(phi/2) = m_C tan(theta/2), eqn 3-31), unit dimensions a, b, c.
Derived here: H peaks where nu_hl changes sign, at theta = 1.299533 (alpha = 150 deg), 1.143718 (135 deg) and
0.955317 = arccos(1/sqrt(3)) (120 deg), solved here; coarser sampled values, 1.2999 (150 deg) and
0.9548 (120 deg), miss it: nu_hl = -8.9e-4 and +7.3e-4 there.
"""

from dataclasses import dataclass
from itertools import product

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from .base import Branch, Event
from .fixed_modes import FixedModeKinematics
from .numeric_pattern import foldable_with_signs
from .vertex4 import flat_foldable_multipliers

VERTICES = ("A", "B", "C", "D")
EDGES = ("AB", "BC", "CD", "DA")
PLEATS = ("A1", "A4", "B1", "B4", "C1", "C4", "D1", "D4")
CREASES = EDGES + PLEATS
FACES = ("square", "side_AB", "side_BC", "side_CD", "side_DA", "corner_A", "corner_B", "corner_C", "corner_D")
INPUT = "AB"
# Vertex k's creases 2 and 3 (the square edges), walked A -> D -> C -> B so that crease 3 of one vertex is
# crease 2 of the next.
LOOP_ORDER = (0, 3, 2, 1)
# A loop gain within this of 1 (relative) is rigid; generic alpha keeps the locked gains O(1) away.
GAIN_TOL = 1e-12


def _check_alpha(alpha: float) -> None:
    if not np.pi / 2 < alpha < np.pi:
        raise ParameterError(
            f"alpha = {np.rad2deg(alpha):.6g} deg; the square twist needs 90 < alpha < 180 deg "
            "(twist angle 180 - alpha in (0, 90), Peng 2018, §3.3)"
        )


def _check_positive(**lengths: float) -> None:
    for name, value in lengths.items():
        if not value > 0:
            raise ParameterError(f"{name} = {value:g} m; it must be positive")


def check_modes(modes: str) -> None:
    """ParameterError unless `modes` gives S or C for each vertex A..D with an even number of S."""
    if len(modes) != 4 or set(modes) - {"S", "C"}:
        raise ParameterError(f"modes {modes!r}: give one mode, S or C, for each of the vertices A, B, C, D")
    if modes.count("S") % 2:
        raise ParameterError(
            f"modes {modes!r} put {modes.count('S')} vertices in mode S; M/V signs close round the central "
            "square only with an even number (derived here)"
        )


def vertex_sectors(alpha: float) -> NDArray[np.float64]:
    """Sector angles (4,) of every vertex, creases 1 to 4 counter-clockwise: (alpha, pi/2, pi - alpha, pi/2)."""
    return np.array([alpha, np.pi / 2, np.pi - alpha, np.pi / 2])


def edge_multipliers(alpha: float) -> dict[str, float]:
    """m23 = tan(rho3/2) / tan(rho2/2) of a vertex in mode 'C' and in mode 'S' (Peng 2018, §3.3)."""
    return {
        "C": float(-np.cos((np.pi / 2 - alpha) / 2) / np.cos((np.pi / 2 + alpha) / 2)),
        "S": float(np.sin((np.pi / 2 - alpha) / 2) / np.sin((np.pi / 2 + alpha) / 2)),
    }


def loop_gain(alpha: float, modes: str) -> float:
    """K = m_C^#C m_S^#S: tan(rho_AB/2) after one turn round the square over its start value (derived here)."""
    m = edge_multipliers(alpha)
    return float(np.prod([m[mode] for mode in modes]))


def tan_ratios(alpha: float, modes: str) -> NDArray[np.float64]:
    """
    k (12,) in CREASES order with tan(rho_i/2) = k_i tan(rho_AB/2), chained from AB through A, D, C, B.

    Exact for a rigid mode string (K = 1). Otherwise the chain does not close (B's crease 3 would be K
    times AB) and k only carries the M/V signs of the assignment (B's crease 4 taken from that chain).
    """
    check_modes(modes)
    m = flat_foldable_multipliers(vertex_sectors(alpha))
    t = {INPUT: 1.0}
    for k in LOOP_ORDER:
        v = VERTICES[k]
        m12, m23, m34, _ = m[modes[k]]
        t2, name3 = t[EDGES[k]], EDGES[(k - 1) % 4]
        t3 = m23 * t2
        t.setdefault(name3, t3)
        t[f"{v}1"], t[f"{v}4"] = t2 / m12, m34 * t3
    return np.array([t[name] for name in CREASES])


def assignment(alpha: float, modes: str) -> str:
    """M/V letters in CREASES order of a mode string at rho_AB > 0 (V: rho > 0, a valley seen from +z)."""
    return "".join("V" if k > 0 else "M" for k in tan_ratios(alpha, modes))


def crease_pattern(alpha: float, side: float = 1.0, pleat: float = 1.0, modes: str | None = None) -> CreasePattern:
    """
    The square twist (module docstring) as a CreasePattern, lengths in metres.

    Creases carry the M/V of `modes` at rho_AB > 0 (any sign-consistent mode string, foldable or not), or
    U (unassigned) when `modes` is None.
    """
    _check_alpha(alpha)
    _check_positive(side=side, pleat=pleat)
    letters = assignment(alpha, modes) if modes is not None else "U" * len(CREASES)
    corners = 0.5 * side * np.array([(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)])
    k = np.arange(4)
    d1 = np.stack([np.cos(k * np.pi / 2 - alpha), np.sin(k * np.pi / 2 - alpha)], -1)
    d4 = np.stack([np.cos(k * np.pi / 2 + 1.5 * np.pi - alpha), np.sin(k * np.pi / 2 + 1.5 * np.pi - alpha)], -1)
    end1, end4 = corners + pleat * d1, corners + pleat * d4
    # vertex indices: corner i, end of its pleat 1 (4 + i), end of its pleat 4 (8 + i), far corner of its face (12 + i)
    vertices = np.vstack([corners, end1, end4, end1 + end4 - corners])
    E1, E4, F = 4, 8, 12
    nxt = [(i + 1) % 4 for i in range(4)]
    faces = (
        (0, 1, 2, 3),
        *((nxt[i], i, E1 + i, E4 + nxt[i]) for i in range(4)),
        *((i, E4 + i, F + i, E1 + i) for i in range(4)),
    )
    ends = {f"{v}{n}": (i, (E1 if n == "1" else E4) + i) for i, v in enumerate(VERTICES) for n in "14"}
    ends |= {EDGES[i]: (i, nxt[i]) for i in range(4)}
    creases = tuple(Crease(name, *ends[name], letter) for name, letter in zip(CREASES, letters, strict=True))
    return CreasePattern(vertices, faces, creases, FACES)


def mode_classes() -> dict[str, tuple[str, ...]]:
    """The sign-consistent mode strings grouped under the 90 deg rotation A -> B -> C -> D, named by geometry."""
    out: dict[str, list[str]] = {"adjacent": [], "opposite": [], "all-C": [], "all-S": []}
    for modes in map("".join, product("CS", repeat=4)):
        n = modes.count("S")
        if n % 2:
            continue
        if n == 2:
            out["opposite" if modes[0] == modes[2] else "adjacent"].append(modes)
        else:
            out["all-C" if n == 0 else "all-S"].append(modes)
    return {name: tuple(members) for name, members in out.items()}


CLASS_OF = {modes: name for name, members in mode_classes().items() for modes in members}
RIGID = mode_classes()["adjacent"] + mode_classes()["opposite"]


@dataclass(frozen=True)
class AssignmentVerdict:
    """
    One class of M/V assignments: its analytic and numeric verdicts.

    `assignment` is the representative's M/V in CREASES order at rho_AB > 0; `residual` is what the numeric
    verdict (`numeric_pattern.foldable_with_signs`) met: the largest closed residual when rigid, the stalled one
    when not.
    """

    name: str
    members: tuple[str, ...]
    assignment: str
    loop_gain: float
    rigid_analytic: bool
    rigid_numeric: bool
    residual: float


def verdict_table(alpha: float, side: float = 1.0, pleat: float = 1.0) -> tuple[AssignmentVerdict, ...]:
    """The four M/V classes (`mode_classes`) with the loop-gain verdict and the sign-held numeric closure."""
    loops = crease_pattern(alpha, side, pleat).loop_system()
    out = []
    for name, members in mode_classes().items():
        modes = members[0]
        gain = loop_gain(alpha, modes)
        rigid, residual = foldable_with_signs(loops, np.sign(tan_ratios(alpha, modes)), CREASES.index(INPUT))
        out.append(AssignmentVerdict(name, members, assignment(alpha, modes), gain, abs(gain - 1.0) <= GAIN_TOL,
                                     rigid, residual))
    return tuple(out)


class SquareTwist(FixedModeKinematics):
    """
    The square twist driven by x = rho_AB in [-pi, pi]; the six rigid mode strings are its branches.

    Parameters
    ----------
    alpha : float
      Sector angle (rad) between pleat 1 and square edge 2 of every vertex, in (pi/2, pi).
    side, pleat : float
      Central square side and pleat length (m).
    """

    input_name = "rhoAB"
    joint_names = tuple(f"rho{c}" for c in CREASES)

    def __init__(self, alpha: float, side: float = 1.0, pleat: float = 1.0):
        self.pattern = crease_pattern(alpha, side, pleat)
        self.alpha, self.side, self.pleat = float(alpha), float(side), float(pleat)
        self.ratios = {modes: tan_ratios(self.alpha, modes) for modes in RIGID}
        self._branches = self._describe()

    def _describe(self) -> tuple[Branch, ...]:
        out = []
        for modes in RIGID:
            c, s = ([v for v, m in zip(VERTICES, modes, strict=True) if m == mode] for mode in "CS")
            mv = assignment(self.alpha, modes)
            text = (f"vertices {', '.join(c)} in mode C (rho3 = rho1), {', '.join(s)} in mode S (rho3 = -rho1): "
                    f"class {CLASS_OF[modes]}; M/V at rhoAB > 0 in joint order: {mv}")
            out.append(Branch(modes, text, (-np.pi, np.pi)))
        return tuple(out)

    def branches(self) -> tuple[Branch, ...]:
        return self._branches

    def events(self) -> tuple[Event, ...]:
        names = RIGID
        flat = Event("bifurcation", 0.0, names, "flat state: the six rigid mode strings cross (mobility 4 there)")
        locks = [Event("lock", end, names, "every crease folded flat at once (|rho| = pi)") for end in (-np.pi, np.pi)]
        return (flat, *locks)

    def gruebler(self) -> int:
        """Kutzbach: 12 creases - 3 per spherical loop (4 vertices) = 0; the pattern moves by its geometry."""
        return len(CREASES) - 3 * 4

    def loop_system(self) -> LoopSystem:
        """Per-vertex PoE closure of the crease pattern."""
        return self.pattern.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return CREASES.index(INPUT), 1.0


@dataclass(frozen=True)
class MetamaterialUnit:
    """Eqns 3-30 and 3-32 at inputs theta (n,): phi (rad), dimensions L, S, H (units of a), Poisson's ratios."""

    theta: NDArray[np.float64]
    phi: NDArray[np.float64]
    L: NDArray[np.float64]
    S: NDArray[np.float64]
    H: NDArray[np.float64]
    nu_sl: NDArray[np.float64]
    nu_hl: NDArray[np.float64]


def metamaterial_unit(
    alpha: float, theta: ArrayLike, a: float = 1.0, b: float = 1.0, c: float = 1.0
) -> MetamaterialUnit:
    """
    The square-twist metamaterial unit (Fig 3-18) at fold angles theta in (0, pi) of crease 2 of a mode-C vertex.

    phi = 2 atan(m_C tan(theta/2)) is its crease 3 (eqn 3-31); L = 2c + a(cos alpha + sin alpha cos theta),
    S = 2b + a(cos alpha + sin alpha cos phi), H = a sin alpha (sin theta + sin phi) (eqn 3-30);
    nu_sl = -(S/L) dL/dS and nu_hl = -(L/H) dH/dL as printed in eqn 3-32.
    """
    _check_alpha(alpha)
    _check_positive(a=a, b=b, c=c)
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    if np.any((theta <= 0) | (theta >= np.pi)):
        bad = float(theta[(theta <= 0) | (theta >= np.pi)][0])
        raise ParameterError(f"theta = {bad:.6g} rad; eqn 3-32 needs 0 < theta < pi")
    phi = 2.0 * np.arctan2(edge_multipliers(alpha)["C"] * np.sin(theta / 2), np.cos(theta / 2))
    ca, sa = np.cos(alpha), np.sin(alpha)
    ct, st, cp, sp = np.cos(theta), np.sin(theta), np.cos(phi), np.sin(phi)
    L = 2 * c + a * (ca + sa * ct)
    S = 2 * b + a * (ca + sa * cp)
    H = a * sa * (st + sp)
    nu_sl = -(S / L) * st * (ca * sp + sa * st * cp) / (sp * (ca * st - sa * ct * sp))
    nu_hl = -(L / H) * (ct + cp * (ca * st - sa * ct * sp) / (ca * sp + sa * st * cp)) / (-st)
    return MetamaterialUnit(theta, phi, L, S, H, nu_sl, nu_hl)
