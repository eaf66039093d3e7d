"""Closure and energy drift over a long free run: the IFToMM A04 Bricard linkage released at rest under gravity
for a million steps of a preset (fast: 8 ms, so 8000 s of simulated time). Prints the closure gap (paired closure
sites) and the energy drift at every decade of steps, and the stepping rate.

    python scripts/long_run.py [steps] [preset]
"""

import sys
import time

import mujoco
import numpy as np

from sim_origami import scenes
from sim_origami.mjcf import ModelOptions
from sim_origami.presets import FAST, Preset, as_preset
from sim_origami.simulate import Bindings, captured_warnings, compile_model, start_pose


def main(steps: int = 1_000_000, preset: Preset = FAST) -> None:
    scene = scenes.get("iftomm-a04").build()
    compiled = compile_model(scene, ModelOptions(preset=preset, drive="none", gravity=True))
    model, data = compiled.fresh()
    binds = Bindings(compiled)
    binds.set_pose(data, start_pose(scene, scene.free_branch, scene.free_start))
    mujoco.mj_forward(model, data)
    e0 = data.energy[0] + data.energy[1]
    sites = binds.site_pairs.ravel()
    print(f"{steps} steps of {model.opt.timestep * 1e3:g} ms ({steps * model.opt.timestep:g} s), E0 = {e0:.6g} J")
    print(f"{'steps':>9s} {'closure gap (m)':>16s} {'max energy drift (J)':>21s} {'steps/s':>10s}")
    done, drift, cpu = 0, 0.0, 0.0
    with captured_warnings() as messages:
        for decade in (10**k for k in range(2, int(np.log10(steps)) + 1)):
            t = time.thread_time()
            while done < decade:
                mujoco.mj_step(model, data)
                drift = max(drift, abs(data.energy[0] + data.energy[1] - e0))
                done += 1
            cpu += time.thread_time() - t
            if messages or not np.all(np.isfinite(data.qpos)):
                raise SystemExit(f"diverged after {done} steps: {messages[:1]}")
            mujoco.mj_kinematics(model, data)
            xpos = data.site_xpos[sites]
            gap = float(np.max(np.linalg.norm(xpos[0::2] - xpos[1::2], axis=-1)))
            print(f"{done:9d} {gap:16.3e} {drift:21.3e} {done / cpu:10.3g}")


if __name__ == "__main__":
    main(*(int(v) if k == 0 else as_preset(v) for k, v in enumerate(sys.argv[1:3])))
