"""The real roslaunch agrees with the static reader on where MoveIt 1's controller list lands:
`roslaunch --dump-params` on the packages of tests/unit/test_controller_list_namespace.py has
`/move_group/controller_list` exactly where validate finds no controller.list-namespace, and
validate with roslaunch reports the defect once (the static finding, with its line). Skipped
where python3-roslaunch is absent."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from marm_setup.validate import validate
from marm_setup.validate.consumers import dump_list_namespace
from tests.unit.test_controller_list_namespace import CASES, list_namespace, ros1_package

pytestmark = pytest.mark.skipif(shutil.which("roslaunch") is None, reason="roslaunch not on PATH")
BUGGY = {"manager-namespace": True, "twice": False, "group-outside-include": False}


def dumped(pkg: Path, tmp_path: Path) -> str:
    env = {**os.environ, "ROS_PACKAGE_PATH": str(pkg), "ROS_HOME": str(tmp_path / "ros_home")}
    done = subprocess.run(
        ["roslaunch", "--dump-params", str(pkg / "launch/move_group.launch")],
        capture_output=True,
        text=True,
        env=env,
        timeout=300,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    return done.stdout


@pytest.mark.parametrize("case", sorted(CASES))
def test_roslaunch_and_the_static_reader_agree(tmp_path, monkeypatch, case):
    pkg = ros1_package(tmp_path / "pkg", **CASES[case])
    text = dumped(pkg, tmp_path)
    assert ("/move_group/controller_list:" not in text) == BUGGY[case]
    from_dump = dump_list_namespace("launch/move_group.launch", text)
    assert len(from_dump) == BUGGY[case]
    monkeypatch.delenv("MARM_SETUP_ROSLAUNCH", raising=False)
    found = validate(pkg, plan=False)
    assert "roslaunch --dump-params" in found.launched_by
    findings = list_namespace(found)
    assert len(findings) == BUGGY[case]
    assert all(f.element.startswith("line ") for f in findings)  # the static one, not the dump's
