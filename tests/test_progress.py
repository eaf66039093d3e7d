"""At a terminal a validation names the phase it is in (single-scene runs printed nothing for 30-40 s); piped, its
output stays clean."""

import fcntl
import os
import pty
import struct
import subprocess
import sys
import termios
from pathlib import Path

import pytest

SIM_ORIGAMI = str(Path(sys.executable).parent / "sim-origami")


def _stderr_at_a_terminal(argv: list[str]) -> tuple[int, str]:
    """Run argv with stderr on a pseudo-terminal of 200 columns; its exit status and what it wrote there."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 50, 200, 0, 0))  # a new pty is 0 x 0: no bar fits
    process = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=slave)
    os.close(slave)
    chunks = []
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # EIO: the terminal's last writer closed it
            break
        if not chunk:
            break
        chunks.append(chunk)
    os.close(master)
    return process.wait(timeout=600), b"".join(chunks).decode(errors="replace")


@pytest.mark.slow
def test_a_single_scene_names_its_phases_at_a_terminal(tmp_path):
    code, err = _stderr_at_a_terminal([SIM_ORIGAMI, "validate", "bennett", "--out", str(tmp_path / "b")])
    assert code == 0
    for phase in ("closed form vs numeric loop closure, bennett", "MuJoCo fast and its projection, bennett",
                  "bifurcation study"):
        assert phase in err, err[-2000:]
    piped = subprocess.run([SIM_ORIGAMI, "validate", "bennett", "--out", str(tmp_path / "p")], capture_output=True,
                           text=True, timeout=600)
    assert piped.returncode == 0 and piped.stderr == ""
