"""ros2_control's mock hardware takes its initial values from the URDF's
`<param name="initial_value">`; `config/initial_positions.yaml` reaches them only through a xacro
that loads it (the Setup Assistant's ros2_control.xacro template:
`xacro.load_yaml(initial_positions_file)['initial_positions']`, its urdf.xacro passing
`initial_positions_file`, moveit2 moveit_setup_assistant/moveit_setup_controllers
templates/config/ros2_control.xacro l.3-4, src/control_xacro_config.cpp l.94). A file of that
name that no xacro, URDF or launch file of the package names is read by nothing (the igus
ReBeL's irc_ros_moveit_config keeps one with `<prefix>joint1` keys its description never
loads): its keys are no finding and the demo does not start from it."""

from __future__ import annotations

from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

INITIAL = "initial_positions:\n  joint_1: 0.0\n  no_such_joint: 0.0\n"
LOADER = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="initial_positions_file" default="initial_positions.yaml"/>
</robot>
"""


def unknown(source, paths) -> list[str]:
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    return [f.element for f in found if f.rule == "pose.initial-unknown-joint"]


def test_an_initial_positions_file_nothing_names_is_not_checked(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "config/initial_positions.yaml").write_text(INITIAL)
    assert unknown(source, paths) == []


def test_one_a_xacro_of_the_package_names_is(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "config/initial_positions.yaml").write_text(INITIAL)
    (source / "config/bot.ros2_control.xacro").write_text(LOADER)
    assert unknown(source, paths) == ["initial_positions.no_such_joint"]
