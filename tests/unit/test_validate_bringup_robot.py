"""A config package with no launch file of its own (denso_robot_moveit_config, flexiv_moveit_config,
tm_moveit_config_*): a bringup package's launch file starts move_group with the config's SRDF and
YAML and its own `robot_description`, which is what MoveIt loads (moveit2 rdf_loader.cpp
l.86-99 reads the node's `robot_description` and `robot_description_semantic`). validate exited
2 asking for --urdf; it now takes that launch file's robot, says which file, and without such a
launch file keeps the exit-2 message."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.errors import InputError
from marm_setup.package import read_package
from tests.vendor_packages import AMENT

URDF = """<robot name="{name}"><link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""
SRDF_XACRO = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="$(arg name)">
  <xacro:arg name="name" default=""/>
  <group name="arm"><joint name="j1"/></group>
</robot>
"""
BRINGUP = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    config_package = LaunchConfiguration("moveit_config_package")
    description = Command([
        PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
        PathJoinSubstitution([FindPackageShare("tri_description"), "urdf", "tri.urdf.xacro"]),
        " robot_ip:=", LaunchConfiguration("robot_ip"),
    ])
    semantic = Command([
        PathJoinSubstitution([FindExecutable(name="xacro")]), " ",
        PathJoinSubstitution([FindPackageShare(config_package), "srdf", "tri.srdf.xacro"]),
        " name:=tri",
    ])
    return LaunchDescription([
        DeclareLaunchArgument("moveit_config_package", default_value="tri_moveit_config"),
        DeclareLaunchArgument("robot_ip"),
        Node(
            package="moveit_ros_move_group",
            executable="move_group",
            parameters=[{"robot_description": description}, {"robot_description_semantic": semantic}],
        ),
    ])
"""
URDF_XACRO = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="tri">
  <xacro:arg name="robot_ip" default=""/>
  <link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""


def _package(folder: Path, files: dict[str, str]) -> Path:
    for rel, text in {"package.xml": AMENT.format(name=folder.name), **files}.items():
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        (folder / rel).write_text(text, encoding="utf-8")
    return folder


def _repository(tmp_path: Path, bringups: dict[str, str]) -> Path:
    """A vendor repository: description, config (no launch folder) and bringup packages."""
    repo = tmp_path / "vendor_ros2"
    _package(repo / "tri_description", {"urdf/tri.urdf.xacro": URDF_XACRO, "urdf/old.urdf": URDF})
    for name, launch in bringups.items():
        _package(repo / name, {f"launch/{name}.launch.py": launch})
    return _package(
        repo / "tri_moveit_config",
        {"srdf/tri.srdf.xacro": SRDF_XACRO, "config/kinematics.yaml": "arm: {}\n"},
    )


def test_the_bringups_robot_and_srdf_are_what_move_group_loads(tmp_path: Path):
    config = _repository(tmp_path, {"tri_bringup": BRINGUP})
    found = read_package(config)
    assert found.urdf == config.parent / "tri_description" / "urdf" / "tri.urdf.xacro"
    assert found.urdf_origin.startswith("robot_description in tri_bringup/launch/tri_bringup.launch.py (")
    assert found.unread_xacro_args == ("robot_ip",)
    assert found.srdf_file is not None and found.srdf_file.path == "srdf/tri.srdf.xacro"
    assert found.srdf_file.srdf is not None and found.srdf_file.srdf.robot_name == "tri"  # name:=tri
    assert not [f for f in found.problems if f.severity == "error"]


def test_of_several_bringups_the_fewest_unknown_args_win_and_the_summary_says_so(tmp_path: Path):
    known = BRINGUP.replace('LaunchConfiguration("robot_ip")', '"10.0.0.2"')
    config = _repository(tmp_path, {"a_bringup": BRINGUP, "b_bringup": known})
    found = read_package(config)
    assert found.urdf_origin.startswith("robot_description in b_bringup/launch/b_bringup.launch.py (")
    assert "chosen among 2 such files" in found.urdf_origin
    assert found.xacro_args == (("robot_ip", "10.0.0.2"),)


@pytest.mark.parametrize(
    "change",
    [
        ("tri_moveit_config", "other_moveit_config"),  # launches another config package
        ('executable="move_group"', 'executable="talker"'),  # starts no MoveIt node...
    ],
)
def test_without_a_launch_file_starting_moveit_with_it_the_exit_2_message_stays(tmp_path: Path, change):
    launch = BRINGUP.replace(*change)
    if change[1] == 'executable="talker"':  # ...and hands no semantic description to one
        launch = launch.replace(', {"robot_description_semantic": semantic}', "")
    config = _repository(tmp_path, {"tri_bringup": launch})
    with pytest.raises(InputError, match="cannot find the robot description") as info:
        read_package(config)
    assert info.value.needs == "--urdf"


XML_BRINGUP = """<launch>
  <arg name="robot_ip" default="10.0.0.3"/>
  <node pkg="moveit_ros_move_group" exec="move_group">
    <param name="robot_description"
      value="$(command 'xacro $(find-pkg-share tri_description)/urdf/tri.urdf.xacro robot_ip:=$(var robot_ip)')"/>
    <param from="$(find-pkg-share tri_moveit_config)/config/kinematics.yaml"/>
  </node>
</launch>
"""


def test_a_ros2_xml_bringup_gives_its_robot_too(tmp_path: Path):
    config = _repository(tmp_path, {})
    _package(config.parent / "tri_bringup", {"launch/move_group.launch.xml": XML_BRINGUP})
    found = read_package(config)
    assert found.urdf == config.parent / "tri_description" / "urdf" / "tri.urdf.xacro"
    assert found.urdf_origin.startswith("robot_description in tri_bringup/launch/move_group.launch.xml (")
    assert found.xacro_args == (("robot_ip", "10.0.0.3"),)


HAND_LOADS = """
import os
import yaml
from ament_index_python.packages import get_package_share_directory


def load_yaml(package_name, file_path):
    with open(os.path.join(get_package_share_directory(package_name), file_path)) as file:
        return yaml.safe_load(file)


def moveit_parameters():
    controllers = {"moveit_simple_controller_manager": load_yaml("tri_moveit_config", "config/controllers.yaml")}
    return [{"robot_description_kinematics": load_yaml("tri_moveit_config", "config/kinematics.yaml")}, controllers]
"""
MOVEIT1_SENSORS = """sensors:
  - sensor_plugin: occupancy_map_monitor/PointCloudOctomapUpdater
    point_cloud_topic: /camera/points
"""
CONTROLLERS = (
    "controller_names: [arm_controller]\narm_controller:\n  type: FollowJointTrajectory\n  joints: [j1]\n"
)


def test_the_package_files_a_bringup_loads_by_hand_are_what_moveit_gets(tmp_path: Path):
    """A bringup that loads the config's kinematics and controllers by hand (the controller list
    under moveit_simple_controller_manager) and no sensors file: the MoveIt 1 sensors_3d.yaml the
    package keeps is not read (MoveIt never loads it), and the list is where the bringup puts it."""
    from marm_setup.validate.runner import validate

    launch = BRINGUP.replace(
        "def generate_launch_description():", HAND_LOADS + "\n\ndef generate_launch_description():"
    )
    launch = launch.replace(
        '{"robot_description_semantic": semantic}]',
        '{"robot_description_semantic": semantic}, *moveit_parameters()]',
    )
    config = _repository(tmp_path, {"tri_bringup": launch})
    _package(config, {"config/sensors_3d.yaml": MOVEIT1_SENSORS, "config/controllers.yaml": CONTROLLERS})
    found = read_package(config)
    assert found.sensors is None
    assert (
        found.moveit_controllers is not None
        and found.moveit_controllers.loaded_into == "moveit_simple_controller_manager"
    )
    rules = {f.rule for f in validate(config, plan=False).findings}
    assert not rules & {"params.type", "controller.no-namespace", "sensors.unknown-plugin"}, rules


def test_launch_args_given_reach_the_bringup_launch_file(tmp_path: Path):
    """`--launch-arg robot_ip:=...` is what the user starts the bringup with: its xacro arg is known."""
    config = _repository(tmp_path, {"tri_bringup": BRINGUP})
    found = read_package(config, launch_args={"robot_ip": "10.0.0.9"})
    assert found.xacro_args == (("robot_ip", "10.0.0.9"),) and found.unread_xacro_args == ()
