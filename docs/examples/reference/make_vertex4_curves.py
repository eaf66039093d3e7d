"""Write vertex4_curves.csv: the degree-4 vertex of vertex4.fold (sectors 60, 100, 90, 110 deg) on its branch
odd2, from sim_origami's closed form of the vertex (`kinematics.vertex4`), at rho1 = 35 ... 65 deg. The FOLD file
route knows no closed form (its truth is a numeric path through the folded state), so this is a check of one
against the other. The columns are named after the FOLD file's creases (edge k -> rho_e<k>)."""

from pathlib import Path

import numpy as np

from sim_origami.kinematics.vertex4 import Vertex4

if __name__ == "__main__":
    vertex = Vertex4(np.deg2rad([60.0, 100.0, 90.0, 110.0]))
    rows = np.rad2deg(vertex.joint_angles("odd2", np.deg2rad(np.arange(35.0, 66.0, 2.5))))
    body = "\n".join(",".join(f"{v:.9f}" for v in row) for row in rows)
    out = Path(__file__).with_name("vertex4_curves.csv")
    out.write_text(f"rho_e0[deg],rho_e1[deg],rho_e2[deg],rho_e3[deg]\n{body}\n")
