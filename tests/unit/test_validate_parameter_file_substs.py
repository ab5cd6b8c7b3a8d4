"""A parameter file a Python launch hands to move_group as
`ParameterFile(path, allow_substs=True)`: launch_ros evaluates the `$(var name)` substitutions
of its text with the launch configurations before rcl parses it (launch_ros
parameter_descriptions.py ParameterFile.evaluate: `if self.__allow_substs: ... parse_substitution`
of the file's text), so `$(var tf_prefix)joint_1` is `joint_1` when tf_prefix defaults to ''
(annin_ar4_moveit_config's controllers.yaml and joint_limits.yaml). Without allow_substs the
text is taken as it is."""

from __future__ import annotations

from pathlib import Path

from marm_setup.findings import Finding
from marm_setup.validate.runner import validate
from tests.vendor_packages import PACKAGES

LAUNCH = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterFile
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    description = Command(
        [FindExecutable(name="xacro"), " ",
         PathJoinSubstitution([FindPackageShare("bot_description"), "urdf", "bot.urdf.xacro"])]
    )
    controllers = ParameterFile(
        PathJoinSubstitution([FindPackageShare("bot_moveit_config"), "config/bot_controllers.yaml"]),
        allow_substs=True,
    )
    return LaunchDescription([
        DeclareLaunchArgument("prefix", default_value=""),
        Node(package="moveit_ros_move_group", executable="move_group",
             parameters=[{"robot_description": description}, controllers]),
    ])
"""
CONTROLLERS = """/**/move_group:
  ros__parameters:
    moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager
    moveit_simple_controller_manager:
      controller_names: [bot_arm_controller]
      bot_arm_controller:
        type: FollowJointTrajectory
        action_ns: follow_joint_trajectory
        default: true
        joints: [$(var prefix)joint_1, $(var prefix)joint_2, $(var prefix)joint_3, $(var prefix)joint_4,
                 $(var prefix)joint_5, $(var prefix)joint_6]
"""


def controller_rules(source: Path, paths: list[Path]) -> list[tuple[str, str]]:
    found: list[Finding] = list(validate(source, package_paths=paths, plan=False, matrix_trials=0).findings)
    return sorted({(f.rule, str(f.severity)) for f in found if f.rule.startswith("controller.unknown")})


def test_a_parameter_file_loaded_with_allow_substs_gets_the_launch_arguments(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    (source / "launch/move_group.launch.py").write_text(LAUNCH)
    (source / "config/bot_controllers.yaml").write_text(CONTROLLERS)
    assert controller_rules(source, paths) == []
    launch = source / "launch/move_group.launch.py"
    launch.write_text(LAUNCH.replace("allow_substs=True", "allow_substs=False"))
    assert controller_rules(source, paths) == [("controller.unknown-joint", "error")]


LIMITS = """/**/move_group:
  ros__parameters:
    robot_description_planning:
      joint_limits:
""" + "".join(
    f"        $(var prefix)joint_{i}:\n          has_velocity_limits: true\n          max_velocity: 0.5\n"
    for i in range(1, 7)
)


def test_a_ros2_parameter_file_of_joint_limits_holds_them_under_robot_description_planning(tmp_path):
    """Handed to move_group as a parameter file, the limits' names are move_group's own:
    `robot_description_planning.joint_limits.<joint>`, where MoveIt reads them
    (moveit2 robot_model_loader.cpp l.133, `<robot_description>_planning.joint_limits.<joint>.`)."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / ".setup_assistant").unlink()
    limits = 'PathJoinSubstitution([FindPackageShare("bot_moveit_config"), "config/joint_limits.yaml"])'
    launch = LAUNCH.replace(
        "    return LaunchDescription([",
        f"    limits = ParameterFile({limits}, allow_substs=True)\n    return LaunchDescription([",
    ).replace("controllers]),", "controllers, limits]),")
    (source / "launch/move_group.launch.py").write_text(launch)
    (source / "config/bot_controllers.yaml").write_text(CONTROLLERS)
    (source / "config/joint_limits.yaml").write_text(LIMITS)
    found = list(validate(source, package_paths=paths, plan=False, matrix_trials=0).findings)
    assert [(f.rule, f.element) for f in found if f.file == "config/joint_limits.yaml" and f.is_error] == []
    missing = [f.element.rsplit(".", 1)[-1] for f in found if f.rule == "limits.missing-joint"]
    assert missing == ["gripper_finger_left_joint"]  # the arm's six are read, the gripper's is not there
