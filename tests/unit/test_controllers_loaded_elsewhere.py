"""controller.no-namespace when no launch file of the package loads MoveIt's controller list:
abb_ros2's robot_specific_config/*_moveit_config has no launch folder, and abb_bringup's
abb_moveit.launch.py hands config/moveit_controllers.yaml (top-level `controller_names`) to
move_group as `{"moveit_simple_controller_manager": load_yaml(...)}`. The key the list lands
under is that other package's launch file's to say: a warning. A launch of the package that
runs MoveItConfigsBuilder hands the file over as it is: still an error."""

from __future__ import annotations

from pathlib import Path

from marm_setup.package import read_package
from marm_setup.validate.rules.controller_rules import check_ros2_namespace

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>tri_moveit_config</name><version>0.0.0</version>
<description>t</description><maintainer email="a@b.c">a</maintainer><license>BSD</license>
<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export>
</package>
"""
CONTROLLERS = """moveit_controller_manager: moveit_simple_controller_manager/MoveItSimpleControllerManager
controller_names: [arm_controller]
arm_controller: {action_ns: follow_joint_trajectory, type: FollowJointTrajectory, default: true, joints: [j1]}
"""
BUILDER_LAUNCH = """from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_demo_launch


def generate_launch_description():
    moveit_config = MoveItConfigsBuilder("tri", package_name="tri_moveit_config").to_moveit_configs()
    return generate_demo_launch(moveit_config)
"""
URDF = """<robot name="tri"><link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""
SRDF = '<robot name="tri"><group name="arm"><joint name="j1"/></group></robot>\n'


def _package(root: Path, launch: bool) -> Path:
    pkg = root / "tri_moveit_config"
    (pkg / "config").mkdir(parents=True)
    (pkg / "package.xml").write_text(PACKAGE_XML, encoding="utf-8")
    (pkg / "config" / "moveit_controllers.yaml").write_text(CONTROLLERS, encoding="utf-8")
    (pkg / "config" / "tri.srdf").write_text(SRDF, encoding="utf-8")
    (root / "tri.urdf").write_text(URDF, encoding="utf-8")
    if launch:
        (pkg / "launch").mkdir()
        (pkg / "launch" / "demo.launch.py").write_text(BUILDER_LAUNCH, encoding="utf-8")
    return pkg


def test_a_list_no_launch_of_the_package_loads_is_a_warning(tmp_path):
    moveit = read_package(
        _package(tmp_path / "bare", launch=False), urdf=tmp_path / "bare" / "tri.urdf"
    ).moveit_controllers
    assert moveit is not None and moveit.load_unknown
    found = check_ros2_namespace(moveit)
    assert [(f.rule, f.severity) for f in found] == [("controller.no-namespace", "warning")]
    assert "no launch file of this package" in found[0].message


def test_a_list_the_packages_builder_loads_is_an_error(tmp_path):
    moveit = read_package(
        _package(tmp_path / "built", launch=True), urdf=tmp_path / "built" / "tri.urdf"
    ).moveit_controllers
    assert moveit is not None and not moveit.load_unknown
    assert [(f.rule, f.severity) for f in check_ros2_namespace(moveit)] == [
        ("controller.no-namespace", "error")
    ]


BRANCHED_LAUNCH = """import os
from launch import LaunchDescription
from launch_ros.actions import Node


def load_yaml(package_name, file_path):
    return {}


def generate_launch_description():
    if not os.environ.get("TRI_GRIPPER"):
        controllers_yaml = load_yaml("tri_moveit_config", "config/moveit_controllers.yaml")
    else:
        controllers_yaml = load_yaml("tri_moveit_config", "config/gripper_controllers.yaml")
    moveit_controllers = {"moveit_simple_controller_manager": controllers_yaml}
    return LaunchDescription([Node(package="moveit_ros_move_group", executable="move_group",
                                   parameters=[moveit_controllers])])
"""


def test_a_list_a_launch_loads_in_either_branch_of_an_if_lands_under_its_key(tmp_path):
    """IFRA-Cranfield's irb120_ros2_moveit2 binds its controller YAML in both branches of an if
    and hands it over under moveit_simple_controller_manager: each branch's file lands there."""
    pkg = _package(tmp_path, launch=False)
    (pkg / "launch").mkdir()
    (pkg / "launch" / "tri.launch.py").write_text(BRANCHED_LAUNCH, encoding="utf-8")
    moveit = read_package(pkg, urdf=tmp_path / "tri.urdf").moveit_controllers
    assert moveit is not None
    assert check_ros2_namespace(moveit) == []
