"""What a scene is: parameters, a kinematics model, a mechanism and how to drive it.

A scene wires one closed-form model (numpy) to one mechanism graph. Everything downstream (MJCF,
simulation, checks, reports, the CLI) reads only the `Scene`, so a new mechanism is one kinematics
module plus one scene module that calls `register`.
"""

import functools
from collections.abc import Callable
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..conventions import LENGTH_RANGE, LENGTH_RATIO_MAX
from ..creases import CreasePattern
from ..errors import AssemblyError, ParameterError
from ..fold import FileNumbering
from ..kinematics.base import Kinematics
from ..mechanism import Mechanism
from ..mjcf import ModelSetup
from ..path import Polyline
from ..precision import Adjustment, Typed, nearest_exact
from ..presets import FAST, Preset

UNITS = {"deg": np.pi / 180.0, "m": 1.0, "": 1.0}
# Closed-form poses per branch, evenly across its domain with both ends, at which `without_implied_closures` finds
# the loops the couplings imply.
CLOSURE_SAMPLES = 9


@dataclass(frozen=True)
class Tuning:
    """
    How a scene's runs are tuned, apart from what its mechanism is: the preset they use unless told otherwise, and
    scales that the `fast` preset (`Scene.model_setup`) and the path rule (`sweep_rate.sweep_duration`) apply. The
    defaults suit every registered scene but the few whose `why` says, in one line, what they need and what it measured.
    """

    # The preset runs use unless told otherwise (with the presets' scaled regulariser `fast` beats `stiff` on every
    # registered scene: `scripts/preset_compare.py`).
    preset: Preset = FAST
    # A sweep lasts the time its path's joint rates ask for (`sweep_rate.sweep_duration`) times this.
    sweep_time_scale: float = 1.0
    # The fast preset's step and its closure and drive time constants times this (their ratio kept); the path rule
    # sweeps slower in proportion (the lag grows as the time constant squared).
    fast_step_scale: float = 1.0
    # The fast preset's closure and drive time constants times this as well, its step unchanged: softer closures lower
    # a large pattern's closure gap mid-path and raise its lag near a lock (docs/fold_files.md).
    fast_timeconst_scale: float = 1.0
    # The fast preset's regulariser scale (mjcf_templates/options/fast.xml) times this: what lets MuJoCo's lag through
    # an ill-conditioned closure near a lock.
    fast_regularization_scale: float = 1.0
    # Why the values differ from the defaults, in one line, with what was measured.
    why: str = ""

    def __post_init__(self) -> None:
        if not isinstance(self.preset, Preset):
            raise ParameterError(f"preset = {self.preset!r}; it must be a Preset (presets.as_preset takes a name)")
        for name in SCALES:
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not np.isfinite(value) or value <= 0:
                raise ParameterError(f"{name} = {value!r}; it must be a finite number > 0")

    @property
    def fast_softening(self) -> float:
        """How much softer than `fast`'s own its closures are: the factor its time constants grow by, which its lag
        grows as the square of (the path rule sweeps this much slower)."""
        return self.fast_step_scale * self.fast_timeconst_scale


# The run-tuning scales, each > 0.
SCALES = ("sweep_time_scale", "fast_step_scale", "fast_timeconst_scale", "fast_regularization_scale")
DEFAULT_TUNING = Tuning()


# Angle ranges (deg) shared by many parameters: sector angles and twists of a spherical or spatial link. An angle
# within ANGLE_MARGIN of a degenerate end (a zero sector, a straight one) makes panels of zero area: trimesh and qhull
# overflowed at alpha = 1e-300 rad.
ANGLE_MARGIN = 1e-3
ACUTE = {"lo": ANGLE_MARGIN, "hi": 90 - ANGLE_MARGIN}
SECTOR = {"lo": ANGLE_MARGIN, "hi": 180 - ANGLE_MARGIN}
TWIST = {"lo": -360, "hi": 360}
# A signed offset along a joint axis (m): zero or either sign, as large as a length.
OFFSET = {"lo": -LENGTH_RANGE[1], "hi": LENGTH_RANGE[1]}


@dataclass(frozen=True)
class Param:
    """
    A scene parameter. `unit` is what people type (deg or m); the API takes radians/metres.

    Every value is checked against the declared rules before a scene is built (`check`): a real finite number, an
    integer where `integer`, inside [lo, hi] (open at an end where `open_lo` / `open_hi`; bounds in `unit`). `limit`
    says why `hi` is where it is when it is a size limit (the estimated cost), so the refusal can say so. Length
    parameters (unit m) without their own bounds get LENGTH_RANGE, and zero as well where `zero_ok`.
    """

    name: str
    unit: str
    default: float
    help: str
    lo: float | None = None
    hi: float | None = None
    open_lo: bool = False
    open_hi: bool = False
    integer: bool = False
    limit: str = ""
    zero_ok: bool = False
    # A preset parameter (e.g. a table's case number): a nonzero value replaces these parameters, 0 uses them as
    # given. A preset never replaces a value the user gave (`SceneType.build`).
    replaces: tuple[str, ...] = ()

    def to_api(self, value: float) -> float:
        """Command-line value (in `unit`) to the API's radians or metres."""
        return value * UNITS[self.unit]

    def to_user(self, value: float) -> float:
        """API value back to `unit`."""
        return value / UNITS[self.unit]

    def bounds(self) -> tuple[float | None, float | None]:
        """(lo, hi) in `unit`; lengths default to LENGTH_RANGE (signed offsets, with lo < 0, keep their own)."""
        if self.unit == "m" and self.lo is None and self.hi is None:
            return LENGTH_RANGE
        return self.lo, self.hi

    def rule(self) -> str:
        """The accepted values in words, e.g. 'a whole number from 2 to 32' or 'a number in (0, 180) deg'."""
        lo, hi = self.bounds()
        unit = f" {self.unit}" if self.unit else ""
        if self.integer:
            text = f"a whole number from {lo:g} to {hi:g}" if hi is not None else f"a whole number >= {lo:g}"
        elif lo is None and hi is None:
            text = "a finite number"
        else:
            left = "(" if self.open_lo or lo is None else "["
            right = ")" if self.open_hi or hi is None else "]"
            low, high = ("-inf" if lo is None else f"{lo:g}"), ("inf" if hi is None else f"{hi:g}")
            text = f"a number in {left}{low}, {high}{right}{unit}"
        if self.zero_ok:
            text += " or 0"
        return text + (f" ({self.limit})" if self.limit else "")

    def check(self, value: object) -> float:
        """
        The API value (radians, metres) as a float after checking it against the rules; ParameterError naming the
        parameter, the value (in `unit`) and the rule otherwise.
        """
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise ParameterError(f"{self.name} = {value!r}; it must be {self.rule()}")
        api = float(value)
        user = self.to_user(api) if np.isfinite(api) else api
        shown = f"{self.name} = {user:.10g}{' ' + self.unit if self.unit else ''}"
        if not np.isfinite(api):
            raise ParameterError(f"{shown}; it must be {self.rule()}")
        if self.zero_ok and api == 0.0:
            return api
        lo, hi = self.bounds()
        too_low = lo is not None and (user < lo or (self.open_lo and user == lo))
        too_high = hi is not None and (user > hi or (self.open_hi and user == hi))
        if too_low or too_high or (self.integer and user != round(user)):
            raise ParameterError(f"{shown}; it must be {self.rule()}")
        return api


@dataclass(frozen=True)
class Scene:
    """
    A built scene.

    Attributes
    ----------
    kinematics : Kinematics
      The closed form; its loop joints map to `loop_joints` of the mechanism in order.
    mechanism : Mechanism
      Bodies and joints; the driven joint is kept in the spanning tree.
    drive_joint : str
      Mechanism joint whose angle is `drive_scale` * input.
    path : (start, stop)
      Default input sweep in radians (inside every branch's domain unless per-branch).
    contact_pairs : pairs of body names that may really collide (thick panels); empty = no contact.
    self_contact : every pair of bodies that shares no vertex of `pattern` may collide (large sheets, where
      explicit pairs would number in the tens of thousands); needs the bodies' collision solids.
    pattern : the crease pattern the mechanism was built from (its crease names are the joints), if any;
      reports then export the simulated motion as a multi-frame FOLD file.
    drive_joints, drive_path : several driven joints moved together along `drive_path` (`path.Polyline` in their
      space, its parameter is the input, rad); `drive_joint` is then the first of them and `drive_scale` 1. Empty
      and None for the single drive (`drive_joint` = `drive_scale` * input).
    adjustments : the values as typed (parameters, a file's numbers) that the nearest exact model moved.
    tuning : how its runs are tuned (`Tuning`), apart from the mechanism; the defaults unless the scene says why.
    """

    name: str
    params: dict[str, float]
    kinematics: Kinematics
    mechanism: Mechanism
    loop_joints: tuple[str, ...]
    drive_joint: str
    drive_scale: float
    path: tuple[float, float]
    contact_pairs: tuple[tuple[str, str], ...] = ()
    gravity: tuple[float, float, float] | None = None  # m/s^2 in the root's frame: adds a free run
    free_start: float = 0.0  # input (rad) at which the free run is released at rest
    free_branch: str = ""  # branch of that start pose
    tuning: Tuning = DEFAULT_TUNING
    notes: str = ""
    pattern: CreasePattern | None = None
    self_contact: bool = False
    drive_joints: tuple[str, ...] = ()
    drive_path: Polyline | None = None
    # Values as typed that the nearest exact model moved (`precision.nearest_exact`): validation checks that model
    # and reports each move against the value's precision.
    adjustments: tuple[Adjustment, ...] = ()
    # A scene read from a user's file: what the reader did and warned of, one sentence each (shown with the verdicts),
    # and the file's unit and numbering, which files written from the scene keep (`fold.FileNumbering`).
    source_notes: tuple[str, ...] = ()
    numbering: FileNumbering | None = None

    @property
    def drives(self) -> tuple[str, ...]:
        """Every driven mechanism joint."""
        return self.drive_joints or (self.drive_joint,)

    def input_of(self, q: ArrayLike) -> NDArray[np.float64]:
        """The input (n,) measured from mechanism angles q (n, n_joints): the drive joint over its scale, or the
        parameter of the drive path's point nearest the driven joints."""
        q = np.atleast_2d(np.asarray(q, dtype=float))
        if self.drive_path is None:
            return q[:, self.mechanism.joint_index(self.drive_joint)] / self.drive_scale
        return self.drive_path.parameter_of(q[:, [self.mechanism.joint_index(n) for n in self.drives]])

    def drive_values(self, x: ArrayLike) -> NDArray[np.float64]:
        """Driven joint angles (n, len(drives)) at inputs x (n,)."""
        x = np.atleast_1d(np.asarray(x, dtype=float))
        return self.drive_scale * x[:, None] if self.drive_path is None else self.drive_path.at(x)

    @property
    def colliding_pairs(self) -> tuple[tuple[str, str], ...]:
        """Pairs of bodies whose collision solids may touch: `contact_pairs`, and with `self_contact` every pair of
        the pattern's faces that shares no vertex (as the MJCF's contact section allows them)."""
        if not self.self_contact:
            return self.contact_pairs
        touching = set(self.pattern.touching_faces())
        names = self.pattern.face_names
        free = tuple((a, b) for i, a in enumerate(names) for b in names[i + 1 :] if (a, b) not in touching)
        return self.contact_pairs + free

    @property
    def length_scale(self) -> float:
        """The model's characteristic length (m): its largest body dimension (`Mechanism.length_scale`). Length
        tolerances of the loop solve and the verdicts are in units of it."""
        return self.mechanism.length_scale

    @property
    def crease_hinges(self) -> frozenset[str]:
        """Hinges that are creases of paper: a crease pattern's creases and an origami vertex's `crease_*` hinges."""
        names = {j.name for j in self.mechanism.joints if j.name.startswith("crease_")}
        if self.pattern is not None:
            names |= {c.name for c in self.pattern.creases}
        return frozenset(names)

    def model_setup(self) -> ModelSetup:
        """What the scene's MuJoCo models hold beyond the mechanism (`mjcf.build_xml`)."""
        return ModelSetup(
            name=self.name, drives=self.drives, notes=self.notes,
            contact_pairs=self.contact_pairs,
            self_contact_exclude=self.pattern.touching_faces() if self.self_contact else None,
            gravity=self.gravity, creases=self.crease_hinges, fast_step_scale=self.tuning.fast_step_scale,
            fast_timeconst_scale=self.tuning.fast_timeconst_scale,
            fast_regularization_scale=self.tuning.fast_regularization_scale,
        )

    def loop_to_mechanism(self, q_loop: ArrayLike) -> NDArray[np.float64]:
        """Mechanism joint angles (n, n_joints) from loop joint angles (n, n_loop)."""
        q_loop = np.atleast_2d(np.asarray(q_loop, dtype=float))
        q = np.zeros((len(q_loop), len(self.mechanism.joints)))
        for k, name in enumerate(self.loop_joints):
            q[:, self.mechanism.joint_index(name)] = q_loop[:, k]
        return q

    def mechanism_to_loop(self, q: ArrayLike) -> NDArray[np.float64]:
        """Loop joint angles (n, n_loop) from mechanism joint angles (n, n_joints)."""
        q = np.atleast_2d(np.asarray(q, dtype=float))
        return q[:, [self.mechanism.joint_index(n) for n in self.loop_joints]]

    def pose(self, branch: str, x: float) -> NDArray[np.float64]:
        """Mechanism joint angles (n_joints,) of the closed form on `branch` at input x."""
        values = self.kinematics.joint_angles(branch, x)
        return self.loop_to_mechanism(self.kinematics.loop_angles(values))[0]

    def domain_poses(self, samples: int) -> NDArray[np.float64]:
        """Mechanism joint angles (k, n_joints) of the closed form at `samples` inputs evenly across each branch's
        domain, ends included, branch after branch."""
        branches = self.kinematics.branches()
        return np.array([self.pose(b.name, x) for b in branches for x in np.linspace(*b.domain, samples)])

    def outputs(self, q: ArrayLike) -> NDArray[np.float64]:
        """Output joints (n, k) of the closed form's naming, measured from mechanism angles."""
        return self.kinematics.observe(self.mechanism_to_loop(q))

    def branch_path(self, branch: str) -> tuple[float, float]:
        """
        The default sweep, kept clear of the domain's ends by 5% of the larger end (so a symmetric
        domain [-L, L] allows [-0.95 L, 0.95 L]), at most a quarter of the domain's width.
        """
        lo, hi = self.kinematics.branch(branch).domain
        margin = min(0.05 * max(abs(lo), abs(hi)), 0.25 * (hi - lo))
        start, stop = np.clip(self.path, lo + margin, hi - margin)
        return float(start), float(stop)


def without_implied_closures(scene: Scene) -> Scene:
    """
    The scene with the closures that its couplings and its other closures imply (`Mechanism.implied_cuts`, at
    CLOSURE_SAMPLES closed-form poses across every branch's domain, ends included) measured but not imposed.

    Measured on the waterbomb tube and twist: implied loops leave <= 1.8e-13 of their closure rows outside the
    span (IMPLIED_RTOL 1e-9), kept ones >= 0.057 at every pose. The 10 x 5 tube keeps 6 of its 131 cut creases
    (1071 constraint rows -> 321) and steps 3.3x faster under `stiff` at the same path error, whose error is the
    step's (scripts/waterbomb_tube_rate.py). Under `fast` the soft closures set the error, which grows as the
    constraint's smallest singular value shrinks: 6 x 5 tube, 8x sweep, fast at 8 ms, all 79 loops 1.5e-8 rad in
    6.3 s of CPU, these 6 loops 1.2e-6 in 3.1 s (sigma_min 0.146 -> 0.014), so scenes impose every loop by default.
    """
    mechanism = replace(scene.mechanism, implied=scene.mechanism.implied_cuts(scene.domain_poses(CLOSURE_SAMPLES)))
    return replace(scene, mechanism=mechanism)


@dataclass(frozen=True)
class Condition:
    """
    An exact condition on a scene's parameters, such as the Bennett condition.

    `residual(values)` takes the API values by name and is zero where the condition holds, scaled by the model's
    size so that it is dimensionless; the scene's values are projected onto it (`SceneType.build`) once it exceeds
    EXACT_RESIDUAL. `text` states it in the user's words.
    """

    text: str
    residual: Callable[[dict[str, float]], float]


# A dimensionless condition residual below this is rounding: 64 units in the last place of a unit-sized value.
EXACT_RESIDUAL = 64 * np.finfo(float).eps


@dataclass(frozen=True)
class SceneType:
    """A registered scene: its parameters, a builder taking API values by name and its exact condition, if any."""

    name: str
    summary: str
    params: tuple[Param, ...]
    build_fn: Callable[..., Scene] = field(repr=False)
    condition: Condition | None = None

    def build(self, precision: dict[str, float] | None = None, **values: float) -> Scene:
        """
        Build with API values (radians, metres). Every value is checked first (`Param.check`, then the scene's
        lengths against LENGTH_RATIO_MAX); unknown names, non-numbers, non-finite or out-of-range values raise
        ParameterError naming the parameter and the rule.

        Where the scene has an exact `condition` and values are given with a `precision` (API units by name, as
        typed: `build_from_user`), the nearest values that meet the condition are built, moving only those values
        (not defaults, integers or presets), and `Scene.adjustments` lists every value that moved. A condition that no
        values within their precision meet raises AssemblyError naming the distance.
        """
        known = {p.name: p for p in self.params}
        for key in values:
            if key not in known:
                raise ParameterError(
                    f"unknown parameter {key!r} for scene {self.name!r}; parameters are {', '.join(known)}"
                )
        full = {p.name: p.to_api(p.default) for p in self.params} | values
        full = {key: known[key].check(value) for key, value in full.items()}
        for preset in (p for p in self.params if p.replaces):
            # A value equal to its default is what the default preset has (case 10's geometry for bricard-plane):
            # listing every parameter with its default, as a generic caller may, conflicts with nothing. Any other
            # preset replaces every parameter it lists, so naming one of them beside it is refused, default or not.
            explicit = [name for name in preset.replaces if name in values]
            given = [name for name in explicit if full[name] != known[name].to_api(known[name].default)]
            default_preset = full[preset.name] == known[preset.name].to_api(known[preset.name].default)
            if given and preset.name not in values:
                full[preset.name] = 0.0  # the user's values, not the default preset's
            elif full[preset.name] != 0.0 and (given or (explicit and not default_preset)):
                given = given or explicit
                raise ParameterError(
                    f"{given[0]} is given with {preset.name} = {full[preset.name]:g}, whose preset replaces it; give "
                    f"{preset.name} = 0 to use {', '.join(given)}, or leave {given[0]} out"
                )
        lengths = {k: abs(v) for k, v in full.items() if known[k].unit == "m" and v != 0.0}
        if len(lengths) > 1:
            small, large = min(lengths, key=lengths.get), max(lengths, key=lengths.get)
            if lengths[large] > LENGTH_RATIO_MAX * lengths[small]:
                raise ParameterError(
                    f"{large} = {lengths[large]:g} m is more than {LENGTH_RATIO_MAX:g} times {small} = "
                    f"{lengths[small]:g} m; a scene's lengths must lie within a factor {LENGTH_RATIO_MAX:g}"
                )
        if self.condition is None:
            return self._build(tuple(sorted(full.items())))
        return self._build_exact(full, {name: value for name, value in (precision or {}).items() if name in values})

    def _build_exact(self, full: dict[str, float], precision: dict[str, float]) -> Scene:
        """Build at the values nearest `full` that meet the condition, moving only the values given with a
        precision (module docstring of `precision`); without one, as given (the kinematics refuse what they must)."""
        known = {p.name: p for p in self.params}
        names = list(full)
        given = np.array([full[n] for n in names])
        scale = np.array([0.0 if known[n].integer or known[n].replaces else precision.get(n, 0.0) for n in names])

        def residual(p: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.array([self.condition.residual(dict(zip(names, p, strict=True)))])

        if not scale.any() or abs(residual(given)[0]) <= EXACT_RESIDUAL:
            return self._build(tuple(sorted(full.items())))
        nearest = nearest_exact(residual, given, scale, EXACT_RESIDUAL)
        moved = [
            Adjustment(n, known[n].to_user(g), known[n].to_user(v), known[n].to_user(s), known[n].unit)
            for n, g, v, s in zip(names, given, nearest.values, scale, strict=True)
            if v != g
        ]
        if nearest.residual > EXACT_RESIDUAL or nearest.ratio > 1.0:
            worst = max(moved, key=lambda a: a.ratio, default=None)
            where = f"; the nearest values that meet it move {worst.text()}" if worst is not None else ""
            raise AssemblyError(
                f"{self.name}: {self.condition.text} is not met within the precision the values were given with"
                f"{where}: give values that meet it, or more of their digits"
            )
        for adjustment in moved:
            known[adjustment.name].check(known[adjustment.name].to_api(adjustment.value))
        scene = self._build(tuple(sorted(zip(names, nearest.values, strict=True))))
        return replace(scene, adjustments=tuple(moved))

    @functools.lru_cache(maxsize=64)  # noqa: B019  (scenes are immutable; the registry lives as long as the process)
    def _build(self, values: tuple[tuple[str, float], ...]) -> Scene:
        """One built scene per set of parameter values (building traces some closed forms' paths)."""
        return self.build_fn(**dict(values))

    def build_from_user(self, values: dict[str, float]) -> Scene:
        """
        Build from command-line values (degrees, metres); checked as `build` checks them. A `precision.Typed` value
        carries the precision it was printed with, which an exact condition is held to.
        """
        known = {p.name: p for p in self.params}
        precision = {k: known[k].to_api(v.precision) for k, v in values.items() if isinstance(v, Typed) and k in known}
        api = {}
        for key, value in values.items():
            if key not in known:
                raise ParameterError(
                    f"unknown parameter {key!r} for scene {self.name!r}; parameters are {', '.join(known)}"
                )
            number = isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool)
            api[key] = known[key].to_api(value) if number else value  # `build` names what is not a number
        return self.build(precision=precision, **api)


REGISTRY: dict[str, SceneType] = {}


def choice(name: str, value: float, options: tuple[str, ...]) -> str:
    """The option a numbered scene parameter picks (1-based, as given on the command line); ParameterError otherwise."""
    if value != int(value) or not 1 <= value <= len(options):
        raise ParameterError(
            f"{name} = {value:g}; it must be a whole number from 1 to {len(options)} ({', '.join(options)})"
        )
    return options[int(value) - 1]


def register(name: str, summary: str, params: tuple[Param, ...], condition: Condition | None = None):
    """Decorator: add a scene builder to the registry under `name`, with its parameters' exact condition if any."""

    def wrap(fn: Callable[..., Scene]) -> Callable[..., Scene]:
        REGISTRY[name] = SceneType(name, summary, params, fn, condition)
        return fn

    return wrap


def get(name: str) -> SceneType:
    """The registered scene `name`; ParameterError listing the names otherwise."""
    if name not in REGISTRY:
        raise ParameterError(f"unknown scene {name!r}; scenes are {', '.join(sorted(REGISTRY))}")
    return REGISTRY[name]


def names() -> tuple[str, ...]:
    """Every registered scene name, sorted."""
    return tuple(sorted(REGISTRY))
