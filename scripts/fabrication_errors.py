"""Yang 2017, ch. 3 fabrication-error study (§3.3 to §3.5): the reference value, ours and the difference.

The reference is the thesis's printed number where it prints one (the headers quote those it prints to fewer places)
and otherwise a worked value of its equations at its own example, computed independently of this package; rows
marked (derived here) are results the thesis does not state.

The RSSR's output errors (exact (3-5) and linearised (3-41...3-45)), its ball-joint waggle (corrected (3-50)),
the overconstrained Bennett with the same errors (closure gap, mobility forced together), and the Myard against
its RRSRR / RSRRR forms (truss counts, forced together after a 1 deg axis tilt). Angles in degrees, lengths in mm
(Bennett) or units of a23 (Myard). Run: /work/venv/bin/python scripts/fabrication_errors.py
"""

import numpy as np

from sim_origami.kinematics.bennett import Bennett
from sim_origami.kinematics.dh import DHRow, dh_from_axes, dh_loop
from sim_origami.kinematics.myard import BRANCH, Myard
from sim_origami.linkage import dh_mechanism
from sim_origami.linkage_forms import chain_poses, reduced_form
from sim_origami.studies.fabrication import (
    DEG,
    FINE_LENGTH,
    NOMINAL,
    RSSR,
    VERY_COARSE,
    FabricationError,
    closure_gap,
    dh_axes,
    max_waggle,
    output_error,
    screw_mobility,
    study,
    tilted,
)
from sim_origami.truss import analyse, truss_of


def row(name: str, reference: float | str, ours: float, digits: int = 3) -> None:
    """One table line: reference value (number or text), ours, difference when the reference is a number."""
    diff = f"{ours - reference:+.{digits}f}" if isinstance(reference, float) else ""
    shown = f"{reference:.{digits}f}" if isinstance(reference, float) else reference
    print(f"  {name:<58} {shown:>12} {ours:>12.{digits}f} {diff:>10}")


def counts(name: str, reference: tuple[int, ...], c) -> None:
    """Truss counts j, b, r, m, s (reference, ours) on five lines."""
    ours = (c.nodes, c.bars, c.rank, c.mobility, c.self_stress)
    for key, s, o in zip("jbrms", reference, ours, strict=True):
        row(f"{name} {key}" if key == "j" else f"  {key}", float(s), o, 0)


def header(title: str) -> None:
    print(f"\n{title}\n  {'quantity':<58} {'reference':>12} {'ours':>12} {'diff':>10}")


def rssr_tables(nominal: RSSR) -> None:
    d_alpha, d_l = VERY_COARSE
    header("RSSR implied Bennett (eqns 3-3 to 3-6, 3-38; worked values)")
    for (a1, a2, alpha), beta, k_a, k_b in [
        ((100, 70.72, 45 * DEG), 30.0044, -4.665482, 1.249732),
        ((101.5, 69.22, 45 * DEG), 28.8309, -4.270901, 1.238316),
        ((100, 70.72, 46 * DEG), 30.5784, -4.618156, 1.262539),
    ]:
        r, other = RSSR(a1, a2, alpha), RSSR(a1, a2, alpha, root=-1)
        row(f"a1 {a1}, a2 {a2}, alpha {alpha / DEG:g}: implied beta (deg)", beta, r.beta / DEG, 4)
        row("  K (3-6a)", k_a, r.K, 6)
        row("  K (3-6b)", k_b, other.K, 6)
    header("RSSR max |d theta2| over theta1 (deg; thesis 0.58 / 5.06 / 0.53; worked values of (3-5), (3-41))")
    cases = [
        ("twist 1 deg, k = +1", FabricationError(d_alpha, 0.0, 1), 0.584, 155.7, 0.577),
        ("length 1.5 mm, k = +1", FabricationError(0.0, d_l, 1), 5.061, 154.7, 5.447),
        ("length 1.5 mm, k = -1", FabricationError(0.0, d_l, -1), 5.639, 156.9, "(derived here)"),
        ("length 0.15 mm, k = +1", FabricationError(0.0, FINE_LENGTH, 1), 0.530, 155.7, 0.534),
        ("length 0.15 mm, k = -1", FabricationError(0.0, FINE_LENGTH, -1), 0.536, 155.9, "(derived here)"),
    ]
    for name, error, value, at, linear in cases:
        s = study(nominal, error)
        row(f"{name}: exact max", value, s.exact.value / DEG)
        row("  at +-theta1", at, s.exact.theta1 / DEG, 1)
        row("  linearised max (3-41)", linear, s.linearised.value / DEG)
        row("  built implied beta", "", s.beta / DEG, 4)
    built = FabricationError(0.0, d_l, 1).built(nominal)
    for theta, reference in ((170.0, 3.431), (179.0, 0.394)):
        row(
            f"length 1.5 mm, k = +1: d theta2 at theta1 = {theta:g}",
            reference,
            output_error(nominal, built, theta * DEG) / DEG,
        )
    header("Ball-joint waggle max |90 - angle(CD, z_D)| (deg; thesis 0.58 / 1.22, printed (3-50): 0.821 / 1.669)")
    for name, error, reference in [
        ("twist -1 deg", FabricationError(-d_alpha, 0.0, 1), 0.581),
        ("a1 - 1.5 mm, a2 + 1.5 mm", FabricationError(0.0, d_l, -1), 1.224),
    ]:
        built = error.built(nominal)
        w = max_waggle(nominal, built)
        row(f"{name}: corrected (3-50)", reference, w.value / DEG)
        row("  |beta_R - beta| (derived here: equals the max)", reference, abs(built.beta - nominal.beta) / DEG)
        row("  at theta1", "", w.theta1 / DEG, 1)


def bennett_tables(nominal: RSSR) -> None:
    header("Overconstrained Bennett with the same errors (a1R, a2R, alpha_R; ground twist beta nominal)")
    good = Bennett(nominal.a1, nominal.alpha, nominal.a2, nominal.beta)
    for name, error in [("length 1.5 mm, k = +1", FabricationError(0.0, 1.5, 1)),
                        ("twist 1 deg, k = +1", FabricationError(DEG, 0.0, 1))]:
        built = error.built(nominal)
        bad = Bennett(built.a1, built.alpha, built.a2, nominal.beta, check=False)
        gaps = []
        for theta in (0.0, 1.0, 2.0, np.pi):
            start = good.loop_angles(good.joint_angles("bennett", theta))
            gaps.append(closure_gap(bad.loop_system(), start, nominal.a1, fixed=(0,)).translation)
        row(f"{name}: closure gap (mm) at theta1 = 0", "0 (folded)", gaps[0], 6)
        row("  closure gap (mm) at theta1 = 1 rad (derived here)", "> 0", gaps[1])
        row("  closure gap (mm) at theta1 = 2 rad (derived here)", "> 0", gaps[2])
        row("  closure gap (mm) at theta1 = pi", "0 (folded)", gaps[3], 6)
        folded = dh_axes(bad.rows, [0, np.pi, 0, -np.pi])
        row("  screw mobility at the folded pose", "locks", screw_mobility(*folded), 0)
    q = good.loop_angles(good.joint_angles("bennett", 1.0))[0]
    points, dirs = dh_axes(good.rows, q)
    dirs = tilted(dirs, 1, 1.5 * DEG)
    rows, angles = dh_from_axes(points, dirs)
    c = analyse(truss_of(dh_mechanism(rows, anchor=50.0, width=5.0), angles))
    row("axis A tilted 1.5 deg: truss r", 18.0, c.rank, 0)
    row("  truss m", 0.0, c.mobility, 0)
    form = reduced_form(rows, (3, 4), anchor=50.0, width=5.0)
    c = analyse(truss_of(form, form.angles_from_poses(chain_poses(rows, angles))[0]))
    row("  its RSSR form: truss m", 1.0, c.mobility, 0)
    row("    s", 0.0, c.self_stress, 0)
    row("    screw mobility (1 + idle spin of CD)", 2.0, screw_mobility(points, dirs, (3, 4)), 0)


def myard_tables() -> None:
    header("Myard 5R (alpha12 = 50 deg, theta3 = 40 deg) and its non-overconstrained forms (§3.4)")
    model = Myard(1.0, 50 * DEG)
    q = model.loop_angles(model.joint_angles(BRANCH, 40 * DEG))[0]
    c = analyse(truss_of(dh_mechanism(model.rows, anchor=0.5, input_joint=3), q))
    counts("5R truss:", (9, 22, 20, 1, 2), c)
    for ball, name in ((1, "RRSRR (S at A)"), (2, "RSRRR (S at B)")):
        form = reduced_form(model.rows, (ball,), anchor=0.5, input_joint=3)
        c = analyse(truss_of(form, form.angles_from_poses(chain_poses(model.rows, q))[0]))
        counts(f"{name} truss:", (8, 17, 17, 1, 0), c)
    points, dirs = dh_axes(model.rows, q)
    dirs = tilted(dirs, 5, DEG)
    rows, angles = dh_from_axes(points, dirs)
    c = analyse(truss_of(dh_mechanism(rows, anchor=0.5, input_joint=3), angles))
    row("axis 5 tilted 1 deg: 5R truss m (derived here)", 0.0, c.mobility, 0)
    for ball, name in ((1, "RRSRR"), (2, "RSRRR")):
        form = reduced_form(rows, (ball,), anchor=0.5, input_joint=3)
        c = analyse(truss_of(form, form.angles_from_poses(chain_poses(rows, angles))[0]))
        row(f"  {name} truss m (s = {c.self_stress})", 1.0, c.mobility, 0)
    perturbed = list(model.rows)
    perturbed[3] = DHRow(0.0, perturbed[3].a, perturbed[3].alpha + DEG)
    gap = closure_gap(dh_loop(tuple(perturbed)), q, 1.0, fixed=(2,))
    row("alpha45 + 1 deg: 5R closure gap at theta3 = 40, rotation (rad) (derived here)", "> 0", gap.rotation, 4)
    row("  translation (units of a23) (derived here)", "> 0", gap.translation, 4)


def main() -> None:
    nominal = RSSR(*NOMINAL)
    rssr_tables(nominal)
    bennett_tables(nominal)
    myard_tables()


if __name__ == "__main__":
    main()
