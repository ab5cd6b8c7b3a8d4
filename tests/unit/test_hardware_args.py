"""The description's args that configure its real ros2_control hardware (robot/hardware_args.py)
and the launch args the launch files offer for them, for init's xacro args and for the
description's own switch (render/hardware.py): expanded with the real xacro."""

from __future__ import annotations

from marm_setup.render.hardware import DescriptionHardware, description_command, description_launch_args
from marm_setup.robot.load import load_robot
from marm_setup.robot.ros2_control import MOCK_PLUGIN, HardwareArg, Ros2ControlSystem
from tests.helpers import build_file_tree

# A vendor-like description: a switch, the robot's address and a port in its real hardware's
# params, an arg that names a joint and reaches a param too (not hardware-only), a boolean one.
VENDOR = """
<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_fake_hardware" default="false"/>
  <xacro:arg name="robot_ip" default="192.168.1.10"/>
  <xacro:arg name="port" default="10000"/>
  <xacro:arg name="joint_name" default="j1"/>
  <xacro:arg name="fast" default="false"/>
  <link name="a"/><link name="b"/>
  <joint name="$(arg joint_name)" type="revolute"><parent link="a"/><child link="b"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
  <ros2_control name="arm" type="system">
    <hardware>
      <xacro:if value="$(arg use_fake_hardware)"><plugin>mock_components/GenericSystem</plugin></xacro:if>
      <xacro:unless value="$(arg use_fake_hardware)">
        <plugin>vendor_driver/ArmHardware</plugin>
        <param name="robot_ip">$(arg robot_ip)</param>
        <param name="port">$(arg port)</param>
        <param name="joint">$(arg joint_name)</param>
        <param name="fast">$(arg fast)</param>
      </xacro:unless>
    </hardware>
    <joint name="$(arg joint_name)"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""


def test_the_args_its_real_hardware_reads_and_nothing_else(tmp_path):
    build_file_tree(tmp_path, {"v.urdf.xacro": VENDOR})
    robot = load_robot(tmp_path / "v.urdf.xacro")
    assert robot.mock_switch is not None and robot.mock_switch.arg == "use_fake_hardware"
    assert robot.hardware_args == (
        HardwareArg("port", "10000", "arm", "port"),
        HardwareArg("robot_ip", "192.168.1.10", "arm", "robot_ip"),
    )
    # given on the command line, an arg is init's, not a default to offer
    given = load_robot(tmp_path / "v.urdf.xacro", {"robot_ip": "10.0.0.2"})
    assert [a.name for a in given.hardware_args] == ["port"]


def test_no_systems_no_hardware_args(tmp_path):
    build_file_tree(tmp_path, {"p.urdf.xacro": VENDOR.split("<ros2_control")[0] + "</robot>"})
    assert load_robot(tmp_path / "p.urdf.xacro").hardware_args == ()


def test_the_launch_args_and_the_command_that_passes_them():
    real = (Ros2ControlSystem("arm", "vendor_driver/ArmHardware", ("j1",)),)
    hw = DescriptionHardware("switch", real, "use_fake_hardware")
    hardware = (
        HardwareArg("robot_ip", "192.168.1.10", "arm", "robot_ip"),
        HardwareArg("bad", "a b", "arm", "x"),
    )
    args = description_launch_args(hw, (("dof", "7"), ("use_sim_time", "x")), hardware)
    assert [(a.name, a.default) for a in args] == [
        ("dof", "7"),
        ("use_fake_hardware", "$(var use_mock_hardware)"),  # the switch follows use_mock_hardware
        ("robot_ip", "192.168.1.10"),
    ]  # our own args are not offered twice; a value launch cannot pass as one word is not offered
    assert "robot_ip of the real hardware of arm" in args[2].description
    command = description_command(hw, "pkg", "v", args)
    assert command.endswith(
        "use_mock_hardware:=$(var use_mock_hardware) dof:=$(var dof) "
        "use_fake_hardware:=$(var use_fake_hardware) robot_ip:=$(var robot_ip)"
    )
    mock = DescriptionHardware("mock", (Ros2ControlSystem("arm", MOCK_PLUGIN, ("j1",)),))
    assert [a.name for a in description_launch_args(mock, (), ())] == []
