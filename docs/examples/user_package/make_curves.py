"""Write the four-bar's reference curves from Freudenstein's equation (numpy only, no sim_origami).

Freudenstein's frame: crank pivot O2 at the origin, rocker pivot O4 at (d, 0); crank a at angle t2, coupler b at
t3, rocker c at t4 (each from +x). With K1 = d/a, K2 = d/c, K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c):
K1 cos t4 - K2 cos t2 + K3 = cos(t2 - t4), solved as t4 = 2 atan2(-B +/- sqrt(B^2 - 4 A C), 2 A), and likewise
t3 with K4 = d/b, K5 = (c^2 - d^2 - a^2 - b^2) / (2 a b).

The scene's D-H loop is the same picture turned by pi (ground from joint 4 to joint 1, along +x): crank
theta1 = t2 + pi, coupler phi2 = t3 + pi, rocker phi3 = t4, so theta2 = t3 - t2, theta3 = t4 - t3 + pi,
theta4 = -t4 (mod 2 pi). `python make_curves.py` writes four_bar_curves.csv (the '-' root) and
four_bar_curves_misprinted.csv, where K3 has -a^2: a misprint the check must catch.
"""

from pathlib import Path

import numpy as np

a, b, c, d = 0.4, 1.2, 0.9, 1.0  # a1, a2, a3, a4 of the scene's defaults (m)


def curves(k3: float) -> np.ndarray:
    theta1 = np.deg2rad(np.arange(-140.0, 140.1, 10.0))
    t2 = theta1 - np.pi
    k1, k2, k4, k5 = d / a, d / c, d / b, (c**2 - d**2 - a**2 - b**2) / (2 * a * b)
    A = np.cos(t2) - k1 - k2 * np.cos(t2) + k3
    B = -2 * np.sin(t2)
    C = k1 - (k2 + 1) * np.cos(t2) + k3
    t4 = 2 * np.arctan2(-B - np.sqrt(B**2 - 4 * A * C), 2 * A)
    D = np.cos(t2) - k1 + k4 * np.cos(t2) + k5
    E = -2 * np.sin(t2)
    F = k1 + (k4 - 1) * np.cos(t2) + k5
    t3 = 2 * np.arctan2(-E - np.sqrt(E**2 - 4 * D * F), 2 * D)
    wrap = lambda v: np.angle(np.exp(1j * v))  # noqa: E731
    return np.rad2deg(np.column_stack([theta1, wrap(t3 - t2), wrap(t4 - t3 + np.pi), wrap(-t4)]))


def write(path: Path, k3: float, note: str) -> None:
    rows = "\n".join(",".join(f"{v:.9f}" for v in row) for row in curves(k3))
    path.write_text(f"# {note}\ntheta1[deg],theta2[deg],theta3[deg],theta4[deg]\n{rows}\n")


if __name__ == "__main__":
    here = Path(__file__).parent
    write(here / "four_bar_curves.csv", (a**2 - b**2 + c**2 + d**2) / (2 * a * c),
          "four-bar (a1..a4 = 0.4, 1.2, 0.9, 1.0 m) from Freudenstein's equation, make_curves.py")
    write(here / "four_bar_curves_misprinted.csv", (-(a**2) - b**2 + c**2 + d**2) / (2 * a * c),
          "the same with a misprinted K3 = (-a^2 - b^2 + c^2 + d^2) / (2 a c)")
