"""
Property-based test of the bad-input contract: random parameter sets for every registered scene (in range, at the
edges, outside: zero, negative, 180/360 deg, huge, tiny, NaN, inf, strings), through the CLI's `main(argv)` in
process (`describe`, `analytic --json`) and the API (`build_from_user`, `evaluate`).

Contract: exit 0, 1 or 2 only; on exit 2 exactly one stderr line naming a parameter it was given; never a traceback
or a warning line; no NaN or inf in any JSON; a scene built or a typed `SimOrigamiError` (ParameterError,
DomainError, AssemblyError), never another exception; `evaluate`'s validity mask equal to the domain `describe`
prints, with finite values that close the loop where valid.

Profiles: the default ("ci") runs a fixed seed and a fixed example count per scene (about a minute on 2 cores);
SIM_ORIGAMI_FUZZ=big runs 10x as many. SIM_ORIGAMI_FUZZ_MEASURE=1 records problems instead of failing and prints
the counts (runs, refusals, failures) at the end: how the before/after numbers of issue 16 were measured.
"""

import atexit
import contextlib
import io
import json
import math
import os
import signal
import warnings
from collections import Counter

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.errors import SimOrigamiError

BIG = os.environ.get("SIM_ORIGAMI_FUZZ") == "big"
MEASURE = os.environ.get("SIM_ORIGAMI_FUZZ_MEASURE") == "1"
# Scenes whose build takes seconds (traced paths, large meshes): fewer examples keep the CI run near a minute.
SLOW_SCENES = {"truncated-octahedron", "truncated-tetrahedron-i", "truncated-tetrahedron-ii", "waterbomb-tube",
               "waterbomb-twist"}
EXAMPLES = 10 if BIG else 1
settings.register_profile("fuzz", derandomize=True, deadline=None, database=None, print_blob=False,
                          suppress_health_check=list(HealthCheck))

COUNTS: Counter = Counter()
PROBLEMS: list[str] = []

# Values at and beyond the edges, as typed on the command line.
EDGE_TEXT = ("0", "-0", "-1", "1", "2", "3", "90", "180", "-180", "360", "720", "1e308", "1e400", "-1e400", "1e-300",
             "1e-9", "-1e-9", "nan", "NaN", "inf", "-inf", "Infinity", "abc", "", "1_0", "0x10", "4.5", "1e10",
             "89.999", "90.001", "45", "30", "60", "135")


def _count_examples(scene: str) -> int:
    n = 6 if scene in SLOW_SCENES else 20
    return n * EXAMPLES


@st.composite
def user_values(draw, scene: str) -> dict[str, str]:
    """A parameter set as command-line text: some defaults, some near them, some at or beyond an edge."""
    out = {}
    for p in scenes.get(scene).params:
        kind = draw(st.sampled_from(("omit", "omit", "near", "edge", "float")))
        if kind == "near":
            out[p.name] = repr(float(p.default) * draw(st.floats(0.5, 1.5)) + draw(st.sampled_from((0.0, 1.0))))
        elif kind == "edge":
            out[p.name] = draw(st.sampled_from(EDGE_TEXT))
        elif kind == "float":
            out[p.name] = repr(draw(st.floats(allow_nan=True, allow_infinity=True, width=64)))
    return out


def _problem(kind: str, where: str, detail: str) -> None:
    COUNTS["failures"] += 1
    COUNTS[f"failures:{kind}"] += 1
    PROBLEMS.append(f"{kind}: {where}: {detail}"[:400])


def _run_cli(argv: list[str]) -> tuple[int, str, str, list]:
    out, err = io.StringIO(), io.StringIO()
    with warnings.catch_warnings(record=True) as caught, contextlib.redirect_stdout(out), \
            contextlib.redirect_stderr(err):
        warnings.simplefilter("always")
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
        except _Hang:
            raise
        except BaseException as exc:
            code = -1
            err.write(f"Traceback (escaped main): {type(exc).__name__}: {exc}\n")
    return code, out.getvalue(), err.getvalue(), caught


def _reject_constant(name: str):
    raise ValueError(f"non-finite JSON constant {name}")


def _check_cli(argv: list[str], given: dict[str, str]) -> tuple[int, str]:
    """Run argv; record the contract's breaches. Returns (exit code, stdout)."""
    where = " ".join(argv)
    code, out, err, caught = _run_cli(argv)
    COUNTS["cli_runs"] += 1
    if code not in (0, 1, 2):
        _problem("exit", where, f"exit {code}: {err.strip()[-300:]}")
    if "Traceback" in err:
        _problem("traceback", where, err.strip().splitlines()[-1])
    if code == 2:
        COUNTS["cli_refusals"] += 1
        lines = err.strip().splitlines()
        if len(lines) != 1 or caught:
            _problem("lines", where, f"{len(lines)} stderr lines, {len(caught)} warnings: {err.strip()[:300]}")
        elif given and not any(name in lines[0] for name in given):
            _problem("unnamed", where, lines[0])
    if code == 0 and "--json" in argv:
        try:
            json.loads(out, parse_constant=_reject_constant)
        except ValueError as exc:
            _problem("json", where, str(exc))
    return code, out


def _to_api_value(text: str):
    """The API's view of a typed value: a float where the text is a plain number, else the text itself."""
    try:
        return float(text)
    except ValueError:
        return text


def _check_api(scene: str, given: dict[str, str]) -> None:
    kind = scenes.get(scene)
    values = {k: _to_api_value(v) for k, v in given.items()}
    where = f"{scene}.build_from_user({values})"
    COUNTS["api_builds"] += 1
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            built = kind.build_from_user(values)
    except SimOrigamiError:
        COUNTS["api_refusals"] += 1
        return
    except Exception as exc:
        _problem("untyped", where, f"{type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else ''}")
        return
    if any(isinstance(v, float) and not math.isfinite(v) for v in built.params.values()):
        _problem("nonfinite-param", where, str(built.params))
    _check_masks(built, where)


def _check_masks(built, where: str) -> None:
    """`evaluate` valid exactly on each branch's closed domain, finite there, NaN elsewhere, closing the loop."""
    kin = built.kinematics
    loops = kin.loop_system()
    for b in kin.branches():
        lo, hi = b.domain
        if not (math.isfinite(lo) and math.isfinite(hi) and lo <= hi):
            _problem("domain", where, f"{b.name} domain {b.domain}")
            continue
        step = 1e-7 * max(1.0, abs(lo), abs(hi))
        x = np.array([lo, hi, 0.5 * (lo + hi), lo + 0.25 * (hi - lo), lo - step, hi + step, -1e10, 1e10])
        expect = (x >= lo) & (x <= hi)
        COUNTS["api_evaluations"] += 1
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                values, valid = kin.evaluate(b.name, x)
                residual = loops.residual_norm(kin.loop_angles(np.where(valid[:, None], values, 0.0)))
        except Exception as exc:
            _problem("evaluate-raised", where, f"{b.name}: {type(exc).__name__}: {exc}")
            continue
        if not np.array_equal(np.asarray(valid, bool), expect):
            _problem("mask", where, f"{b.name} domain [{lo!r}, {hi!r}] at {x.tolist()}: valid {valid.tolist()}")
        elif not (np.all(np.isfinite(values[valid])) and np.all(np.isnan(values[~valid]))):
            _problem("values", where, f"{b.name}: non-finite inside or finite outside the domain")
        else:
            # Inside, the closed form closes its loop to rounding; at a domain end (a lock or turning point) the
            # roots' discriminant vanishes and 1e-16 of rounding becomes sqrt(1e-16) = 1e-8 (measured 7.8e-8 on
            # kokotsakis case 2 at its ends).
            scale = max(1.0, _length_scale(built))
            bound = np.where(np.isin(x, (lo, hi)), 1e-6, 1e-9) * scale
            if np.any(residual[valid] > bound[valid]):
                _problem("residual", where, f"{b.name}: closed form misses its loop by {np.max(residual[valid]):.3g}")


def _length_scale(built) -> float:
    scale = getattr(built, "length_scale", None)
    if scale is not None:
        return float(scale)
    return max([abs(v) for k, v in built.params.items() if k not in ("case", "scheme", "modes")] + [1.0])


def _argv_params(given: dict[str, str]) -> list[str]:
    return [f"--param={k}={v}" for k, v in given.items()]


class _Hang(BaseException):
    """An example still running after HANG_S seconds (measuring only: a hang is counted, not waited for)."""


HANG_S = 60


def _on_alarm(signum, frame):
    raise _Hang()


def _fuzz_one(scene: str, given: dict[str, str]) -> None:
    COUNTS["examples"] += 1
    before = len(PROBLEMS)
    if MEASURE:
        signal.signal(signal.SIGALRM, _on_alarm)
        signal.alarm(HANG_S)
        try:
            _fuzz_checks(scene, given)
        except _Hang:
            _problem("hang", scene, f"{given} still running after {HANG_S} s")
        finally:
            signal.alarm(0)
    else:
        _fuzz_checks(scene, given)
    if len(PROBLEMS) > before and not MEASURE:
        pytest.fail("\n".join(PROBLEMS[before:]))


def _fuzz_checks(scene: str, given: dict[str, str]) -> None:
    code, _ = _check_cli(["describe", scene, *_argv_params(given)], given)
    if code == 0:
        kin = scenes.get(scene).build_from_user({k: float(v) for k, v in given.items()}).kinematics
        degrees = [v for b in kin.branches() for v in np.rad2deg(b.domain)] + [0.0, -1e6]
        _check_cli(["analytic", scene, *_argv_params(given), "--input=" + ",".join(f"{d:.6f}" for d in degrees),
                    "--json"], given)
    _check_api(scene, given)


@pytest.mark.slow
@pytest.mark.parametrize("scene", scenes.names())
def test_fuzz_scene(scene):
    @settings(settings.get_profile("fuzz"), max_examples=_count_examples(scene))
    @given(user_values(scene))
    def run(given):
        _fuzz_one(scene, given)

    run()


def _report() -> None:
    if MEASURE and COUNTS:
        kinds = {k: v for k, v in sorted(COUNTS.items()) if k.startswith("failures:")}
        print(f"\nfuzz counts: examples {COUNTS['examples']}, CLI runs {COUNTS['cli_runs']} "
              f"(refusals {COUNTS['cli_refusals']}), API builds {COUNTS['api_builds']} "
              f"(refusals {COUNTS['api_refusals']}), evaluations {COUNTS['api_evaluations']}, "
              f"failures {COUNTS['failures']} {kinds}")
        path = os.environ.get("SIM_ORIGAMI_FUZZ_PROBLEMS")
        if path:
            with open(path, "w") as fh:
                fh.write("\n".join(PROBLEMS) + "\n")


atexit.register(_report)
