"""The ROS 2 consumer harness (../shared/ros2-consumer, README there) from the tests: a generated
package run through the real launch / launch_xml / launch_ros of a distro and rcl's parameter
parser, and the parameter values rcl hands one node.

Skips where the harness or its venvs (~/.cache/ros2-consumer/<distro>) are absent (CI). Kept
apart so it can move onto the shared fixture issue 21 adds for every generated ROS 2 package.
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

from tests import ros2_zygote
from tests.ros2_harness import HARNESS, harness_python

CONSUMER = HARNESS

# Asks rcl, through the harness's own function, for the parameters a node started with this
# argv gets: argv[1] is the JSON command line, argv[2] the node's name.
_NODE_VALUES = """
import json, sys
sys.path.insert(0, {consumer!r})
import check_ros2_pkg
full, params, error = check_ros2_pkg.rcl_node_params(json.loads(sys.argv[1]), sys.argv[2])
print(json.dumps({{"node": full, "error": error, "params": params}}))
"""


def consumer_python(distro: str) -> Path:
    """The harness venv's python for `distro` (tests/ros2_harness.py: skips without ../shared)."""
    return harness_python(distro)


@contextlib.contextmanager
def harness_report(
    pkg: Path, distro: str, description_pkgs: list[Path], launch_files: list[str] | None = None
) -> Iterator[dict]:
    """The harness's JSON report on `pkg` (its fake install prefix and launch's temporary
    parameter files kept until the block ends, so `node_values` can re-read a node's argv)."""
    python = consumer_python(distro)
    command = [
        str(python),
        str(CONSUMER / "check_ros2_pkg.py"),
        str(pkg),
        "--distro",
        distro,
        "--keep-prefix",
    ]
    for description in description_pkgs:
        command += ["--description-pkg", str(description)]
    for launch in launch_files or ():
        command += ["--launch", str(pkg / launch)]
    result = ros2_zygote.run(python, command[1:], _env(), timeout=600)
    report = json.loads(result.stdout)
    try:
        yield report
    finally:
        shutil.rmtree(Path(report["fake_prefix"]).parent.parent, ignore_errors=True)
        for entry in report["launch"].values():
            for process in entry["processes"]:
                for path in process.get("params_files", []):
                    if Path(path).name.startswith("launch_params_"):
                        Path(path).unlink(missing_ok=True)


def launched(report: dict, launch: str, executable: str) -> dict:
    """The one process `launch` (a path in the package) starts with `executable`."""
    processes = [p for p in report["launch"][launch]["processes"] if p.get("executable") == executable]
    assert len(processes) == 1, (launch, executable, report["launch"][launch]["processes"])
    return processes[0]


def node_values(process: dict, distro: str) -> dict[str, tuple[str, object]]:
    """{parameter: (rcl type, value)} of the node `process` (from `launched`) as rcl parses its
    argv, e.g. `('DOUBLE', 0.034)`."""
    cmd = process["cmd"]
    assert not any(arg.startswith("<") and arg.endswith(" chars>") for arg in cmd), (
        cmd
    )  # shortened by the report
    name = process["node"].rsplit("/", 1)[-1]
    script = _NODE_VALUES.format(consumer=str(CONSUMER))
    result = ros2_zygote.run(
        consumer_python(distro), ["-c", script, json.dumps(cmd), name], _env(), timeout=120
    )
    assert result.returncode == 0, result.stderr[-2000:]
    out = json.loads(result.stdout.strip().splitlines()[-1])
    assert out["error"] is None, out["error"]
    return {key: (kind, value) for key, (kind, value) in out["params"].items()}


def _env() -> dict[str, str]:
    """rcl's logs in a folder of this test session, not ~/.ros/log."""
    return {**os.environ, "ROS_AUTOMATIC_DISCOVERY_RANGE": "OFF", "ROS_LOG_DIR": _log_dir()}


@functools.lru_cache(maxsize=1)
def _log_dir() -> str:
    return tempfile.mkdtemp(prefix="ros2_consumer_logs_")
