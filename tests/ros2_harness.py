"""The ROS 2 consumer harness of ../shared/ros2-consumer (its README): a package's launch files
in the real launch / launch_xml / launch_ros of Humble or Jazzy, every node's parameters
through rcl. Tests skip where ../shared is absent; where it is present and its environments are
not built yet, `setup.sh` builds them once (about 35 s, PyPI only, CPython 3.11).
"""

from __future__ import annotations

import functools
import json
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import pytest

from tests import ros2_zygote
from tests.conftest import ROOT

HARNESS = ROOT.parent / "shared" / "ros2-consumer"
CHECK = HARNESS / "check_ros2_pkg.py"
DISTROS = ("humble", "jazzy")
# Kilted and Rolling: Jazzy's launch frontend and MoveIt tables (setup.sh links their environments
# to Jazzy's); the tests run them on a few packages only (test_ros2_consumer.py)
NEWER_DISTROS = ("kilted", "rolling")
RUNS: list[tuple[str, float]] = []  # (package, wall time [s]) of each harness run, for the summary


def _venv_root() -> Path:
    return Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "ros2-consumer"


@functools.lru_cache(maxsize=1)
def _built() -> str:
    """'' when both environments import, else why they could not be built."""
    if all((_venv_root() / d / "bin" / "python").exists() for d in (*DISTROS, *NEWER_DISTROS)):
        return ""
    python = shutil.which("python3.11") or shutil.which("python3") or "python3"
    done = subprocess.run(
        [str(HARNESS / "setup.sh")], env={**os.environ, "PYTHON": python}, capture_output=True, text=True
    )
    return "" if done.returncode == 0 else f"setup.sh failed: {done.stderr[-2000:]}"


def harness_python(distro: str) -> Path:
    """The harness interpreter of `distro`; skips without ../shared, fails when it cannot be built."""
    if not CHECK.is_file():
        pytest.skip(f"{HARNESS} not present")
    problem = _built()
    if problem:
        pytest.fail(f"the ROS 2 consumer harness could not be built: {problem}")
    return _venv_root() / distro / "bin" / "python"


# The harness with planner plugins its table of a distro's binaries lacks, as a user who built
# them from source has them: argv[1] the JSON list of plugins, then the harness's own argv.
_WITH_PLUGINS = """
import json, sys
sys.path.insert(0, {harness!r})
import check_ros2_pkg as check
distro = sys.argv[sys.argv.index("--distro") + 1]
check.PLUGINS[distro]["planners"].update(json.loads(sys.argv[1]))
sys.argv = sys.argv[2:]
sys.exit(check.main())
"""


def check_package(
    pkg: Path,
    distro: str,
    description_dirs: tuple[Path, ...] = (),
    *,
    require_mock: bool = True,
    launch: tuple[str, ...] = (),
    args: tuple[str, ...] = (),
    built_from_source: tuple[str, ...] = (),
) -> dict:
    """The harness's JSON report on `pkg` (every launch file unless `launch` names some);
    `built_from_source`: planner plugins the distro's binaries lack and the user built (STOMP
    on Humble), known to the harness for this run only."""
    python = str(harness_python(distro))
    argv = [python, str(CHECK), str(pkg), "--distro", distro]
    if built_from_source:
        script = _WITH_PLUGINS.format(harness=str(HARNESS))
        argv = [python, "-c", script, json.dumps(list(built_from_source)), *argv[1:]]
    argv += [a for d in description_dirs for a in ("--description-pkg", str(d))]
    argv += [a for f in launch for a in ("--launch", str(pkg / f))]
    argv += [a for x in args for a in ("--arg", x)]
    argv += ["--require-mock"] if require_mock else []
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="ros2_harness_") as home:
        env = {**os.environ, "ROS_HOME": home, "ROS_LOG_DIR": os.path.join(home, "log")}
        done = ros2_zygote.run(Path(argv[0]), argv[1:], env, timeout=600)
    RUNS.append((f"{pkg} ({distro})", time.monotonic() - start))
    assert done.stdout.strip(), done.stderr[-3000:]
    return json.loads(done.stdout)


def node_processes(report: dict, launch_file: str) -> list[dict]:
    """The processes one launch file would start, as the harness resolved them."""
    return report["launch"][launch_file]["processes"]


def ros2_control_of(report: dict, launch_file: str, executable: str = "robot_state_publisher") -> dict:
    """{system: hardware plugin} of the robot description `executable` gets."""
    for process in node_processes(report, launch_file):
        if process.get("executable") == executable:
            return process["key_values"].get("ros2_control", {})
    raise AssertionError(f"{launch_file} starts no {executable}")
