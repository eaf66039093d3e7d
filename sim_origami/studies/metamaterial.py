"""Double-corrugated metamaterial elements 1, 2 and 3 (Peng 2018, §3.2.3, eqns 3-24 to 3-28) measured on
the simulated geometry of the double-corrugated sheet (numpy only).

Input is geometry, never a MuJoCo object: vertex positions (n, V, 3) of the P-unit sheet of
`kinematics.corrugated_sheet` (`poisson.vertex_positions` of a motion's body poses) and the input phi. Lengths in
metres (every crease l = 1 in the thesis), angles in radians.

The thesis's formulas. phi is the dihedral angle of crease A2B2 (pi flat, 0 folded flat), whose neighbours A2A1 and A2A3
make sectors pi - alpha (= gamma) and beta with it: the spherical law of cosines gives the angle psi = A1A2A3, so
W = |A1A3|; H is the height of B2 above the plane A1A2A3 (B2' its foot there) and L twice the in-plane
component of A2B2 along the bisector of psi. Element 2 has the same W and twice H and L. Element 3 (3-26, 3-27)
turns this round at B5: theta is the dihedral angle of B4B5, whose neighbours B5A5 and B5C5 make sectors
pi - alpha and pi - beta with it, so L = |A5C5| is the chord of the angle A5B5C5, H twice the height of B4 above
the plane A5B5C5 and W four times the in-plane component of B5B4 along the bisector of A5B5C5.

Placement (reconstructed here; the thesis's Fig 3-11 is lost in our copy). In the sheet's lattice (vertex (i, j), i
along u, j along v; `corrugated_sheet` docstring) the thesis's labels read letter = i (A = 1) and digit = j: A2 = (1,
2), A1 = (1, 1), A3 = (1, 3), so that A2B2 = u1_2, the crease between A2's sectors gamma and beta, and phi = pi -
|rho_u1_2| on every element:

* element 1 = branch SCSC (the thesis's P1): the u row (k, 2) is a zig-zag of period two steps, translated along
  the bisector of psi; L = |A2C2|, H = distance of B2 from the plane A1A2A3 (every u crease folds with |x|);
* element 2 = branch SCCS: the u row climbs two steps and comes down two, heights 0, H1, 2 H1, H1, 0 (the
  thesis's C' = C reflected in the plane B1B2D1D2); L = |A2E2|, H = distance of C2 from the plane A1A2A3;
* element 3 = branch CCSS: u creases at odd j fold with |x|, those at even j (A2B2 among them) with tan-half
  gain 0.101, every v crease with 0.1645 (at alpha = 3 pi/4, beta = pi/3). The even-j vertices stay in one plane,
  the thesis's A2A4B2B4, and the rows j = 1, 5 and j = 3 in two planes parallel to it at equal distances either
  side, mirror images in it (measured <= 1.5e-14 m): W = |B1B5|, L = |A5C5|, H = distance of B3 from the plane
  A5B5C5 (twice that of B4), theta = pi - |rho_v2_4|. Its L equals element 1's at every phi (measured 6.7e-16 m).

All three agree with the thesis's formulas to rounding at every phi (tests/test_metamaterial.py). Element 1's
vertices also follow eqn 3-24 on CCSS (the thesis's original pattern P2, tentatively; there A2B2 folds with gain
0.101, so phi stays near pi unless x nears pi) and on CSSC; on CSCS, SCCS and SSCC they do not (L misses by
>= 0.6 m). Element 2's follow eqn 3-25 on SCCS only, element 3's eqns 3-26/3-27 on CCSS only (W, H or L
>= 1.25 m off).

Reading note, element 3 (as printed, 3-26 gives theta < 0 at alpha = 3 pi/4, beta = pi/3). Only
cos(theta) enters 3-27, so the sign is harmless; the magnitude is not. As printed, tan(theta/2) =
tan(phi/2) cos((beta + alpha)/2) / cos((beta - alpha)/2) has gain -0.1645: theta's crease folds 6.08 times as
fast as A2B2. On the sheet only a u crease against a v crease has that ratio, but cos(A5B5C5) = cos(beta)
cos(alpha) + sin(beta) sin(alpha) cos(theta) needs B4B5 between sectors summing to alpha + beta (or 2 pi minus
that), which are the v creases. Measured on the 3 x 3 P and Q sheets, all six rigid strings of each, with every
crease as A2B2 and every crease, at either end, as B4B5: none is both at the printed theta and at 3-27's L, H/2,
W/4 there (0 hits); the printed formula's W, H, L miss the CCSS sheet's vertex distances by up to 1.38 m. With
the neighbour sector of A2B2 that the thesis itself uses in 3-24, gamma = pi - alpha in place of alpha (the hint
of the mode multipliers of its §3.2.1),

    theta = 2 arctan(tan(phi/2) cos((beta + gamma)/2) / cos((beta - gamma)/2))    (gain 0.614 > 0),

theta is the dihedral angle of v2_4 on CCSS to 8.9e-16 rad, and W, H, L are the vertex distances above to
1.9e-14 m over phi in [0.01, pi - 0.01] (9.0e-14 m for alpha = 120, beta = 70 deg). This module uses that
reading and the rest of 3-26/3-27 as printed. It gives the text's claims: "(d) has a much larger phi_II"
(2.526 against 0.955 rad) and "maximum heights of (b)-(d) are equal and twice that of (a)" (2 sin(alpha) =
1.414214 against sin(alpha)).

Poisson's ratios (3-28): nu_in = -(dL/L)/(dW/W), nu_out = -(dH/H)/(dW/W); closed form by complex-step
differentiation of the formulas (exact to rounding), measured by `poisson.poisson_ratio` on the samples.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..creases import CreasePattern
from ..errors import ParameterError
from .poisson import poisson_ratio, thin


@dataclass(frozen=True)
class Placement:
    """
    An element on the P sheet: its rigid mode string, the thesis's labels -> lattice vertices (i, j), and its
    measures by label: W, L = |first second|, H = distance of `apex` from the plane of `base`.
    """

    branch: str
    labels: dict[str, tuple[int, int]]
    W: tuple[str, str]
    L: tuple[str, str]
    apex: str
    base: tuple[str, str, str]


_ROW = {"A1": (1, 1), "A2": (1, 2), "A3": (1, 3)}
ELEMENTS = {
    1: Placement("SCSC", {**_ROW, "B2": (2, 2), "C2": (3, 2)}, ("A1", "A3"), ("A2", "C2"), "B2", ("A1", "A2", "A3")),
    2: Placement("SCCS", {**_ROW, "C2": (3, 2), "E2": (5, 2)}, ("A1", "A3"), ("A2", "E2"), "C2", ("A1", "A2", "A3")),
    3: Placement(
        "CCSS",
        {"B1": (2, 1), "B3": (2, 3), "A5": (1, 5), "B5": (2, 5), "C5": (3, 5)},
        ("B1", "B5"), ("A5", "C5"), "B3", ("A5", "B5", "C5"),
    ),
}
# Complex step for the derivative of the closed forms: truncation h^2 ~ 1e-40, no cancellation.
COMPLEX_STEP = 1e-20


@dataclass(frozen=True)
class ElementDimensions:
    """W, H, L (n,) in metres (l = 1) of an element at input phi (n,) rad."""

    phi: NDArray[np.float64]
    W: NDArray[np.float64]
    H: NDArray[np.float64]
    L: NDArray[np.float64]


def _check_element(element: int) -> Placement:
    if element not in ELEMENTS:
        raise ParameterError(f"element = {element}; elements 1, 2 and 3 are modelled (Peng 2018, §3.2.3)")
    return ELEMENTS[element]


def element3_theta(phi, alpha: float, beta: float):
    """
    Dihedral angle theta of B4B5 (rad) at phi: eqn 3-26 with gamma = pi - alpha in place of alpha (module
    docstring, reading note); phi may be complex (complex-step derivative).
    """
    gamma = np.pi - alpha
    return 2 * np.arctan(np.tan(phi / 2) * np.cos((beta + gamma) / 2) / np.cos((beta - gamma) / 2))


def element3_dimensions(theta, alpha: float, beta: float):
    """W, H, L of element 3 (l = 1) from the dihedral angle theta of B4B5, eqn 3-27 literally; theta may be complex."""
    cos_ang = np.cos(beta) * np.cos(alpha) + np.sin(beta) * np.sin(alpha) * np.cos(theta)
    ang = np.arccos(cos_ang)  # A5B5C5
    L = 2 * np.sin(ang / 2)
    cos_b = (-np.cos(beta) + np.cos(alpha) * cos_ang) / (np.sin(alpha) * np.sin(ang))
    pb = np.sin(alpha)
    H = 2 * pb * np.sqrt(1 - cos_b**2)  # 2 PB4 sin(B4PB4'), the angle in [0, pi]
    pb_foot, pb5 = pb * cos_b, -np.cos(alpha)
    b5_foot = np.sqrt(pb_foot**2 + pb5**2)
    W = 4 * b5_foot * np.cos(ang / 2 - np.arctan(pb_foot / pb5))
    return W, H, L


def _raw(phi, alpha: float, beta: float, element: int):
    """Peng 2018's eqns 3-24/3-25 literally, 3-26/3-27 as read here, l = 1; phi may be complex (complex step)."""
    if element == 3:
        return element3_dimensions(element3_theta(phi, alpha, beta), alpha, beta)
    cos_psi = -np.cos(beta) * np.cos(alpha) + np.sin(beta) * np.sin(alpha) * np.cos(phi)
    psi = np.arccos(cos_psi)
    W = 2 * np.sin(psi / 2)
    cos_b = (-np.cos(alpha) - np.cos(beta) * cos_psi) / (np.sin(beta) * np.sin(psi))
    pb = np.sin(beta)
    H = pb * np.sqrt(1 - cos_b**2)  # PB2 sin(B2PB2'), the angle in [0, pi]
    pb_foot, pa = pb * cos_b, np.cos(beta)
    a_foot = np.sqrt(pb_foot**2 + pa**2)
    L = 2 * a_foot * np.cos(np.arctan(pb_foot / pa) - psi / 2)
    scale = 1 if element == 1 else 2
    return W, scale * H, scale * L


def _check_angles(phi: NDArray[np.float64], alpha: float, beta: float, element: int) -> None:
    if not 0 < alpha < np.pi:
        raise ParameterError(f"alpha = {alpha:g} rad; a sector angle lies in (0, pi)")
    if element == 3 and not alpha > np.pi / 2:
        raise ParameterError(f"alpha = {alpha:g} rad; Peng 2018's arctan(PB4'/PB5) needs PB5 = -cos(alpha) > 0")
    if element != 3 and not 0 < beta < np.pi / 2:
        raise ParameterError(f"beta = {beta:g} rad; Peng 2018's arctan(PB2'/PA2) needs PA2 = cos(beta) > 0")
    if not 0 < beta < np.pi:
        raise ParameterError(f"beta = {beta:g} rad; a sector angle lies in (0, pi)")
    if np.any(~np.isfinite(phi)) or np.any((phi <= 0) | (phi >= np.pi)):
        raise ParameterError(f"phi in [{np.min(phi):g}, {np.max(phi):g}] rad; the dihedral angle lies in (0, pi)")


def element_formulas(phi: ArrayLike, alpha: float, beta: float, element: int) -> ElementDimensions:
    """Peng 2018's W, H, L (n,) of element 1, 2 or 3 (l = 1) at dihedral angles phi (n,) in (0, pi)."""
    _check_element(element)
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    _check_angles(phi, alpha, beta, element)
    return ElementDimensions(phi, *_raw(phi, alpha, beta, element))


def formula_poisson(phi: ArrayLike, alpha: float, beta: float, element: int) -> tuple[NDArray, NDArray]:
    """Closed-form nu_in = -(W/L) L'/W' and nu_out = -(W/H) H'/W' (n,), derivatives in phi by complex step."""
    dims = element_formulas(phi, alpha, beta, element)
    dW, dH, dL = (np.imag(v) / COMPLEX_STEP for v in _raw(dims.phi + 1j * COMPLEX_STEP, alpha, beta, element))
    return -(dims.W / dims.L) * dL / dW, -(dims.W / dims.H) * dH / dW


def max_height_angle(alpha: float, beta: float, element: int = 1, tol: float = 1e-13) -> float:
    """phi_II (rad): where H of the element peaks, dH/dphi = 0, by bisection on (0, pi) (1 and 2 share it)."""
    _check_element(element)
    _check_angles(np.array([np.pi / 2]), alpha, beta, element)

    def slope(p: float) -> float:
        return float(np.imag(_raw(np.array([p + 1j * COMPLEX_STEP]), alpha, beta, element)[1])[0])

    lo, hi = 1e-6, np.pi - 1e-6
    if not slope(lo) > 0 > slope(hi):
        raise ParameterError(f"H has no interior maximum at alpha = {alpha:g}, beta = {beta:g} rad")
    while hi - lo > tol:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if slope(mid) > 0 else (lo, mid)
    return (lo + hi) / 2


def _lattice(pattern: CreasePattern, i: int, j: int) -> int:
    """Vertex (i, j) of a `corrugated_sheet.sheet_pattern`: an end of a u or v crease there."""
    names = {c.name: c for c in pattern.creases}
    for start, end in ((f"u{i}_{j}", f"u{i - 1}_{j}"), (f"v{i}_{j}", f"v{i}_{j - 1}")):
        if start in names:
            return names[start].start
        if end in names:
            return names[end].end
    raise ParameterError(f"the sheet has no vertex ({i}, {j}); elements 2 and 3 need 2 x 2 units (1 fits on 1 x 1)")


def element_vertices(pattern: CreasePattern, element: int) -> dict[str, int]:
    """Pattern vertex indices of the element's labelled vertices (`ELEMENTS`, module docstring)."""
    return {name: _lattice(pattern, *ij) for name, ij in _check_element(element).labels.items()}


def element_dimensions(pattern: CreasePattern, positions: ArrayLike, phi: ArrayLike, element: int) -> ElementDimensions:
    """W, H, L (n,) measured from vertex positions (n, V, 3) of the P sheet as distances between its vertices."""
    p = np.asarray(positions, dtype=float)
    placement = _check_element(element)
    at = {name: p[:, k] for name, k in element_vertices(pattern, element).items()}
    b0, b1, b2 = (at[name] for name in placement.base)
    normal = np.cross(b1 - b0, b2 - b0)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    W = np.linalg.norm(at[placement.W[1]] - at[placement.W[0]], axis=-1)
    H = np.abs(np.einsum("ij,ij->i", at[placement.apex] - b0, normal))
    L = np.linalg.norm(at[placement.L[1]] - at[placement.L[0]], axis=-1)
    return ElementDimensions(np.asarray(phi, dtype=float), W, H, L)


@dataclass(frozen=True)
class ElementCheck:
    """
    Measured dimensions and Poisson's ratios against the thesis's at the measured phi; `samples` are the thinned
    path samples the ratios use. Errors are absolute (m for dimensions, 1 for ratios).
    """

    measured: ElementDimensions
    samples: NDArray[np.int64]
    nu_in: NDArray[np.float64]
    nu_out: NDArray[np.float64]
    formula_nu_in: NDArray[np.float64]
    formula_nu_out: NDArray[np.float64]
    dimension_error: float
    nu_in_error: float
    nu_out_error: float


def check_element(
    pattern: CreasePattern,
    positions: ArrayLike,
    phi: ArrayLike,
    alpha: float,
    beta: float,
    element: int,
    *,
    min_step: float = 0.002,
) -> ElementCheck:
    """
    Element 1, 2 or 3 measured on the P sheet's vertex positions (n, V, 3) at the measured phi (n,) =
    pi - |rho_u1_2| against eqns 3-24 to 3-27 and the ratios 3-28; the ratios from finite differences over
    samples `min_step` apart.
    """
    dims = element_dimensions(pattern, positions, phi, element)
    thesis = element_formulas(dims.phi, alpha, beta, element)
    k = thin(dims.phi, min_step)
    nu_in = poisson_ratio(dims.L[k], dims.W[k], dims.phi[k])
    nu_out = poisson_ratio(dims.H[k], dims.W[k], dims.phi[k])
    f_in, f_out = formula_poisson(dims.phi[k], alpha, beta, element)
    dim_err = max(float(np.max(np.abs(m - f))) for m, f in ((dims.W, thesis.W), (dims.H, thesis.H), (dims.L, thesis.L)))
    return ElementCheck(
        measured=dims, samples=k, nu_in=nu_in, nu_out=nu_out, formula_nu_in=f_in, formula_nu_out=f_out,
        dimension_error=dim_err, nu_in_error=float(np.max(np.abs(nu_in - f_in))),
        nu_out_error=float(np.max(np.abs(nu_out - f_out))),
    )
