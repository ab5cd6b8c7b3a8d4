"""Progress on long work: a rich bar on stderr when it is a terminal (a real pseudo-terminal
here), nothing in a pipe and nothing with --format json."""

from __future__ import annotations

import json
import os
import pty
import subprocess
import sys
from pathlib import Path

import pytest

from tests.conftest import MARM_URDF
from tests.validate_helpers import generate_marm

SCRIPT = [sys.executable, "-m", "marm_setup"]


def _run_on_terminal(*args: str | Path) -> tuple[subprocess.CompletedProcess[str], str]:
    """`marm-setup args` with stderr on a pseudo-terminal (stdout a pipe): (result, what the
    terminal received)."""
    master, slave = pty.openpty()
    env = {**os.environ, "COLUMNS": "120", "TERM": "xterm"}
    proc = subprocess.Popen(
        [*SCRIPT, *map(str, args)], stdout=subprocess.PIPE, stderr=slave, text=True, env=env
    )
    os.close(slave)
    seen = bytearray()
    while True:
        try:
            chunk = os.read(master, 65536)
        except OSError:  # the child closed its end
            break
        if not chunk:
            break
        seen += chunk
    stdout, _ = proc.communicate()
    os.close(master)
    return subprocess.CompletedProcess(proc.args, proc.returncode, stdout, ""), seen.decode(errors="replace")


def test_collisions_draws_a_bar_on_a_terminal_only_for_text():
    result, terminal = _run_on_terminal("collisions", MARM_URDF, "--trials", "20000", "--jobs", "1")
    assert result.returncode == 0 and "sampling" in terminal and "%" in terminal
    result, terminal = _run_on_terminal(
        "collisions", MARM_URDF, "--trials", "20000", "--jobs", "1", "--format", "json"
    )
    assert result.returncode == 0 and json.loads(result.stdout)["trials"] == 20000
    assert terminal == ""


def test_nothing_extra_in_a_pipe():
    out = subprocess.run(
        [*SCRIPT, "collisions", str(MARM_URDF), "--trials", "20000", "--jobs", "1"],
        capture_output=True,
        text=True,
    )
    assert out.returncode == 0 and out.stderr == ""


@pytest.fixture(scope="module")
def package(tmp_path_factory) -> Path:
    return generate_marm(tmp_path_factory.mktemp("progress"), "ros1")


def test_validate_shows_its_planning_on_a_terminal_never_for_json(package):
    result, terminal = _run_on_terminal("validate", package)
    assert result.returncode == 0 and "planning pose pairs" in terminal
    result, terminal = _run_on_terminal("validate", package, "--format", "json")
    assert result.returncode == 0 and json.loads(result.stdout)["errors"] == 0 and terminal == ""


def test_report_shows_each_stage_on_a_terminal(package, tmp_path):
    result, terminal = _run_on_terminal("report", package, "-o", tmp_path / "r.html")
    assert result.returncode == 0, terminal
    assert all(stage in terminal for stage in ("checking", "planning", "collision matrix"))
    out = subprocess.run(
        [*SCRIPT, "report", str(package), "-o", str(tmp_path / "p.html")], capture_output=True, text=True
    )
    assert out.returncode == 0 and out.stderr == "" and out.stdout.startswith("wrote ")


def test_the_estimate_is_a_line_of_its_own_above_a_drawn_bar():
    """A long sampling's estimate goes through the bar's console (rich prints it above the bar)
    instead of being written into the bar's line."""
    import io

    from rich.console import Console
    from rich.progress import Progress

    from marm_setup.cli.progress import SamplingProgress

    said: list[str] = []
    progress = SamplingProgress(say=said.append)
    progress._tell("without a bar")
    terminal = io.StringIO()
    bar = Progress(console=Console(file=terminal, force_terminal=True, width=60), transient=True)
    bar.start()
    progress._bar = bar
    progress._tell("sampling 1,000,000 trials: about 12 min here (from the first 2,000)")
    bar.stop()
    assert said == ["without a bar"]
    assert "sampling 1,000,000 trials: about 12 min here (from the first 2,000)\n" in terminal.getvalue()
