"""controller.interface-unavailable: a JointTrajectoryController claiming a joint's command or
state interface the robot's <ros2_control> does not list is never activated (controller_manager
jazzy l.4365-4411: "... is not available"; humble l.1614-1637, l.1660-1672: the claim throws).
Only joints some <ros2_control> lists count; mock hardware offers exactly what it lists."""

from __future__ import annotations

import yaml

from marm_setup.package.driver_file import read_ros2_control, read_ros2_controllers
from marm_setup.package.files import located_text
from marm_setup.robot import systems_in_urdf
from marm_setup.validate import validate
from marm_setup.validate.rules.interface_rules import check_controller_interfaces, offered_interfaces

ROS2_CONTROL = """<robot name="tri">
  <ros2_control name="sys" type="system">
    <hardware><plugin>PLUGIN</plugin></hardware>
    <joint name="j1"><command_interface name="position"/>
      <state_interface name="position"/><state_interface name="velocity"/></joint>
    <joint name="j2"><command_interface name="position"/>
      <state_interface name="position"/><state_interface name="velocity"/></joint>
  </ros2_control>
</robot>
"""
CONTROLLERS = """controller_manager:
  ros__parameters:
    update_rate: 100
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
arm_controller:
  ros__parameters:
    joints: [j1, j2]
    command_interfaces: COMMAND
    state_interfaces: STATE
"""


def _found(command: str, state: str = "[position, velocity]", plugin: str = "mock_components/GenericSystem"):
    driver = read_ros2_controllers(
        located_text(CONTROLLERS.replace("COMMAND", command).replace("STATE", state), "config/c.yaml")
    )
    offered = offered_interfaces(systems_in_urdf(ROS2_CONTROL.replace("PLUGIN", plugin)))
    return [(f.severity, f.element) for f in check_controller_interfaces(driver, offered)]


def test_interfaces_the_hardware_lists_are_fine():
    assert _found("[position]") == []


def test_a_command_or_state_interface_mock_hardware_lacks_is_an_error():
    assert _found("[effort]") == [("error", "arm_controller.ros__parameters.command_interfaces")]
    assert _found("[position]", "[position, velocity, acceleration]") == [
        ("error", "arm_controller.ros__parameters.state_interfaces")
    ]


def test_another_plugin_may_export_more_than_it_lists():
    assert _found("[effort]", plugin="acme_driver/AcmeSystem") == [
        ("warning", "arm_controller.ros__parameters.command_interfaces")
    ]


def test_no_ros2_control_for_the_joints_is_no_claim():
    driver = read_ros2_controllers(
        located_text(CONTROLLERS.replace("COMMAND", "[effort]").replace("STATE", "[position]"), "c.yaml")
    )
    assert check_controller_interfaces(driver, offered_interfaces(())) == []
    other = offered_interfaces(systems_in_urdf(ROS2_CONTROL.replace("j1", "x1").replace("j2", "x2")))
    assert check_controller_interfaces(driver, other) == []


def test_a_package_xacro_lists_its_literal_joints_interfaces():
    xacro = ROS2_CONTROL.replace('"j2"', '"${prefix}j2"').replace("PLUGIN", "mock_components/GenericSystem")
    (system,) = read_ros2_control("config/tri.ros2_control.xacro", xacro).systems
    assert [i.joint for i in system.interfaces] == ["j1"]
    assert system.plugin == "mock_components/GenericSystem"


def test_the_generated_package_checked_as_launched(ros2_packages):
    """Our layout: the package's own ros2_control xacro is what the launch adds to the URDF."""
    pkg = ros2_packages.copy("marm", "jazzy", "interfaces")
    roots = ros2_packages.get("marm", "jazzy").roots
    path = pkg / "config" / "ros2_controllers.yaml"
    data = yaml.safe_load(path.read_text())
    assert [f.rule for f in validate(pkg, package_paths=roots, plan=False, matrix_trials=0).findings] == []
    data["arm_controller"]["ros__parameters"]["command_interfaces"] = ["effort"]
    path.write_text(yaml.safe_dump(data))
    found = validate(pkg, package_paths=roots, plan=False, matrix_trials=0).findings
    assert [(f.rule, f.severity) for f in found] == [("controller.interface-unavailable", "error")]
