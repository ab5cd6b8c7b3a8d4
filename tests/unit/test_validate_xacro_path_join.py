"""`PathJoinSubstitution([FindExecutable(name="xacro")])` as a Command's first part (the form of
ros2_control's demos, UR's drivers and annin_ar4_moveit_config): launch joins one path, the
executable FindExecutable finds (ros2/launch path_join_substitution.py `perform`: os.path.join
of its one part), so the command runs xacro as `FindExecutable(name="xacro")` alone does."""

from __future__ import annotations

from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

LAUNCH = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    description = Command(
        [PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
         PathJoinSubstitution([FindPackageShare("bot_description"), "urdf", "bot.urdf.xacro"]),
         " hw:=", LaunchConfiguration("hw")]
    )
    return LaunchDescription([
        DeclareLaunchArgument("hw", default_value="mock"),
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[{"robot_description": description}]),
    ])
"""


def test_a_path_joined_xacro_executable_is_a_xacro_command(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    (source / "launch/move_group.launch.py").write_text(LAUNCH)
    result = validate(source, package_paths=paths, plan=False, matrix_trials=0)
    assert (result.robot, result.urdf_origin) == ("bot", "xacro command in launch/move_group.launch.py")


NAMED_SHARE = """import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.substitutions import Command
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    share = get_package_share_directory("bot_description")
    file = os.path.join(share, "urdf", "bot.urdf.xacro")
    description = ParameterValue(Command(["xacro ", file, " hw:=mock"]), value_type=str)
    return LaunchDescription([
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[{"robot_description": description}]),
    ])
"""


def test_a_xacro_command_under_a_package_no_path_holds_names_that_package(tmp_path):
    """get_package_share_directory("pkg") of a package no package path holds: the description
    is unknown until that package is found (urdf.package-missing naming it), not a command
    validate cannot read."""
    import shutil

    source, _ = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    (source / "launch/move_group.launch.py").write_text(NAMED_SHARE)
    shutil.rmtree(tmp_path / "bot_description")
    result = validate(source, plan=False, matrix_trials=0)
    assert result.robot is None
    missing = [
        (f.rule, f.severity, f.file, f.element) for f in result.findings if "package-missing" in f.rule
    ]
    assert missing == [
        ("urdf.package-missing", "warning", "launch/move_group.launch.py", "robot_description")
    ]
    assert not [f for f in result.findings if f.rule == "urdf.runtime-only"]
    assert (
        result.urdf_origin
        == "xacro command in launch/move_group.launch.py, from package 'bot_description' not found"
    )
