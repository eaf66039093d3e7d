"""What leaving things out of a model saves, measured in one run: CPU time of the same driven sweep with one
feature put back at a time (contact detection, gravity, island discovery, render assets, sensors, redundant closure
rows), on scenes with couplings the closures they imply taken out (`without_implied_closures`), and the cost of
rendering every N steps. Best of REPEATS; ratios to the pruned model as generated.

    python scripts/pruning.py [scene ...]      (default: vertex4 miura-sheet)
"""

import dataclasses
import sys
import time

# isort: off
import sim_origami  # noqa: F401  (chooses MUJOCO_GL before MuJoCo is imported: rendering below)
import mujoco

# isort: on
import numpy as np

from sim_origami import scenes
from sim_origami.mjcf import ModelOptions, drive_name
from sim_origami.presets import FAST
from sim_origami.scenes.base import without_implied_closures
from sim_origami.simulate import Bindings, compile_model, ramp, scene_xml, start_pose

REPEATS = 3


def stepping_cpu(model: mujoco.MjModel, scene, branch: str, steps: int, render_every: int = 0) -> float:
    """CPU time of `steps` driven steps (the harness's drive), optionally rendering every `render_every` steps. The
    variants' joints are the generated model's (`compile_model`): its qpos map serves them all."""
    data = mujoco.MjData(model)
    binds = Bindings(compile_model(scene))
    start, stop = scene.branch_path(branch)
    binds.set_pose(data, start_pose(scene, branch, start))
    mujoco.mj_forward(model, data)
    targets = start + (stop - start) * ramp(np.linspace(0, 1, steps))[0]
    setpoint = model.eq_data[model.equality(drive_name(scene.drive_joint)).id]  # a variant's own equality ids
    renderer = mujoco.Renderer(model, 240, 320) if render_every else None
    t = time.thread_time()
    for k, value in enumerate(targets.tolist()):
        setpoint[0] = value
        mujoco.mj_step(model, data)
        if renderer and k % render_every == 0:
            renderer.update_scene(data)
            renderer.render()
    cpu = time.thread_time() - t
    if renderer:
        renderer.close()
    return cpu


def variants(scene) -> dict[str, mujoco.MjModel]:
    """The generated (pruned) model and one variant per feature put back."""

    def compile_(xml: str) -> mujoco.MjModel:
        return mujoco.MjModel.from_xml_string(xml)

    base = scene_xml(scene, ModelOptions())
    out = {"as generated": compile_(base)}
    contact = scene if (scene.contact_pairs or scene.self_contact) else None
    if contact is not None:
        out["+ contact detection"] = compile_(scene_xml(scene, ModelOptions(contact=True)))
    gravity = compile_(base)
    gravity.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_GRAVITY)
    out["+ gravity"] = gravity
    islands = compile_(base)  # every model is one mechanism: one island, found again at every step
    islands.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_ISLAND)
    out["+ island discovery"] = islands
    out["+ render assets (lights, sky)"] = compile_(scene_xml(scene, ModelOptions(render=True)))
    sensors = base.replace(
        "</mujoco>",
        "<sensor>"
        + "".join(
            f'<jointpos joint="{j.name}"/><jointvel joint="{j.name}"/>'
            for j in scene.mechanism.joints
            if j.name not in {scene.mechanism.joints[i].name for i in scene.mechanism.cut_joints}
        )
        + "</sensor></mujoco>",
    )
    sensed = compile_(sensors)
    sensed.opt.disableflags &= ~int(mujoco.mjtDisableBit.mjDSBL_SENSOR)
    out["+ sensors (pos, vel of every hinge)"] = sensed
    redundant = dataclasses.replace(
        scene.mechanism,
        joints=tuple(
            dataclasses.replace(j, anchors=(*j.anchors, 0.25 * j.anchors[-1])) for j in scene.mechanism.joints
        ),
    )
    out["+ a third connect per cut crease"] = compile_(
        scene_xml(dataclasses.replace(scene, mechanism=redundant), ModelOptions())
    )
    if scene.mechanism.couplings:
        out["- closures the couplings imply"] = compile_(scene_xml(without_implied_closures(scene), ModelOptions()))
    return out


def main(names: list[str]) -> None:
    for name in names or ["vertex4", "miura-sheet"]:
        scene = scenes.get(name).build()
        branch = scene.kinematics.branches()[0].name
        models = variants(scene)
        steps = round(FAST.sweep_duration / models["as generated"].opt.timestep)
        base = min(stepping_cpu(models["as generated"], scene, branch, steps) for _ in range(REPEATS))
        print(f"\n{name} ({branch}, {steps} fast steps): as generated {base * 1e3:.1f} ms")
        print(f"| {'model':40s} | CPU (ms) | ratio |")
        for label, model in models.items():
            cpu = min(stepping_cpu(model, scene, branch, steps) for _ in range(REPEATS))
            print(f"| {label:40s} | {cpu * 1e3:8.1f} | {cpu / base:5.2f} |")
        for every in (1, 10, 100):
            cpu = stepping_cpu(models["+ render assets (lights, sky)"], scene, branch, steps, render_every=every)
            print(f"| {f'render 320x240 every {every} steps':40s} | {cpu * 1e3:8.1f} | {cpu / base:5.2f} |")


if __name__ == "__main__":
    main(sys.argv[1:])
