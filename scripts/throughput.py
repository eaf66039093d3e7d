"""Closed-form throughput of every model: configurations per second of `kinematics.evaluate` (issue 7: >= 1e6).

Each branch of each registered scene at its default parameters, inputs evenly along its default sweep, CPU of
this thread, best of REPEATS after one untimed call:

* "one call": one call on 1e6 inputs, whose result (1e6 x joints float64: 2 GB for the 258 creases of the 6 x 5
  tube) the operating system must first provide;
* "in calls of 1e4": the same 1e6 inputs evaluated 1e4 at a time (each result a few MB, reused by the allocator).

    python scripts/throughput.py [scene ...]

Measured (the 2-core machine, 58 branches of 28 scenes; the table and the memory behind the gap are in
docs/performance.md, "Closed-form throughput"): in calls of 1e4, 1.5e6 (tube) to 7.5e7/s; in one call, 1.0e6
(tube) to 5.0e7/s.
"""

import sys
import time

import numpy as np

from sim_origami import scenes

N = 1_000_000
CHUNK = 10_000
REPEATS = 3


def best_rate(evaluate, x: np.ndarray, chunk: int) -> float:
    """Configurations per second of evaluate over x in calls of `chunk` inputs, best of REPEATS after one warm-up."""
    parts = [x[i : i + chunk] for i in range(0, len(x), chunk)]
    evaluate(parts[0])
    best = np.inf
    for _ in range(REPEATS):
        t = time.thread_time()
        for part in parts:
            evaluate(part)
        best = min(best, time.thread_time() - t)
    return len(x) / best


def main(names: list[str]) -> None:
    print(f"| scene | branch | joints | one call (1/s) | in calls of {CHUNK:g} (1/s) |")
    print("|---|---|---|---|---|")
    for name in names or scenes.names():
        scene = scenes.get(name).build()
        for branch in scene.kinematics.branches():
            x = np.linspace(*scene.branch_path(branch.name), N)

            def evaluate(inputs, model=scene.kinematics, branch=branch.name):
                return model.evaluate(branch, inputs)

            joints = evaluate(x[:2])[0].shape[1]
            print(f"| {name} | {branch.name} | {joints} | {best_rate(evaluate, x, N):.2e} | "
                  f"{best_rate(evaluate, x, CHUNK):.2e} |", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:])
