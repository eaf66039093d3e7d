"""Generalised triangle-twist origami: three flat-foldable vertices round a triangle (Feng 2018, §3.2-3.3).

Pattern (reconstructed here; it reproduces Feng 2018's D-H data of §3.4 exactly). The flat
sheet lies in the XY plane (normal +z), lengths in metres: A = (0, 0), B = (d, 0), C = d sin(beta) /
sin(alpha + beta) (cos(alpha), sin(alpha)); interior angles alpha, beta, pi - alpha - beta. Each corner is a
degree-4 vertex with creases z1..z4 counter-clockwise: z1 and z4 the triangle edges (A: AC, AB; B: BA, BC;
C: CB, CA), z2 and z3 two pleats (at most `pleat` long, `_points`). With c the corner angle (alpha41) and p the
pleat angle (alpha12: gamma at A, delta at B, epsilon at C) the sectors are (alpha12, alpha23, alpha34,
alpha41) = (p, pi - c, pi - p, c) (eqn 3-5): z2 turned p counter-clockwise from z1, z3 a further pi - c.
Seven faces: the triangle T,
the pleat panels P_AB, P_BC, P_CA (between a triangle edge and the pleats next to it) and the corner panels
O_A, O_B, O_C (between a vertex's two pleats). Nine creases, three loops.

Angles are fold angles rho (`sim_origami.creases`: 0 flat, > 0 a valley seen from +z); the input is
x = rho_AB in [-pi, pi]. (Feng 2018's dihedrals are phi = pi - |rho|, so its mu = tan(phi4/2)/tan(phi1/2)
is |tan(rho1/2)/tan(rho4/2)|.)

Closed form. A flat-foldable vertex folds in mode S (rho3 = -rho1, rho4 = rho2) or mode C (rho3 = rho1,
rho4 = -rho2), linear in t = tan(rho/2) (`vertex4.flat_foldable_multipliers`). Which crease then folds
opposite to the other three is fixed by the geometry, and is Feng 2018's vertex type (§3.3):

* mode C: type P (crease z2 odd) if p < c, type R (z4 odd) if p > c;
* mode S: type S (z1 odd) if p < pi - c, type Q (z3 odd) if p > pi - c.

(The thesis's rule "P: minimum sector at alpha12 or alpha23", etc., is the same condition.) Chaining t round
the triangle, AB -> B -> BC -> C -> CA -> A -> AB, multiplies t(AB) by the loop gain K = k_A k_B k_C with
k = t(z4)/t(z1) of each vertex; |k| = 1/mu. A scheme (a type per vertex, named in the order A, B, C) folds
rigidly iff K = 1: the signs close with an even number of types R, S (32 of 64 strings) and the magnitudes
with mu_a mu_b mu_c = 1 (eqn 3-11). Then tan(rho_i/2) = r_i tan(x/2) on every crease, a single branch through
flat that ends where every crease folds flat at once (x = +-pi). Types P and R have mu > 1, S and Q mu < 1,
so schemes of only P, R or only S, Q never fold (PPP, PRR, QQQ, QSS); the other 8 of the 12 classes under
rotation fold for the epsilon of the thesis's eqns 3-12 to 3-37.

At the thesis's Fig. 3-5 angles (55, 50, 50, 45 deg, epsilon = 35.4368 deg) the rigid scheme is SSP with M/V
AB, BC, CA = V, M, M, A2, A3 = V, V, B2, B3 = M, M, C2, C3 = V, M, as derived here from the vertex types (5 M / 4 V).
The thesis's PSR example (30, 80, 90, 45 deg) has gamma > alpha, so vertex A is type R, not P: it realises
RSP, a rotation of PRS, which the formula cannot tell from PSR (mu_r = -mu_p as printed) (derived here).
PQQ and QQQ fold 6 M / 3 V (up to a global flip), as the thesis's prose says, not 5/4 as its Table 3-1 lists.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..closure import LoopSystem
from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from .base import Branch, Event
from .fixed_modes import FixedModeKinematics
from .numeric_pattern import foldable_with_signs
from .vertex4 import flat_foldable_multipliers

VERTICES = ("A", "B", "C")
EDGES = ("AB", "BC", "CA")
PLEATS = ("A2", "A3", "B2", "B3", "C2", "C3")
CREASES = EDGES + PLEATS
FACES = ("T", "P_AB", "P_BC", "P_CA", "O_A", "O_B", "O_C")
INPUT = "AB"
# Vertex k's creases z1 and z4 (triangle edges); walked B -> C -> A so that z4 of one vertex is z1 of the next.
Z1 = {"A": "CA", "B": "AB", "C": "BC"}
Z4 = {"A": "AB", "B": "BC", "C": "CA"}
LOOP_ORDER = ("B", "C", "A")
MODE_OF = {"P": "C", "R": "C", "S": "S", "Q": "S"}
# The 12 scheme classes under rotation (Feng 2018, §3.3, Fig. 3-8): 8 rigid-foldable, 4 never.
RIGID_SCHEMES = ("PPQ", "PQQ", "PRS", "PSS", "QRS", "QRR", "PSR", "QSR")
LOCKED_SCHEMES = ("PPP", "PRR", "QQQ", "QSS")
SCHEMES = RIGID_SCHEMES + LOCKED_SCHEMES
# Every sign-consistent type string (32) -> its class: the class name rotated A -> B -> C.
CLASS_OF = {name[k:] + name[:k]: name for name in SCHEMES for k in range(3)}
# One realisation per class: (type string at A, B, C; alpha, beta, gamma, delta in deg; epsilon in deg for a
# locked class, None where the thesis's formula gives it). PSS is Feng 2018's Fig. 3-5 (realised as SSP), PRS
# its "PSR" example (realised as RSP); the others maximise, on a 5 deg grid (angles 20..160), the smallest
# distance of any vertex from its type boundary, of a pleat angle from 0 or 180 and of the triangle's corners
# from 20 deg (rigid ones with every |r_i| in [1/6, 6]): 20 deg for PPQ, PQQ, 25 for PPP, QQQ, else >= 50.
EXAMPLES: dict[str, tuple[str, float, float, float, float, float | None]] = {
    "PPQ": ("PPQ", 45.0, 80.0, 20.0, 20.0, None),
    "PQQ": ("PQQ", 50.0, 65.0, 30.0, 160.0, None),
    "PRS": ("RSP", 30.0, 80.0, 90.0, 45.0, None),
    "PSS": ("SSP", 55.0, 50.0, 50.0, 45.0, None),
    "QRS": ("QRS", 130.0, 30.0, 125.0, 80.0, None),
    "QRR": ("QRR", 140.0, 20.0, 110.0, 105.0, None),
    "PSR": ("PSR", 130.0, 30.0, 55.0, 100.0, None),
    "QSR": ("QSR", 130.0, 20.0, 125.0, 50.0, None),
    "PPP": ("PPP", 60.0, 60.0, 30.0, 30.0, 35.0),
    "PRR": ("PRR", 140.0, 20.0, 70.0, 90.0, 100.0),
    "QQQ": ("QQQ", 55.0, 55.0, 150.0, 150.0, 145.0),
    "QSS": ("QSS", 140.0, 20.0, 110.0, 70.0, 85.0),
}
# A loop gain within this of 1 is rigid; rigid ones measured within 1e-15, locked ones >= 1e-3 away (parallel pleats).
GAIN_TOL = 1e-12
# A pleat angle this close (rad) to c or pi - c puts two creases of a vertex on one line: no type.
COLLINEAR_TOL = 1e-9


@dataclass(frozen=True)
class TwistAngles:
    """Triangle corners alpha (at A), beta (at B) and pleat angles gamma, delta, epsilon (at A, B, C), radians."""

    alpha: float
    beta: float
    gamma: float
    delta: float
    epsilon: float

    def __post_init__(self):
        for name in ("alpha", "beta", "gamma", "delta", "epsilon"):
            value = getattr(self, name)
            if not 0.0 < value < np.pi:
                raise ParameterError(f"{name} = {np.rad2deg(value):.6g} deg; it must lie in (0, 180) deg")
        if not self.alpha + self.beta < np.pi:
            raise ParameterError(
                f"alpha + beta = {np.rad2deg(self.alpha + self.beta):.6g} deg; a triangle needs alpha + beta < 180 deg"
            )
        # the parameters behind each vertex's (corner, pleat), named in the refusal
        names = (("alpha", "gamma"), ("beta", "delta"), ("180 - alpha - beta", "epsilon"))
        for v, (c, p), (cn, pn) in zip(VERTICES, self.corners_and_pleats(), names, strict=True):
            for bound, rule in ((c, cn), (np.pi - c, f"180 - ({cn})" if " " in cn else f"180 - {cn}")):
                if abs(p - bound) < COLLINEAR_TOL:
                    raise ParameterError(
                        f"vertex {v}: pleat angle {pn} = {np.rad2deg(p):.6g} deg equals {rule} = "
                        f"{np.rad2deg(bound):.6g} deg (its corner); two of its creases are collinear and its M-V type "
                        "is undefined (Feng 2018, §3.3)"
                    )

    def corners_and_pleats(self) -> tuple[tuple[float, float], ...]:
        """(corner c = alpha41, pleat p = alpha12) at A, B, C, radians."""
        return (
            (self.alpha, self.gamma),
            (self.beta, self.delta),
            (np.pi - self.alpha - self.beta, self.epsilon),
        )


def vertex_sectors(c: float, p: float) -> NDArray[np.float64]:
    """Sector angles (alpha12, alpha23, alpha34, alpha41) = (p, pi - c, pi - p, c) of creases z1..z4 (eqn 3-5)."""
    return np.array([p, np.pi - c, np.pi - p, c])


def vertex_type(c: float, p: float, mode: str) -> str:
    """Type (P, Q, R or S; Feng 2018, §3.3) of a vertex with corner c and pleat p folding in mode 'C' or 'S'
    (module docstring)."""
    if mode == "C":
        return "P" if p < c else "R"
    return "S" if p < np.pi - c else "Q"


def check_types(types: str) -> None:
    """ParameterError unless `types` gives P, Q, R or S for each vertex A, B, C with an even number of R, S."""
    if len(types) != 3 or set(types) - set(MODE_OF):
        raise ParameterError(f"scheme {types!r}: give one type, P, Q, R or S, for each of the vertices A, B, C")
    flips = sum(t in "RS" for t in types)
    if flips % 2:
        raise ParameterError(
            f"scheme {types!r} has {flips} vertices of type R or S; M/V signs close round the triangle only with "
            "an even number (Feng 2018, §3.3: 32 of 64 strings)"
        )


def realised_types(angles: TwistAngles, modes: str) -> str:
    """Type string at A, B, C of a mode string (C or S per vertex) at these angles."""
    pairs = angles.corners_and_pleats()
    return "".join(vertex_type(c, p, m) for (c, p), m in zip(pairs, modes, strict=True))


def modes_of(angles: TwistAngles, types: str) -> str:
    """Mode string of a type string; ParameterError if the angles realise another type at some vertex."""
    check_types(types)
    modes = "".join(MODE_OF[t] for t in types)
    got = realised_types(angles, modes)
    if got != types:
        v = next(k for k in range(3) if got[k] != types[k])
        c, p = angles.corners_and_pleats()[v]
        raise ParameterError(
            f"vertex {VERTICES[v]} (corner {np.rad2deg(c):.6g} deg, pleat {np.rad2deg(p):.6g} deg) is type "
            f"{got[v]}, not {types[v]}: in mode {modes[v]} type P needs pleat < corner, R pleat > corner, S "
            "pleat < 180 - corner, Q pleat > 180 - corner (Feng 2018, §3.3)"
        )
    return modes


def tan_ratios(angles: TwistAngles, types: str) -> NDArray[np.float64]:
    """
    r (9,) in CREASES order with tan(rho_i/2) = r_i tan(rho_AB/2), chained from AB through B, C and A.

    Exact for a rigid scheme (loop gain 1). Otherwise the chain does not close (A's z4 would be K times AB) and
    r only carries the M/V signs of the scheme.
    """
    modes = modes_of(angles, types)
    t = {INPUT: 1.0}
    for v in LOOP_ORDER:
        k = VERTICES.index(v)
        m12, m23, m34, _ = flat_foldable_multipliers(vertex_sectors(*angles.corners_and_pleats()[k]))[modes[k]]
        t1 = t[Z1[v]]
        t[f"{v}2"] = m12 * t1
        t[f"{v}3"] = m23 * t[f"{v}2"]
        t.setdefault(Z4[v], m34 * t[f"{v}3"])
    return np.array([t[name] for name in CREASES])


def loop_gain(angles: TwistAngles, types: str) -> float:
    """K = k_A k_B k_C, k = tan(rho_z4/2) / tan(rho_z1/2) of each vertex in its scheme's mode: 1 iff rigid."""
    modes = modes_of(angles, types)
    gain = 1.0
    for (c, p), mode in zip(angles.corners_and_pleats(), modes, strict=True):
        gain /= flat_foldable_multipliers(vertex_sectors(c, p))[mode][3]  # m41 = t1 / t4
    return float(gain)


def assignment(angles: TwistAngles, types: str) -> str:
    """M/V letters in CREASES order of a scheme at rho_AB > 0 (V: rho > 0, a valley seen from +z)."""
    return "".join("V" if r > 0 else "M" for r in tan_ratios(angles, types))


def mu(letter: str, c: float, p: float) -> float:
    """Feng 2018's mu = tan(phi4/2) / tan(phi1/2) of a vertex of type `letter`, corner c, pleat p (eqns 3-17a-d)."""
    if letter in "PR":
        value = np.sin((c + p) / 2) / np.sin((c - p) / 2)
    else:
        value = np.cos((c + p) / 2) / np.cos((c - p) / 2)
    return float(value if letter in "PS" else -value)


def epsilon_formula(types: str, alpha: float, beta: float, gamma: float, delta: float) -> float:
    """
    Pleat angle epsilon at C (rad, in (-pi, pi)) that makes scheme `types` rigid (Feng 2018, §3.3, eqns 3-12
    to 3-37): mu_c(epsilon) = zeta = 1 / (mu_a mu_b) solved for C's type. Outside (0, pi): no compatible pattern.
    """
    check_types(types)
    zeta = 1.0 / (mu(types[0], alpha, gamma) * mu(types[1], beta, delta))
    T = np.tan((alpha + beta) / 2)
    num, den = {
        "P": (zeta - 1, (zeta + 1) * T),  # eqn 3-12
        "Q": ((zeta + 1) * T, 1 - zeta),  # eqns 3-20, 3-22
        "R": (zeta + 1, (zeta - 1) * T),  # eqns 3-30, 3-35, 3-37
        "S": ((1 - zeta) * T, zeta + 1),  # eqns 3-25, 3-27, 3-32
    }[types[2]]
    return float(2.0 * np.arctan2(num * np.sign(den), abs(den)))  # 2 atan(num / den), also where den = 0


def scheme_class(types: str) -> str:
    """The name (SCHEMES) of the rotation class of a sign-consistent type string."""
    check_types(types)
    return CLASS_OF[types]


def example_angles(scheme: str) -> tuple[str, TwistAngles]:
    """(realised type string, angles) of the EXAMPLES entry of a scheme class; epsilon by the thesis's formula."""
    if scheme not in EXAMPLES:
        raise ParameterError(f"unknown scheme {scheme!r}; the classes are {', '.join(SCHEMES)}")
    types, *deg, eps = EXAMPLES[scheme]
    a, b, g, d = np.deg2rad(deg)
    eps = epsilon_formula(types, a, b, g, d) if eps is None else np.deg2rad(eps)
    return types, TwistAngles(float(a), float(b), float(g), float(d), float(eps))


def _points(angles: TwistAngles, d: float, pleat: float) -> NDArray[np.float64]:
    """
    Vertices (9, 2): A, B, C, then the ends of A2, A3, B2, B3, C2, C3 (m).

    A pleat is `pleat` long, or half the distance to where it meets the facing pleat of its pleat panel
    (A3 and B2, B3 and C2, C3 and A2) when that is shorter. Every pleat panel is then a convex quadrilateral
    (diverging or parallel pleats keep it convex at any length).
    """
    a, b = angles.alpha, angles.beta
    corners = np.array([(0.0, 0.0), (d, 0.0), d * np.sin(b) / np.sin(a + b) * np.array([np.cos(a), np.sin(a)])])
    dirs = []
    for k, (c, p) in enumerate(angles.corners_and_pleats()):
        to_z1 = corners[(k + 2) % 3] - corners[k]  # A -> C, B -> A, C -> B
        start = np.arctan2(to_z1[1], to_z1[0])
        dirs += [np.array([np.cos(angle), np.sin(angle)]) for angle in (start + p, start + p + np.pi - c)]
    lengths = np.full(6, pleat)
    for k in range(3):  # panel on edge k -> k+1: pleat z3 of vertex k faces pleat z2 of vertex k+1
        i, j = 2 * k + 1, (2 * k + 2) % 6
        gap = corners[(k + 1) % 3] - corners[k]
        # corners[k] + s dirs[i] = corners[k + 1] + u dirs[j] (Cramer); parallel pleats (cross = 0) never meet
        cross = dirs[i][0] * dirs[j][1] - dirs[i][1] * dirs[j][0]
        s = (gap[0] * dirs[j][1] - gap[1] * dirs[j][0]) / cross if cross else -1.0
        u = (gap[0] * dirs[i][1] - gap[1] * dirs[i][0]) / cross if cross else -1.0
        if s > 0 and u > 0:
            lengths[i], lengths[j] = min(pleat, s / 2), min(pleat, u / 2)
    ends = [corners[k // 2] + lengths[k] * dirs[k] for k in range(6)]
    return np.vstack([corners, ends])


def crease_pattern(angles: TwistAngles, d: float = 1.0, pleat: float = 0.5, types: str | None = None) -> CreasePattern:
    """
    The triangle twist (module docstring) with side AB = d and pleats at most `pleat` long (m; `_points`).

    Creases carry the M/V of scheme `types` at rho_AB > 0 (any sign-consistent scheme the angles realise,
    rigid or not), or U (unassigned) when `types` is None.

    Raises
    ------
    ParameterError
      For non-positive lengths.
    """
    for name, value in (("d", d), ("pleat", pleat)):
        if not value > 0:
            raise ParameterError(f"{name} = {value:g} m; it must be positive")
    letters = assignment(angles, types) if types is not None else "U" * len(CREASES)
    A, B, C, A2, A3, B2, B3, C2, C3 = range(9)
    faces = ((A, B, C), (A, A3, B2, B), (B, B3, C2, C), (C, C3, A2, A), (A, A2, A3), (B, B2, B3), (C, C2, C3))
    ends = {"AB": (A, B), "BC": (B, C), "CA": (C, A), "A2": (A, A2), "A3": (A, A3), "B2": (B, B2),
            "B3": (B, B3), "C2": (C, C2), "C3": (C, C3)}
    points = _points(angles, d, pleat)
    creases = tuple(Crease(n, *ends[n], m) for n, m in zip(CREASES, letters, strict=True))
    return CreasePattern(points, faces, creases, FACES)


def sign_consistent_types(angles: TwistAngles) -> tuple[str, ...]:
    """
    The type strings these angles realise (one per mode string) whose M/V signs close (an even number of R, S):
    4 of the 8, or all or none when at no vertex exactly one mode flips the sign from z1 to z4.
    """
    out = []
    for k in range(8):
        modes = "".join("CS"[(k >> (2 - i)) & 1] for i in range(3))
        types = realised_types(angles, modes)
        if sum(t in "RS" for t in types) % 2 == 0:
            out.append(types)
    return tuple(out)


def rigid_types(angles: TwistAngles) -> tuple[str, ...]:
    """The sign-consistent schemes of these angles whose loop gain is 1 (GAIN_TOL): the pattern's motions."""
    return tuple(t for t in sign_consistent_types(angles) if abs(loop_gain(angles, t) - 1.0) <= GAIN_TOL)


@dataclass(frozen=True)
class SchemeVerdict:
    """
    One scheme class at its EXAMPLES realisation: analytic and numeric rigid-foldability verdicts.

    `mu` holds Feng 2018's mu_a, mu_b, mu_c (eqns 3-17); `rigid_analytic` is mu_a mu_b mu_c = 1 (eqn 3-11, to
    GAIN_TOL), which for the locked classes cannot hold for any epsilon (`mixed` False: every mu on one side
    of 1). `rigid_numeric` and `residual` are the sign-held closure of the crease pattern
    (`numeric_pattern.foldable_with_signs`): the largest closed residual when rigid, the stalled one when not.
    """

    name: str
    types: str
    angles: TwistAngles
    assignment: str
    mu: tuple[float, float, float]
    loop_gain: float
    rigid_numeric: bool
    residual: float

    @property
    def mixed(self) -> bool:
        """Some mu above 1 and some below: the only way the product can be 1 (types P, R above; S, Q below)."""
        return len({m > 1 for m in self.mu}) == 2

    @property
    def rigid_analytic(self) -> bool:
        return self.mixed and abs(float(np.prod(self.mu)) - 1.0) <= GAIN_TOL


def scheme_verdict(scheme: str, d: float = 1.0, pleat: float = 0.5) -> SchemeVerdict:
    """The verdicts of one scheme class (SchemeVerdict) at its EXAMPLES realisation."""
    types, angles = example_angles(scheme)
    loops = crease_pattern(angles, d, pleat).loop_system()
    rigid, residual = foldable_with_signs(loops, np.sign(tan_ratios(angles, types)), CREASES.index(INPUT))
    mus = tuple(mu(t, c, p) for t, (c, p) in zip(types, angles.corners_and_pleats(), strict=True))
    return SchemeVerdict(scheme, types, angles, assignment(angles, types), mus, loop_gain(angles, types), rigid,
                         residual)


def verdict_table(d: float = 1.0, pleat: float = 0.5) -> tuple[SchemeVerdict, ...]:
    """The 12 scheme classes (SCHEMES order) with their analytic and numeric verdicts."""
    return tuple(scheme_verdict(s, d, pleat) for s in SCHEMES)


class TriangleTwist(FixedModeKinematics):
    """
    The triangle twist driven by x = rho_AB in [-pi, pi]; its rigid schemes (type strings at A, B, C) are the
    branches.

    Parameters
    ----------
    angles : TwistAngles
      Corner and pleat angles (rad); at least one sign-consistent scheme must have loop gain 1.
    d, pleat : float
      Side AB and pleat length (m).
    types : str, optional
      The scheme whose M/V the pattern's creases record (default: the first rigid scheme).
    """

    input_name = "rhoAB"
    joint_names = tuple(f"rho{c}" for c in CREASES)

    def __init__(self, angles: TwistAngles, d: float = 1.0, pleat: float = 0.5, types: str | None = None):
        rigid = rigid_types(angles)
        if not rigid:
            gains = ", ".join(f"{t} {loop_gain(angles, t):.6g}" for t in sign_consistent_types(angles))
            raise ParameterError(
                f"no M-V scheme folds rigidly at these angles: loop gains {gains} (1 needed, eqn 3-11); "
                "take epsilon from epsilon_formula"
            )
        self.angles, self.d, self.pleat = angles, float(d), float(pleat)
        self.pattern = crease_pattern(angles, d, pleat, types or rigid[0])
        self.ratios = {t: tan_ratios(angles, t) for t in rigid}
        self._branches = tuple(self._describe(t) for t in rigid)

    def _describe(self, types: str) -> Branch:
        modes = modes_of(self.angles, types)
        text = (f"scheme {types} (class {scheme_class(types)}): vertices A, B, C in modes {', '.join(modes)}; "
                f"M/V at rhoAB > 0 in joint order: {assignment(self.angles, types)}")
        return Branch(types, text, (-np.pi, np.pi))

    def branches(self) -> tuple[Branch, ...]:
        return self._branches

    def events(self) -> tuple[Event, ...]:
        names = tuple(b.name for b in self._branches)
        out = [Event("lock", end, names, "every crease folded flat at once (|rho| = pi)") for end in (-np.pi, np.pi)]
        if len(names) > 1:
            out.append(Event("bifurcation", 0.0, names, "flat state: the rigid schemes cross"))
        return tuple(out)

    def gruebler(self) -> int:
        """Kutzbach: 9 creases - 3 per spherical loop (3 vertices) = 0; the pattern moves by its geometry."""
        return len(CREASES) - 3 * len(VERTICES)

    def loop_system(self) -> LoopSystem:
        """Per-vertex PoE closure of the crease pattern."""
        return self.pattern.loop_system()

    def loop_input(self) -> tuple[int, float]:
        return CREASES.index(INPUT), 1.0
