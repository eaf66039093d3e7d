"""Scene `thick-diamond`: a thick-panel six-crease diamond vertex = plane-symmetric Bricard (Peng 2018, §4.4.1).

Panels are slabs between their hinge planes and collide (relieved from the creases as in `thick-vertex4`,
with q, the distance between hinges 2 and 3, as the thickness scale). With h = (0, p, p - q, -2q, p - q, p)
creases 1, 2, 4 and 6 join the same faces: on branch 'diamond' they fold freely for rho1 < 0 and collide at
once the other way, and the mixed-face creases 3 and 5 collide at |rho3| = pi/2, i.e.
rho1 = -2 atan(cos(alpha)) (-1.427 at 30 deg). Branch 'counter23' folds crease 4 with crease 2 for
r/p > 1 + sqrt(2) (the defaults), so its slabs collide at once in both directions: kinematic runs only.
"""

import itertools

from ..kinematics.thick_diamond import ThickDiamond
from ..origami import vertex_mechanism
from .base import ANGLE_MARGIN, Param, Scene, register
from .thick_vertex4 import RELIEF

PARAMS = (
    Param("alpha", "deg", 30.0, "sector angle in (0, 45]; sectors a, 180 - 2a, a, a, 180 - 2a, a",
          lo=ANGLE_MARGIN, hi=45),
    Param("p", "m", 0.03, "hinge spacing a12 = a61 (thickness of panels 1 and 6)"),
    Param("q", "m", 0.05, "hinge spacing a23 = a56 (thickness of panels 2 and 5)"),
    Param("r", "m", 0.08, "hinge spacing a34 = a45 (thickness of panels 3 and 4); must equal p + q"),
    Param("length", "m", 1.0, "crease length"),
)

# Default sweep of rho1 (rad): collision-free on branch 'diamond', clear of the flat bifurcation (where the
# thin loop is ill-conditioned) and of the mixed-face contact near rho1 = -1.427 (alpha = 30 deg).
PATH = (-0.4, -1.0)

# MuJoCo layout. The zero-thickness vertex has 3 DOF, so the thick loop keeps two singular values of about
# p/length and q/length (0.03) along the motion, and the soft closure's violation is amplified by their
# inverse. Fast path error (diamond / counter23) over rho1 = -0.4..-1.2 by fixed panel / cut crease, closure
# points at 0.5 and 1 x length as in thick-vertex4: panel 1 / crease 6 1.1e-4 / 2.7e-5 rad, panel 1 /
# crease 2 1.0e-5 / 4.7e-6, panel 3 / crease 3 5.0e-6 / 3.2e-6; with the points at both ends of the hinge
# (0 and 1 x length) 2.2e-5 / 8.7e-6, 2.7e-6 / 1.7e-6 and 2.7e-6 / 5.5e-7. The error peaks at the sweep's
# far end and grows with its length: -0.4..-1.0 gives 1.7e-6 / 4.2e-7 (panel 3 / crease 3, both ends).
ROOT, CUT = 3, 3
ANCHORS = (0.0, 1.0)  # fractions of the crease length


@register("thick-diamond", "thick-panel six-crease diamond vertex = Bricard linkage (Peng 2018, §4.4.1), input rho1",
          PARAMS)
def build(alpha: float, p: float, q: float, r: float, length: float) -> Scene:
    kinematics = ThickDiamond(alpha, p, q, r)
    keep = tuple(k for k in range(1, 7) if k != CUT)
    mechanism = vertex_mechanism(
        kinematics.sectors,
        length=length,
        inset=RELIEF * q,
        root=ROOT,
        keep=keep,
        heights=kinematics.heights,
        anchors=ANCHORS,
    )
    return Scene(
        name="thick-diamond",
        params={"alpha": alpha, "p": p, "q": q, "r": r, "length": length},
        kinematics=kinematics,
        mechanism=mechanism,
        loop_joints=tuple(f"crease_{k}" for k in range(1, 7)),
        drive_joint="crease_1",
        drive_scale=1.0,
        path=PATH,
        contact_pairs=tuple(itertools.combinations([f"panel_{i}" for i in range(1, 7)], 2)),
        notes="hinge k on the line through (0, 0, h_k) along d_k, h = (0, p, p - q, p - q - r, p - q, p), r = p + q; "
        "qpos = fold angle of the zero-thickness vertex",
    )
