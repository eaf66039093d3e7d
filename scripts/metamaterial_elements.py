"""Double-corrugated metamaterial elements 1, 2 and 3 (Peng 2018, §3.2.3): worked value, ours, difference.

    python scripts/metamaterial_elements.py      (under 1 s of CPU; no MuJoCo)

The thesis prints no numbers for these elements, so the reference is a table of worked values of its formulas
(eqns 3-24, 3-25) computed independently of this package at alpha = 3 pi/4, beta = pi/3, l = 1 and phi = pi/3,
pi/2, 2 pi/3. For those it prints W, H, L of the three elements from the thesis's formulas
(`checks.metamaterial.element_formulas`) and measured as vertex distances on the closed-form P sheet of scene
`corrugated-sheet` (element 1 on SCSC, element 2 on SCCS, element 3 on CCSS; `checks.metamaterial` docstring), then
element 3's theta (the worked values take eqn 3-26 as printed; ours reads gamma = pi - alpha for alpha), phi_II
(maximum height) and the closed-form Poisson's ratios. The worked table has no W, H, L for element 3 (column
'worked' shows nan).
"""

import numpy as np

import sim_origami.scenes.corrugated_sheet  # noqa: F401  (registers `corrugated-sheet`)
from sim_origami import scenes
from sim_origami.studies.metamaterial import (
    ELEMENTS,
    element3_theta,
    element_dimensions,
    element_formulas,
    formula_poisson,
    max_height_angle,
)
from sim_origami.studies.poisson import vertex_positions

ALPHA, BETA = 3 * np.pi / 4, np.pi / 3
PHI = np.array([np.pi / 3, np.pi / 2, 2 * np.pi / 3])
NAN3 = (np.nan, np.nan, np.nan)
# worked values: element -> (W, H, L) per phi; theta of eqn 3-26 as printed
WORKED = {
    1: ((0.824937, 0.705701, 1.325076), (1.137055, 0.654654, 1.467314), (1.380314, 0.530926, 1.668058)),
    2: ((0.824937, 1.411402, 2.650152), (1.137055, 1.309307, 2.934628), (1.380314, 1.061852, 3.336116)),
    3: (NAN3, NAN3, NAN3),
}
WORKED_THETA = (-0.189408, -0.326128, -0.555214)


def sheet_positions(sc, branch: str) -> np.ndarray:
    """Closed-form vertex positions (3, V, 3) on `branch` where u1_2 (A2B2) has dihedral angle PHI."""
    gain = sc.kinematics.ratios[branch][[c.name for c in sc.pattern.creases].index("u1_2")]
    x = 2 * np.arctan(np.tan((np.pi - PHI) / 2) / abs(gain))
    q = sc.loop_to_mechanism(sc.kinematics.joint_angles(branch, x))
    return vertex_positions(sc.pattern, sc.mechanism.body_poses(q))[0]


def main() -> None:
    sc = scenes.get("corrugated-sheet").build(unit=0.0, rows=2, cols=2)
    print(f"{'element':>7} {'phi':>8} {'dim':>3} {'worked':>9} {'formula':>12} {'sheet':>12} {'formula-worked':>14}")
    for element, placement in ELEMENTS.items():
        positions = sheet_positions(sc, placement.branch)
        ours = element_formulas(PHI, ALPHA, BETA, element)
        sheet = element_dimensions(sc.pattern, positions, PHI, element)
        for k, phi in enumerate(PHI):
            for col, name in enumerate("WHL"):
                worked, f, m = WORKED[element][k][col], getattr(ours, name)[k], getattr(sheet, name)[k]
                print(f"{element:>7} {phi:>8.6f} {name:>3} {worked:>9.6f} {f:>12.9f} {m:>12.9f} {f - worked:>14.2e}")
    gamma = np.pi - ALPHA
    literal = 2 * np.arctan(np.tan(PHI / 2) * np.cos((BETA + ALPHA) / 2) / np.cos((BETA - ALPHA) / 2))
    print(f"theta (3-26 as printed): worked {WORKED_THETA}, recomputed {np.round(literal, 6)}")
    print(f"theta (alpha -> gamma = {gamma:.6f}): {np.round(element3_theta(PHI, ALPHA, BETA), 9)} rad")
    for element in (1, 3):
        phi_ii = max_height_angle(ALPHA, BETA, element)
        h_max = element_formulas(phi_ii, ALPHA, BETA, element).H[0]
        print(f"element {element}: phi_II (maximum height) = {phi_ii:.9f} rad, H_max = {h_max:.9f} m")
    print("element 2 peaks with element 1 at twice its H_max")
    for element in ELEMENTS:
        nu_in, nu_out = (np.round(v, 6) for v in formula_poisson(PHI, ALPHA, BETA, element))
        print(f"element {element}: nu_in = {nu_in}, nu_out = {nu_out} at phi = {np.round(PHI, 6)}")


if __name__ == "__main__":
    main()
