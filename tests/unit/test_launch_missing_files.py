"""A parameter file a launch file loads that does not exist (validate/rules/launch_rules.py
check_paths): an error where the launcher stops (roslaunch's <rosparam file>) or the node starts
without it (launch_ros skips a <param from> that is not a file); a warning on a branch only
non-default launch args take."""

from __future__ import annotations

from lxml import etree

from marm_setup.validate.rules.launch_rules import check_paths
from tests.helpers import build_file_tree

ROS1 = """<launch>
  <arg name="sim" default="false"/>
  <rosparam file="$(find bot_moveit_config)/config/{first}.yaml" command="load"/>
  <group if="$(arg sim)">
    <rosparam file="$(find bot_moveit_config)/config/{second}.yaml" command="load"/>
  </group>
</launch>
"""
ROS2 = """<launch>
  <arg name="use_servo" default="false"/>
  <node pkg="moveit_ros_move_group" exec="move_group">
    <param from="$(find-pkg-share bot_moveit_config)/config/{first}.yaml"/>
  </node>
  <node pkg="moveit_servo" exec="servo_node" if="$(var use_servo)">
    <param from="$(find-pkg-share bot_moveit_config)/config/{second}.yaml"/>
  </node>
</launch>
"""


def found(tmp_path, text: str, ros2: bool) -> list[tuple[str, str, str]]:
    root = build_file_tree(tmp_path, {"launch/x.launch": text, "config/here.yaml": "a: 1\n"})
    tree = etree.parse(str(root / "launch/x.launch")).getroot()
    return [
        (str(f.severity), f.element.split(": ")[0], f.message)
        for f in check_paths(tree, "launch/x.launch", root, "bot_moveit_config", ros2)
    ]


def test_ros1_rosparam_file_missing_stops_roslaunch_unless_on_a_non_default_branch(tmp_path):
    out = found(tmp_path, ROS1.format(first="gone", second="gone_too"), ros2=False)
    assert [(s, line) for s, line, _ in out] == [("error", "line 3"), ("warning", "line 5")]
    assert "roslaunch stops" in out[0][2] and "non-default launch args" in out[1][2]
    assert found(tmp_path / "ok", ROS1.format(first="here", second="here"), ros2=False) == []


def test_ros2_param_file_missing_leaves_the_node_without_it(tmp_path):
    out = found(tmp_path, ROS2.format(first="gone", second="gone_too"), ros2=True)
    assert [(s, line) for s, line, _ in out] == [("error", "line 4"), ("warning", "line 7")]
    assert "the node starts without these parameters" in out[0][2]
    sim = ROS2.replace('default="false"', 'default="true"').format(first="here", second="gone")
    assert [(s, line) for s, line, _ in found(tmp_path / "b", sim, ros2=True)] == [("error", "line 7")]


GDB = """<launch>
  <arg name="debug" default="false"/>
  <arg unless="$(arg debug)" name="launch_prefix" value=""/>
  <arg if="$(arg debug)" name="launch_prefix" value="gdb -x $(dirname)/gdb_settings.gdb --ex run --args"/>
  <arg name="rviz_config" default="$(find bot_moveit_config)/launch/{config}"/>
</launch>
"""


def test_a_path_no_launcher_opens_on_a_branch_the_defaults_skip_is_no_finding(tmp_path):
    """MoveIt's Setup Assistant template: gdb_settings.gdb, never written, only with debug:=true."""
    assert found(tmp_path, GDB.format(config="moveit.rviz"), ros2=False) == [
        (
            "warning",
            "line 5",
            "default refers to '$(find bot_moveit_config)/launch/moveit.rviz', which does not exist",
        )
    ]  # on the branch the defaults take, a likely mistake still
    debug = GDB.replace('name="debug" default="false"', 'name="debug" default="true"')
    assert [line for _, line, _ in found(tmp_path / "d", debug.format(config="x.rviz"), ros2=False)] == [
        "line 4",
        "line 5",
    ]
