"""Package layout discovery: what the launch files load, `srdf/`, `*.srdf.xacro` with the launch
args, config sub-folders, the URDF paired by robot name, `--srdf` / `--xacro-arg`, and a
`.setup_assistant` naming a missing SRDF. Each case writes a small package into tmp_path."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.errors import InputError
from marm_setup.package.read import read_package

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2"><name>{name}</name><version>0.1.0</version><description>x</description>
<maintainer email="a@b.c">a</maintainer><license>BSD</license>
<buildtool_depend>{build}</buildtool_depend></package>
"""
URDF = """<robot name="{robot}">
  <link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
SRDF = """<?xml version="1.0" ?>
<robot name="{robot}">
  <group name="{group}"><joint name="j1"/></group>
</robot>
"""
SRDF_XACRO = """<?xml version="1.0" ?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="bot">
  <xacro:arg name="arm" default="none"/>
  <group name="$(arg arm)_arm"><joint name="j1"/></group>
</robot>
"""
CONTEXT = """<launch>
  <arg name="arm" default="left"/>
  <param name="robot_description_semantic"
         command="$(find xacro)/xacro '$(find pkg)/config/bot.srdf.xacro' arm:=$(arg arm)"/>
  <rosparam command="load" file="$(find pkg)/config/7dof/joint_limits.yaml" ns="robot_description_planning"/>
</launch>
"""


def write(root: Path, files: dict[str, str]) -> Path:
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text, encoding="utf-8")
    return root


@pytest.fixture
def urdf(tmp_path) -> Path:
    return write(tmp_path / "desc", {"bot.urdf": URDF.format(robot="bot")}) / "bot.urdf"


def ros1(tmp_path, files) -> Path:
    return write(tmp_path / "pkg", {"package.xml": PACKAGE_XML.format(name="pkg", build="catkin"), **files})


def test_srdf_in_an_srdf_folder(tmp_path, urdf):
    pkg = ros1(tmp_path, {"srdf/bot.srdf": SRDF.format(robot="bot", group="arm")})
    found = read_package(pkg, urdf=urdf)
    assert found.srdf_path == "srdf/bot.srdf"
    assert [g.name for g in found.srdf.groups] == ["arm"]


def test_srdf_xacro_expanded_with_the_args_the_launch_file_passes(tmp_path, urdf):
    pkg = ros1(
        tmp_path,
        {
            "config/bot.srdf.xacro": SRDF_XACRO,
            "launch/planning_context.launch": CONTEXT,
            "config/7dof/joint_limits.yaml": "joint_limits: {}\n",
        },
    )
    found = read_package(pkg, urdf=urdf)
    assert (found.srdf_path, [g.name for g in found.srdf.groups]) == ("config/bot.srdf.xacro", ["left_arm"])
    # --xacro-arg overrides what discovery found
    found = read_package(pkg, urdf=urdf, xacro_args={"arm": "right"})
    assert [g.name for g in found.srdf.groups] == ["right_arm"]
    # config sub-folders: the limits file the launch file loads
    assert found.joint_limits.where.file == "config/7dof/joint_limits.yaml"


def test_the_urdf_is_paired_by_the_srdf_robot_name(tmp_path):
    """MoveIt 2: config/<robot>.urdf.xacro for the SRDF's <robot name>, not the SRDF file name."""
    pkg = write(
        tmp_path / "pkg",
        {
            "package.xml": PACKAGE_XML.format(name="pkg", build="ament_cmake"),
            "config/bot_arm_hand.srdf": SRDF.format(robot="bot", group="arm"),
            "config/aaa.urdf.xacro": URDF.format(robot="aaa"),
            "config/bot.urdf.xacro": URDF.format(robot="bot"),
        },
    )
    assert read_package(pkg).urdf.name == "bot.urdf.xacro"


def test_explicit_srdf(tmp_path, urdf):
    pkg = ros1(tmp_path, {"config/bot.srdf": SRDF.format(robot="bot", group="arm")})
    other = write(tmp_path, {"elsewhere/other.srdf": SRDF.format(robot="bot", group="other")})
    found = read_package(pkg, urdf=urdf, srdf=other / "elsewhere/other.srdf")
    assert (found.srdf_path, [g.name for g in found.srdf.groups]) == ("../elsewhere/other.srdf", ["other"])
    with pytest.raises(InputError, match="file not found"):
        read_package(pkg, urdf=urdf, srdf=tmp_path / "nope.srdf")


def test_setup_assistant_naming_a_missing_srdf_is_a_warning(tmp_path, urdf):
    """Only the Setup Assistant reads .setup_assistant; move_group loads the SRDF that exists."""
    sa = "moveit_setup_assistant_config:\n  SRDF:\n    relative_path: config/gone.srdf\n"
    pkg = ros1(tmp_path, {".setup_assistant": sa, "config/bot.srdf": SRDF.format(robot="bot", group="arm")})
    found = read_package(pkg, urdf=urdf)
    assert found.srdf_path == "config/bot.srdf"  # the other rules still run on the one that exists
    assert [(f.rule, f.severity, f.file, f.element) for f in found.problems] == [
        ("srdf.missing", "warning", ".setup_assistant", "SRDF.relative_path")
    ]
