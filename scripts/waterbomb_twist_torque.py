"""The free waterbomb tube twisted by a torque about its axis, without imposed symmetry (Feng 2018, §6.4:
the twist branches off the contraction's end; §6.4.2, eqns 6-53, 6-54: a twist from any other state is non-rigid).

The 6 x 3 tube of scene `waterbomb-tube` with its symmetry couplings removed (4n - 6 = 18 DOF), posed by the closed
form on the radial contraction at theta = eta01 (default: its lower end 2 pi / n, the fully folded middle row, where
the rigid twist branches off). No drive (its equality disabled), gravity and contact off. Equal and opposite torques
about the tube's axis act on the top row's and the bottom row's faces (`data.xfrc_applied`, TORQUE / 6n per face), the
axis re-measured every step as the line through the two end rings' centroids (it tilts as the root face, fixed in the
world, turns with the middle row). The motion is made quasi-static by hinge damping DAMPING on every hinge, with the
integrator switched from the fast preset's RK4 to implicitfast (RK4 at h = 8 ms went unstable at this damping: QACC
NaN at t = 0.04 s); measured quasi-static: damping 5 and 50 N m s/rad at equal TORQUE / DAMPING ended within 2 % of
each other (ring twist 2.93 vs 2.96 deg at 0.5 N m / 5 over 3 s), while undamped runs (the preset disables MuJoCo's
damper; enabled here) broke the n-fold symmetry by 0.2 rad.

Measured: which creases move (per row), the reached twist input x = rho of A1_0_2, every crease against
`WaterbombTwist.folds` at that x, the sense, phi_B0,4 (the middle row's vertical edges at rho = -pi), the plane
symmetry of the other rows, the units' likeness, the end-ring twist against the closed form's 2 delta, and the closure
gap (largest distance between paired connect sites).

    python scripts/waterbomb_twist_torque.py

Measured (6 x 3, alpha 40 deg, TORQUE 1 N m, DAMPING 5 N m s/rad, 3 s, 0.11-0.13 s of stepping CPU per run):
* Contraction end (theta = 60 deg), +torque: the twist-ccw sense (x rose by 7.25e-2 rad, eta02 43.56 deg from 47.71),
  end rings turned +5.840 deg (closed form at that x: 6.394). The middle row moves most (7.30e-2 rad against 1.31e-2
  bottom row, 1.06e-2 top row), but the free tube does not follow path II exactly: every crease within 1.345e-2 rad of
  the closed form at the reached x (ratio 0.19 of the motion, the same in every row: 1.35e-2, 1.32e-2, 1.24e-2),
  phi_B0,4 off 0 by 6.8e-3 rad, the other rows' plane symmetry broken by 1.19e-2, the middle row's line symmetry by
  3.8e-3, the units of a row differ by 1.66e-2; closure gap 2.9e-6 m. The torque, projected on the free tube's 18
  DOF, drives other modes along with the twist; the loading does not set that mix (tangential forces at the end
  rows' face centres instead of torques on the faces: ring twist 5.838 deg, crease error 1.339e-2, within 0.5 %).
  -torque: twist-cw (x fell by 7.29e-2), -5.831 deg, error 1.355e-2.
* theta = 80 deg (no row squeezed): locked. Rings turned 4.9e-7 deg (1.2e7 times less), creases moved <= 7.5e-9 rad,
  closure gap 1.2e-9 m: only the connects' elastic give (the rigid twist needs a squeezed row, eqns 6-53, 6-54).
* beta = beta_max = 42.0105238 deg (every row squeezed at the end): every row twists at once, rings turned 11.10 deg
  (1.9 x the beta = 40 deg tube); crease motion 4.3e-2, 7.5e-2, 5.4e-2 rad (bottom, middle, top row), plane symmetry
  broken by 9.3e-2; no single row's closed-form twist fits (errors 7.5e-2, 5.6e-2, 7.6e-2 rad against rows -1, 0, +1).
"""

import dataclasses
import time
from dataclasses import dataclass

import mujoco
import numpy as np
from numpy.typing import NDArray

from sim_origami import scenes
from sim_origami.errors import ParameterError, SimulationError
from sim_origami.geometry import rigid_fit, wrap
from sim_origami.kinematics.waterbomb_tube import beta_max
from sim_origami.kinematics.waterbomb_twist import WaterbombTwist
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import FAST
from sim_origami.scenes.base import Scene
from sim_origami.simulate import Bindings, captured_warnings, compile_model

CONTRACTION = "radial-contraction"
TORQUE = 1.0  # N m about the axis on each end row (split equally over its faces)
DAMPING = 5.0  # N m s / rad on every hinge
DURATION = 3.0  # s of simulated time


@dataclass(frozen=True)
class TorqueRun:
    """
    One run. Angles in radians (fold angles `sim_origami.creases`: 0 flat, > 0 valley), lengths in metres.

    `names` are the tube's creases (`WaterbombTube.crease_names`), `q0` / `q` their angles at the start and the end,
    `ring_twist` the top end ring's turn about the axis (+z of the closed form: bottom to top) against the bottom
    one's, counter-clockwise positive, `closure_gap` the largest connect-site distance at the end.
    """

    names: tuple[str, ...]
    q0: NDArray[np.float64]
    q: NDArray[np.float64]
    ring_twist: float
    closure_gap: float
    cpu_time_s: float

    def angle(self, name: str) -> float:
        """The end angle of crease `name` (rad)."""
        return float(self.q[self.names.index(name)])


def free_tube(beta: float = np.deg2rad(40.0), n: int = 6, m: int = 3) -> Scene:
    """Scene `waterbomb-tube` (alpha 40 deg, a 0.5 m) without its symmetry couplings; beta in rad."""
    scene = scenes.get("waterbomb-tube").build(n=n, m=m, alpha=np.deg2rad(40.0), beta=beta)
    return dataclasses.replace(scene, mechanism=scene.mechanism.uncoupled())


class VertexMap:
    """World positions of the tube's vertices (`layout.keys`) from MuJoCo body poses: each vertex on one face body
    containing it, its body-frame coordinates fixed at a closed pose X (keys, 3) in the tube frame mapped to the world
    by the root face (the world body, at its flat placement: `geometry.rigid_fit` on its three vertices)."""

    def __init__(self, scene: Scene, model: mujoco.MjModel, data: mujoco.MjData, X: NDArray[np.float64]):
        layout, pattern, root = scene.kinematics.layout, scene.kinematics.pattern, scene.mechanism.root
        face = list(pattern.faces[pattern.face_names.index(root)])
        fit = rigid_fit(X[layout.strip_keys[face]], np.c_[pattern.vertices[face], np.zeros(3)])
        world = X @ fit[:3, :3].T + fit[:3, 3]
        self.body = np.zeros(len(layout.keys), dtype=int)
        for name, verts in zip(pattern.face_names, pattern.faces, strict=True):
            self.body[layout.strip_keys[list(verts)]] = 0 if name == root else model.body(name).id
        rot = data.xmat[self.body].reshape(-1, 3, 3)
        self.local = np.einsum("kji,kj->ki", rot, world - data.xpos[self.body])

    def world(self, data: mujoco.MjData) -> NDArray[np.float64]:
        """Vertex positions (keys, 3) in m, world frame."""
        return data.xpos[self.body] + np.einsum("kij,kj->ki", data.xmat[self.body].reshape(-1, 3, 3), self.local)


def end_rings(scene: Scene) -> tuple[NDArray[np.int64], NDArray[np.int64]]:
    """Vertex keys of the top end ring (B, C of the top row) and of the bottom one (B, C of the row below)."""
    keys = scene.kinematics.layout.keys
    top, bottom = max(k[1] for k in keys), min(k[1] for k in keys)
    ring = [np.array([v for v, (kind, i, _) in enumerate(keys) if i == row and kind in "BC"]) for row in (top, bottom)]
    return ring[0], ring[1]


def axis_of(W: NDArray[np.float64], top: NDArray[np.int64], bottom: NDArray[np.int64]) -> NDArray[np.float64]:
    """Unit tube axis (3,) from the bottom ring's centroid to the top ring's (vertices W (keys, 3), m)."""
    axis = W[top].mean(0) - W[bottom].mean(0)
    return axis / np.linalg.norm(axis)


def ring_turn(W0: NDArray, W: NDArray, top: NDArray[np.int64], bottom: NDArray[np.int64]) -> float:
    """Turn (rad) of the top ring about the axis relative to the bottom ring from vertices W0 to W (keys, 3):
    azimuths about each pose's own axis, in a frame whose x is world y x axis (common rigid turns cancel)."""

    def azimuth(Wk: NDArray) -> NDArray:
        axis = axis_of(Wk, top, bottom)
        e1 = np.cross([0.0, 1.0, 0.0], axis)
        e1 /= np.linalg.norm(e1)
        Y = Wk - Wk[top].mean(0)
        return np.arctan2(Y @ np.cross(axis, e1), Y @ e1)

    turn = wrap(azimuth(W) - azimuth(W0))
    return float(np.mean(wrap(turn[top] - np.mean(turn[bottom]))))


def run(
    scene: Scene, theta: float | None = None, torque: float = TORQUE, damping: float = DAMPING,
    duration: float = DURATION,
) -> TorqueRun:
    """
    The torque experiment on the free tube `scene` posed on the contraction at theta = eta01 (rad; default its lower
    end, 2 pi / n), torque (N m, counter-clockwise about the axis on the top row, the opposite on the bottom row),
    hinge damping (N m s / rad), duration (s). ParameterError for a theta outside the contraction's domain.
    """
    kin = scene.kinematics
    lo, hi = kin.domain
    x0 = lo if theta is None else theta - np.pi
    if not lo <= x0 <= hi:
        raise ParameterError(
            f"theta = {np.rad2deg(x0 + np.pi):.6g} deg is outside the contraction's domain "
            f"[{np.rad2deg(lo + np.pi):.6g}, {np.rad2deg(hi + np.pi):.6g}] deg"
        )
    compiled = compile_model(scene, ModelOptions(preset=FAST))
    model, data = compiled.fresh()
    model.opt.integrator = mujoco.mjtIntegrator.mjINT_IMPLICITFAST
    model.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_DAMPER)
    model.dof_damping[:] = damping
    data.eq_active[compiled.ids.drive_equalities[0]] = 0
    binds = Bindings(compiled)
    binds.set_pose(data, scene.pose(CONTRACTION, x0))
    mujoco.mj_forward(model, data)
    vertices = VertexMap(scene, model, data, kin.vertices(np.array([x0]))[0])
    top, bottom = end_rings(scene)
    rows = np.array([int(name[1:].split("_")[0]) for name in kin.pattern.face_names])
    names = np.array(kin.pattern.face_names)
    ends = [np.array([model.body(f).id for f in names[rows == r]]) for r in (rows.max(), rows.min())]
    W0 = vertices.world(data)
    qpos0 = data.qpos.copy()
    with captured_warnings() as messages:
        cpu = time.thread_time()
        for _ in range(round(duration / model.opt.timestep)):
            axis = axis_of(vertices.world(data), top, bottom)
            data.xfrc_applied[ends[0], 3:] = torque / len(ends[0]) * axis
            data.xfrc_applied[ends[1], 3:] = -torque / len(ends[1]) * axis
            mujoco.mj_step(model, data)
        cpu = time.thread_time() - cpu
    if messages or not np.all(np.isfinite(data.qpos)):
        raise SimulationError(f"free tube, torque {torque:g} N m, damping {damping:g} N m s/rad: {messages[:1]}")
    mujoco.mj_kinematics(model, data)
    sites = data.site_xpos[binds.site_pairs]
    q = scene.mechanism_to_loop(binds.angles(scene, np.stack([qpos0, data.qpos.copy()])))
    return TorqueRun(
        names=kin.crease_names, q0=q[0], q=q[1], ring_twist=ring_turn(W0, vertices.world(data), top, bottom),
        closure_gap=float(np.max(np.linalg.norm(sites[:, 0] - sites[:, 1], axis=-1))), cpu_time_s=cpu,
    )


def row_of(name: str) -> int:
    """Row (counted from the bottom) of a crease name A<r>_<k>_<j>, V<r>_<k>, T<r>_<k>_<side>."""
    return int(name[1:].split("_")[0])


def measure(run: TorqueRun, n: int = 6, m: int = 3) -> dict[str, float]:
    """
    Symmetry and motion measures of a run (rad): 'move_row<r>' the largest crease motion of each row, 'phi_B04' the
    middle row's vertical edges' largest distance from rho = -pi (folded flat), 'plane_sym' the other rows' largest
    |A_2 - A_6|, |A_3 - A_5|, |T_r - T_l|, 'line_sym' the middle row's |A_1 - A_4|, |A_2 - A_5|, |A_3 - A_6|,
    'units' the largest spread of one crease over the units of its row; 'x' the twist input rho of A<r0>_0_2.
    """
    r0 = (m - 1) // 2
    a = run.angle
    out = {f"move_row{r}": float(np.max([abs(wrap(q - p)) for q, p, name in zip(run.q, run.q0, run.names, strict=True)
                                          if row_of(name) == r])) for r in range(m)}
    out["phi_B04"] = max(abs(wrap(a(f"V{r0}_{k}") + np.pi)) for k in range(n))
    pairs = [(f"A{r}_{k}_2", f"A{r}_{k}_6") for r in range(m) for k in range(n) if r != r0]
    pairs += [(f"A{r}_{k}_3", f"A{r}_{k}_5") for r in range(m) for k in range(n) if r != r0]
    pairs += [(f"T{r}_{k}_r", f"T{r}_{k}_l") for r in range(m - 1) for k in range(n) if r != r0]
    out["plane_sym"] = max(abs(wrap(a(p) - a(q))) for p, q in pairs)
    line = [(f"A{r0}_{k}_{j}", f"A{r0}_{k}_{j + 3}") for k in range(n) for j in (1, 2, 3)]
    out["line_sym"] = max(abs(wrap(a(p) - a(q))) for p, q in line)
    spread = [np.ptp([a(f"A{r}_{k}_{j}") for k in range(n)]) for r in range(m) for j in range(1, 7)]
    out["units"] = float(max(spread))
    out["x"] = a(f"A{r0}_0_2")
    return out


def compare_twist(run: TorqueRun, twist: WaterbombTwist) -> dict[str, float | str]:
    """The run against the closed-form twist at the run's own input x (rho of the twisting row's A_0_2): 'branch'
    (by x against the start), 'dx' (rad), 'error' (largest crease error, rad), 'error_row<r>' per row, 'ring_model'
    (the closed form's end-ring twist 2 delta, rad)."""
    x = run.angle(twist.input_crease)
    branch = "twist-ccw" if x > twist.start else "twist-cw"
    err = np.abs(wrap(run.q - twist.folds(branch, x)[0]))
    out: dict[str, float | str] = {"branch": branch, "dx": x - twist.start, "error": float(err.max())}
    for r in range(twist.m):
        out[f"error_row{r}"] = float(max(e for e, name in zip(err, run.names, strict=True) if row_of(name) == r))
    out["ring_model"] = float(twist.end_twist(branch, x)[0])
    return out


def report(label: str, run: TorqueRun, twist: WaterbombTwist | None = None) -> None:
    """Print one run's measures (angles in rad unless marked deg)."""
    got = measure(run)
    moves = " ".join(f"{got[f'move_row{r}']:.3e}" for r in range(3))
    print(f"{label}: ring twist {np.rad2deg(run.ring_twist):+.4e} deg, crease motion per row (bottom..top) {moves}, "
          f"closure gap {run.closure_gap:.2e} m, CPU {run.cpu_time_s:.2f} s")
    print(f"    phi_B0,4 {got['phi_B04']:.2e}, plane symmetry {got['plane_sym']:.2e}, middle-row line symmetry "
          f"{got['line_sym']:.2e}, units alike {got['units']:.2e}, x {got['x']:.6f}")
    if twist is not None:
        c = compare_twist(run, twist)
        rows = " ".join(f"{c[f'error_row{r}']:.2e}" for r in range(3))
        eta02 = np.rad2deg(np.pi - run.angle(twist.input_crease))
        print(f"    vs {c['branch']} (row {twist.row}): dx {c['dx']:+.4e}, max error {c['error']:.3e} (rows {rows}), "
              f"ring twist model {np.rad2deg(c['ring_model']):+.4f} deg, eta02 {eta02:.3f} deg")


def main() -> None:
    alpha, beta = np.deg2rad(40.0), np.deg2rad(40.0)
    scene = free_tube()
    twist = WaterbombTwist(6, 3, alpha, beta, 0.5)
    print(
        f"free 6 x 3 tube, alpha = beta = 40 deg, torque {TORQUE:g} N m, damping {DAMPING:g} N m s/rad, {DURATION:g} s"
    )
    report("end, +torque", run(scene), twist)
    report("end, -torque", run(scene, torque=-TORQUE), twist)
    report("theta 80 deg", run(scene, theta=np.deg2rad(80.0)))
    bmax = beta_max(alpha, 6)
    scene_max = free_tube(beta=bmax)
    result = run(scene_max)
    report(f"beta_max {np.rad2deg(bmax):.7f} deg", result)
    for row in (-1, 0, 1):
        c = compare_twist(result, WaterbombTwist(6, 3, alpha, bmax, 0.5, row))
        print(f"    vs row {row:+d} {c['branch']}: dx {c['dx']:+.4e}, max error {c['error']:.3e}")


if __name__ == "__main__":
    main()
