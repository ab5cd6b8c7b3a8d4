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
