"""Scene `waterbomb-tube`: the generalized waterbomb tube on its radial contraction (Feng, Ma and Chen 2020,
§2; Feng 2018, ch. 6).

Every triangular face is a body (6nm) and every crease a hinge (9nm - 2n). The flat strip
(`kinematics.waterbomb_tube`) gives the bodies and the strip's creases (`origami.pattern_mechanism`); the 2m - 1
seam creases are added as hinges whose two frames sit on their two copies, 2 n a apart in the flat sheet, so
that the spanning tree may keep them or cut them like any other crease: the tree is the shortest-path one from
the input crease's face round the whole tube (`WaterbombTube.tree_creases`), and the connects on its cut
creases roll the strip into a tube. The free tube has 4n - 6 DOF; the sources' symmetry (units alike round a row,
plane-symmetric units, equatorial mirror or half-turn) is imposed by joint couplings, every tree crease to the
first of its symmetry class (`WaterbombTube.couplings`, 98 on the 6 x 3 tube, 164 on the 6 x 5: redundant,
4n - 7 would do), which leaves the 1-DOF contraction, driven at the equatorial row's top midline A<r0>_0_1
(theta = pi + rho). Every face carries a collision solid and the scene has self contact (panels sharing a vertex
of the tube excluded): with contact on, panels that pass through each other collide (INSET).
"""

from dataclasses import dataclass

from ..creases import Crease, CreasePattern
from ..errors import ParameterError
from ..kinematics.waterbomb_tube import WaterbombTube
from ..mechanism import Joint, Mechanism
from ..origami import pattern_mechanism
from .base import ACUTE, Param, Scene, register

# Largest tube accepted: n <= 24, m <= 15 and n m <= 120 units (`check_size`): 12 x 9 builds in 4.6 s of CPU,
# 20 x 11 in 24 s (the closed form's trace and the spanning tree grow faster than the panel count).
TUBE_UNITS = {"lo": 3, "hi": 24, "integer": True, "limit": "at most 24 units round, 120 units in all"}
TUBE_ROWS = {"lo": 1, "hi": 15, "integer": True, "limit": "at most 15 rows, 120 units in all"}
TUBE_CELLS_MAX = 120
PARAMS = (
    Param("n", "", 6, "units round the tube (>= 3)", **TUBE_UNITS),
    Param("m", "", 5, "rows (>= 1); odd: equatorial row, even: equatorial row boundary", **TUBE_ROWS),
    Param("alpha", "deg", 40.0, "design angle alpha (big triangles' apex 180 - 2 alpha)", **ACUTE),
    Param("beta", "deg", 40.0, "design angle beta (small triangles' angle at the corner)", **ACUTE),
    Param("a", "m", 0.5, "half-width of a unit"),
)
# Default sweep: the middle PATH_SHARE of the contraction's range of theta, clear of the fully folded equatorial
# row at 2 pi / n (the free tube gains its twist mode there: the coupled closure's smallest singular value falls
# from 2.3e-2 to 1.4e-4 at 60.01 deg) and of the top row's fold (eqn 14). 6 x 5, 40/40 deg: theta 69.8 -> 115.4
# deg, through both uniform-radius states (98.72, 111.28 deg), which are regular points of the coupled closure.
PATH_SHARE = 0.7
# The symmetry couplings are soft (MuJoCo joint equalities) and set the path error, which falls as the square of
# the sweep time. With MuJoCo's own regulariser: fast, default sweep, every crease, 6 x 5 tube 2.8e-7 rad at 16x
# (70 s CPU), 1.2e-6 at 8x; stiff did better at equal CPU: 1.3e-7 at 8x (16 s CPU, 786 steps/s). With the presets'
# regulariser (scaled 0.01) fast at 8x measured 1.5e-8 rad in 11.5 s of CPU against stiff's 1.3e-7 in 17.8 s (6 x
# 5; 6 x 3: 1.3e-8 in 4.1 s), so the scene runs fast.
# Rates (scripts/waterbomb_tube_rate.py, preset stiff: steps/s of the cheapest step, CPU of the stepping loop,
# contact off), on the breadth-first spanning tree (`WaterbombTube.tree_creases`): 1328 steps/s on the 6 x 5 tube
# (180 panels), 796 on 8 x 5, 554 on 10 x 5 (300 panels, 3.5e-7 rad; the crease-order tree: 648, 422, 297);
# contact on costs 35-45 %. With only the loops the couplings do not imply (`without_implied_closures`: 6 of 131
# on 10 x 5) 4054, 2510 and 1793 steps/s at the same error; the scene imposes every loop, which `fast` needs.
ANCHORS = (0.5, 1.0)
# Collision solids: each face's plate (NOMINAL_THICKNESS x the longest crease thick) inset from every edge by INSET * a.
# Panels that share a vertex of the tube (across the seam too: `TubePattern`) never collide, so only the sources'
# "physical interference" does (Feng, Ma and Chen 2020, Fig. 8c, n6 m7 beta 40: middle-row collisions from
# alpha = 54.6 deg). Measured with INSET = 0.003: onset at alpha = 54.593 deg (bare triangles 54.578, paper 54.6); at
# alpha = 56 deg contact from the bottom of the range (88.786 deg; an independent triangle test: 88.79) to theta =
# 95.130 deg (bare triangles 95.168, the independent test 95.04), where a force-limited servo driven inward stops
# (95.107 deg). The end moves with the inset: 95.777, 95.377, 94.881, 93.329 deg for 0, 0.002, 0.004, 0.01 a. The
# default tube's solids touch only below theta = 60.83 deg (middle row folded flat, its A's on the axis), clear of
# its sweep. tests/test_waterbomb_tube_contact.py.
INSET = 0.003


@dataclass(frozen=True)
class TubePattern(CreasePattern):
    """The flat strip of a tube, whose seam vertices are one vertex each (`strip_keys`: strip vertex -> tube vertex),
    so that faces on the two sides of the seam that meet there count as touching."""

    strip_keys: tuple[int, ...] = ()

    def touching_faces(self) -> tuple[tuple[str, str], ...]:
        """Pairs of faces that share a vertex of the tube, sorted by face order."""
        at: dict[int, set[int]] = {}
        for f, face in enumerate(self.faces):
            for v in face:
                at.setdefault(self.strip_keys[v], set()).add(f)
        pairs = {(a, b) for group in at.values() for a in group for b in group if a < b}
        return tuple((self.face_names[a], self.face_names[b]) for a, b in sorted(pairs))


def check_size(n: float, m: float) -> None:
    """ParameterError when the tube has more than TUBE_CELLS_MAX units (n and m are checked one by one already)."""
    if n * m > TUBE_CELLS_MAX:
        raise ParameterError(
            f"n = {n:g} and m = {m:g} make {n * m:g} units; a tube may have at most {TUBE_CELLS_MAX} (n m <= "
            f"{TUBE_CELLS_MAX}: 12 x 9 builds in about 5 s, 20 x 11 in 24 s)"
        )


def tube_pattern(kinematics: WaterbombTube) -> TubePattern:
    """The tube's strip (`kinematics.pattern`) with its seam vertices identified (`TubePattern`)."""
    strip = kinematics.pattern
    keys = tuple(int(k) for k in kinematics.layout.strip_keys)
    return TubePattern(strip.vertices, strip.faces, strip.creases, strip.face_names, strip_keys=keys)


def seam_joints(pattern: CreasePattern, kinematics: WaterbombTube) -> tuple[Joint, ...]:
    """The seam creases as hinges from their right face (parent) to their left face (child), each frame on that
    face's copy of the crease in the flat sheet (`sim_origami.creases` for the sign)."""
    out = []
    for seam in kinematics.layout.seam:
        frames = [pattern.hinge_frame(Crease(seam.name, *ends)) for ends in (seam.right_ends, seam.left_ends)]
        span = pattern.length(Crease(seam.name, *seam.left_ends))
        out.append(Joint(seam.name, seam.right_face, seam.left_face, frames[0], frames[1],
                         tuple(f * span for f in ANCHORS)))
    return tuple(out)


def tube_mechanism(kinematics: WaterbombTube, collision_inset: float | None = None) -> Mechanism:
    """Faces as bodies, every crease of the tube as a hinge, the symmetry couplings; root: the input crease's
    right face. With `collision_inset` (m) the faces carry collision solids inset by that much from every edge."""
    pattern = kinematics.pattern
    drive = kinematics.input_crease
    root = kinematics.tree_root
    couplings = tuple((a, b, 1.0) for a, b in kinematics.couplings)
    strip = pattern_mechanism(pattern, root=root, anchors=ANCHORS, collision_inset=collision_inset)
    joints = strip.joints + seam_joints(pattern, kinematics)
    return Mechanism(strip.bodies, joints, root, (drive,), couplings, breadth_first=True)


def default_path(kinematics: WaterbombTube) -> tuple[float, float]:
    """The middle PATH_SHARE of the contraction's domain of the input rho (rad), swept outward (theta rising)."""
    lo, hi = kinematics.domain
    margin = 0.5 * (1 - PATH_SHARE) * (hi - lo)
    return lo + margin, hi - margin


@register("waterbomb-tube", "generalized waterbomb tube, n units x m rows, radial contraction under the "
          "sources' symmetry (Feng, Ma and Chen 2020, §2; Feng 2018, §6.1-6.2), input rho of the equatorial top "
          "midline", PARAMS)
def build(n: float, m: float, alpha: float, beta: float, a: float) -> Scene:
    check_size(n, m)
    kinematics = WaterbombTube(n, m, alpha, beta, a)
    return Scene(
        name="waterbomb-tube", params={"n": n, "m": m, "alpha": alpha, "beta": beta, "a": a},
        kinematics=kinematics, mechanism=tube_mechanism(kinematics, INSET * a), loop_joints=kinematics.crease_names,
        drive_joint=kinematics.input_crease, drive_scale=1.0, path=default_path(kinematics),
        pattern=tube_pattern(kinematics), self_contact=True,
        notes=f"{int(n)} x {int(m)} tube; {len(kinematics.couplings)} symmetry couplings; "
        f"{len(kinematics.layout.seam)} seam creases closed by connects",
    )
