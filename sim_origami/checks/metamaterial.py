"""Double-corrugated metamaterial elements 1 and 2 (seed 003 §3.2.3, digest M8 eqns 3-24, 3-25, 3-28) measured on
the simulated geometry of the double-corrugated sheet (numpy only).

Input is geometry, never a MuJoCo object: vertex positions (n, V, 3) of the P-unit sheet of
`kinematics.corrugated_sheet` (`poisson.vertex_positions` of a motion's body poses) and the input phi. Lengths in
metres (every crease l = 1 in the seed), angles in radians.

Seed formulas. phi is the dihedral angle of crease A2B2 (pi flat, 0 folded flat), whose neighbours A2A1 and A2A3
make sectors pi - alpha (= gamma) and beta with it: the spherical law of cosines gives the angle psi = A1A2A3, so
W = |A1A3|; H is the height of B2 above the plane A1A2A3 (B2' its foot there) and L twice the in-plane
component of A2B2 along the bisector of psi. Element 2 has the same W and twice H and L.

Placement (reconstructed here; the seed's Fig 3-11 is lost). In the sheet's lattice (vertex (i, j), i along u,
j along v; `corrugated_sheet` docstring) take A2 = (1, 2), A1 = (1, 1), A3 = (1, 3) (A2's v neighbours) and the
u row (k, 2), k = 1..5, so that A2B2 = u1_2, the crease between A2's sectors gamma and beta; phi = pi - |rho_u1_2|
(on SCSC and SCCS every u crease folds with |rho| = |x|, x = rho of the input u1_1), and:

* element 1 = branch SCSC (the seed's P1): the u row is a zig-zag of period two steps, translated along the
  bisector of psi; L = |(1, 2)(3, 2)|, H = distance of (2, 2) from the plane of (1, 1), (1, 2), (1, 3);
* element 2 = branch SCCS: the u row climbs two steps and comes down two, heights 0, H1, 2 H1, H1, 0 (the
  seed's C' = C reflected in the plane B1B2D1D2); L = |(1, 2)(5, 2)|, H = distance of (3, 2) from that plane.

Both agree with the seed's formulas to rounding at every phi (tests/test_metamaterial.py). Element 1's
vertices also follow eqn 3-24 on CCSS (the seed's original pattern P2, tentatively; there the u row folds with
tan-half gain 0.101, so phi stays near pi unless x nears pi) and on CSSC; on CSCS, SCCS and SSCC they do not (L
misses by >= 0.6 m). Element 2's follow eqn 3-25 on SCCS only.

Poisson's ratios (3-28): nu_in = -(dL/L)/(dW/W), nu_out = -(dH/H)/(dW/W); closed form by complex-step
differentiation of the formulas (exact to rounding), measured by `poisson.poisson_ratio` on the samples.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..creases import CreasePattern
from ..errors import ParameterError
from .poisson import poisson_ratio, thin

# element -> (rigid mode string of the P sheet, u steps from A2 to the element's far end, apex step)
ELEMENTS = {1: ("SCSC", 2, 1), 2: ("SCCS", 4, 2)}
# Complex step for the derivative of the closed forms: truncation h^2 ~ 1e-40, no cancellation.
COMPLEX_STEP = 1e-20


@dataclass(frozen=True)
class ElementDimensions:
    """W, H, L (n,) in metres (l = 1) of an element at input phi (n,) rad."""

    phi: NDArray[np.float64]
    W: NDArray[np.float64]
    H: NDArray[np.float64]
    L: NDArray[np.float64]


def _check_element(element: int) -> tuple[str, int, int]:
    if element not in ELEMENTS:
        raise ParameterError(f"element = {element}; elements 1 and 2 are modelled (element 3: digest M8 warns)")
    return ELEMENTS[element]


def _raw(phi, alpha: float, beta: float, element: int):
    """The seed's eqns 3-24/3-25 literally, l = 1; phi may be complex (complex-step derivative)."""
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


def _check_angles(phi: NDArray[np.float64], alpha: float, beta: float) -> None:
    if not 0 < alpha < np.pi:
        raise ParameterError(f"alpha = {alpha:g} rad; a sector angle lies in (0, pi)")
    if not 0 < beta < np.pi / 2:
        raise ParameterError(f"beta = {beta:g} rad; the seed's arctan(PB2'/PA2) needs PA2 = cos(beta) > 0")
    if np.any(~np.isfinite(phi)) or np.any((phi <= 0) | (phi >= np.pi)):
        raise ParameterError(f"phi in [{np.min(phi):g}, {np.max(phi):g}] rad; the dihedral angle lies in (0, pi)")


def element_formulas(phi: ArrayLike, alpha: float, beta: float, element: int) -> ElementDimensions:
    """The seed's W, H, L (n,) of element 1 or 2 (l = 1) at dihedral angles phi (n,) in (0, pi)."""
    _check_element(element)
    phi = np.atleast_1d(np.asarray(phi, dtype=float))
    _check_angles(phi, alpha, beta)
    return ElementDimensions(phi, *_raw(phi, alpha, beta, element))


def formula_poisson(phi: ArrayLike, alpha: float, beta: float, element: int) -> tuple[NDArray, NDArray]:
    """Closed-form nu_in = -(W/L) L'/W' and nu_out = -(W/H) H'/W' (n,), derivatives in phi by complex step."""
    dims = element_formulas(phi, alpha, beta, element)
    dW, dH, dL = (np.imag(v) / COMPLEX_STEP for v in _raw(dims.phi + 1j * COMPLEX_STEP, alpha, beta, element))
    return -(dims.W / dims.L) * dL / dW, -(dims.W / dims.H) * dH / dW


def max_height_angle(alpha: float, beta: float, tol: float = 1e-13) -> float:
    """phi_II (rad): where H (either element) peaks, dH/dphi = 0, by bisection on (0, pi)."""
    _check_angles(np.array([np.pi / 2]), alpha, beta)

    def slope(p: float) -> float:
        return float(np.imag(_raw(np.array([p + 1j * COMPLEX_STEP]), alpha, beta, 1)[1])[0])

    lo, hi = 1e-6, np.pi - 1e-6
    if not slope(lo) > 0 > slope(hi):
        raise ParameterError(f"H has no interior maximum at alpha = {alpha:g}, beta = {beta:g} rad")
    while hi - lo > tol:
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if slope(mid) > 0 else (lo, mid)
    return (lo + hi) / 2


def _lattice(pattern: CreasePattern, i: int, j: int) -> int:
    """Vertex (i, j) of a `corrugated_sheet.sheet_pattern`: start of crease u<i>_<j>, or end of u<i-1>_<j>."""
    names = {c.name: c for c in pattern.creases}
    if f"u{i}_{j}" in names:
        return names[f"u{i}_{j}"].start
    if f"u{i - 1}_{j}" in names:
        return names[f"u{i - 1}_{j}"].end
    raise ParameterError(f"the sheet has no vertex ({i}, {j}); elements need at least 2 x 2 units")


def element_vertices(pattern: CreasePattern, element: int) -> dict[str, int]:
    """Pattern vertex indices of A1, A2, A3, the apex (B2 or C') and the far end (module docstring)."""
    _, steps, apex = _check_element(element)
    return {
        "A1": _lattice(pattern, 1, 1),
        "A2": _lattice(pattern, 1, 2),
        "A3": _lattice(pattern, 1, 3),
        "apex": _lattice(pattern, 1 + apex, 2),
        "end": _lattice(pattern, 1 + steps, 2),
    }


def element_dimensions(pattern: CreasePattern, positions: ArrayLike, phi: ArrayLike, element: int) -> ElementDimensions:
    """W, H, L (n,) measured from vertex positions (n, V, 3) of the P sheet as distances between its vertices."""
    p = np.asarray(positions, dtype=float)
    v = element_vertices(pattern, element)
    a1, a2, a3 = p[:, v["A1"]], p[:, v["A2"]], p[:, v["A3"]]
    normal = np.cross(a1 - a2, a3 - a2)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    W = np.linalg.norm(a3 - a1, axis=-1)
    H = np.abs(np.einsum("ij,ij->i", p[:, v["apex"]] - a2, normal))
    L = np.linalg.norm(p[:, v["end"]] - a2, axis=-1)
    return ElementDimensions(np.asarray(phi, dtype=float), W, H, L)


@dataclass(frozen=True)
class ElementCheck:
    """
    Measured dimensions and Poisson's ratios against the seed's at the measured phi; `samples` are the thinned
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
    Element 1 or 2 measured on the P sheet's vertex positions (n, V, 3) at the measured phi (n,) = pi - |rho_u1_2|
    against eqns 3-24/3-25 and the ratios 3-28; the ratios from finite differences over samples `min_step` apart.
    """
    dims = element_dimensions(pattern, positions, phi, element)
    seed = element_formulas(dims.phi, alpha, beta, element)
    k = thin(dims.phi, min_step)
    nu_in = poisson_ratio(dims.L[k], dims.W[k], dims.phi[k])
    nu_out = poisson_ratio(dims.H[k], dims.W[k], dims.phi[k])
    f_in, f_out = formula_poisson(dims.phi[k], alpha, beta, element)
    dim_err = max(float(np.max(np.abs(m - f))) for m, f in ((dims.W, seed.W), (dims.H, seed.H), (dims.L, seed.L)))
    return ElementCheck(
        measured=dims, samples=k, nu_in=nu_in, nu_out=nu_out, formula_nu_in=f_in, formula_nu_out=f_out,
        dimension_error=dim_err, nu_in_error=float(np.max(np.abs(nu_in - f_in))),
        nu_out_error=float(np.max(np.abs(nu_out - f_out))),
    )  # fmt: skip
