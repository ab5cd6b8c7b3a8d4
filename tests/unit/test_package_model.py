"""The package model: which file feeds each MoveIt file kind (ROS 1 launch files evaluated with
their args through includes, ROS 2 XML, MoveItConfigsBuilder read statically from Python launch
files), and the typed values with their positions. Small packages written into tmp_path."""

from __future__ import annotations

from marm_setup.package.files import located_text
from marm_setup.package.kinematics_file import read_kinematics
from marm_setup.package.perception_files import read_sensors, read_servo
from marm_setup.package.read import read_package
from tests.helpers import build_file_tree
from tests.vendor_packages import PACKAGES


def test_args_pass_down_an_include_chain(tmp_path):
    """demo.launch passes dof:=7 to move_group.launch, which passes it to planning_context.launch
    and (pass_all_args) to the execution file: the 7-DOF SRDF, limits and controllers are read."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    demo = (
        '<launch><include file="$(dirname)/move_group.launch"><arg name="dof" value="7"/></include></launch>'
    )
    (source / "launch" / "demo.launch").write_text(demo)
    pkg = read_package(source, package_paths=paths)
    assert pkg.srdf_path == "config/7dof/vx.srdf"
    assert pkg.joint_limits.where.file == "config/7dof/default_joint_limits.yaml"
    assert pkg.moveit_controllers.where.file == "config/7dof/controllers.yaml"
    assert [c.name for c in pkg.moveit_controllers.controllers] == [
        "vx7/arm_trajectory",
        "vx7/gripper_command",
    ]
    assert [c.where.file for c in pkg.alt_moveit_controllers] == ["config/6dof/controllers.yaml"]


def test_a_branch_the_defaults_do_not_take_is_an_alternative(tmp_path):
    """`<rosparam if="$(arg gazebo)">`: the file is a controller list a launch may load instead."""
    source, paths = PACKAGES["arg_selected"](tmp_path)
    execution = source / "launch" / "trajectory_execution.launch.xml"
    text = execution.read_text().replace(
        "</launch>",
        '<arg name="gazebo" default="false"/>'
        '<rosparam if="$(eval arg(\'gazebo\') == True)" file="$(find vx_moveit_config)/config/sim.yaml"/>'
        "</launch>",
    )
    execution.write_text(text)
    (source / "config" / "sim.yaml").write_text(
        "controller_list:\n  - {name: sim, action_ns: follow_joint_trajectory, type: FollowJointTrajectory,"
        " joints: [joint_1]}\n"
    )
    pkg = read_package(source, package_paths=paths)
    assert pkg.moveit_controllers.where.file == "config/6dof/controllers.yaml"
    assert [c.where.file for c in pkg.alt_moveit_controllers] == ["config/sim.yaml"]
    assert "on a branch the launch args' defaults do not take" not in pkg.source("moveit_controllers").how


def test_moveit_configs_builder_is_read_without_running_the_launch_file(tmp_path):
    """file_path through os.path.join of get_package_share_directory, a LaunchConfiguration's
    literal default in the mappings, the ros2_control_node's parameter file."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    launch = source / "launch" / "move_group.launch.py"
    text = launch.read_text().replace(
        '        .planning_pipelines(pipelines=["ompl"])\n',
        '        .planning_pipelines(pipelines=["ompl"])\n'
        "        .trajectory_execution(file_path=os.path.join(get_package_share_directory("
        '"bot_moveit_config"), "config", "other_controllers.yaml"))\n',
    )
    text = "import os\nfrom ament_index_python.packages import get_package_share_directory\n" + text
    text = text.replace(
        "    return LaunchDescription([",
        '    control = Node(package="controller_manager", executable="ros2_control_node",\n'
        '                   parameters=[os.path.join(get_package_share_directory("bot_moveit_config"), "config", "hw.yaml")])\n'
        "    return LaunchDescription([control,",
    )
    launch.write_text(text)
    (source / "config" / "other_controllers.yaml").write_text(
        (source / "config" / "bot_controllers.yaml").read_text()
    )
    (source / "config" / "hw.yaml").write_text((source / "config" / "ros2_controllers.yaml").read_text())
    pkg = read_package(source, package_paths=paths)
    assert pkg.moveit_controllers.where.file == "config/other_controllers.yaml"
    assert pkg.source("moveit_controllers").how.endswith("in launch/move_group.launch.py")
    assert pkg.ros2_controllers.where.file == "config/hw.yaml"
    assert dict(pkg.xacro_args)["use_sim"] == "false"  # DeclareLaunchArgument's default


def test_trajectory_execution_guesses_as_moveit_configs_builder_does(tmp_path):
    """One `*_controllers.yaml`: that one; several: moveit, moveit2, then `<robot>` (the
    builder's robot name); none of those: MoveIt's builder raises, we read none."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    config = source / "config"
    assert (
        read_package(source, package_paths=paths).moveit_controllers.where.file
        == "config/bot_controllers.yaml"
    )
    (config / "moveit2_controllers.yaml").write_text((config / "bot_controllers.yaml").read_text())
    assert (
        read_package(source, package_paths=paths).moveit_controllers.where.file
        == "config/moveit2_controllers.yaml"
    )
    (config / "moveit2_controllers.yaml").unlink()
    (config / "bot_controllers.yaml").rename(config / "arm_controllers.yaml")
    assert read_package(source, package_paths=paths).moveit_controllers is None


def test_ros2_xml_launch_param_files(tmp_path):
    """A ROS 2 XML launch hands move_group a parameter file: its sections are the kinds."""
    source, paths = PACKAGES["python_launch"](tmp_path)
    (source / "launch" / "move_group.launch.py").unlink()
    params = (
        "move_group:\n  ros__parameters:\n    robot_description_kinematics:\n      arm:\n"
        "        kinematics_solver: pick_ik/PickIkPlugin\n        mode: global\n"
    )
    build_file_tree(
        source,
        {
            "config/mg.yaml": params,
            "launch/move_group.launch.xml": (
                '<launch><arg name="cfg" default="mg"/><node pkg="moveit_ros_move_group" exec="move_group"'
                ' name="move_group"><param from="$(find-pkg-share bot_moveit_config)/config/$(var cfg).yaml"/>'
                "</node></launch>"
            ),
        },
    )
    pkg = read_package(source, package_paths=paths)
    arm = pkg.kinematics.group("arm")
    assert arm.where.element == "move_group.ros__parameters.robot_description_kinematics.arm"
    assert [(p.key, p.value) for p in arm.options] == [("mode", "global")]
    assert pkg.source("kinematics").how == "handed to move_group by launch/move_group.launch.xml"


def test_values_keep_their_line():
    doc = located_text("arm:\n  kinematics_solver: kdl\n  position_only_ik: true\n", "config/kinematics.yaml")
    option = read_kinematics(doc).group("arm").options[0]
    assert (option.key, option.value, option.where.line, str(option.where)) == (
        "position_only_ik",
        True,
        3,
        "config/kinematics.yaml: arm.position_only_ik",
    )


def test_sensors_of_both_moveit_versions_and_servo():
    ros1 = located_text("sensors:\n  - sensor_plugin: a/B\n    max_range: 2.0\n", "config/sensors_3d.yaml")
    ros2 = located_text(
        "sensors: [cam]\ncam:\n  sensor_plugin: a/B\n  max_range: 2.0\n", "config/sensors_3d.yaml"
    )
    for doc, name in ((ros1, "0"), (ros2, "cam")):
        (sensor,) = read_sensors(doc).sensors
        assert (sensor.name, sensor.plugin, [(p.key, p.value) for p in sensor.params]) == (
            name,
            "a/B",
            [("max_range", 2.0)],
        )
    servo = located_text(
        "moveit_servo:\n  move_group_name: arm\n  command_in_type: unitless\n", "config/servo.yaml"
    )
    assert read_servo(servo).group == "arm"
    assert read_servo(located_text("move_group_name: arm\n", "config/x.yaml")) is None


def test_an_unreadable_file_is_a_finding_not_an_exception(tmp_path):
    source, paths = PACKAGES["position_only"](tmp_path)
    (source / "config" / "joint_limits.yaml").write_text("joint_limits: [\n")
    pkg = read_package(source, package_paths=paths)
    assert pkg.joint_limits is None
    assert [(f.rule, f.file) for f in pkg.problems] == [("yaml.parse", "config/joint_limits.yaml")]
