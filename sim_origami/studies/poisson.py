"""Poisson's ratios measured from a simulated motion against the closed forms of Peng 2018 (numpy only).

Input is geometry, never a MuJoCo object: body poses (n, 4, 4) per face of a crease pattern (e.g.
`Mechanism.body_poses` of a trajectory's joint angles), from which every pattern vertex is placed. Lengths in
metres, angles in radians, the world frame of the flat sheet (normal +z).

A Poisson's ratio of a response dimension R to a load dimension D along a one-parameter motion x is
nu = -(dR/R) / (dD/D) = -(D/R) (dR/dx) / (dD/dx) (Peng 2018, eqns 3-28, 3-32), here from second-order finite
differences on the simulated samples, thinned to a minimum step in x so that the integrator's noise is not
divided by a vanishing step where the minimum-jerk drive starts and stops.

Square-twist metamaterial unit (Peng 2018, §3.3, Fig 3-18, eqns 3-30 to 3-32) (reconstructed here: the figure is lost in
the text we have). On the square twist of `kinematics.square_twist` with vertex A in mode C, theta = rho_AB and phi =
rho_DA (creases 2 and 3 of A), and the central square fixed in the plane z = 0 with AB along +x, the thesis's
three dimensions are exactly these distances between pattern vertices (a = pleat, 2b = 2c = side):

* L = y(end of pleat C4) - y(end of pleat A1) = 2c + a(cos alpha + sin alpha cos theta): A1 turns about AB (an
  x line) and C4 about BC (a y line), so only A1's in-plane perpendicular part a sin alpha cos theta moves;
* S = x(end of pleat B4) - x(end of pleat A4) = 2b + a(cos alpha + sin alpha cos phi), the same with the roles
  of the axes swapped (A4 turns about DA, B4 about AB);
* H = z(far corner of face corner_A) - z(A) = a sin alpha (sin theta + sin phi): the corner square is the
  image of A1 + A4, and eqn 3-31 is exactly its right angle at A.
"""

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..creases import CreasePattern
from ..errors import ParameterError
from ..kinematics.square_twist import metamaterial_unit


def vertex_positions(pattern: CreasePattern, poses: dict[str, ArrayLike]) -> tuple[NDArray[np.float64], float]:
    """
    Every pattern vertex in the world (n, V, 3) from face poses {face name: (n, 4, 4)}, and the largest
    distance (m) between two faces' placements of one vertex (the closure error the poses carry).
    """
    first: dict[int, NDArray[np.float64]] = {}
    gap = 0.0
    for name, face in zip(pattern.face_names, pattern.faces, strict=True):
        if name not in poses:
            raise ParameterError(f"no pose for face {name!r}; poses name {sorted(poses)}")
        T = np.asarray(poses[name], dtype=float).reshape(-1, 4, 4)
        for v in face:
            p = T[:, :3, :3] @ np.array([*pattern.vertices[v], 0.0]) + T[:, :3, 3]
            if v in first:
                gap = max(gap, float(np.max(np.linalg.norm(p - first[v], axis=-1))))
            else:
                first[v] = p
    return np.stack([first[v] for v in range(len(pattern.vertices))], axis=1), gap


def thin(x: ArrayLike, min_step: float) -> NDArray[np.int64]:
    """Indices of samples of a monotonic path x (n,) at least `min_step` apart in x, the first always kept."""
    x = np.asarray(x, dtype=float)
    if not min_step > 0:
        raise ParameterError(f"min_step = {min_step:g}; it must be positive")
    keep, last = [0], x[0]
    for k in range(1, len(x)):
        if abs(x[k] - last) >= min_step:
            keep.append(k)
            last = x[k]
    if len(keep) < 3:
        raise ParameterError(f"only {len(keep)} samples are {min_step:g} apart; finite differences need 3")
    return np.array(keep)


def poisson_ratio(response: ArrayLike, load: ArrayLike, x: ArrayLike) -> NDArray[np.float64]:
    """
    nu = -(load / response) (d response / dx) / (d load / dx) (n,) from second-order finite differences in the
    path parameter x (n,), strictly monotonic; dimensions (n,) in any one length unit.
    """
    response, load, x = (np.asarray(v, dtype=float) for v in (response, load, x))
    steps = np.diff(x)
    if not (np.all(steps > 0) or np.all(steps < 0)):
        raise ParameterError("the path parameter must be strictly monotonic for finite differences")
    d_load = np.gradient(load, x, edge_order=2)
    if np.any(d_load == 0) or np.any(response == 0):
        raise ParameterError("the load dimension is stationary (or the response zero) on the path: nu is undefined")
    return -(load / response) * np.gradient(response, x, edge_order=2) / d_load


@dataclass(frozen=True)
class UnitDimensions:
    """Square-twist metamaterial dimensions (n,) in metres at fold angles theta = rho_AB, phi = rho_DA (rad)."""

    theta: NDArray[np.float64]
    phi: NDArray[np.float64]
    L: NDArray[np.float64]
    S: NDArray[np.float64]
    H: NDArray[np.float64]


def _crease_end(pattern: CreasePattern, name: str, vertex: int) -> int:
    crease = pattern.crease(name)
    return crease.end if crease.start == vertex else crease.start


def square_twist_dimensions(
    pattern: CreasePattern, positions: ArrayLike, theta: ArrayLike, phi: ArrayLike
) -> UnitDimensions:
    """
    L, S and H of the square twist (module docstring) from vertex positions (n, V, 3) of `pattern` (a
    `kinematics.square_twist.crease_pattern`), the central square fixed with AB along +x.
    """
    p = np.asarray(positions, dtype=float)
    a_, b_, c_, _ = (pattern.crease(e).start for e in ("AB", "BC", "CD", "DA"))
    corner = pattern.faces[pattern.face_names.index("corner_A")]
    named = {a_, _crease_end(pattern, "A1", a_), _crease_end(pattern, "A4", a_)}
    (far,) = set(corner) - named
    L = p[:, _crease_end(pattern, "C4", c_), 1] - p[:, _crease_end(pattern, "A1", a_), 1]
    S = p[:, _crease_end(pattern, "B4", b_), 0] - p[:, _crease_end(pattern, "A4", a_), 0]
    H = p[:, far, 2] - p[:, a_, 2]
    return UnitDimensions(np.asarray(theta, dtype=float), np.asarray(phi, dtype=float), L, S, H)


@dataclass(frozen=True)
class PoissonCheck:
    """
    Measured dimensions and Poisson's ratios against eqns 3-30 and 3-32 at the measured theta; `samples` are
    the thinned path samples the ratios use. Differences are absolute (m for dimensions, 1 for ratios).
    """

    measured: UnitDimensions
    samples: NDArray[np.int64]
    nu_sl: NDArray[np.float64]
    nu_hl: NDArray[np.float64]
    formula_nu_sl: NDArray[np.float64]
    formula_nu_hl: NDArray[np.float64]
    dimension_error: float
    phi_error: float
    nu_sl_error: float
    nu_hl_error: float


def check_square_twist(
    pattern: CreasePattern,
    positions: ArrayLike,
    theta: ArrayLike,
    phi: ArrayLike,
    alpha: float,
    *,
    min_step: float = 0.002,
) -> PoissonCheck:
    """
    The square twist's measured L, S, H and nu_SL = -(S/L) dL/dS, nu_HL = -(L/H) dH/dL against the thesis's
    formulas (`kinematics.square_twist.metamaterial_unit` with a = pleat, b = c = side / 2) at the measured
    theta (n,) in (0, pi); phi (n,) is the measured rho_DA, compared with eqn 3-31's.
    """
    side = pattern.length(pattern.crease("AB"))
    pleat = pattern.length(pattern.crease("A1"))
    dims = square_twist_dimensions(pattern, positions, theta, phi)
    unit = metamaterial_unit(alpha, dims.theta, pleat, side / 2, side / 2)
    k = thin(dims.theta, min_step)
    nu_sl = poisson_ratio(dims.L[k], dims.S[k], dims.theta[k])
    nu_hl = poisson_ratio(dims.H[k], dims.L[k], dims.theta[k])
    dim_err = max(float(np.max(np.abs(m - f))) for m, f in ((dims.L, unit.L), (dims.S, unit.S), (dims.H, unit.H)))
    return PoissonCheck(
        measured=dims, samples=k, nu_sl=nu_sl, nu_hl=nu_hl, formula_nu_sl=unit.nu_sl[k], formula_nu_hl=unit.nu_hl[k],
        dimension_error=dim_err, phi_error=float(np.max(np.abs(dims.phi - unit.phi))),
        nu_sl_error=float(np.max(np.abs(nu_sl - unit.nu_sl[k]))),
        nu_hl_error=float(np.max(np.abs(nu_hl - unit.nu_hl[k]))),
    )
