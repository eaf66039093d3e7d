"""Agreement tolerances, each beside the measurement behind it (MuJoCo 4.0.1, this 2-core machine).

A tolerance is about 10x the worst value measured on the registered scenes' default sweeps, so a
regression of one order of magnitude fails while run-to-run noise (bitwise-deterministic here)
does not.
"""

from dataclasses import dataclass


@dataclass(frozen=True)
class Tolerances:
    # Closed form vs numeric loop closure (LM solve to 1e-14): measured <= 1e-15 rad.
    closed_form_rad: float = 1e-12
    # Closure residual of a closed form (product of joint transforms): measured <= 1e-15.
    closed_form_residual: float = 1e-12
    # MuJoCo path error, preset fast (RK4 5 ms): vertex4 7.0e-9, miura 1.1e-7 rad.
    fast_rad: float = 1e-6
    # Preset accurate (RK4 0.1 ms, 4 s sweep): vertex4 3.7e-12, miura 1.8e-10 rad.
    accurate_rad: float = 2e-9
    # Kinematic projection (Gauss-Newton on efc_pos to 1e-14 m): measured 2.4e-13 rad.
    projection_rad: float = 1e-11
    # Closure-site gap (m, for 1 m creases): fast 6.4e-8, accurate 5.9e-12, projection 6e-15.
    fast_residual_m: float = 1e-6
    accurate_residual_m: float = 1e-10
    projection_residual_m: float = 1e-12
    # Blockage: servo stop vs kinematic contact angle (stiff contacts, kp 50, +-20 N m): measured
    # below 1e-3 rad on the thick Miura vertex; spec mujoco.md 6.2 saw 2e-3 with default contacts.
    blockage_rad: float = 1e-2

    def angle(self, mode: str) -> float:
        """Path-error tolerance (rad) for a run mode: 'fast', 'accurate' or 'projection'."""
        return {"fast": self.fast_rad, "accurate": self.accurate_rad, "projection": self.projection_rad}[mode]

    def residual(self, mode: str) -> float:
        """Closure-residual tolerance (m) for a run mode."""
        return {
            "fast": self.fast_residual_m,
            "accurate": self.accurate_residual_m,
            "projection": self.projection_residual_m,
        }[mode]


TOLERANCES = Tolerances()
