"""Threefold-symmetric Bricard 6R linkage (Yang 2017: eqns 1-27, 2-8 to 2-11, 5-42 = 6-48, 6-50...6-52).

D-H rows (Yang 2017's convention, eqn 1-2): every a_(i,i+1) = a; alpha_12 = alpha_34 = alpha_56 = alpha and
alpha_23 = alpha_45 = alpha_61 = 2 pi - alpha; every R = 0. The motion keeps the threefold symmetry:
theta1 = theta3 = theta5 = theta and theta2 = theta4 = theta6 = phi, with (5-42 = 6-48)

    F = cos^2 a + sin^2 a (cos theta + cos phi) + (1 + cos^2 a) cos theta cos phi - 2 cos a sin theta sin phi = 0,

i.e. A cos phi + B sin phi + C = 0 with A = sin^2 a + (1 + cos^2 a) cos theta, B = -2 cos a sin theta,
C = cos^2 a + sin^2 a cos theta. Both roots are phi = atan2(B, A) +/- atan2(sqrt(D), -C), where the
discriminant D = A^2 + B^2 - C^2 reduces to (4 cos^2 a - 1) + 4 sin^2 a cos^2(theta/2), so:

* cos^2 a > 1/4: D > 0 on the whole input circle: two disjoint closed motions, no event;
* cos^2 a = 1/4 (alpha = 60, 120, 240, 300 deg; the thesis's Ch. 2 example): D = 0 only at theta = pi,
  where both motions pass through the bundle (every joint angle pi, joints 1 = 3 = 5 and 2 = 4 = 6
  coincide): a bifurcation, where a smooth motion crosses from one branch to the other;
* cos^2 a < 1/4: |theta| <= theta_max = 2 arcsin(sqrt(3) / (2 |sin a|)); the two branches are the
  halves of one closed motion, joined at the turning points theta = +/- theta_max.

Branches are named by geometry. Let u be the threefold symmetry axis, oriented so that the screw
carrying joint 1's frame onto joint 3's is a +120 deg turn about u (R13 = Rz(theta) Rx(a) Rz(phi) Rx(-a)
in frame 1, so u = vee(R13 - R13^T) / sqrt 3). Then z_2 . u = (A sin phi - B cos phi) / sqrt 3 = sin(spread)
|(A, B)| / sqrt 3, so the "+" root of this atan2 form is exactly the configuration in which the axes of joints 2, 4, 6
lean along u, and the "-" root the one in which they lean against it; they meet (z_2 . u = 0, the
even axes square to the symmetry axis) only at the turning points and the bundle, never inside a
domain, so each name is smooth over its open domain. In the tan-half form (6-51, 6-52) the along
branch is the '-' sign and the against branch the '+' sign, for every alpha. At theta = 0,
phi = +120 deg (along) or -120 deg (against) for every alpha, since F(0, phi) = 1 + 2 cos phi.

Only cos a and sin^2 a enter: alpha and 2 pi - alpha give the same motion (the thesis's printed axis
orientation, twists 300/60 deg, and 60/300 deg), and pi - alpha negates phi and swaps the names.
"""

from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ParameterError
from .base import Branch, Event, as_inputs, domain_of
from .dh import DHKinematics, DHRow

ALONG = "even-axes-along"
AGAINST = "even-axes-against"
# |4 cos^2 alpha - 1| below this counts as the bifurcating case cos^2 alpha = 1/4 exactly: the
# nearest doubles to 60/120/240/300 deg give 8.9e-16, which would otherwise turn the bundle of
# alpha = 120 deg into two turning points 6e-8 rad short of theta = pi. Snapping moves phi by at
# most sqrt(1e-13) ~ 3e-7 rad at the bundle and the closure residual by about 1e-13.
SPECIAL_TOL = 1e-13


class BricardThreefold(DHKinematics):
    """
    Threefold-symmetric Bricard linkage driven by theta1.

    Parameters
    ----------
    a : float
      Common link length (m), > 0.
    alpha : float
      Twist alpha_12 = alpha_34 = alpha_56 (rad), in (0, 2 pi) and != pi; the other three twists
      are 2 pi - alpha.
    """

    input_name = "theta1"
    joint_names = ("theta1", "theta2", "theta3", "theta4", "theta5", "theta6")

    def __init__(self, a: float, alpha: float):
        if not (np.isfinite(a) and a > 0):
            raise ParameterError(f"link length a = {a:g} m; it must be positive and finite")
        if not 0.0 < alpha < 2 * np.pi:
            raise ParameterError(
                f"twist alpha = {np.rad2deg(alpha):.6g} deg; it must lie in (0, 360) deg "
                "(alpha = 0 or 360 makes all six axes parallel)"
            )
        if abs(alpha - np.pi) < 1e-12:
            raise ParameterError(
                f"twist alpha = {np.rad2deg(alpha):.12g} deg; it must differ from 180 deg "
                "(all six axes would be parallel: a planar 6R with 3 degrees of freedom, not a Bricard linkage)"
            )
        self.a, self.alpha = float(a), float(alpha)
        self.c = float(np.cos(alpha))
        self.s2 = float(np.sin(alpha) ** 2)
        gap = 4 * self.c**2 - 1
        self.gap = 0.0 if abs(gap) <= SPECIAL_TOL else gap
        # Largest input (rad): pi unless cos^2 alpha < 1/4, where sin(theta_max / 2) = sqrt(3) / (2 |sin alpha|).
        self.theta_max = float(np.pi if self.gap >= 0 else 2 * np.arcsin(np.sqrt(3.0 / (4 * self.s2))))

    @property
    def kind(self) -> str:
        """'disjoint' (cos^2 a > 1/4), 'bifurcating' (= 1/4) or 'turning' (< 1/4)."""
        return "disjoint" if self.gap > 0 else "bifurcating" if self.gap == 0 else "turning"

    @property
    def rows(self) -> tuple[DHRow, ...]:
        """D-H rows of joints 1..6 (eqn 1-27)."""
        odd, even = DHRow(0.0, self.a, self.alpha), DHRow(0.0, self.a, 2 * np.pi - self.alpha)
        return (odd, even) * 3

    def discriminant(self, theta: ArrayLike) -> NDArray[np.float64]:
        """
        D = A^2 + B^2 - C^2 of the closure in phi; >= 0 exactly where the linkage assembles.

        Written without cancellation: (4 c^2 - 1) + 4 s^2 cos^2(theta/2) when both terms are >= 0,
        else 4 s^2 sin((theta_max - theta)/2) sin((theta_max + theta)/2), which is >= 0 exactly for
        |theta| <= theta_max.
        """
        t = np.asarray(theta, dtype=float)
        if self.gap >= 0:
            return self.gap + 4 * self.s2 * np.cos(t / 2) ** 2
        return 4 * self.s2 * np.sin((self.theta_max - t) / 2) * np.sin((self.theta_max + t) / 2)

    def roots(self, theta: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        """
        phi of both roots, (2, n): [along, against], each continuous on the open input domain.

        Returns
        -------
        phi : (2, n) float
          atan2(B, A) +/- spread; not wrapped (atan2(B, A) only jumps at theta = +/- pi).
        real : (n,) bool
          |theta| <= pi and D >= 0.
        """
        t = np.atleast_1d(np.asarray(theta, dtype=float))
        c, s2 = self.c, self.s2
        A = s2 + (1 + c * c) * np.cos(t)
        B = -2 * c * np.sin(t)
        C = c * c + s2 * np.cos(t)
        D = self.discriminant(t)
        real = (np.abs(t) <= np.pi) & (D >= 0)
        base = np.arctan2(B, A)
        spread = np.arctan2(np.sqrt(np.maximum(D, 0.0)), -C)
        return np.stack([base + spread, base - spread]), real

    def closure(self, theta: ArrayLike, phi: ArrayLike) -> NDArray[np.float64]:
        """Left side F of (5-42 = 6-48); zero on the motion."""
        t, p = np.asarray(theta, dtype=float), np.asarray(phi, dtype=float)
        c, s2 = self.c, self.s2
        return (
            c * c + s2 * (np.cos(t) + np.cos(p)) + (1 + c * c) * np.cos(t) * np.cos(p) - 2 * c * np.sin(t) * np.sin(p)
        )

    def evaluate(self, branch: str, x: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
        index = (ALONG, AGAINST).index(self.branch(branch).name)
        t = as_inputs(x)
        phi, valid = self.roots(t)
        p = phi[index]
        values = np.stack([t, p, t, p, t, p], -1)
        values[~valid] = np.nan
        return values, valid

    @cached_property
    def _branches(self) -> tuple[Branch, ...]:
        domain = domain_of(lambda x: self.roots(x)[1], -np.pi, np.pi, 0.0)
        lean = "u oriented so that joint 1's frame turns +120 deg about u onto joint 3's"
        return (
            Branch(
                ALONG,
                f"the axes of joints 2, 4, 6 lean along the threefold axis u (z2 . u > 0), {lean}; "
                "phi = +120 deg at theta = 0; the '-' sign of (6-51, 6-52)",
                domain,
            ),
            Branch(
                AGAINST,
                f"the axes of joints 2, 4, 6 lean against the threefold axis u (z2 . u < 0), {lean}; "
                "phi = -120 deg at theta = 0; the '+' sign of (6-51, 6-52)",
                domain,
            ),
        )

    def branches(self) -> tuple[Branch, ...]:
        return self._branches

    def events(self) -> tuple[Event, ...]:
        both = (ALONG, AGAINST)
        if self.kind == "bifurcating":
            detail = (
                "bundle: every joint angle is pi, joints 1 = 3 = 5 and 2 = 4 = 6 coincide; both branches "
                "cross here and a smooth motion continues on the other branch (Yang 2017, §2.4)"
            )
            return tuple(Event("bifurcation", end, both, detail) for end in (-np.pi, np.pi))
        if self.kind == "turning":
            lo, hi = self._branches[0].domain
            detail = (
                "turning point: the input turns back, the axes of joints 2, 4, 6 are square to the threefold "
                "axis and the motion goes on along the other branch"
            )
            return tuple(Event("turning_point", end, both, detail) for end in (lo, hi))
        return ()


Triple = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]


def bricard_trig(bricard: BricardThreefold, theta: NDArray[np.float64]) -> tuple[NDArray[np.float64], ...]:
    """
    cos theta, sin theta, cos phi, sin phi (n,) of `bricard` at inputs theta (n,) (rad) on its 'along' branch: phi
    the root atan2(B, A) + atan2(sqrt D, -C) of A cos phi + B sin phi + C = 0 (`BricardThreefold.roots`), so
    (cos phi, sin phi) = (-A C - B sqrt D, A sqrt D - B C) / (A^2 + B^2), with no angle computed.
    """
    c, s2 = bricard.c, bricard.s2
    ct, st = np.cos(theta), np.sin(theta)
    A, B, C = s2 + (1.0 + c * c) * ct, -2.0 * c * st, c * c + s2 * ct
    root, norm = np.sqrt(bricard.discriminant(theta)), A * A + B * B
    return ct, st, (-A * C - B * root) / norm, (A * root - B * C) / norm


def bricard_axis(bricard: BricardThreefold, theta: NDArray[np.float64]) -> tuple[Triple, Triple, NDArray, NDArray]:
    """
    The threefold axis of `bricard` at inputs theta (n,) (rad, 'along' branch) in the D-H frame of link 1 (joint
    1's frame after Rz(theta)), without poses: unit direction u and a point p (m), each as 3 arrays (n,) of x, y, z,
    and cos phi, sin phi (`bricard_trig`). The turn carrying link 1 onto link 3, T = Tx(a) Rx(alpha) Rz(phi) Tx(a)
    Rx(-alpha) Rz(theta) (the rows), is +120 deg about u = vee(R - R^T) / |.|, and p = t_perp / 2 + u x t / (2 sqrt 3)
    solves (I - R) p = t across u (cot 60 deg = 1 / sqrt 3).
    """
    c, s, a, s2 = bricard.c, np.sin(bricard.alpha), bricard.a, bricard.s2
    ct, st, cp, sp = bricard_trig(bricard, theta)
    v = 1.0 - cp
    u = (
        s * (v * c * (1.0 - ct) - sp * st),
        s * (v * c * st - sp * (1.0 + ct)),
        2.0 * c * sp * ct + (2.0 * cp + v * s2) * st,
    )
    size = np.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
    u = u[0] / size, u[1] / size, u[2] / size
    t = a * (1.0 + cp), a * c * sp, a * s * sp
    along = t[0] * u[0] + t[1] * u[1] + t[2] * u[2]
    k = 0.5 / np.sqrt(3.0)
    p = (0.5 * (t[0] - along * u[0]) + k * (u[1] * t[2] - u[2] * t[1]),
         0.5 * (t[1] - along * u[1]) + k * (u[2] * t[0] - u[0] * t[2]),
         0.5 * (t[2] - along * u[2]) + k * (u[0] * t[1] - u[1] * t[0]))
    return u, p, cp, sp
