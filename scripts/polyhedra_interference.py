"""Interference of the transformable polyhedra's designs (Yang 2017, §5.5 zeta study, §6.5 delta study).

For each design it decides, two ways, whether the motion from the Archimedean solid reaches the Platonic one:
(a) the closed form (`TruncatedOctahedronCube.outcome`: pseudo-arclength to the first fold; the tetrahedron
models' traced path and its end), (b) MuJoCo with the collision plates on and a force-limited servo on the input
(`simulate(..., drive="servo", contact=True)` from the deployed pose to the end of the path): where the motion
stops and the shape there. Prints the thesis's feasible ranges against ours. Angles printed in degrees.

Run: /work/venv/bin/python scripts/polyhedra_interference.py [--quick]
(--quick: a few designs per scene, about 40 s of CPU; the full grid takes a few minutes.)
"""

import sys
import time
from dataclasses import dataclass

import numpy as np

import sim_origami.scenes.truncated_octahedron as octahedron_scene
import sim_origami.scenes.truncated_tetrahedron as tetrahedron_scene
from sim_origami.errors import ParameterError
from sim_origami.kinematics.truncated_octahedron import CUBE, NAMES, PathOutcome, TruncatedOctahedronCube
from sim_origami.scenes.base import Scene
from sim_origami.simulate import simulate
from sim_origami.validation import BLOCKAGE_HOLD

DEG = np.pi / 180
ZETAS = (-89.9, -85, -80, -75, -70, -65, -63, -62, -61.5, -61, -60.9, -60.7, -60.5, -60, -55, -40, -20, -10, 0,
         10, 15, 18, 18.3, 18.6, 18.9, 19, 19.5, 20, 22, 25, 30, 40, 50, 70)
ZETAS_MUJOCO = (-89.9, -80, -70, -63, -62, -60.7, -40, -20, 0, 15, 18.9, 19.5, 22, 30, 40)
QUICK = (-70, 0, 30, 40)
DELTAS = {"I": (-30, -10, -5, -4, -3.5, -3, 0, 5, 15), "II": (-10, -5, 0, 5, 10)}
PRINTED_RANGE = (-60.9, 19.5)  # deg, Yang 2017 §5.5
CORNERS = tuple(tuple(v for v in NAMES if np.allclose(CUBE[v], c)) for c in {tuple(CUBE[v]) for v in NAMES})
INDEX = {v: k for k, v in enumerate(NAMES)}


@dataclass(frozen=True)
class Stop:
    """Where a servo run with contact ended: input (rad), first contact input (rad, nan if none), shape."""

    input: float
    target: float
    contact: float
    rho1: float
    rho2: float
    corner_gap: float  # largest distance (m) between vertices that merge at the cube
    cpu_s: float

    @property
    def reached(self) -> bool:
        """
        The cube is formed: merging vertices within 0.15 m. The collision plates stop the motion 9.8 mrad of A1
        before the cube, where zeta = 0's merging vertices are still 0.070 m apart (rho2 = 4.0 deg, measured);
        designs that miss it stop 0.86 m apart or more (zeta = 30 deg).
        """
        return self.corner_gap < 0.15


def servo_run(scene: Scene, stop: float) -> tuple[np.ndarray, np.ndarray, float, float]:
    """Servo with contact from the deployed pose (all joints 0) to input `stop`: inputs, mechanism angles, first
    contact input (nan if none), CPU (s)."""
    branch = scene.kinematics.branches()[0].name
    run = simulate(scene, branch, drive="servo", contact=True, start=0.0, stop=stop, hold=BLOCKAGE_HOLD,
                   initial=np.zeros(len(scene.mechanism.joints)))
    x = run.q[:, scene.mechanism.joint_index(scene.drive_joint)] / scene.drive_scale
    touched = np.flatnonzero(run.contacts > 0)
    return x, run.q, float(x[touched[0]]) if len(touched) else float("nan"), run.cpu_time_s


def octahedron_stop(zeta_deg: float) -> Stop:
    """MuJoCo with contact for the truncated octahedron at zeta (deg), driven to A1 = theta_f - theta_d."""
    scene = octahedron_scene.interference_scene(zeta_deg * DEG)
    cube = scene.path[1]
    x, q, touch, cpu = servo_run(scene, cube)
    P = scene.kinematics.observe_points(scene.mechanism_to_loop(q[-1:]))[0]

    def angle(a: str, at: str, b: str) -> float:
        u, w = P[INDEX[a]] - P[INDEX[at]], P[INDEX[b]] - P[INDEX[at]]
        return float(np.arctan2(np.linalg.norm(np.cross(u, w)), u @ w))

    gap = max(np.linalg.norm(P[INDEX[a]] - P[INDEX[b]]) for c in CORNERS for a in c for b in c)
    return Stop(float(x[-1]), cube, touch, angle("B1", "C2", "C1"), angle("D1", "F2", "F1"), float(gap), cpu)


def octahedron_table(zetas: tuple[float, ...], mujoco: tuple[float, ...]) -> list[tuple[float, PathOutcome]]:
    """Print one row per zeta (deg): closed-form outcome, and MuJoCo's stop for those in `mujoco`."""
    print("truncated octahedron -> cube (Yang 2017 §5.5): zeta study")
    print(f"{'zeta':>6} {'closed form':>14} {'rho1/rho2 at fold':>18} {'turns of theta':>16} {'rho1 max':>8} "
          f"{'max|rho1-rho2|':>14} | MuJoCo servo + contact: {'stop A1':>8} {'/ target':>8} {'contact':>8} "
          f"{'rho1':>6} {'rho2':>6} {'gap m':>7} {'CPU s':>5}")
    rows = []
    for z in zetas:
        o = TruncatedOctahedronCube(z * DEG).outcome()
        rows.append((z, o))
        turns = ",".join(f"{t / DEG:.2f}" for t in o.turns[:2]) or "-"
        line = (f"{z:6.1f} {o.kind:>14} {o.rho1 / DEG:8.3f}/{o.rho2 / DEG:8.3f} {turns:>16} {o.rho1_max / DEG:8.3f} "
                f"{o.gap_max / DEG:14.2f} |")
        if z in mujoco:
            s = octahedron_stop(z)
            verdict = "cube" if s.reached else "stops"
            line += (f" {verdict:>5} {s.input / DEG:8.3f} / {s.target / DEG:8.3f} {s.contact / DEG:8.3f} "
                     f"{s.rho1 / DEG:6.2f} {s.rho2 / DEG:6.2f} {s.corner_gap:7.4f} {s.cpu_s:5.2f}")
        print(line, flush=True)
    return rows


def feasible_band(rows: list[tuple[float, PathOutcome]], key: str) -> tuple[float, float]:
    """The contiguous band of zeta (deg) around 0 where `key` ('feasible' or 'drivable') holds on the grid."""
    ok = [(z, getattr(o, key)) for z, o in rows]
    start = next(k for k, (z, _) in enumerate(ok) if z == 0)
    lo = hi = start
    while lo > 0 and ok[lo - 1][1]:
        lo -= 1
    while hi < len(ok) - 1 and ok[hi + 1][1]:
        hi += 1
    return ok[lo][0], ok[hi][0]


def tetrahedron_table(scheme: str, deltas: tuple[float, ...]) -> None:
    """Print one row per delta (deg) of a truncated-tetrahedron scheme: closed form, then MuJoCo with contact."""
    print(f"\ntruncated tetrahedron -> tetrahedron, scheme {scheme} (Yang 2017 §6.5): delta{len(scheme)} study")
    print(f"{'delta':>6} {'closed form end':>34} {'rho max':>8} | MuJoCo servo + contact: {'stop':>8} "
          f"{'/ end':>8} {'contact':>8} {'rho':>7} {'|BK| m':>7} {'|AE| m':>7} {'CPU s':>5}")
    for d in deltas:
        try:
            scene = (
                tetrahedron_scene.build_scheme_1(d * DEG)
                if scheme == "I"
                else tetrahedron_scene.build_scheme_2(d * DEG)
            )
        except ParameterError as error:
            print(f"{d:6.1f} closed form refuses it: {error}")
            continue
        model = scene.kinematics.model
        lo, hi = model.domain
        end = "tetrahedron" if model.end_gap < 1e-9 else f"Bricard fold, |BK| = {model.end_gap:.4f} m"
        rho = model.monitors(np.linspace(lo, hi, 201))["rho"]
        far = scene.path[1]
        x, q, touch, cpu = servo_run(scene, far)
        P = scene.kinematics.observe_points(scene.mechanism_to_loop(q[-1:]))[0]
        p = {v: P[k] for k, v in enumerate(tetrahedron_scene.NAMES)}
        u, w = p["A"] - p["F"], p["E"] - p["F"]
        rho_stop = np.arctan2(np.linalg.norm(np.cross(u, w)), u @ w)
        bk, ae = np.linalg.norm(p["B"] - p["K"]), np.linalg.norm(p["A"] - p["E"])
        print(f"{d:6.1f} {end:>34} {rho.max() / DEG:8.3f} | {x[-1] / DEG:8.3f} / {far / DEG:8.3f} "
              f"{touch / DEG:8.3f} {rho_stop / DEG:7.3f} {bk:7.4f} {ae:7.4f} {cpu:5.2f}", flush=True)


def main() -> None:
    quick = "--quick" in sys.argv
    t0 = time.process_time()
    rows = octahedron_table(QUICK if quick else ZETAS, QUICK if quick else ZETAS_MUJOCO)
    if not quick:
        print(f"\nYang 2017: feasible {PRINTED_RANGE[0]} <= zeta <= {PRINTED_RANGE[1]} deg")
        lo, hi = feasible_band(rows, "feasible")
        print(f"ours on the grid: reaches the cube for {lo} <= zeta <= {hi} deg (turning points allowed)")
        lo, hi = feasible_band(rows, "drivable")
        print(f"ours on the grid: reaches it with theta (A1) monotone for {lo} <= zeta <= {hi} deg")
    for scheme in ("I", "II"):
        tetrahedron_table(scheme, DELTAS[scheme][2:4] if quick else DELTAS[scheme])
    print(f"\nCPU {time.process_time() - t0:.1f} s")


if __name__ == "__main__":
    main()
