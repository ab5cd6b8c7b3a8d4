"""MoveIt Servo and 3D perception through their real consumers: the marm with a wrist camera
(`sensors: [{name: wrist_camera, type: pointcloud, topic: /wrist_camera/depth/points}]`) for
noetic (real `roslaunch --dump-params` of servo.launch and demo.launch), humble and jazzy (the
ROS 2 consumer harness: real launch_xml / launch_ros and rcl's parameter parser).
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from marm_setup.flows import InitRequest, RobotInput, build_setup
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from tests.conftest import FIXTURES, MARM_URDF
from tests.integration.test_roslaunch import dump_params, needs_roslaunch
from tests.render_helpers import MARM_SPEC, marm_robot
from tests.ros2_consumer import harness_report, launched, node_values

CAMERA = "{name: wrist_camera, type: pointcloud, topic: /wrist_camera/depth/points}"
TOPIC = "/wrist_camera/depth/points"
POINTCLOUD = "occupancy_map_monitor/PointCloudOctomapUpdater"


def write_marm(tmp_path: Path, target: str, distro: str, extra: str = "") -> Path:
    """The marm package `init --setup SPEC` writes for a SPEC with the wrist camera (and `extra`)."""
    spec = tmp_path / "spec.yaml"
    text = MARM_SPEC.read_text(encoding="utf-8").replace("target: ros1\n", "").replace("driver: arbotix", "")
    spec.write_text(f"{text}\ntarget: {target}\nros_distro: {distro}\nsensors:\n- {CAMERA}\n{extra}")
    out = tmp_path / "marm_moveit_config"
    robot = marm_robot()
    model = build_setup(InitRequest(RobotInput.parse(MARM_URDF), out=out, spec=spec), robot)
    apply_writes(plan_writes(render_package(model, robot), out), out)
    return out


@needs_roslaunch
def test_noetic_servo_and_sensor_reach_their_nodes(tmp_path):
    pkg = write_marm(tmp_path, "ros1", "noetic")
    roots = [FIXTURES / "marm", pkg]
    servo = dump_params(pkg / "launch" / "servo.launch", roots, tmp_path)
    assert servo["/servo_server/move_group_name"] == "arm"
    assert servo["/servo_server/planning_frame"] == "base_link"  # the link the arm's Jacobian is in
    assert servo["/servo_server/ee_frame_name"] == "grasping_frame"
    assert servo["/servo_server/command_out_type"] == "trajectory_msgs/JointTrajectory"
    assert servo["/servo_server/command_out_topic"] == "/arm_controller/command"
    for key in ("publish_period", "scale/linear", "collision_check_rate", "lower_singularity_threshold"):
        assert isinstance(servo[f"/servo_server/{key}"], float), key
    assert (
        "/robot_description_semantic" in servo
        and "/robot_description_kinematics/arm/kinematics_solver" in servo
    )
    demo = dump_params(pkg / "launch" / "demo.launch", roots, tmp_path)
    (sensor,) = demo["/move_group/sensors"]
    assert sensor["sensor_plugin"] == POINTCLOUD and sensor["point_cloud_topic"] == TOPIC
    assert isinstance(sensor["max_range"], float) and isinstance(sensor["point_subsample"], int)
    assert demo["/move_group/octomap_resolution"] == 0.025
    assert not any(k.startswith("/servo_server") for k in demo)  # servo is a launch of its own


# moveit_servo parameters declared as integers; every other number is a double (humble
# servo_parameters.cpp declare(); jazzy servo_parameters.yaml `type:`).
SERVO_INTEGERS = {
    "humble": {"moveit_servo.num_outgoing_halt_msgs_to_publish"},
    "jazzy": {"moveit_servo.thread_priority"},
}


@pytest.mark.parametrize("distro", ["humble", "jazzy", "kilted", "rolling"])
def test_ros2_servo_node_and_move_group_sensor(tmp_path, distro):
    from marm_setup.ros import DISTROS

    row = DISTROS[distro]
    pkg = write_marm(tmp_path, "ros2", distro)
    with harness_report(pkg, distro, [FIXTURES / "marm"]) as report:
        assert report["errors"] == []
        servo = node_values(launched(report, "launch/servo.launch.xml", row.servo_executable), distro)
        move_group = node_values(launched(report, "launch/move_group.launch.xml", "move_group"), distro)
    assert servo["moveit_servo.move_group_name"] == ("STRING", "arm")
    assert servo["moveit_servo.command_out_topic"] == ("STRING", "/arm_controller/joint_trajectory")
    assert servo["moveit_servo.command_out_type"] == ("STRING", "trajectory_msgs/JointTrajectory")
    assert servo["robot_description_kinematics.arm.kinematics_solver"][1].startswith("kdl_kinematics_plugin")
    for key in ("robot_description", "robot_description_semantic"):
        assert servo[key][0] == "STRING"
    numbers = {
        k: t for k, (t, _) in servo.items() if k.startswith("moveit_servo.") and t in ("INTEGER", "DOUBLE")
    }
    assert {k for k, t in numbers.items() if t == "INTEGER"} <= SERVO_INTEGERS[row.params]
    assert numbers["moveit_servo.publish_period"] == "DOUBLE"
    if row.params == "humble":
        assert servo["moveit_servo.planning_frame"] == ("STRING", "base_link")
        assert servo["moveit_servo.ee_frame_name"] == ("STRING", "grasping_frame")
    else:  # Jazzy's servo takes both frames from the IK solver: no such parameters
        assert not {"moveit_servo.planning_frame", "moveit_servo.ee_frame_name"} & set(servo)
        assert servo["moveit_servo.joint_limit_margins"] == ("DOUBLE_ARRAY", [0.1])
    assert move_group["sensors"] == ("STRING_ARRAY", ["wrist_camera"])
    assert move_group["wrist_camera.sensor_plugin"] == ("STRING", POINTCLOUD)
    assert move_group["wrist_camera.point_cloud_topic"] == ("STRING", TOPIC)
    assert move_group["wrist_camera.max_range"] == ("DOUBLE", 5.0)
    assert move_group["wrist_camera.point_subsample"] == ("INTEGER", 1)
    assert move_group["octomap_resolution"][0] == "DOUBLE"
    assert not any(k.startswith("wrist_camera") or k == "sensors" for k in servo)  # move_group's alone


@pytest.mark.parametrize("distro", ["jazzy", "rolling"])  # Rolling: ForwardCommandController
def test_ros2_forward_position_controller_is_loaded_inactive(tmp_path, distro):
    import yaml

    extra = "servo:\n- {group: arm, command_out: position}\n"
    pkg = write_marm(tmp_path, "ros2", distro, extra)
    with harness_report(pkg, distro, [FIXTURES / "marm"]) as report:
        assert report["errors"] == []
        servo = node_values(launched(report, "launch/servo.launch.xml", "servo_node"), distro)
        spawners = [
            p["cmd"]
            for p in report["launch"]["launch/demo.launch.xml"]["processes"]
            if p.get("executable") == "spawner"
        ]
    assert servo["moveit_servo.command_out_type"] == ("STRING", "std_msgs/Float64MultiArray")
    assert servo["moveit_servo.command_out_topic"] == ("STRING", "/arm_position_controller/commands")
    assert servo["moveit_servo.publish_joint_velocities"] == ("BOOL", False)
    forward = [c for c in spawners if c[1] == "arm_position_controller"]
    assert len(forward) == 1 and "--inactive" in forward[0]
    assert not any("--inactive" in c for c in spawners if c[1] != "arm_position_controller")
    assert math.isclose(servo["moveit_servo.publish_period"][1], 0.01)
    controllers = yaml.safe_load((pkg / "config" / "ros2_controllers.yaml").read_text())
    forward_type = controllers["controller_manager"]["ros__parameters"]["arm_position_controller"]["type"]
    if distro == "rolling":  # position_controllers removed (ros2_controllers master 27ea539)
        assert forward_type == "forward_command_controller/ForwardCommandController"
        assert controllers["arm_position_controller"]["ros__parameters"]["interface_name"] == "position"
    else:
        assert forward_type == "position_controllers/JointGroupPositionController"


DEPTH = "{name: depth_camera, type: depth_image, topic: /camera/depth/image_raw}"


@pytest.mark.parametrize(
    ("target", "distro", "command_out"),
    [("ros1", "noetic", "trajectory"), ("ros2", "humble", "trajectory"), ("ros2", "humble", "position"),
     ("ros2", "jazzy", "position")],
)  # fmt: skip
def test_validate_reads_our_servo_and_sensors_and_finds_nothing(tmp_path, target, distro, command_out):
    """Our own packages: the package model reads the servo config and both sensors, and the servo
    and sensor rules (validate/rules/perception_rules.py) have nothing to say about them."""
    from marm_setup.package.read import read_package
    from marm_setup.validate.runner import validate

    extra = f"- {DEPTH}\nservo:\n- {{group: arm, command_out: {command_out}}}\n"
    pkg = write_marm(tmp_path, target, distro, extra)
    model = read_package(pkg)
    assert [s.name for s in model.sensors.sensors] in (["wrist_camera", "depth_camera"], ["0", "1"])
    assert [s.group for s in model.servo] == ["arm"]
    found = [f for f in validate(pkg, plan=False).findings if f.rule.startswith(("servo.", "sensors."))]
    assert found == []  # ROS 1 without ArbotiX: the topic is that of MoveIt's arm_controller
