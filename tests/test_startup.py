"""Starting the command: `python -m sim_origami`, Ctrl-C while its modules import (a 10-22-line traceback before),
and a machine without libEGL (every command, even --version, was a traceback)."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

SIM_ORIGAMI = str(Path(sys.executable).parent / "sim-origami")


@pytest.mark.slow
def test_python_dash_m_runs_the_command():
    done = subprocess.run([sys.executable, "-m", "sim_origami", "list"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "bennett" in done.stdout, done.stderr


@pytest.mark.slow
def test_ctrl_c_while_starting_is_one_line_and_130():
    """SIGINT 0.5-0.9 s after start lands while MuJoCo and the command's modules import (about 1 s here, more on a
    busy machine): one line, status 130. A machine that imports faster finishes `list` first (status 0), which is no
    traceback either. The package's own first lines (about 50 ms: choosing the GL backend) are not guarded: a
    library import must leave SIGINT alone."""
    outcomes = []
    for delay in (0.5, 0.7, 0.9):
        process = subprocess.Popen([SIM_ORIGAMI, "list"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                   text=True)
        time.sleep(delay)
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=120)
        assert "Traceback" not in err and len(err.splitlines()) <= 1, err
        outcomes.append((process.returncode, err.strip()))
    assert all(code in (0, 130) for code, _ in outcomes), outcomes
    assert (130, "sim-origami: interrupted while starting") in outcomes or all(c == 0 for c, _ in outcomes)


def _without_egl(command: str) -> subprocess.CompletedProcess:
    """`command` in a mount namespace where every libEGL file reads as empty (as on a machine without the library
    that still lists it in the linker cache)."""
    hide = "; ".join(f"mount --bind /dev/null {p}" for p in Path("/usr/lib").rglob("libEGL.so*") if not p.is_symlink())
    env = {k: v for k, v in os.environ.items() if k != "MUJOCO_GL"}  # this process's choice is not the machine's
    return subprocess.run(["unshare", "-m", "bash", "-c", f"{hide}; {command}"], capture_output=True, text=True,
                          timeout=300, env=env)


@pytest.mark.slow
def test_without_egl_commands_that_do_not_render_run_and_render_is_refused_in_one_line(tmp_path):
    probe = _without_egl("true")
    if probe.returncode != 0 or not list(Path("/usr/lib").rglob("libEGL.so*")):
        pytest.skip(f"needs libEGL and unshare -m (root): {probe.stderr.strip()[:100]}")
    version = _without_egl(f"{SIM_ORIGAMI} --version")
    assert version.returncode == 0 and "MUJOCO_GL=disable" in version.stdout, version.stderr
    listed = _without_egl(f"{SIM_ORIGAMI} list")
    assert listed.returncode == 0 and "bennett" in listed.stdout, listed.stderr
    out = tmp_path / "out"
    render = _without_egl(f"{SIM_ORIGAMI} validate bennett --render --out {out}")
    assert render.returncode == 2 and render.stderr.count("\n") == 1, render.stderr
    assert "install Debian's libegl1 libgl1-mesa-dri" in render.stderr and not out.exists()
