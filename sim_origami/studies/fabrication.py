"""Fabrication errors of the Bennett linkage and of its non-overconstrained forms (Yang 2017, ch. 3: §3.3 Bennett
-> RSSR, §3.4 Myard, §3.5 errors). Numpy only.

Fabrication errors (Sec. 3.5): x1 = alpha, x2 = a1 / a2; an error of scale k in [-1, 1] gives alpha + k d_alpha,
a1 + k d_l, a2 - k d_l (3-44), so k = +1 means a1 longer and a2 shorter. The output error of a built RSSR is
th2_built - th2_nominal at the same th1 (exact), or (3-41) with the partial derivatives of (3-42) (linearised;
evaluated in the K form above, which is (3-42) rewritten and stays finite at th1 = 0). The error is odd in th1
(th2(-th1) = -th2(th1)), so its peaks come in pairs +-th1; `peak` reports the one in (0, pi).

Ball-joint waggle (3-46...3-50): the angle between bar CD of the built RSSR and the nominal Bennett axis z_D (frame D: x
along DA, z_A at the nominal beta from z_D about x), |90 deg - angle(CD, z_D)|. CORRECTION (3-49): |CD| = a1R, not the
printed a2R: only a1R gives the thesis's waggles 0.58 and 1.22 deg. Derived here: its maximum over th1 is
|beta_R - beta| exactly, beta_R the built RSSR's implied beta: the balls turn about the implied Bennett's axes.

Overconstrained forms. A Bennett linkage built with the errors above (opposite sides still equal, ground twist
beta nominal) closes only at its two folded poses, theta1 = 0, theta2 = pi and theta1 = pi, theta2 = 0, where the
loop product is [Rz(pi) Tx(a2 -+ a1) Rx(beta -+ alpha)]^2 = I for any lengths and twists, and it is rigid there
(derived here); at every other input the loop residual stays (`closure_gap`). A Myard 5R with a twist error does not
close either. Forced together at one configuration (one axis tilted, `tilted`) either is a structure, mobility 0
(`screw_mobility`: freedoms minus the rank of the joint twists of a single closed loop), while its
non-overconstrained forms (balls in place of some R joints) keep mobility 1 with the same error.

Units: angles in radians; lengths in any one unit (the thesis's example is in mm).
"""
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closure import LoopSystem
from ..errors import ParameterError
from ..geometry import rotation, rotation_vector, transform_z, unit, wrap
from ..kinematics.dh import DHRow
from ..kinematics.rssr import RSSR, positive_length

DEG = np.pi / 180
# Yang 2017, §3.5: the nominal design (mm, rad) and the ISO 2768 tolerances of (3-43).
NOMINAL = (100.0, 70.72, 45 * DEG)  # a1R, a2R, alpha_R
VERY_COARSE = (1 * DEG, 1.5)  # d_alpha (rad), d_l (mm)
FINE_LENGTH = 0.15  # d_l (mm), class "fine"
# Singular values of a joint-twist matrix below this x the largest count as zero (exact twists: rounding only).
SCREW_RTOL = 1e-9



@dataclass(frozen=True)
class FabricationError:
    """Tolerances d_alpha (rad) and d_length (length unit), applied with scale k in [-1, 1] (3-43, 3-44)."""

    d_alpha: float = 0.0
    d_length: float = 0.0
    k: float = 1.0

    def __post_init__(self):
        if not (np.isfinite(self.d_alpha) and np.isfinite(self.d_length)):
            raise ParameterError(f"d_alpha = {self.d_alpha!r} rad, d_length = {self.d_length!r}: both must be finite")
        if not (np.isfinite(self.k) and -1 <= self.k <= 1):
            raise ParameterError(f"scale factor k = {self.k!r}; it must lie in [-1, 1] (3-44)")

    def built(self, nominal: RSSR) -> RSSR:
        """The RSSR as built: alpha + k d_alpha, a1 + k d_l, a2 - k d_l, on the nominal's root (3-44)."""
        k = self.k
        return RSSR(nominal.a1 + k * self.d_length, nominal.a2 - k * self.d_length, nominal.alpha + k * self.d_alpha,
                    nominal.root)

    def increments(self, nominal: RSSR) -> tuple[float, float]:
        """(dx1, dx2) of (3-44): k d_alpha and (a1 + k d_l) / (a2 - k d_l) - a1 / a2."""
        built = self.built(nominal)
        return self.k * self.d_alpha, built.x2 - nominal.x2


def output_error(nominal: RSSR, built: RSSR, theta1: ArrayLike) -> NDArray[np.float64]:
    """Exact output error theta2_built - theta2_nominal (rad, wrapped) at inputs theta1 (rad)."""
    return wrap(built.theta2(theta1) - nominal.theta2(theta1))


def linearised_error(nominal: RSSR, error: FabricationError, theta1: ArrayLike) -> NDArray[np.float64]:
    """(3-41) with (3-42), (3-45): d theta2 = (df/dx1) dx1 + (df/dx2) dx2 (rad) at inputs theta1 (rad)."""
    dx1, dx2 = error.increments(nominal)
    f1, f2 = nominal.sensitivity(theta1)
    return f1 * dx1 + f2 * dx2


def waggle(nominal: RSSR, built: RSSR, theta1: ArrayLike) -> NDArray[np.float64]:
    """
    |90 deg - angle(CD, z_D)| (rad) of the built RSSR at inputs theta1 (rad), z_D the nominal Bennett axis at D:
    the corrected (3-50), cos(gamma) = (a2R / a1R) [sin th2 (sin aR cos b + cos aR sin b cos th1)
    + sin b cos th2 sin th1] + sin b sin th1, with b the nominal beta and th2 the built RSSR's exact output.
    """
    t1 = np.asarray(theta1, dtype=float)
    t2, b, a = built.theta2(t1), nominal.beta, built.alpha
    sb, cb = np.sin(b), np.cos(b)
    bracket = np.sin(t2) * (np.sin(a) * cb + np.cos(a) * sb * np.cos(t1)) + sb * np.cos(t2) * np.sin(t1)
    cos_gamma = bracket / built.x2 + sb * np.sin(t1)
    return np.abs(np.arcsin(np.clip(cos_gamma, -1.0, 1.0)))  # 90 deg - gamma = arcsin(cos gamma); clip: rounding


@dataclass(frozen=True)
class Peak:
    """Largest |f| (f's unit) over an input interval and the input theta1 (rad) where it occurs."""

    value: float
    theta1: float


def peak(f: Callable[[NDArray], NDArray], lo: float = 0.0, hi: float = np.pi, samples: int = 3601) -> Peak:
    """Max of |f| on [lo, hi] (rad): a grid, then golden-section search between the best sample's neighbours."""
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi and samples >= 3):
        raise ParameterError(f"interval [{lo!r}, {hi!r}] with {samples!r} samples; need lo < hi, finite, >= 3 samples")
    x = np.linspace(lo, hi, samples)
    y = np.abs(f(x))
    if not np.all(np.isfinite(y)):
        raise ParameterError(f"f is not finite at theta1 = {x[~np.isfinite(y)][0]:.6g} rad")
    i = int(np.argmax(y))
    a, b = x[max(i - 1, 0)], x[min(i + 1, samples - 1)]
    g = (np.sqrt(5.0) - 1) / 2
    for _ in range(80):
        c, d = b - g * (b - a), a + g * (b - a)
        if abs(f(np.array([c]))[0]) > abs(f(np.array([d]))[0]):
            b = d
        else:
            a = c
    t = 0.5 * (a + b)
    return Peak(float(abs(f(np.array([t]))[0])), float(t))


@dataclass(frozen=True)
class ErrorStudy:
    """One row of Yang 2017's §3.5 study: exact and linearised peak output errors (rad), built implied beta."""

    error: FabricationError
    exact: Peak
    linearised: Peak
    beta: float


def study(nominal: RSSR, error: FabricationError) -> ErrorStudy:
    """Peak output errors over theta1 in (0, pi) (odd in theta1: the same at -theta1) of one fabrication error."""
    built = error.built(nominal)
    return ErrorStudy(
        error,
        peak(lambda t: output_error(nominal, built, t)),
        peak(lambda t: linearised_error(nominal, error, t)),
        built.beta,
    )


def max_waggle(nominal: RSSR, built: RSSR) -> Peak:
    """Largest ball-joint waggle (rad) over the whole input circle and where (equal to |beta_R - beta|)."""
    return peak(lambda t: waggle(nominal, built, t), -np.pi, np.pi, 7201)


# -- overconstrained forms: closure and single-loop mobility ------------------------------------------------------


def dh_axes(rows: tuple[DHRow, ...], q: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Joint origins and unit axes (n, 3) of a D-H loop at angles q (rad), in the frame of joint 1."""
    q = np.asarray(q, dtype=float)
    if q.shape != (len(rows),) or not np.all(np.isfinite(q)):
        raise ParameterError(f"q has shape {q.shape}; it must hold {len(rows)} finite joint angles (rad)")
    T, points, dirs = np.eye(4), [], []
    for row, angle in zip(rows, q, strict=True):
        points.append(T[:3, 3].copy())
        dirs.append(T[:3, 2].copy())
        T = T @ transform_z(angle) @ row.link()
    return np.array(points), np.array(dirs)


def tilted(dirs: ArrayLike, joint: int, angle: float) -> NDArray[np.float64]:
    """
    Axis directions (n, 3) with axis `joint` (1-based) turned by `angle` (rad) about the common normal to the next
    axis, its origin kept: a twist error of that link, the loop forced together at this configuration.
    """
    s = unit(np.asarray(dirs, dtype=float))
    if not 1 <= joint <= len(s) or not np.isfinite(angle):
        raise ParameterError(f"joint {joint!r}, angle {angle!r}: joint must be 1..{len(s)}, angle finite (rad)")
    k = joint - 1
    normal = np.cross(s[k], s[(k + 1) % len(s)])
    if np.linalg.norm(normal) < 1e-12:
        raise ParameterError(f"axes {joint} and {(k + 1) % len(s) + 1} are parallel: no unique common normal")
    out = s.copy()
    out[k] = rotation(unit(normal), angle) @ s[k]
    return out


def screw_mobility(
    points: ArrayLike, dirs: ArrayLike, spherical: tuple[int, ...] = (), rtol: float = SCREW_RTOL
) -> int:
    """
    Instantaneous mobility of ONE closed loop: its joint freedoms minus the rank of their unit twists
    (s, p x s), a revolute joint one twist along its axis, a spherical joint (1-based index in `spherical`) three
    through its point. Counts the idle spin of a bar between two balls (the truss method does not).
    """
    P, s = np.asarray(points, dtype=float), unit(np.asarray(dirs, dtype=float))
    bad = [k for k in spherical if not 1 <= k <= len(P)]
    if bad or P.shape != s.shape or P.ndim != 2 or P.shape[1] != 3:
        raise ParameterError(f"spherical joints {bad} / shapes {P.shape}, {s.shape}: need (n, 3) and joints 1..n")
    twists = []
    for k in range(len(P)):
        for axis in np.eye(3) if k + 1 in spherical else s[k : k + 1]:
            twists.append(np.concatenate([axis, np.cross(P[k], axis)]))
    sv = np.linalg.svd(np.array(twists).T, compute_uv=False)
    return len(twists) - int(np.sum(sv > rtol * sv.max()))


@dataclass(frozen=True)
class Gap:
    """Smallest loop residual found: joint angles (rad), rotation gap (rad) and translation gap (length unit)."""

    q: NDArray[np.float64]
    rotation: float
    translation: float


def closure_gap(
    loops: LoopSystem, starts: ArrayLike, scale: float, fixed: tuple[int, ...] = (), iterations: int = 100
) -> Gap:
    """
    The least residual of a single loop over the joint angles not in `fixed` (0-based; held at their start values),
    by damped Gauss-Newton from each start row (n_starts, n_joints), translation weighted by 1 / `scale` (a
    characteristic length). Zero where the loop can be assembled.
    """
    starts = np.atleast_2d(np.asarray(starts, dtype=float))
    positive_length("scale", scale)
    if len(loops.loops) != 1:
        raise ParameterError(f"closure_gap measures one loop; this system has {len(loops.loops)}")
    if starts.shape[1] != loops.n_joints or not len(starts) or not np.all(np.isfinite(starts)):
        raise ParameterError(f"starts of shape {starts.shape}; rows must hold {loops.n_joints} finite angles (rad)")
    if any(not 0 <= k < loops.n_joints for k in fixed):
        raise ParameterError(f"fixed joints {fixed}; they must be 0-based indices below {loops.n_joints}")
    weight = np.repeat([1.0, 1.0 / scale], 3)
    free = np.ones(loops.n_joints, dtype=bool)
    free[list(fixed)] = False
    gaps = []
    for q in starts:
        damping = 1e-6
        r = weight * loops.residual(q)
        for _ in range(iterations):
            J = weight[:, None] * loops.jacobian(q)[:, free]
            JtJ = J.T @ J
            trial = q.copy()
            trial[free] -= np.linalg.solve(JtJ + damping * (np.diag(np.diag(JtJ)) + 1e-12 * np.eye(len(JtJ))), J.T @ r)
            r_trial = weight * loops.residual(trial)
            if r_trial @ r_trial < r @ r:
                q, r, damping = trial, r_trial, max(damping / 10, 1e-12)
            else:
                damping *= 10
                if damping > 1e8:
                    break
        T = loops.loops[0].product(q)
        gaps.append(Gap(wrap(q), float(np.linalg.norm(rotation_vector(T[:3, :3]))), float(np.linalg.norm(T[:3, 3]))))
    return min(gaps, key=lambda g: g.rotation + g.translation / scale)
