"""A Python launch without MoveItConfigsBuilder that loads `joint_limits.yaml` and
`kinematics.yaml` by hand (`load_yaml(path)`) and hands their dicts to move_group as they are:
the files' top-level keys become move_group's parameters, so a file whose top level is
`robot_description_planning: {joint_limits: ...}` puts the limits at
`robot_description_planning.joint_limits.<joint>`, where MoveIt reads them (moveit2
robot_model_loader.cpp l.133), and `robot_description_kinematics: {<group>: ...}` puts the
solver at `robot_description_kinematics.<group>`, where MoveIt looks (humble
kinematics_plugin_loader.cpp l.306-319; jazzy l.260). The igus ReBeL's irc_ros_moveit_config
does so. Put under that key once more by the launch (`{"robot_description_planning": limits}`)
the file is nested twice and MoveIt reads none of it."""

from __future__ import annotations

from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES, _limits

LAUNCH = """import os
from pathlib import Path

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.substitutions import Command, FindExecutable, PathJoinSubstitution
from launch_param_builder import load_yaml
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = get_package_share_directory("bot_moveit_config")
    description = Command(
        [FindExecutable(name="xacro"), " ",
         PathJoinSubstitution([FindPackageShare("bot_description"), "urdf", "bot.urdf.xacro"])]
    )
    limits = load_yaml(Path(os.path.join(share, "config", "joint_limits.yaml")))
    kinematics = load_yaml(Path(os.path.join(share, "config", "kinematics.yaml")))
    controllers = load_yaml(Path(os.path.join(share, "config", "bot_controllers.yaml")))
    params = {"robot_description": description}
    for part in (LIMITS, kinematics, controllers):
        params.update(part)
    return LaunchDescription([
        Node(package="moveit_ros_move_group", executable="move_group", parameters=[params]),
    ])
"""
KINEMATICS = (
    "robot_description_kinematics:\n  arm:\n    kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n"
    "    kinematics_solver_timeout: 0.05\n"
)


def findings(tmp_path, limits_item: str = "limits") -> list[tuple[str, str]]:
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    (source / "launch/move_group.launch.py").write_text(LAUNCH.replace("LIMITS", limits_item))
    (source / "config/joint_limits.yaml").write_text(
        "robot_description_planning:\n"
        + "".join(f"  {line}\n" for line in _limits(6, 0.8, 2.5, 0.5).splitlines())
    )
    (source / "config/kinematics.yaml").write_text(KINEMATICS)
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    wanted = ("config/joint_limits.yaml", "config/kinematics.yaml")
    return sorted({(f.rule, str(f.severity)) for f in found if f.file in wanted and f.severity != "info"})


def test_a_file_handed_over_as_it_is_holds_the_parameter_namespace_itself(tmp_path):
    # the gripper's joint has no entry in the six-joint file: the one finding left
    assert findings(tmp_path) == [("limits.missing-joint", "warning")]


def test_a_file_the_launch_puts_under_the_namespace_again_is_not_read_by_moveit(tmp_path):
    found = findings(tmp_path, '{"robot_description_planning": limits}')
    assert ("limits.malformed", "error") in found
