"""The MuJoCo presets, each one `Preset` value: its option template's settings (mjcf_templates/options/<name>.xml, read
once here) and its agreement tolerances, each beside the measurement behind it (MuJoCo 4.0.1, this 2-core machine;
set as `tolerances` says: about 10x the worst value measured on the registered scenes' default sweeps).

Code passes `Preset` values; a preset a user names becomes one at the API or command-line edge (`as_preset`).
"""

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from importlib import resources

from .errors import ParameterError

# Projection onto the closures after each step (`stabilize`), by the code a template states in its custom numeric
# `stabilize`: 0 none (plain MuJoCo, also a template that states none), 1 position, 2 position and velocity.
STABILIZE_MODES = ("none", "position", "position-velocity")


@dataclass(frozen=True)
class Preset:
    """
    One preset: its MJCF options (step, integrator, the closures' solref time constant and solimp), the sweep time a
    path's rate scales (`sweep_rate.sweep_duration`), the regulariser scale `simulate.compile_model` applies, the
    stabilisation after each step (STABILIZE_MODES), and its tolerances: path error (rad), closure gap per metre of
    model size, and a free run's energy drift (J).
    """

    name: str
    timestep: float
    integrator: str
    closure_timeconst: float
    closure_solimp: tuple[float, ...]
    sweep_duration: float
    regularization_scale: float
    stabilize: str
    angle_rad: float
    residual_per_m: float
    energy_j: float

    @property
    def template(self) -> str:
        """Its option template, under mjcf_templates/."""
        return f"options/{self.name}.xml"

    def residual(self, length_scale: float = 1.0) -> float:
        """
        Closure-residual tolerance (m) for a model whose characteristic length (`Scene.length_scale`, its largest body
        dimension) is `length_scale` m: the values were measured on models of about 1 m, and a gap between closure
        sites is an angle error times a lever arm, so it scales with the model's size (bennett with a = 1000,
        b = 1500 m: gap 1.0e-4 m at 6.7e-8 rad of path error).
        """
        return length_scale * self.residual_per_m


def _read(name: str, *, angle_rad: float, residual_per_m: float, energy_j: float) -> Preset:
    """The preset `name`: its template's settings with these tolerances."""
    text = resources.files("sim_origami.mjcf_templates").joinpath(f"options/{name}.xml").read_text()
    root = ET.fromstring(text)
    option, closure = root.find("option"), root.find(".//default[@class='closure']/equality")
    numbers = {n.get("name"): float(n.get("data")) for n in root.iter("numeric")}
    code = numbers.get("stabilize", 0.0)
    if code not in (0, 1, 2):
        raise ParameterError(f"preset {name}: stabilize {code!r} is not 0 (none), 1 (position), 2 (position-velocity)")
    return Preset(
        name=name, timestep=float(option.get("timestep")), integrator=option.get("integrator"),
        closure_timeconst=float(closure.get("solref").split()[0]),
        closure_solimp=tuple(float(v) for v in closure.get("solimp").split()),
        sweep_duration=numbers["sweep_duration"], regularization_scale=numbers["regularization_scale"],
        stabilize=STABILIZE_MODES[int(code)], angle_rad=angle_rad, residual_per_m=residual_per_m, energy_j=energy_j,
    )


# Energy drift: free motion under gravity (IFToMM A04, 10 s from rest, E0 = -29.43 J), max |E - E0| (J) at the
# trajectory's states (`simulate.state_energy`). Read from data.energy after each RK4 step (an internal stage of the
# step, not its state) fast, accurate and fast-projected measured 5.2e-5, 2.9e-9 and 1.3e-5 J, and the tolerances
# were set on those.
FAST = _read(
    "fast",
    # MuJoCo path error, RK4 8 ms, default sweeps of every scene, each sweep as long as its path's joint rates ask
    # (`sweep_rate`: timed for a lag of 0.2 x this tolerance): worst 2.2e-7 rad (waterbomb-tube), 2.0e-7
    # (waterbomb-twist), 1.9e-7 (waterbomb-vertex), <= 1.5e-7 on every other scene (run `validate --all`); Bennett
    # linkages turning their output 9-87x as fast as their input 1.4e-7 .. 3.3e-7.
    # Non-default geometries measured with RK4 5 ms: flat-foldable vertex branch S 2.1e-7, Myard alpha12 = 70 deg
    # 1.6e-7 (8 ms costs up to 3x on fast-turning linkages at equal sweep time).
    angle_rad=1e-6,
    # Closure-site gap (m, 1 m links): worst 1.7e-7 (IFToMM A04).
    residual_per_m=2e-6,
    # Energy drift (RK4 8 ms) 1.4e-5 J.
    energy_j=1.5e-4,
)
STIFF = _read(
    "stiff",
    # Held to fast's path error and closure gap.
    angle_rad=FAST.angle_rad,
    residual_per_m=FAST.residual_per_m,
    # Energy drift (semi-implicit Euler 1.25 ms, closures 2.5 ms) 6.9e-2 J.
    energy_j=0.7,
)
ACCURATE = _read(
    "accurate",
    # RK4 0.1 ms, closures 4 h, regulariser x 0.01, 8 s sweep x the path's `sweep_rate` scale: with the scenes' former
    # hand-set slow-downs (2-32x) default sweeps <= 1.7e-12 rad (waterbomb-vertex; truncated polyhedra 1.1e-12, most
    # scenes 1e-14 .. 2e-13); with the rule's (1.5-5x) waterbomb-vertex 4.8e-12, thick diamond 3.9e-13. The A04 free
    # run 2.3e-11 (10 s under gravity). Before the regulariser scale: 8.4e-11 (thick diamond).
    angle_rad=2e-10,
    # Closure-site gap (m, 1 m links): 4.6e-13 (A04; 2.5e-11 before the regulariser scale).
    residual_per_m=5e-12,
    # Energy drift (RK4 0.1 ms) 6.7e-10 J.
    energy_j=7e-9,
)
# Fast plus one Gauss-Newton step onto the closures per step (`stabilize`): not plain MuJoCo.
FAST_PROJECTED = _read(
    "fast-projected",
    # Default sweeps <= 1.5e-14 rad (bricard-plane; bennett 2.2e-15, A04 driven 2.7e-15, free 8.9e-16), closure gaps
    # <= 9e-15 m; the A04 free run's energy drift 1.6e-6 J at its states (fast: 1.4e-5).
    # On 2 s sweeps (scripts/fast_vs_defaults.py) worst 9.7e-13 rad (waterbomb-sheet), 4.6e-13 (truncated
    # tetrahedron I); closure gaps <= 1.9e-14 m where measured (tube), the angle error's size or less.
    angle_rad=1e-11,
    residual_per_m=1e-11,
    energy_j=2e-5,
)
PRESETS = (FAST, STIFF, ACCURATE, FAST_PROJECTED)
PRESET_NAMES = tuple(p.name for p in PRESETS)


def as_preset(value: Preset | str) -> Preset:
    """
    `value` itself, or the preset a user named: the one way from a name to a preset.

    Raises
    ------
    ParameterError
      For a name that is no preset's.
    """
    if isinstance(value, Preset):
        return value
    for preset in PRESETS:
        if preset.name == value:
            return preset
    raise ParameterError(f"unknown preset {value!r}; presets are {', '.join(PRESET_NAMES)}")
