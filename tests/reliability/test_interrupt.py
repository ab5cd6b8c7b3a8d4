"""Ctrl-C (issue 36): one line saying what was left as it was, exit 130, nothing half-written."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

from tests.conftest import MARM_URDF


def test_ctrl_c_is_one_line_and_exit_130(tmp_path):
    out = tmp_path / "m.srdf"
    args = [
        sys.executable,
        "-m",
        "marm_setup.cli.app",
        "collisions",
        str(MARM_URDF),
        "--trials",
        "50M",
        "--yes",
    ]
    child = subprocess.Popen(
        [*args, "--output", str(out)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    try:
        time.sleep(4)  # imports done, sampling under way
        child.send_signal(signal.SIGINT)
        _stdout, stderr = child.communicate(timeout=60)
    finally:
        child.kill()
    lines = stderr.strip().splitlines()
    assert child.returncode == 130, stderr
    errors = [line for line in lines if line.startswith("error: ")]  # besides the time estimate
    assert errors == lines[-1:] and lines[-1].startswith("error: interrupted (Ctrl-C)"), stderr
    assert "nothing half-written" in lines[-1] and "Traceback" not in stderr and not out.exists()
    assert not list(tmp_path.iterdir())  # no temporary file left beside it
