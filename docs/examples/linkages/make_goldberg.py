"""Write goldberg-5r.json (a Goldberg 5R linkage as axis lines) and goldberg-5r_curves.csv (its joints from the two
Bennett closed forms). numpy only: nothing here uses sim_origami, so the curves are an independent reference.

    python make_goldberg.py

The construction (Goldberg 1943; Yang 2017, section 1.2.3): two Bennett linkages share a link DA and its joints
A and D, the link DA is removed and the two links at A (AB of the first, AE of the second) are fixed together at
the angle DELTA. What is left is a loop of five hinges B, C, D, F, E with one freedom.

Bennett 1 has D-H rows (a, alpha), (b, beta), (a, alpha), (b, beta) at joints A, B, C, D and Bennett 2 rows
(b, beta), (c, gamma), (b, beta), (c, gamma) at joints D, A, E, F, with sin(alpha)/a = sin(beta)/b = sin(gamma)/c,
in the D-H convention T = Rz(theta) Tz(R) Tx(a) Rx(alpha). Their closed forms (Yang 2017, eqn 1-18):
tan(t1/2) tan(t2/2) = K with K = sin((beta + alpha)/2) / sin((beta - alpha)/2), t3 = -t1, t4 = -t2. The 5R's joint
angles:
B = t2, C = -t1, D = -t2 - p1, F = -p2, E = -p1, with p2 = t1 + DELTA and p1 the second Bennett's angle at D.
"""

import json
import re
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
A, ALPHA = 1.0, np.deg2rad(30.0)
B, BETA = 1.5, np.arcsin(0.75)  # sin(alpha)/a = sin(beta)/b = 0.5
C, GAMMA = 1.2, np.arcsin(0.6)  # sin(gamma)/c = 0.5
DELTA = np.deg2rad(60.0)  # AE turned from AB about A
DRAWN = np.deg2rad(80.0)  # input C in the drawn pose
RANGE = (40.0, 140.0)  # input C (deg)
SAMPLES = np.arange(45.0, 136.0, 5.0)  # inputs of the reference curves (deg)


def link(a: float, alpha: float) -> np.ndarray:
    """Tx(a) Rx(alpha): a joint's frame (after its turn) to the next joint's frame."""
    c, s = np.cos(alpha), np.sin(alpha)
    return np.array([[1, 0, 0, a], [0, c, -s, 0], [0, s, c, 0], [0, 0, 0, 1.0]])


def rz(t: float) -> np.ndarray:
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, 0, 0], [s, c, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1.0]])


def bennett(t: np.ndarray, a: float, alpha: float, b: float, beta: float) -> np.ndarray:
    """The second joint's angle of a Bennett linkage (rows a, alpha; b, beta) from the first's (Yang 2017, 1-18)."""
    K = np.sin((beta + alpha) / 2) / np.sin((beta - alpha) / 2)
    return 2 * np.arctan2(K * np.cos(t / 2), np.sin(t / 2))


def joints(c_input: np.ndarray) -> dict[str, np.ndarray]:
    """The 5R's joint angles (rad) at inputs C (rad)."""
    t1 = -c_input
    t2 = bennett(t1, A, ALPHA, B, BETA)
    p2 = t1 + DELTA
    p1 = bennett(p2, B, BETA, C, GAMMA)  # Bennett 2's rows from A: b, beta; c, gamma (symmetric in its two angles)
    return {"B": t2, "C": -t1, "D": -t2 - p1, "F": -p2, "E": -p1}


def axes(c_input: float) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each hinge's point and direction (m) in the drawn pose, in the frame of the removed link DA."""
    t1 = -c_input
    t2 = bennett(np.array(t1), A, ALPHA, B, BETA)
    p2 = t1 + DELTA
    p1 = bennett(np.array(p2), B, BETA, C, GAMMA)
    ab = link(B, BETA) @ rz(t1)  # Bennett 1: DA is the identity, A at the end of row (b, beta)
    bc = ab @ link(A, ALPHA) @ rz(t2)
    cd = bc @ link(B, BETA) @ rz(-t1)
    ae = link(B, BETA) @ rz(p2)  # Bennett 2 from DA: A, then E and F
    ef = ae @ link(C, GAMMA) @ rz(-p1)
    frames = {"B": ab @ link(A, ALPHA), "C": bc @ link(B, BETA), "D": cd @ link(A, ALPHA),
              "E": ae @ link(C, GAMMA), "F": ef @ link(B, BETA)}
    assert np.allclose(frames["F"] @ rz(-p2) @ link(C, GAMMA) @ rz(p1), np.eye(4), atol=1e-12)  # Bennett 2 closes
    return {name: (T[:3, 3], T[:3, 2]) for name, T in frames.items()}


def main() -> None:
    lines = axes(DRAWN)
    start = {k: float(np.rad2deg(v)) for k, v in joints(np.array(DRAWN)).items()}
    bodies = {"B": ["EB", "BC"], "C": ["BC", "CD"], "D": ["CD", "DF"], "F": ["EF", "DF"], "E": ["EB", "EF"]}
    doc = {
        "sim_origami_linkage": 1,
        "form": "axes",
        "name": "goldberg-5r",
        "notes": "Goldberg 5R from two Bennett linkages (a = 1 m, alpha = 30 deg; b = 1.5 m, beta = arcsin 0.75; "
                 "c = 1.2 m, gamma = arcsin 0.6) sharing link DA, AB and AE fixed 60 deg apart (make_goldberg.py)",
        "units": {"length": "m", "angle": "deg"},
        "ground": "EB",
        "joints": [{"name": n, "bodies": bodies[n], "point": [round(float(v), 15) for v in lines[n][0]],
                    "direction": [round(float(v), 15) for v in lines[n][1]], "theta0": round(start[n], 12)}
                   for n in ("B", "C", "D", "F", "E")],
        "input": {"joint": "C", "range": list(RANGE)},
    }
    text = json.dumps(doc, indent=2)
    # short lists (bodies, points, directions, the range) on one line each
    text = re.sub(r"\[\s+([^\[\]{}]*?)\s+\]", lambda m: "[" + ", ".join(v.strip() for v in m[1].split(",")) + "]", text)
    (HERE / "goldberg-5r.json").write_text(text + "\n")
    values = joints(np.deg2rad(SAMPLES))
    rows = ["# Goldberg 5R (goldberg-5r.json): joints from the two Bennett closed forms, make_goldberg.py",
            "C[deg],B[deg],D[deg],F[deg],E[deg]"]
    for k, x in enumerate(SAMPLES):
        rows.append(",".join(f"{v:.10f}" for v in [x, *(np.rad2deg(values[n][k]) for n in "BDFE")]))
    (HERE / "goldberg-5r_curves.csv").write_text("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
