"""`marm-setup init ... | head -1`: the reader leaves after one line, the command still does its work."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import MARM_URDF

SCRIPT = Path(sys.executable).parent / "marm-setup"


@pytest.mark.skipif(not SCRIPT.exists(), reason="needs the installed console script")
def test_init_into_a_pipe_closed_after_one_line(tmp_path):
    out = tmp_path / "pkg"
    argv = [str(SCRIPT), "init", str(MARM_URDF), "--out", str(out), "--trials", "100"]
    with subprocess.Popen(argv, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as proc:
        assert proc.stdout is not None and proc.stderr is not None
        assert proc.stdout.readline().startswith("setup for robot marm")
        proc.stdout.close()  # as `head -1` does: every later print meets a closed pipe
        stderr = proc.stderr.read()
        code = proc.wait()
    assert (code, stderr) == (0, "")
    assert (out / "config" / "marm.srdf").is_file()
