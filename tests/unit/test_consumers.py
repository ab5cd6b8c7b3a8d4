"""Which real consumer validate uses (validate/consumers.py), and how the check script's report
becomes findings naming the launch file. The real runs are in tests/integration/test_launch_defects.py."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest

from marm_setup.package.launch_xml import parse_launch
from marm_setup.validate.consumers import _dump_problem, _needs_args, _run, ros2_findings, ros2_python
from tests.helpers import build_file_tree

REPORT = {
    "launch": {
        "launch/demo.launch.xml": {
            "code": 0,
            "errors": [],
            "nodes": [
                {
                    "package": "robot_state_publisher",
                    "executable": "robot_state_publisher",
                    "name": "robot_state_publisher",
                    "error": None,
                    "ros2_control": {"arm": "acme/Arm", "hand": "mock_components/GenericSystem"},
                },
                {
                    "package": "rviz2",
                    "executable": "rviz2",
                    "name": "rviz2",
                    "error": "ValueError: Cannot declare a statically typed parameter with default value of type PARAMETER_NOT_SET",
                },
            ],
        },
        "launch/move_group.launch.xml": {
            "code": 1,
            "errors": ["Caught exception in launch: executed command showed stderr output"],
            "nodes": [],
        },
    },
    "params": {
        "config/moveit.yaml": ["move_group: ValueError: PARAMETER_NOT_SET"],
        "config/ros2_controllers.yaml": [],
    },
}


def test_the_report_becomes_findings_naming_the_launch_file():
    found = {(f.rule, f.file, f.element) for f in ros2_findings(REPORT, "jazzy")}
    assert found == {
        ("demo.real-hardware", "launch/demo.launch.xml", "ros2_control[arm]"),
        ("ros2.params", "launch/demo.launch.xml", "node[rviz2]"),
        ("ros2.launch", "launch/move_group.launch.xml", "launch"),
        ("ros2.params", "config/moveit.yaml", "move_group"),
    }
    assert all(f.is_error for f in ros2_findings(REPORT, "jazzy"))


def test_humbles_fake_components_count_as_mock_on_humble_only():
    report = {
        "launch": {
            "launch/demo.launch.xml": {
                "code": 0,
                "errors": [],
                "nodes": [
                    {
                        "package": "p",
                        "executable": "ros2_control_node",
                        "name": "controller_manager",
                        "error": None,
                        "ros2_control": {"arm": "fake_components/GenericSystem"},
                    }
                ],
            }
        }
    }
    assert ros2_findings(report, "humble") == []
    assert [f.rule for f in ros2_findings(report, "jazzy")] == ["demo.real-hardware"]


def test_no_ros_no_consumer(monkeypatch):
    monkeypatch.delenv("MARM_SETUP_ROS2_PYTHON", raising=False)
    monkeypatch.delenv("ROS_DISTRO", raising=False)
    assert ros2_python() is None  # not sourced: not even probed
    monkeypatch.setenv("MARM_SETUP_ROS2_PYTHON", "")
    monkeypatch.setenv("ROS_DISTRO", "jazzy")
    assert ros2_python() is None  # empty: never
    monkeypatch.setenv("MARM_SETUP_ROS2_PYTHON", sys.executable)  # a Python without launch_ros
    assert ros2_python() is None


def test_a_launch_file_with_an_arg_without_value_is_an_include(tmp_path):
    root = build_file_tree(
        tmp_path,
        {
            "a.launch": '<launch><arg name="x"/></launch>',
            "b.launch": '<launch><arg name="x" default="1"/></launch>',
        },
    )
    a, b = (parse_launch(root / rel, rel).root for rel in ("a.launch", "b.launch"))
    assert _needs_args(a) and not _needs_args(b)


@pytest.mark.parametrize(
    ("code", "stdout", "stderr", "problem"),
    [
        (0, "/a: 1\n", "", ""),
        (0, "Unable to load file x.launch: boom", "", "Unable to load file x.launch: boom"),
        (
            1,
            "",
            "RLException: [x.launch] is neither a launch file\n",
            "RLException: [x.launch] is neither a launch file",
        ),
    ],
)
def test_a_dump_that_prints_no_parameter_tree_failed(code, stdout, stderr, problem):
    assert _dump_problem(subprocess.CompletedProcess([], code, stdout, stderr)) == problem


def test_a_python_launch_file_needing_a_module_this_ros_lacks_is_a_warning():
    """MoveIt Setup Assistant launch files import moveit_configs_utils: without MoveIt installed
    the launcher cannot run them, which says nothing about the package."""
    message = "Caught exception in launch: ModuleNotFoundError: No module named 'moveit_configs_utils'"
    report = {"launch": {"launch/demo.launch.py": {"code": 1, "errors": [message], "nodes": []}}}
    (finding,) = ros2_findings(report, "humble")
    assert (finding.rule, finding.severity) == ("ros2.launch-unrun", "warning")


def test_a_launcher_that_does_not_finish_is_killed_with_its_children(tmp_path):
    """The consumer's child runs in its own process group: on timeout every process of it goes
    (a launcher's $(command) children included)."""
    pid_file = tmp_path / "child.pid"
    script = f"sleep 60 & echo $! > {pid_file}; wait"
    assert _run(["sh", "-c", script], dict(os.environ), 1.0) is None
    child = int(pid_file.read_text())
    with pytest.raises(ProcessLookupError):
        for _ in range(50):  # reaped by init shortly after the kill
            os.kill(child, 0)
            time.sleep(0.1)
