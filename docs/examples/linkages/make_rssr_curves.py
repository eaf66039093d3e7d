"""Write rssr_curves.csv: the RSSR's output theta2 from Yang 2017's closed form, for `rssr.json`.

    python make_rssr_curves.py

numpy only: nothing here uses sim_origami, so the curves are an independent reference. The RSSR (Yang 2017, section
3.3) has revolute joints A (theta1) and B (theta2), AB = CD = a1 with twist alpha, BC = DA = a2; its loop closes when
(eqn 3-3) a1 (cos t1 + cos t2) + a2 (cos t1 cos t2 + 1 - cos(alpha) sin t1 sin t2) = 0, solved by (eqn 3-5)
t2 = 2 arctan[(A + sqrt(A^2 + B^2 - C^2)) / (B + C)] with (eqn 3-4) x2 = a1 / a2, A = cos(alpha) sin t1,
B = -cos t1 - x2, C = 1 + x2 cos t1: the root of the Bennett branch (eqn 3-6a) for these lengths.
"""

from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
A1, A2, ALPHA = 1.0, 0.7072, np.deg2rad(45.0)
SAMPLES = np.arange(35.0, 166.0, 5.0)  # inputs theta1 (deg), inside rssr.json's sweep


def theta2(t1: np.ndarray) -> np.ndarray:
    """Eqn 3-5 with the + root (rad), wrapped into (-pi, pi]."""
    x2 = A1 / A2
    a, b, c = np.cos(ALPHA) * np.sin(t1), -np.cos(t1) - x2, 1 + x2 * np.cos(t1)
    t2 = 2 * np.arctan((a + np.sqrt(a**2 + b**2 - c**2)) / (b + c))
    return np.angle(np.exp(1j * t2))


def main() -> None:
    t1 = np.deg2rad(SAMPLES)
    t2 = theta2(t1)
    x2 = A1 / A2
    closure = x2 * (np.cos(t1) + np.cos(t2)) + np.cos(t1) * np.cos(t2) + 1 - np.cos(ALPHA) * np.sin(t1) * np.sin(t2)
    assert np.max(np.abs(closure)) < 1e-12, closure  # eqn 3-3 holds
    rows = "".join(f"{a:.10f},{b:.10f}\n" for a, b in zip(SAMPLES, np.rad2deg(t2), strict=True))
    (HERE / "rssr_curves.csv").write_text("# RSSR (rssr.json): theta2 from Yang 2017, eqn 3-5, make_rssr_curves.py\n"
                                          "theta1[deg],theta2[deg]\n" + rows)


if __name__ == "__main__":
    main()
