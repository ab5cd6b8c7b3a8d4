"""Controller rules follow MoveIt's real reading and selection (keep-one-thing / break-one-thing).

Each case writes a small controllers file shaped like a real package's (ROS-Industrial's
`name: ""`, the dual panda's several defaults, Motoman's non-default sub-controllers) for the
real panda robot of ../shared/realworld.
"""

from __future__ import annotations

import dataclasses

import yaml

from marm_setup.package.controllers_file import ControllersFile, read_controllers
from marm_setup.package.driver_file import read_ros2_controllers, read_ros_controllers
from marm_setup.package.files import located_text
from marm_setup.validate.rules.controller_rules import (
    check_coverage,
    check_listed,
    check_moveit_controllers,
    check_ros2_namespace,
)
from marm_setup.validate.rules.driver_rules import check_driver_controllers

ARM = [f"panda_joint{i}" for i in range(1, 8)]


def section(text: str, prefix: str = "") -> ControllersFile:
    """The controllers file as the package model reads it (`prefix`: the list's namespace,
    which the reader finds by itself)."""
    return read_controllers(located_text(text, "config/controllers.yaml"))


def findings(text: str, panda1, prefix: str = ""):
    srdf, robot = panda1
    sec = section(text, prefix)
    out = check_listed(sec) + check_moveit_controllers(sec, robot)
    out += check_coverage(sec, srdf, robot)
    return list(sec.controllers), out


def entry(name, joints, default=None, action_ns="follow_joint_trajectory"):
    item = {"name": name, "action_ns": action_ns, "type": "FollowJointTrajectory", "joints": joints}
    if default is not None:
        item["default"] = default
    return item


def dump(*entries) -> str:
    return yaml.safe_dump({"controller_list": list(entries)})


HAND = entry("hand_controller", ["panda_finger_joint1"], True)


def test_empty_name_is_the_ros_industrial_convention(panda1):
    """fanuc_cr7ia_moveit_config/config/controllers.yaml: `name: ""`, action_ns joint_trajectory_action."""
    ctrls, out = findings(dump(entry("", ARM, action_ns="joint_trajectory_action"), HAND), panda1)
    assert out == []
    assert ctrls[0].action == "/joint_trajectory_action"


def test_a_missing_key_makes_moveit_skip_the_controller(panda1):
    arm = entry("arm_controller", ARM, True)
    del arm["type"]
    _, out = findings(dump(arm, HAND), panda1)
    rules = sorted({f.rule for f in out if f.is_error})
    assert rules == ["controller.malformed", "controller.uncovered-joint"]


def test_missing_action_ns_is_an_error_but_an_empty_one_is_not(panda1):
    arm = entry("arm_controller", ARM, True)
    del arm["action_ns"]
    _, out = findings(dump(arm, HAND), panda1)
    assert "controller.missing-action-ns" in {f.rule for f in out}
    _, out = findings(dump(entry("arm_controller", ARM, True, action_ns=""), HAND), panda1)
    assert out == []


def test_several_defaults_on_different_joints_are_fine(panda1):
    """dual_panda_moveit_config: every controller default, one of them spanning both arms."""
    both = entry("both_controller", [*ARM, "panda_finger_joint1"], True)
    _, out = findings(dump(entry("arm_controller", ARM, True), both, HAND), panda1)
    assert out == []


def test_non_default_controllers_are_used_directly(panda1):
    """motoman_sda10f / ur5e: no `default` anywhere; a single matching option is used as it is."""
    _, out = findings(dump(entry("arm_controller", ARM), entry("hand", ["panda_finger_joint1"])), panda1)
    assert out == []


def test_two_equal_options_are_an_ambiguity_warning(panda1):
    _, out = findings(dump(entry("a", ARM, True), entry("b", ARM, True), HAND), panda1)
    assert [(f.rule, f.severity, f.element) for f in out] == [
        ("controller.ambiguous", "warning", "group[panda_arm]"),
        ("controller.ambiguous", "warning", "group[panda_arm_hand]"),
    ]
    _, out = findings(dump(entry("a", ARM, True), entry("b", ARM, False), HAND), panda1)
    assert out == []  # the default breaks the tie


def test_overlapping_controllers_cannot_be_combined(panda1):
    _, out = findings(dump(entry("a", ARM[:4], True), entry("b", ARM[3:], True), HAND), panda1)
    assert {(f.rule, f.element) for f in out if f.is_error} == {
        ("controller.no-combination", "group[panda_arm]"),
        ("controller.no-combination", "group[panda_arm_hand]"),
    }


MC2 = """
moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager
controller_names: [panda_arm_controller]
panda_arm_controller:
  action_ns: follow_joint_trajectory
  type: FollowJointTrajectory
  default: true
  joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5, panda_joint6, panda_joint7]
"""


def test_ros2_controllers_outside_the_simple_manager_namespace():
    assert [f.rule for f in check_ros2_namespace(section(MC2))] == ["controller.no-namespace"]
    nested = "moveit_simple_controller_manager:\n" + "".join(f"  {line}\n" for line in MC2.splitlines())
    assert check_ros2_namespace(section(nested, "moveit_simple_controller_manager")) == []
    ros2_control = MC2.replace(
        "moveit_simple_controller_manager/MoveItSimpleControllerManager", "x/Ros2ControlManager"
    )
    assert check_ros2_namespace(section(ros2_control)) == []
    by_launch = dataclasses.replace(section(MC2), loaded_into="moveit_simple_controller_manager")
    assert check_ros2_namespace(by_launch) == []  # `{"moveit_simple_controller_manager": load_yaml(...)}`
    twice = dataclasses.replace(section(nested), loaded_into="moveit_simple_controller_manager")
    assert [f.rule for f in check_ros2_namespace(twice)] == ["controller.no-namespace"]


KORTEX_R2C = """
controller_manager:
  ros__parameters:
    joint_trajectory_controller:
      type: joint_trajectory_controller/JointTrajectoryController
    twist_controller:
      type: picknik_twist_controller/PicknikTwistController
joint_trajectory_controller:
  ros__parameters:
    joints: [panda_joint1, panda_joint2, panda_joint3, panda_joint4, panda_joint5, panda_joint6, panda_joint7]
twist_controller:
  ros__parameters:
    joint: tcp
"""


def test_a_driver_controller_of_unknown_type_names_no_urdf_joints(panda1):
    """ros2_kortex: the twist controller's `joint: tcp` is a Cartesian frame."""
    _, robot = panda1
    driver = read_ros2_controllers(located_text(KORTEX_R2C, "config/ros2_controllers.yaml"))
    moveit = section(dump(entry("joint_trajectory_controller", ARM, True)))
    assert check_driver_controllers(moveit, driver, robot) == []
    broken = KORTEX_R2C.replace("joints: [panda_joint1,", "joints: [tcp,")
    found = check_driver_controllers(
        moveit, read_ros2_controllers(located_text(broken, "config/ros2_controllers.yaml")), robot
    )
    assert "controller.unknown-joint" in {f.rule for f in found}


def test_an_empty_joints_list_is_a_controller_moveit1_takes():
    """MoveIt 1's simple and fake managers check only that `joints` is an array
    (moveit_simple_controller_manager.cpp l.75-91, moveit_fake_controller_manager.cpp l.86-105):
    `joints: []` (a vacuum gripper's fake controller) is loaded and drives nothing. MoveIt 2's
    `controller_names` form still needs a joint."""
    text = yaml.safe_dump({"controller_list": [{"name": "suction", "joints": []}]})
    fake = read_controllers(located_text(text, "config/fake_controllers.yaml"), ("name", "joints"))
    assert check_listed(fake) == []
    assert [(c.name, c.joints) for c in fake.controllers] == [("suction", ())]
    ros1 = section(dump({**entry("suction", []), "type": "FollowJointTrajectory"}))
    assert check_listed(ros1) == [] and ros1.controllers[0].joints == ()
    ros2 = section(
        "controller_names: [suction]\nsuction: {action_ns: x, type: FollowJointTrajectory, joints: []}\n"
    )
    assert [f.rule for f in check_listed(ros2)] == ["controller.malformed"]


STATE_ONLY = """
hardware_interface:
  joints: [joint1, joint2]
joint_state_controller:
  type: joint_state_controller/JointStateController
  publish_rate: 50
"""
TRAJECTORY = """
other_controller:
  type: position_controllers/JointTrajectoryController
  joints: [joint1, joint2]
"""


def test_a_ros1_driver_file_serving_no_action_is_not_where_moveits_controllers_are(marm):
    """A ROS 1 `ros_controllers.yaml` holding only a joint_state_controller (xarm_ros' examples):
    the spawner starts only the controllers it names, and MoveIt's action servers are a vendor
    driver's; a file with a trajectory controller, or a ROS 2 file, is still held to MoveIt's
    (a ROS 2 file that drives none of the controller's joints: a warning, see below)."""
    moveit = section(dump(entry("arm_controller", ["joint1", "joint2"], True)))
    state_only = read_ros_controllers(located_text(STATE_ONLY, "config/ros_controllers.yaml"))
    assert check_driver_controllers(moveit, state_only, marm, ros1=True) == []
    assert [f.rule for f in check_driver_controllers(moveit, state_only, marm)] == [
        "controller.driver-missing"
    ]
    serving = read_ros_controllers(located_text(STATE_ONLY + TRAJECTORY, "config/ros_controllers.yaml"))
    found = check_driver_controllers(moveit, serving, marm, ros1=True)
    assert [(f.rule, f.severity) for f in found] == [("controller.driver-missing", "error")]


ROS2_ARM = """
controller_manager:
  ros__parameters:
    update_rate: 100
    arm_controller: {type: joint_trajectory_controller/JointTrajectoryController}
    joint_state_broadcaster: {type: joint_state_broadcaster/JointStateBroadcaster}
    vendor_state_broadcaster: {type: vendor_broadcasters/StateBroadcaster}
arm_controller:
  ros__parameters:
    joints: [joint1, joint2]
    command_interfaces: [position]
    state_interfaces: [position]
"""
MOVEIT_ARM_GRIPPER = """
controller_names: [arm_controller, gripper]
arm_controller: {action_ns: follow_joint_trajectory, type: FollowJointTrajectory, default: true, joints: [joint1, joint2]}
gripper: {action_ns: gripper_action, type: GripperCommand, default: true, joints: [finger_joint1]}
"""


def test_a_moveit_controller_on_joints_no_ros2_control_controller_drives_may_be_another_nodes(marm):
    """franka_ros2: MoveIt's simple controller manager connects to `<name>/<action_ns>`
    whoever serves it (moveit_simple_controller_manager.cpp l.111-182); its gripper is a
    vendor node's action server, not a ros2_control controller, and no controller of
    ros2_controllers.yaml names its joints (a broadcaster of unknown type names none): a
    warning. A MoveIt controller whose joints a ros2_control controller drives under another
    name (a rename, a typo) is still an error: nothing serves the action MoveIt connects to."""
    driver = read_ros2_controllers(located_text(ROS2_ARM, "config/ros2_controllers.yaml"))
    found = check_driver_controllers(section(MOVEIT_ARM_GRIPPER), driver, marm)
    assert [(f.rule, f.severity, f.element) for f in found] == [
        ("controller.driver-missing", "warning", "gripper")
    ]
    renamed = section(MOVEIT_ARM_GRIPPER.replace("arm_controller", "arm_ctrl"))
    found = check_driver_controllers(renamed, driver, marm)
    assert sorted((f.rule, f.severity, f.element) for f in found) == [
        ("controller.driver-missing", "error", "arm_ctrl"),
        ("controller.driver-missing", "warning", "gripper"),
    ]
    no_joints = ROS2_ARM.split("arm_controller:\n  ros__parameters:")[0]  # a JTC whose joints are not given
    found = check_driver_controllers(renamed, read_ros2_controllers(located_text(no_joints, "x.yaml")), marm)
    assert ("controller.driver-missing", "error", "arm_ctrl") in {
        (f.rule, f.severity, f.element) for f in found
    }
