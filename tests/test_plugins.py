"""Scenes from outside the package: `custom_scene`, the entry point group `sim_origami.scenes`, and the worked example
docs/examples/user_package (a planar four-bar with its own closed form and reference curves from Freudenstein's
equation).

The example is made importable the way an installed package is: its source folder on the path and a
`*.dist-info` folder holding the entry point copied from its pyproject.toml, so no network or build is needed.
"""

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from sim_origami import scenes
from sim_origami.cli import main
from sim_origami.errors import ParameterError, SimOrigamiError
from sim_origami.kinematics.bennett import Bennett
from sim_origami.linkage import dh_mechanism
from sim_origami.scenes import plugins
from sim_origami.scenes.base import REGISTRY

EXAMPLE = Path(__file__).resolve().parents[1] / "docs" / "examples" / "user_package"
EXE = Path(sys.executable).parent / "sim-origami"


def distribution(folder: Path, name: str, entry_points: str) -> Path:
    """A minimal installed distribution (METADATA + entry_points.txt) in `folder`, as pip would leave it."""
    info = folder / f"{name}-0.1.0.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: 0.1.0\n")
    (info / "entry_points.txt").write_text(f"[sim_origami.scenes]\n{entry_points}\n")
    return folder


def example_env(tmp_path: Path, extra: str = "") -> dict[str, str]:
    """Environment in which the example package (and `extra` entry points) is installed."""
    pyproject = (EXAMPLE / "pyproject.toml").read_text()
    name, value = re.search(r'\[project\.entry-points\."sim_origami\.scenes"\]\n(\S+) = "(.+)"\n', pyproject).groups()
    site = distribution(tmp_path / "site", "sim_origami_fourbar", f"{name} = {value}")
    if extra:  # a distribution of its own: one name is one distribution (an editable install may already hold it)
        distribution(site, "other_plugins", extra)
    path = os.pathsep.join([str(EXAMPLE / "src"), str(site), str(tmp_path / "mods")])
    return os.environ | {"PYTHONPATH": path}


def cli(env, *argv, cwd) -> subprocess.CompletedProcess:
    return subprocess.run([str(EXE), *argv], capture_output=True, text=True, env=env, cwd=cwd)


@pytest.fixture
def registry():
    """Restore the registry and the plugin state after a test that loads plugins in this process."""
    scenes.load_builtins()  # registered on first use: kept in the saved registry
    saved, failed, loaded = dict(REGISTRY), list(plugins.FAILED), plugins._loaded
    yield
    REGISTRY.clear()
    REGISTRY.update(saved)
    plugins.FAILED[:] = failed
    plugins._loaded = loaded


def test_custom_scene_fills_the_drive_from_the_closed_form():
    kin = Bennett(1.0, np.deg2rad(30.0), 1.5, np.arcsin(0.75))
    scene = scenes.custom_scene("my-bennett", kin, dh_mechanism(kin.rows), path=(0.6, 2.4))
    assert scene.loop_joints == ("joint_1", "joint_2", "joint_3", "joint_4")
    assert (scene.drive_joint, scene.drive_scale) == ("joint_1", 1.0)


class Broken(Bennett):
    """A Bennett whose closed form breaks one rule of the contract, chosen by `rule`."""

    def __init__(self, rule: str):
        super().__init__(1.0, np.deg2rad(30.0), 1.5, np.arcsin(0.75))
        self.rule = rule
        if rule == "names":
            self.joint_names = ("theta1", "theta1", "theta3", "theta4")

    def evaluate(self, branch, x):
        values, valid = super().evaluate(branch, x)
        if self.rule == "shape":
            return values[:, :3], valid
        if self.rule == "nan":
            values[0, 1] = np.nan
        if self.rule == "observe":
            values[:, 1] += 0.1 * values[:, 0]  # outputs that are not the loop joints JointSpaceKinematics says
            return values, valid
        return values, valid

    def observe(self, q_loop):
        out = super().observe(q_loop)
        return out + 1e-6 if self.rule == "observe" else out


@pytest.mark.parametrize(
    ("rule", "needle"),
    [("names", "names a joint twice"), ("shape", "returned shapes (7, 3)"), ("nan", "not finite inside its domain"),
     ("observe", "observe(loop_angles(v)) differs from v")],
)
def test_custom_scene_refuses_a_closed_form_that_breaks_the_contract(rule, needle):
    kin = Broken(rule)
    with pytest.raises(ParameterError) as err:
        scenes.custom_scene("broken", kin, dh_mechanism(kin.rows))
    assert needle in str(err.value)


def test_custom_scene_refuses_a_mechanism_that_does_not_fit():
    kin = Bennett(1.0, np.deg2rad(30.0), 1.5, np.arcsin(0.75))
    with pytest.raises(ParameterError, match="loop_joints joint_9 are not joints of the mechanism"):
        scenes.custom_scene("b", kin, dh_mechanism(kin.rows), loop_joints=("joint_1", "joint_2", "joint_3", "joint_9"))


def test_plugins_load_and_broken_ones_are_left_out_with_one_line(tmp_path, monkeypatch, capsys, registry):
    mods = tmp_path / "mods"
    mods.mkdir()
    (mods / "good_plugin.py").write_text(textwrap.dedent("""
        from sim_origami.kinematics.bennett import Bennett
        from sim_origami.linkage import dh_mechanism
        from sim_origami.scenes import Param, custom_scene, register

        @register("plugin-bennett", "a Bennett from a plugin", (Param("a", "m", 1.0, "link a"),))
        def build(a):
            kin = Bennett(a, 0.5235987755982988, 1.5 * a, 0.848062078981481)
            return custom_scene("plugin-bennett", kin, dh_mechanism(kin.rows), path=(0.6, 2.4))

        def register_late():
            register("plugin-late", "registered by a callable", ())(build)

        @register("plugin-buggy", "a builder with a bug", ())
        def buggy():
            return {}["no such key"]
        """))
    (mods / "clobber_plugin.py").write_text(
        "from sim_origami.scenes import register\nregister('miura', 'not the Miura vertex', ())(lambda: None)\n"
    )
    (mods / "raising_plugin.py").write_text("raise RuntimeError('boom\\non two lines')\n")
    site = distribution(tmp_path / "site", "plugins_under_test", "\n".join([
        "good = good_plugin", "late = good_plugin:register_late", "clobber = clobber_plugin",
        "missing = no_such_module_xyz", "raising = raising_plugin"]))
    monkeypatch.syspath_prepend(str(mods))
    monkeypatch.syspath_prepend(str(site))
    miura = REGISTRY["miura"]
    added = plugins.load_plugins(force=True)
    assert set(added) == {"plugin-bennett", "plugin-late", "plugin-buggy"}
    assert REGISTRY["miura"] is miura and "bennett" in scenes.names()
    err = capsys.readouterr().err.splitlines()
    assert len(err) == 3, err
    assert any("'clobber'" in e and "miura, which is already registered" in e for e in err)
    assert any("'missing'" in e and "ModuleNotFoundError" in e for e in err)
    assert any("'raising'" in e and "RuntimeError: boom on two lines" in e for e in err)
    scene = scenes.get("plugin-bennett").build_from_user({"a": 2.0})
    assert scene.kinematics.a == 2.0 and scene.drive_joint == "joint_1"
    with pytest.raises(SimOrigamiError, match=r"scene 'plugin-buggy' of plugin 'good' \(good_plugin\) failed to build: "
                       "KeyError: 'no such key'"):
        scenes.get("plugin-buggy").build()
    assert main(["describe", "plugin-buggy"]) == 2 and capsys.readouterr().err.count("\n") == 1


@pytest.mark.slow
def test_example_package_lists_and_validates_with_its_reference(tmp_path, monkeypatch, capsys, registry):
    env = example_env(tmp_path)
    for folder in env["PYTHONPATH"].split(os.pathsep):
        monkeypatch.syspath_prepend(folder)
    assert plugins.load_plugins(force=True) == ("four-bar",)
    assert main(["list"]) == 0
    listed = capsys.readouterr()
    assert re.search(r"^four-bar\s+planar four-bar", listed.out, re.M) and "bennett" in listed.out
    assert not listed.err
    good = ["validate", "four-bar", "--reference", str(EXAMPLE / "four_bar_curves.csv"), "--out", "good"]
    assert main(good) == 0, capsys.readouterr()
    assert "ok   reference curves vs numeric loop closure: samples over tolerance: 0" in capsys.readouterr().out
    bad = ["validate", "four-bar", "--branch", "elbow-cw", "--reference",
           str(EXAMPLE / "four_bar_curves_misprinted.csv"), "--out", "bad"]
    assert main(bad) == 1
    printed = capsys.readouterr().out
    assert "FAIL reference curves vs numeric loop closure: samples over tolerance: 29" in printed
    assert "theta4 at theta1 = -140 deg (line 3, branch elbow-cw)" in printed


@pytest.mark.slow
def test_installed_script_lists_plugins_and_survives_a_broken_one(tmp_path):
    (tmp_path / "mods").mkdir()
    (tmp_path / "mods" / "bad_syntax.py").write_text("def broken(:\n")
    env = example_env(tmp_path, extra="oops = bad_syntax")
    listed = cli(env, "list", cwd=tmp_path)
    assert listed.returncode == 0 and "four-bar" in listed.stdout and "miura" in listed.stdout
    assert listed.stderr.count("\n") == 1 and "scene plugin 'oops' (bad_syntax) left out: SyntaxError" in listed.stderr
    assert "Traceback" not in listed.stderr
