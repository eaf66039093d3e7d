"""Agreement tolerances, each beside the measurement behind it (MuJoCo 4.0.1, this 2-core machine).

A tolerance is about 10x the worst value measured on the registered scenes' default sweeps, so a
regression of one order of magnitude fails while run-to-run noise (bitwise-deterministic here)
does not.
"""

from dataclasses import dataclass


@dataclass(frozen=True)
class Tolerances:
    # Closed form vs numeric loop closure (LM continuation to 1e-14, its steps quadratic: `closure.FOLLOW_DAMPING`):
    # every registered branch within 5.3e-14 rad (truncated octahedron), most within 1e-14.
    closed_form_rad: float = 1e-12
    # The continuation stops once the residual is below 1e-14 (about 45 eps), which leaves the angles up to that over
    # the closure Jacobian's smallest singular value: on ill-conditioned paths a sample is held to
    # max(closed_form_rad, closed_form_cond_factor eps cond) (`checks.paths.floor_verdict_values`). Set at 10x the 15
    # eps cond the 16 x 16 Miura FOLD sheet measured with linearly converging steps (1.66e-12 rad at cond 492); with
    # quadratic ones it reads 2.4e-14 there, so the factor is a margin now, not re-measured over the FOLD gallery.
    closed_form_cond_factor: float = 150.0
    # Closure residual of a closed form (product of joint transforms): worst 7.3e-16 (origami),
    # 5.3e-15 (Myard with a23 = 10 m).
    closed_form_residual: float = 1e-12
    # MuJoCo path error, preset fast (RK4 8 ms), default sweeps of every scene, each sweep as long as its path's joint
    # rates ask (`sweep_rate`: timed for a lag of 0.2 x this tolerance): worst 2.2e-7 rad (waterbomb-tube), 2.0e-7
    # (waterbomb-twist), 1.9e-7 (waterbomb-vertex), <= 1.5e-7 on every other scene (run `validate --all`); Bennett
    # linkages turning their output 9-87x as fast as their input 1.4e-7 .. 3.3e-7.
    # Non-default geometries measured with RK4 5 ms: flat-foldable vertex branch S 2.1e-7, Myard alpha12 = 70 deg
    # 1.6e-7 (8 ms costs up to 3x on fast-turning linkages at equal sweep time).
    fast_rad: float = 1e-6
    # Preset accurate (RK4 0.1 ms, closures 4 h, regulariser x 0.01, 8 s sweep x the path's `sweep_rate` scale): with
    # the scenes' former hand-set slow-downs (2-32x) default sweeps <= 1.7e-12 rad (waterbomb-vertex; truncated
    # polyhedra 1.1e-12, most scenes 1e-14 .. 2e-13); with the rule's (1.5-5x) waterbomb-vertex 4.8e-12, thick diamond
    # 3.9e-13. The A04 free run 2.3e-11 (10 s under gravity). Before the regulariser scale: 8.4e-11 (thick diamond).
    accurate_rad: float = 2e-10
    # Kinematic projection (Gauss-Newton chord steps on MuJoCo's efc_pos to the rounding floor): worst 7.4e-14 rad over
    # every scene's branches (waterbomb-twist twist-cw) with the factorisation kept across inputs; before, 4.3e-14
    # (corrugated sheet CCSS; 2.9e-14 the thin thick waterbomb loop, 2.2e-14 the tube, 2e-15 single vertices).
    # Stopping at 1e-14 m instead left 1.8e-13 on the Miura sheet and 1.9e-13 on the waterbomb with a = 0.02 m.
    projection_rad: float = 1e-13
    # The projection and a numerically traced reference both stop at their residual's rounding floor, which moves the
    # angles by about eps times the closure Jacobian's condition number (inputs held). The 16 x 16 Miura FOLD sheet
    # (480 creases, a lock at its folded end) measured at most 4.3 eps cond (2.5e-13 rad at cond 265; the other 94
    # samples above 3e-14 rad within 2.2 eps cond, 3.2e-14 at cond 104 mid-path), so a sample is held to
    # max(projection_rad, 40 eps cond) (`checks.paths.floor_verdict_values`): projection_rad itself wherever
    # cond < 11. Before the reference was polished to its own floor it was 3.7e-12 off there (stopped at a 5e-14
    # residual), which no tolerance should have covered.
    projection_cond_factor: float = 40.0
    # Closure-site gap (m, 1 m links): fast worst 1.7e-7 (IFToMM A04), accurate 4.6e-13 (A04; 2.5e-11 before the
    # regulariser scale). Projection stops once
    # every equality row is below 1e-14 m, so a gap can reach sqrt(3) 1e-14 (measured 1.2e-14).
    # Preset fast-projected (fast plus one Gauss-Newton step onto the closures per step, `stabilize`): default
    # sweeps <= 1.5e-14 rad (bricard-plane; bennett 2.2e-15, A04 driven 2.7e-15, free 8.9e-16), closure gaps
    # <= 9e-15 m; the A04 free run's energy drift 1.6e-6 J at its states (fast: 1.4e-5).
    # On 2 s sweeps (scripts/fast_vs_defaults.py) worst 9.7e-13 rad (waterbomb-sheet), 4.6e-13 (truncated
    # tetrahedron I); closure gaps <= 1.9e-14 m where measured (tube), the angle error's size or less.
    projected_rad: float = 1e-11
    projected_residual_m: float = 1e-11
    projected_energy: float = 2e-5
    fast_residual_m: float = 2e-6
    accurate_residual_m: float = 5e-12
    projection_residual_m: float = 1e-13
    # Blockage: servo stop vs kinematic contact angle (stiff contacts, kp 50, +-20 N m, held 3 s): measured
    # 9.8e-6 rad on the thick Miura vertex (t = 0.02; 3.2e-4 held 1 s), 2.5e-5 on the truncated octahedron at
    # zeta = 15 deg (3.1e-3 held 1 s); a Miura vertex folding onto itself stopped 2e-3 past its blocking angle
    # with default contacts (measured here).
    blockage_rad: float = 3e-3
    # Free motion under gravity (IFToMM A04, 10 s from rest, E0 = -29.43 J): total-energy drift max |E - E0| (J) at
    # the trajectory's states (`simulate.state_energy`): fast (RK4 8 ms) 1.4e-5 J, accurate (RK4 0.1 ms) 6.7e-10,
    # fast-projected 1.6e-6 (above), stiff (semi-implicit Euler 1.25 ms, closures 2.5 ms) 6.9e-2. Read from
    # data.energy after each RK4 step (an internal stage of the step, not its state) these were 5.2e-5, 2.9e-9 and
    # 1.3e-5 J, and the tolerances were set on those.
    fast_energy: float = 1.5e-4
    accurate_energy: float = 7e-9
    stiff_energy: float = 0.7

    def energy(self, preset: str) -> float:
        """Energy-drift tolerance (J) of a free run with this preset."""
        return {"fast": self.fast_energy, "stiff": self.stiff_energy, "accurate": self.accurate_energy,
                "fast-projected": self.projected_energy}[preset]

    def angle(self, mode: str) -> float:
        """Path-error tolerance (rad) for a run mode: 'fast' or 'stiff' (held to the same), 'accurate', 'projection',
        'fast-projected'."""
        return {"fast": self.fast_rad, "stiff": self.fast_rad, "accurate": self.accurate_rad,
                "projection": self.projection_rad, "fast-projected": self.projected_rad}[mode]

    def residual(self, mode: str, length_scale: float = 1.0) -> float:
        """
        Closure-residual tolerance (m) for a run mode, for a model whose characteristic length (`Scene.length_scale`,
        its largest body dimension) is `length_scale` m: the values above were measured on models of about 1 m,
        and a gap between closure sites is an angle error times a lever arm, so it scales with the model's size
        (bennett with a = 1000, b = 1500 m: gap 1.0e-4 m at 6.7e-8 rad of path error).
        """
        return length_scale * {
            "fast": self.fast_residual_m,
            "stiff": self.fast_residual_m,
            "accurate": self.accurate_residual_m,
            "projection": self.projection_residual_m,
            "fast-projected": self.projected_residual_m,
        }[mode]

    def loop_residual(self, length_scale: float = 1.0) -> float:
        """
        Tolerance of a closed form's loop residual (max |rotation vector (rad), translation (m)|) for a model of
        characteristic length `length_scale` m: the translation's rounding grows with the size, the rotation's
        does not, so the bound is the 1 m value times max(1, size).
        """
        return self.closed_form_residual * max(1.0, length_scale)


TOLERANCES = Tolerances()
