"""A launch file's `MoveItConfigsBuilder(...).robot_description(os.path.join(
get_package_share_directory("pkg"), "urdf/x.xacro"))` (lbr_fri_ros2_stack's move_group.launch.py)
names a description in another package: the builder joins it to its package path, an absolute
path wins, and move_group gets that file. validate took `.setup_assistant`'s instead; the two
differ here, so the robot checked was not the one MoveIt loads."""

from __future__ import annotations

from pathlib import Path

from marm_setup.package import read_package

LAUNCH = """import os

from ament_index_python import get_package_share_directory
from moveit_configs_utils import MoveItConfigsBuilder
from moveit_configs_utils.launches import generate_move_group_launch


def generate_launch_description():
    moveit_config = (
        MoveItConfigsBuilder("tri", package_name="tri_moveit_config")
        .robot_description(os.path.join(get_package_share_directory("tri_description"), "urdf/tri.urdf"))
        .to_moveit_configs()
    )
    return generate_move_group_launch(moveit_config)
"""
SETUP_ASSISTANT = """moveit_setup_assistant_config:
  urdf:
    package: tri_description
    relative_path: urdf/old.urdf
  srdf:
    relative_path: config/tri.srdf
"""
URDF = """<robot name="tri"><link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
  <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>
"""


def _package_xml(name: str) -> str:
    return (
        f'<?xml version="1.0"?><package format="3"><name>{name}</name><version>0.0.0</version>'
        '<description>t</description><maintainer email="a@b.c">a</maintainer><license>BSD</license>'
        "<buildtool_depend>ament_cmake</buildtool_depend><export><build_type>ament_cmake</build_type></export>"
        "</package>\n"
    )


def test_the_builders_description_in_another_package_is_the_one_validated(tmp_path: Path):
    desc = tmp_path / "tri_description"
    (desc / "urdf").mkdir(parents=True)
    (desc / "package.xml").write_text(_package_xml("tri_description"), encoding="utf-8")
    (desc / "urdf" / "tri.urdf").write_text(URDF, encoding="utf-8")
    (desc / "urdf" / "old.urdf").write_text(URDF.replace('"tri"', '"old"'), encoding="utf-8")
    pkg = tmp_path / "tri_moveit_config"
    (pkg / "config").mkdir(parents=True)
    (pkg / "launch").mkdir()
    (pkg / "package.xml").write_text(_package_xml("tri_moveit_config"), encoding="utf-8")
    (pkg / ".setup_assistant").write_text(SETUP_ASSISTANT, encoding="utf-8")
    (pkg / "config" / "tri.srdf").write_text('<robot name="tri"/>\n', encoding="utf-8")
    (pkg / "launch" / "move_group.launch.py").write_text(LAUNCH, encoding="utf-8")
    found = read_package(pkg, package_paths=[tmp_path])
    assert found.urdf == desc / "urdf" / "tri.urdf"
    assert (
        found.urdf_origin
        == "MoveItConfigsBuilder.robot_description(file_path) in launch/move_group.launch.py"
    )
