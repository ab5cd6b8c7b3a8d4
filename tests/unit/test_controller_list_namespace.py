"""MoveIt 1's simple controller manager reads `controller_list` from move_group's private
namespace only (moveit_simple_controller_manager.cpp: `node_handle_("~")`): a list a launch file
loads under another namespace is never read. Each case writes a small ROS 1 package into tmp_path
and validates it as the static reader sees it (no roslaunch: tests/integration/
test_controller_list_roslaunch.py runs the real one on the same packages)."""

from __future__ import annotations

from pathlib import Path

import pytest

from marm_setup.package.read import read_package
from marm_setup.validate import validate

PACKAGE_XML = """<?xml version="1.0"?>
<package format="2"><name>pkg</name><version>0.1.0</version><description>x</description>
<maintainer email="a@example.com">a</maintainer><license>BSD</license>
<buildtool_depend>catkin</buildtool_depend></package>
"""
URDF = """<robot name="bot">
  <link name="base"/><link name="l1"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>
"""
SRDF = """<?xml version="1.0" ?>
<robot name="bot"><group name="arm"><joint name="j1"/></group></robot>
"""
CONTROLLERS = """controller_list:
  - name: arm_controller
    action_ns: follow_joint_trajectory
    type: FollowJointTrajectory
    default: true
    joints: [j1]
"""
CONTEXT = """<launch>
  <param name="robot_description" textfile="$(find pkg)/config/bot.urdf"/>
  <param name="robot_description_semantic" textfile="$(find pkg)/config/bot.srdf"/>
</launch>
"""
SIMPLE = "moveit_simple_controller_manager/MoveItSimpleControllerManager"
EXECUTION = """<launch>
  <param name="moveit_controller_manager" value="{simple}"/>
{load}
</launch>
"""
MOVE_GROUP = """<launch>
  <include file="$(find pkg)/launch/planning_context.launch"/>
{before}
  <include ns="move_group" file="$(find pkg)/launch/trajectory_execution.launch.xml"/>
{after}
  <node name="move_group" pkg="moveit_ros_move_group" type="move_group" respawn="false"/>
</launch>
"""
LOAD = '  <rosparam command="load" file="$(find pkg)/config/controllers.yaml"{ns}/>'
ROS_CONTROL = """<launch>
  <rosparam command="load" file="$(find pkg)/config/controllers.yaml" ns="arm_driver"/>
</launch>
"""


def ros1_package(root: Path, load: str, before: str = "", after: str = "", extra=None) -> Path:
    """A ROS 1 MoveIt package whose move_group.launch includes trajectory_execution.launch.xml
    under ns="move_group" (the Setup Assistant's layout); `load` is that file's controller list
    load, `before` / `after` what move_group.launch holds around the include."""
    files = {
        "package.xml": PACKAGE_XML,
        "config/bot.urdf": URDF,
        "config/bot.srdf": SRDF,
        "config/controllers.yaml": CONTROLLERS,
        "launch/planning_context.launch": CONTEXT,
        "launch/trajectory_execution.launch.xml": EXECUTION.format(simple=SIMPLE, load=load),
        "launch/move_group.launch": MOVE_GROUP.format(before=before, after=after),
        **(extra or {}),
    }
    for rel, text in files.items():
        (root / rel).parent.mkdir(parents=True, exist_ok=True)
        (root / rel).write_text(text, encoding="utf-8")
    return root


# the three packages of the rule (tests/integration/test_controller_list_roslaunch.py runs them too)
CASES = {
    "manager-namespace": dict(load=LOAD.format(ns=' ns="moveit_simple_controller_manager"')),
    "twice": dict(
        load=LOAD.format(ns=""),
        before='  <include file="$(find pkg)/launch/ros_controllers.launch"/>',
        extra={"launch/ros_controllers.launch": ROS_CONTROL},
    ),
    "group-outside-include": dict(
        load="", after=f'  <group ns="move_group">\n  {LOAD.format(ns="")}\n  </group>'
    ),
}


def list_namespace(found) -> list:
    return [f for f in found.findings if f.rule == "controller.list-namespace"]


@pytest.fixture(autouse=True)
def no_roslaunch(monkeypatch):
    """The static reader alone: validate must find the defect without roslaunch."""
    monkeypatch.setenv("MARM_SETUP_ROSLAUNCH", "")


def test_a_list_under_the_managers_namespace_is_never_read(tmp_path):
    """`<rosparam ns="moveit_simple_controller_manager">` inside move_group's include: the list
    lands at /move_group/moveit_simple_controller_manager/controller_list."""
    pkg = ros1_package(tmp_path / "pkg", **CASES["manager-namespace"])
    found = validate(pkg, plan=False)
    [finding] = list_namespace(found)
    assert (finding.severity, finding.file, finding.element) == (
        "error",
        "launch/trajectory_execution.launch.xml",
        "line 3: <rosparam>",
    )
    assert "'/move_group/moveit_simple_controller_manager'" in finding.message
    assert "'/move_group/controller_list'" in finding.message
    assert "move_group's namespace" in finding.hint
    assert "static rules only" in found.launched_by


def test_the_same_file_loaded_for_ros_control_and_for_move_group_is_read(tmp_path):
    """A ros_control namespace first, then move_group's: any load at move_group's is the one."""
    found = validate(ros1_package(tmp_path / "pkg", **CASES["twice"]), plan=False)
    assert list_namespace(found) == []
    assert [f for f in found.findings if f.is_error] == []


def test_a_list_loaded_by_a_group_outside_the_include_is_read(tmp_path):
    """`<group ns="move_group">` in move_group.launch, beside the include: same namespace."""
    found = validate(ros1_package(tmp_path / "pkg", **CASES["group-outside-include"]), plan=False)
    assert list_namespace(found) == []
    assert [f for f in found.findings if f.is_error] == []


def test_a_move_group_in_a_namespace_reads_its_own(tmp_path):
    """The node under `<group ns="robot1">` but the include still under ns="move_group": the list
    lands at /move_group/controller_list, move_group reads /robot1/move_group/controller_list."""
    pkg = ros1_package(tmp_path / "pkg", load=LOAD.format(ns=""))
    launch = pkg / "launch/move_group.launch"
    node = '<node name="move_group" pkg="moveit_ros_move_group" type="move_group" respawn="false"/>'
    launch.write_text(launch.read_text().replace(node, f'<group ns="robot1">{node}</group>'))
    [finding] = list_namespace(validate(pkg, plan=False))
    assert finding.file == "launch/trajectory_execution.launch.xml"
    assert "into '/move_group'" in finding.message
    assert "'/robot1/move_group/controller_list'" in finding.message


def test_the_last_load_in_move_groups_namespace_wins(tmp_path):
    """Two list files in move_group's namespace: rosparam overwrites, MoveIt reads the last."""
    other = CONTROLLERS.replace("arm_controller", "other_controller")
    load = LOAD.format(ns="") + "\n" + LOAD.format(ns="").replace("controllers.yaml", "other.yaml")
    pkg = ros1_package(tmp_path / "pkg", load=load, extra={"config/other.yaml": other})
    assert list_namespace(validate(pkg, plan=False)) == []
    listed = read_package(pkg).moveit_controllers
    assert listed is not None
    assert [c.name for c in listed.controllers] == ["other_controller"]


def list_not_loaded(found) -> list:
    return [f for f in found.findings if f.rule == "controller.list-not-loaded"]


def test_the_simple_manager_with_no_list_loaded_anywhere_is_a_warning(tmp_path):
    """The manager is set on move_group's namespace but no launch file loads a list (the
    Setup Assistant's file sits unloaded in config/): MoveIt reads none. A warning, as a launch
    file of another package may load one."""
    found = validate(ros1_package(tmp_path / "pkg", load=""), plan=False)
    [finding] = list_not_loaded(found)
    assert (finding.severity, finding.file) == ("warning", "launch/trajectory_execution.launch.xml")
    assert "config/controllers.yaml is never loaded" in finding.message
    assert list_namespace(found) == []


def test_no_list_warning_when_a_list_is_loaded_or_another_manager_is_set(tmp_path):
    assert list_not_loaded(validate(ros1_package(tmp_path / "a", load=LOAD.format(ns="")), plan=False)) == []
    pkg = ros1_package(tmp_path / "b", load="")
    execution = pkg / "launch/trajectory_execution.launch.xml"
    execution.write_text(
        execution.read_text().replace(SIMPLE, "moveit_ros_control_interface::MoveItControllerManager")
    )
    assert list_not_loaded(validate(pkg, plan=False)) == []
    pkg = ros1_package(tmp_path / "c", load="")  # the simple manager only on a branch the defaults skip
    execution = pkg / "launch/trajectory_execution.launch.xml"
    text = execution.read_text().replace(
        "<param name=", '<arg name="simple" default="false"/>\n  <param if="$(arg simple)" name='
    )
    execution.write_text(text)
    assert list_not_loaded(validate(pkg, plan=False)) == []
