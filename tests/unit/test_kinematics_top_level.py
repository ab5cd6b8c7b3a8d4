"""kinematics.top-level: groups a launch file hands to move_group as its own top-level
parameters (`<group>.kinematics_solver`) are found by Humble's kinematics plugin loader only
(moveit2 humble kinematics_plugin_loader.cpp l.306-319); Jazzy, Kilted and Rolling look only at
`robot_description_kinematics.<group>` (jazzy l.258-272, main l.260): the group has no IK solver.
MoveItConfigsBuilder wraps the file itself; a dict keyed robot_description_kinematics does too."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.validate import validate

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>tri_moveit_config</name><version>0.0.0</version>
<description>t</description><maintainer email="a@example.com">a</maintainer><license>BSD</license>
<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export>
</package>
"""
URDF = """<robot name="tri"><link name="base"/><link name="l1"/><link name="l2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><axis xyz="0 1 0"/>
  <origin xyz="0 0 0.1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""
SRDF = '<robot name="tri"><group name="arm"><chain base_link="base" tip_link="l2"/></group></robot>\n'
GROUPS = "arm:\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n  kinematics_solver_timeout: 0.05\n"
PYTHON_LAUNCH = """import os
import yaml
from launch import LaunchDescription
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory


def load_yaml(package_name, file_path):
    with open(os.path.join(get_package_share_directory(package_name), file_path)) as f:
        return yaml.safe_load(f)


def generate_launch_description():
    kinematics_yaml = load_yaml("tri_moveit_config", "config/kinematics.yaml")
    move_group = Node(package="moveit_ros_move_group", executable="move_group", parameters=[ITEM])
    return LaunchDescription([move_group])
"""
XML_LAUNCH = """<launch>
  <node pkg="moveit_ros_move_group" exec="move_group" output="screen">
    <param from="$(find-pkg-share tri_moveit_config)/config/kinematics.yaml"/>
  </node>
</launch>
"""


def _package(root: Path, kinematics: str, launch: tuple[str, str]) -> Path:
    pkg = root / "tri_moveit_config"
    (pkg / "config").mkdir(parents=True)
    (pkg / "launch").mkdir()
    (pkg / "package.xml").write_text(PACKAGE_XML, encoding="utf-8")
    (pkg / "config" / "tri.srdf").write_text(SRDF, encoding="utf-8")
    (pkg / "config" / "kinematics.yaml").write_text(kinematics, encoding="utf-8")
    (pkg / "launch" / launch[0]).write_text(launch[1], encoding="utf-8")
    (root / "tri.urdf").write_text(URDF, encoding="utf-8")
    return pkg


def _top_level(root: Path, kinematics: str, launch: tuple[str, str], distro: str | None):
    pkg = _package(root, kinematics, launch)
    found = validate(
        pkg, urdf=root / "tri.urdf", srdf=pkg / "config" / "tri.srdf", plan=False, ros_distro=distro
    ).findings
    return [(f.severity, f.file, f.element) for f in found if f.rule == "kinematics.top-level"]


BARE = ("move_group.launch.py", PYTHON_LAUNCH.replace("ITEM", "kinematics_yaml"))
KEYED = (
    "move_group.launch.py",
    PYTHON_LAUNCH.replace("ITEM", '{"robot_description_kinematics": kinematics_yaml}'),
)
XML = ("move_group.launch.xml", XML_LAUNCH)
BUILDER = (
    "demo.launch.py",
    """from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_demo_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder("tri", package_name="tri_moveit_config").to_moveit_configs()
    return generate_demo_launch(moveit_config)
""",
)
ROS2_GROUPS = "/**:\n  ros__parameters:\n" + "".join(f"    {line}\n" for line in GROUPS.splitlines())
ROS2_NESTED = "/**:\n  ros__parameters:\n    robot_description_kinematics:\n" + "".join(
    f"      {line}\n" for line in GROUPS.splitlines()
)


@pytest.mark.parametrize("distro", ["jazzy", "kilted", "rolling"])
def test_groups_listed_bare_among_move_groups_parameters_have_no_solver_on_jazzy_and_later(tmp_path, distro):
    assert _top_level(tmp_path, GROUPS, BARE, distro) == [("error", "config/kinematics.yaml", "arm")]


def test_humble_finds_them_and_an_unknown_distro_is_a_warning(tmp_path):
    assert _top_level(tmp_path / "h", GROUPS, BARE, "humble") == []
    assert _top_level(tmp_path / "u", GROUPS, BARE, None) == [("warning", "config/kinematics.yaml", "arm")]


def test_a_dict_keyed_robot_description_kinematics_is_read_everywhere(tmp_path):
    assert _top_level(tmp_path / "keyed", GROUPS, KEYED, "jazzy") == []
    # MoveItConfigsBuilder puts the file under robot_description_kinematics itself
    assert _top_level(tmp_path / "builder", GROUPS, BUILDER, "jazzy") == []


def test_a_parameter_file_an_xml_launch_hands_to_move_group(tmp_path):
    assert _top_level(tmp_path / "top", ROS2_GROUPS, XML, "jazzy") == [
        ("error", "config/kinematics.yaml", "/**.ros__parameters.arm")
    ]
    assert _top_level(tmp_path / "nested", ROS2_NESTED, XML, "jazzy") == []
