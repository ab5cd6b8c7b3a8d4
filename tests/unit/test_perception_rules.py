"""validate's servo and sensor rules on minimal packages (MoveIt 2 and MoveIt 1 layouts): a servo
group that does not exist, frames that are no link, an output no controller takes or takes with
another message type; sensors with an unknown plugin, no topic, missing or mistyped parameters
(validate/rules/perception_rules.py; severities from moveit_servo and the occupancy map monitor)."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.moveit_params import SENSOR_TYPES
from marm_setup.package.read import read_package
from marm_setup.validate.runner import validate
from tests.helpers import ARM, build_file_tree, urdf

SRDF = """<?xml version="1.0"?>
<robot name="bot">
  <virtual_joint name="vj" type="fixed" parent_frame="world" child_link="base"/>
  <group name="arm"><chain base_link="base" tip_link="l3"/></group>
</robot>
"""
ROS2_XML = """<?xml version="1.0"?>
<package format="3"><name>bot_moveit_config</name><version>0.0.0</version><description>d</description>
<maintainer email="a@b.c">a</maintainer><license>BSD</license>
<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export></package>
"""
ROS1_XML = ROS2_XML.replace("ament_cmake</buildtool_depend>", "catkin</buildtool_depend>").replace(
    "<export><build_type>ament_cmake</build_type></export>", ""
)
ROS2_CONTROLLERS = """
controller_manager:
  ros__parameters:
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
    arm_position_controller:
      type: position_controllers/JointGroupPositionController
"""
ROS1_CONTROLLERS = """
arm_controller:
  type: position_controllers/JointTrajectoryController
  joints: [j1, j2, j3]
"""
SERVO = """
/**:
  ros__parameters:
    moveit_servo:
      move_group_name: {group}
      planning_frame: {frame}
      ee_frame_name: l3
      command_in_type: unitless
      publish_period: 0.034
      command_out_type: {out_type}
      command_out_topic: {topic}
"""
KIND = SENSOR_TYPES["pointcloud"]  # MoveIt's updater and the Setup Assistant's values
POINTCLOUD = {"sensor_plugin": KIND.plugin, "point_cloud_topic": "/camera/points", **dict(KIND.defaults)}


def ros2_package(
    root: Path, servo: dict | None = None, sensor: dict | None = None, controllers: bool = True
) -> Path:
    files = {
        "package.xml": ROS2_XML,
        "config/bot.urdf.xacro": urdf(ARM, "bot"),
        "config/bot.srdf": SRDF,
    }
    if controllers:
        files["config/ros2_controllers.yaml"] = ROS2_CONTROLLERS
    given = {"group": "arm", "frame": "base", "out_type": "trajectory_msgs/JointTrajectory"}
    given["topic"] = "/arm_controller/joint_trajectory"
    files["config/arm_servo.yaml"] = SERVO.format(**{**given, **(servo or {})})
    if sensor is not None:
        body = "".join(f"      {k}: {v}\n" for k, v in sensor.items())
        files["config/sensors_3d.yaml"] = f"sensors:\n  - cam\ncam:\n{body.replace('      ', '  ')}"
    return build_file_tree(root, files)


def ros1_package(root: Path, servo_topic: str, sensor: dict) -> Path:
    servo = SERVO.format(
        group="arm", frame="world", out_type="trajectory_msgs/JointTrajectory", topic=servo_topic
    )
    plain = "\n".join(line[6:] for line in servo.splitlines()[4:])  # MoveIt 1: top-level keys
    body = "".join(f"    {k}: {v}\n" for k, v in sensor.items())
    return build_file_tree(
        root,
        {
            "package.xml": ROS1_XML,
            "config/bot.urdf.xacro": urdf(ARM, "bot"),
            "config/bot.srdf": SRDF,
            "config/ros_controllers.yaml": ROS1_CONTROLLERS,
            "config/arm_servo.yaml": plain + "\n",
            "config/sensors_3d.yaml": "sensors:\n  -\n" + body.replace("    ", "    ", 1),
        },
    )


def rules(pkg: Path, family: tuple[str, ...] = ("servo.", "sensors.")) -> dict[str, list[str]]:
    out: dict[str, list[str]] = {}
    for f in validate(pkg, plan=False).findings:
        if f.rule.startswith(family):
            out.setdefault(f.rule, []).append(f"{f.severity} {f.element}: {f.message}")
    return out


def test_a_good_package_has_no_servo_or_sensor_finding(tmp_path):
    pkg = ros2_package(tmp_path / "bot_moveit_config", sensor=POINTCLOUD)
    model = read_package(pkg)
    assert [s.group for s in model.servo] == ["arm"] and model.sensors is not None
    assert rules(pkg) == {}


def test_a_servo_group_that_does_not_exist(tmp_path):
    found = rules(ros2_package(tmp_path / "bot_moveit_config", {"group": "manipulator"}))
    assert list(found) == ["servo.unknown-group"]
    assert found["servo.unknown-group"][0].startswith("error")
    assert "unknown group 'manipulator' (groups: arm)" in found["servo.unknown-group"][0]


@pytest.mark.parametrize(
    ("servo", "message"),
    [
        ({"topic": "/nobody/joint_trajectory"}, "no controller of config/ros2_controllers.yaml subscribes"),
        ({"out_type": "std_msgs/Float64MultiArray"}, "arm_controller takes trajectory_msgs/JointTrajectory"),
        (
            {"topic": "/arm_position_controller/commands"},
            "arm_position_controller takes std_msgs/Float64MultiArray",
        ),
    ],
)
def test_a_servo_output_with_no_controller_behind_it(tmp_path, servo, message):
    found = rules(ros2_package(tmp_path / "bot_moveit_config", servo))
    assert list(found) == ["servo.no-controller"], found
    assert found["servo.no-controller"][0].startswith("error") and message in found["servo.no-controller"][0]


def test_a_forward_position_output_to_its_controller_passes(tmp_path):
    servo = {"out_type": "std_msgs/Float64MultiArray", "topic": "arm_position_controller/commands"}
    assert rules(ros2_package(tmp_path / "bot_moveit_config", servo)) == {}


def test_without_controller_files_an_unmatched_output_is_a_warning(tmp_path):
    found = rules(ros2_package(tmp_path / "bot_moveit_config", {"topic": "/x/y"}, controllers=False))
    assert [m.split()[0] for m in found["servo.no-controller"]] == ["warning"]


MOVEIT_LIST = """controller_list:
  - name: arm_controller
    action_ns: follow_joint_trajectory
    type: FollowJointTrajectory
    default: true
    joints: [j1, j2, j3]
"""


@pytest.mark.parametrize(
    ("target", "topic"), [("ros1", "/arm_controller/command"), ("ros2", "arm_controller/joint_trajectory")]
)
def test_without_controller_files_the_topic_of_moveits_trajectory_controller_passes(tmp_path, target, topic):
    """The trajectory controller a driver runs for MoveIt's `arm_controller/follow_joint_trajectory`
    subscribes its `command` (ROS 1) / `joint_trajectory` (ROS 2) topic too: no warning; another
    topic still warns."""
    if target == "ros1":
        pkg = ros1_package(tmp_path / "bot_moveit_config", topic, POINTCLOUD)
        (pkg / "config/ros_controllers.yaml").unlink()
        listed = MOVEIT_LIST
    else:
        pkg = ros2_package(tmp_path / "bot_moveit_config", {"topic": topic}, controllers=False)
        listed = "moveit_simple_controller_manager:\n" + "".join(
            f"  {line}\n" for line in MOVEIT_LIST.splitlines()
        )
        listed += (
            "moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager\n"
        )
    (
        pkg / "config/controllers.yaml" if target == "ros1" else pkg / "config/moveit_controllers.yaml"
    ).write_text(listed, encoding="utf-8")
    assert rules(pkg, ("servo.",)) == {}
    servo = pkg / "config/arm_servo.yaml"
    servo.write_text(
        servo.read_text(encoding="utf-8").replace("arm_controller", "other_controller"), encoding="utf-8"
    )
    assert [m.split()[0] for m in rules(pkg, ("servo.",))["servo.no-controller"]] == ["warning"]


def test_frames_that_are_no_link_and_an_unknown_output_type(tmp_path):
    found = rules(
        ros2_package(tmp_path / "bot_moveit_config", {"frame": "tool0", "out_type": "geometry_msgs/Twist"})
    )
    assert set(found) == {"servo.unknown-frame", "servo.output-type"}
    assert "planning_frame: 'tool0' is no link" in found["servo.unknown-frame"][0]


@pytest.mark.parametrize(
    ("change", "rule", "severity"),
    [
        ({"sensor_plugin": "occupancy_map_monitor/LaserUpdater"}, "sensors.unknown-plugin", "error"),
        ({"point_cloud_topic": "''"}, "sensors.no-topic", "error"),
        ({"max_range": 5}, "sensors.parameter-type", "error"),  # an integer for a double: rclcpp throws
        ({"point_subsample": "one"}, "sensors.parameter-type", "error"),
        ({"max_update_rate": None}, "sensors.missing-parameter", "error"),
    ],
)
def test_sensor_rules_on_moveit2(tmp_path, change, rule, severity):
    sensor = {k: v for k, v in {**POINTCLOUD, **change}.items() if v is not None}
    found = rules(ros2_package(tmp_path / "bot_moveit_config", sensor=sensor))
    assert list(found) == [rule], found
    assert found[rule][0].startswith(severity)


def test_a_users_own_updater_plugin_is_not_judged(tmp_path):
    sensor = {"sensor_plugin": "my_pkg/LidarUpdater", "topic": "/scan"}
    assert rules(ros2_package(tmp_path / "bot_moveit_config", sensor=sensor)) == {}


def test_moveit1_servo_and_sensors(tmp_path):
    """MoveIt 1: the virtual joint's parent is a frame servo takes; readXmlParam takes an integer
    for a double (no finding) but no string; JointTrajectoryController listens on <name>/command."""
    sensor = {**POINTCLOUD, "max_range": 5, "padding_scale": "big"}
    del sensor["filtered_cloud_topic"]  # MoveIt 1 does not need every parameter
    pkg = ros1_package(tmp_path / "bot_moveit_config", "/arm_controller/command", sensor)
    assert read_package(pkg).target == "ros1"
    found = rules(pkg)
    assert list(found) == ["sensors.parameter-type"], found
    assert "padding_scale: expected a double, got 'big'" in found["sensors.parameter-type"][0]
    other = ros1_package(tmp_path / "b" / "bot_moveit_config", "/arm_controller/joint_trajectory", POINTCLOUD)
    assert list(rules(other)) == ["servo.no-controller"]


@pytest.mark.parametrize(
    "sensors",
    ["sensors:\n  - {}\n", "sensors: [{}]\n", "sensors:\n  - {sensor_plugin: ''}\n"],
)
def test_moveit1_setup_assistants_empty_sensor_is_no_error(tmp_path, sensors):
    """MoveIt 1's Setup Assistant writes `sensors: - {}` when no sensor was chosen: MoveIt logs
    'No sensor plugin specified; ignoring' and goes on (a warning); an empty plugin it skips
    on purpose (nothing)."""
    pkg = ros1_package(tmp_path / "bot_moveit_config", "/arm_controller/command", POINTCLOUD)
    (pkg / "config/sensors_3d.yaml").write_text(sensors, encoding="utf-8")
    found = rules(pkg)
    expected = [] if "sensor_plugin" in sensors else ["sensors.empty"]
    assert list(found) == expected, found
    assert all(m.startswith("warning") for ms in found.values() for m in ms)


@pytest.mark.parametrize(("listed", "rule"), [('[""]', "sensors.empty"), ("[cam]", "sensors.unknown-plugin")])
def test_moveit2_empty_sensor_name_is_a_warning_a_named_one_without_plugin_an_error(tmp_path, listed, rule):
    pkg = ros2_package(tmp_path / "bot_moveit_config")
    (pkg / "config/sensors_3d.yaml").write_text(f"sensors: {listed}\n", encoding="utf-8")
    found = rules(pkg)
    assert list(found) == [rule], found
    assert found[rule][0].startswith("warning" if rule == "sensors.empty" else "error")


SENSOR_MANAGER = """<launch>
  <rosparam command="load" file="$(find bot_moveit_config)/config/kinematics.yaml" ns="robot_description_kinematics"/>
  {sensors}
</launch>
"""


@pytest.mark.parametrize("loaded", [True, False])
def test_a_moveit1_sensors_file_no_launch_loads_is_not_read(tmp_path, loaded):
    """Launch files that load the package's YAML but not config/sensors_3d.yaml (its load
    commented out): move_group finds no `sensors` parameter (occupancy_map_monitor.cpp l.106),
    so the file's empty entry is nothing MoveIt logs. Loaded, it is the sensors.empty warning."""
    pkg = ros1_package(tmp_path / "bot_moveit_config", "/arm_controller/command", POINTCLOUD)
    (pkg / "config/sensors_3d.yaml").write_text("sensors:\n  - {}\n", encoding="utf-8")
    (pkg / "config/kinematics.yaml").write_text(
        "arm: {kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin}\n"
    )
    load = '<rosparam command="load" file="$(find bot_moveit_config)/config/sensors_3d.yaml"/>'
    text = SENSOR_MANAGER.format(sensors=load if loaded else f"<!-- {load} -->")
    (pkg / "launch").mkdir()
    (pkg / "launch/move_group.launch").write_text(text, encoding="utf-8")
    assert list(rules(pkg, ("sensors.",))) == (["sensors.empty"] if loaded else [])
