"""A YAML file a Python launch reads through nav2_common's `ReplaceString(source_file=...,
replacements={...})`: the substitution writes a copy of the file in which, line by line, each
key is replaced by its value (ros-navigation/navigation2 nav2_common/launch/replace_string.py,
`ReplaceString.replace`: `line.replace(key, value)` for each pair), and the launch loads that
copy. So `<prefix>joint_1` is `joint_1` when the prefix argument defaults to '' (the igus
ReBeL's irc_ros_moveit_config reads its controllers, limits and kinematics so). With a
`condition` the file may be taken as it is, so validate reads it as written."""

from __future__ import annotations

from marm_setup.validate.runner import validate
from tests.vendor_packages import BOT_CONTROLLERS, PACKAGES

LAUNCH = """import os
from pathlib import Path

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_param_builder import load_yaml
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare
from nav2_common.launch import ReplaceString


def setup(context):
    prefix = LaunchConfiguration("prefix")
    description = Command(
        [FindExecutable(name="xacro"), " ",
         PathJoinSubstitution([FindPackageShare("bot_description"), "urdf", "bot.urdf.xacro"])]
    )
    controllers_file = os.path.join(
        get_package_share_directory("bot_moveit_config"), "config", "bot_controllers.yaml"
    )
    controllers = ReplaceString(source_file=controllers_file, replacements={"<prefix>": prefix}CONDITION)
    controllers_dict = load_yaml(Path(controllers.perform(context)))
    moveit_controllers = {
        "moveit_simple_controller_manager": controllers_dict,
        "moveit_controller_manager": "moveit_simple_controller_manager/MoveItSimpleControllerManager",
    }
    return [
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[{"robot_description": description}, moveit_controllers]),
    ]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("prefix", default_value=""),
        OpaqueFunction(function=setup),
    ])
"""
CONTROLLERS = (
    BOT_CONTROLLERS.split("moveit_simple_controller_manager:\n", 1)[1]
    .replace("  ", "", 1)
    .replace("\n  ", "\n")
    .replace("[joint_", "[<prefix>joint_")
    .replace(" joint_", " <prefix>joint_")
)


def unknown_joints(tmp_path, condition: str = "") -> list[str]:
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    (source / "launch/move_group.launch.py").write_text(LAUNCH.replace("CONDITION", condition))
    (source / "config/bot_controllers.yaml").write_text(CONTROLLERS)
    found = validate(source, package_paths=paths, plan=False, matrix_trials=0).findings
    return sorted(f.message for f in found if f.rule == "controller.unknown-joint")


def test_a_file_read_through_replace_string_gets_its_replacements(tmp_path):
    assert "<prefix>joint_1" in CONTROLLERS
    assert unknown_joints(tmp_path) == []


def test_a_conditional_replace_string_is_read_as_written(tmp_path):
    found = unknown_joints(tmp_path, ", condition=IfCondition(LaunchConfiguration('rename'))")
    assert found and all("<prefix>" in message for message in found)


def test_replacements_are_made_line_by_line_in_order_and_bounded():
    import pytest

    from marm_setup.bounded_read import YAML_BYTES
    from marm_setup.package.files import FileProblem, replaced

    assert replaced("a: <p>x\nb: <p><p>\n", (("<p>", "q_"), ("q_x", "y"))) == "a: y\nb: q_q_\n"
    with pytest.raises(FileProblem):
        replaced("k" * 1000 + "\n", (("k", "v" * YAML_BYTES),))
