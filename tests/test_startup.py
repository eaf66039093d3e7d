"""Starting the command: `python -m sim_origami`, and Ctrl-C while its modules import (a 10-22-line traceback
before)."""

import signal
import subprocess
import sys
import time
from pathlib import Path

SIM_ORIGAMI = str(Path(sys.executable).parent / "sim-origami")


def test_python_dash_m_runs_the_command():
    done = subprocess.run([sys.executable, "-m", "sim_origami", "list"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "bennett" in done.stdout, done.stderr


def test_ctrl_c_while_starting_is_one_line_and_130():
    """SIGINT 0.2-0.5 s after start lands while MuJoCo and the command's modules import (about 1 s here): one line,
    status 130. A machine that imports faster finishes `list` first (status 0), which is no traceback either."""
    outcomes = []
    for delay in (0.2, 0.3, 0.5):
        process = subprocess.Popen([SIM_ORIGAMI, "list"], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                   text=True)  # fmt: skip
        time.sleep(delay)
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=120)
        assert "Traceback" not in err and len(err.splitlines()) <= 1, err
        outcomes.append((process.returncode, err.strip()))
    assert all(code in (0, 130) for code, _ in outcomes), outcomes
    assert (130, "sim-origami: interrupted while starting") in outcomes or all(c == 0 for c, _ in outcomes)
