"""The static rules for what the ROS 2 launcher and rcl fail on though every file parses:
`$(command)` around a command that writes to stderr, an empty map or list in a parameter file,
a path that climbs out of the share folder, a demo on real hardware; and the evaluation of ROS 2
XML launch substitutions they stand on (validate/launch_eval.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from lxml import etree

from marm_setup.robot.ros_packages import find_packages
from marm_setup.validate.launch_eval import LaunchEvaluator, parse_call
from marm_setup.validate.rules.ros2_launch_rules import (
    _climbs_out,
    check_command_stderr,
    check_demo_hardware,
    launch_scope,
)
from marm_setup.validate.rules.ros2_params_rules import empty_values
from tests.helpers import build_file_tree

PKG = "<package format='3'><name>{name}</name></package>"
WARNS = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r">
  <xacro:property name="pi" value="3.14"/>
  <link name="a"/>
</robot>
"""
QUIET = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r"><link name="a"/></robot>\n'
ROBOT_WITH = (
    '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="r"><link name="a"/>'
    '<xacro:arg name="mock" default="true"/>'
    '<ros2_control name="arm" type="system"><hardware>'
    '<xacro:if value="$(arg mock)"><plugin>mock_components/GenericSystem</plugin></xacro:if>'
    '<xacro:unless value="$(arg mock)"><plugin>acme/Arm</plugin></xacro:unless>'
    '</hardware><joint name="j"/></ros2_control></robot>\n'
)


def test_parse_call_keeps_nested_substitutions_and_quotes_apart():
    text = "x $(command 'xacro $(find-pkg-share p)/a.xacro m:=$(var m)' warn) y"
    call = parse_call(text, 2)
    assert call.name == "command"
    assert call.args == ("xacro $(find-pkg-share p)/a.xacro m:=$(var m)", "warn")
    assert text[call.end :] == " y"
    assert parse_call("$(var x", 0) is None


def _evaluator(tmp_path: Path, launch: str) -> tuple[object, LaunchEvaluator]:
    tree = etree.fromstring(launch.encode())
    packages = find_packages([tmp_path], environ={})
    return tree, LaunchEvaluator(tmp_path / "p" / "launch", packages, launch_scope(tree))


@pytest.fixture
def package(tmp_path):
    return build_file_tree(
        tmp_path,
        {
            "p/package.xml": PKG.format(name="p"),
            "p/config/warns.urdf.xacro": WARNS,
            "p/config/quiet.urdf.xacro": QUIET,
            "p/config/robot.urdf.xacro": ROBOT_WITH,
        },
    )


def test_the_evaluator_resolves_var_find_pkg_share_and_commands(package):
    launch = """<launch><arg name="f" default="quiet"/><let name="d" value="$(command 'xacro $(find-pkg-share p)/config/$(var f).urdf.xacro')"/></launch>"""
    _, ev = _evaluator(package, launch)
    assert ev.value("$(find-pkg-share p)/x") == f"{package / 'p'}/x"
    assert '<link name="a"/>' in ev.value("$(var d)")
    assert ev.value("$(env HOME)") is None  # not evaluated without ROS: unknown, not guessed
    assert ev.value("$(var nothing)") is None


@pytest.mark.parametrize(
    ("file", "on_stderr", "errors"),
    [("warns", "", 1), ("warns", " warn", 0), ("warns", " ignore", 0), ("quiet", "", 0)],
)
def test_command_fails_on_stderr_unless_told_otherwise(package, file, on_stderr, errors):
    launch = f"""<launch><node pkg="robot_state_publisher" exec="robot_state_publisher">
      <param name="robot_description" value="$(command 'xacro $(find-pkg-share p)/config/{file}.urdf.xacro'{on_stderr})" type="str"/>
    </node></launch>"""
    tree, ev = _evaluator(package, launch)
    found = check_command_stderr(tree, "launch/x.launch.xml", ev)
    assert len(found) == errors
    if errors:
        assert "redefining global symbol: pi" in found[0].message
        assert found[0].element == "line 2: param[robot_description]"


@pytest.mark.parametrize(("mock", "errors"), [("true", 0), ("false", 1)])
def test_demo_hardware_is_the_description_with_default_args(package, mock, errors):
    launch = f"""<launch><arg name="use_mock" default="{mock}"/>
      <let name="robot_description" value="$(command 'xacro $(find-pkg-share p)/config/robot.urdf.xacro mock:=$(var use_mock)' warn)"/>
      <node pkg="robot_state_publisher" exec="robot_state_publisher"><param name="robot_description" value="$(var robot_description)" type="str"/></node>
      <node pkg="controller_manager" exec="ros2_control_node"><param name="robot_description" value="$(var robot_description)" type="str"/></node>
    </launch>"""
    tree, ev = _evaluator(package, launch)
    found = check_demo_hardware(tree, "launch/demo.launch.xml", ev, "jazzy")
    assert len(found) == errors  # once per system, not per node
    if errors:
        assert "'arm' on 'acme/Arm'" in found[0].message


def test_a_node_switched_off_by_its_if_is_not_started(package):
    launch = """<launch><node pkg="robot_state_publisher" exec="robot_state_publisher" if="false">
      <param name="robot_description" value="$(command 'xacro $(find-pkg-share p)/config/robot.urdf.xacro mock:=false' warn)" type="str"/>
    </node></launch>"""
    tree, ev = _evaluator(package, launch)
    assert check_demo_hardware(tree, "launch/demo.launch.xml", ev, "jazzy") == []


@pytest.mark.parametrize(
    ("tail", "depth", "out"),
    [
        ("/../../x", 0, True),
        ("/config/../config/x", 0, False),
        ("/../config/x", 1, False),
        ("/../../x", 1, True),
        ("/./x", 0, False),
    ],
)
def test_climbing_out_of_the_share_folder(tail, depth, out):
    assert _climbs_out(tail, depth) is out


@pytest.mark.parametrize("target", ["ros2", "ros1"])
def test_a_path_out_of_the_package_is_an_error_on_ros2_a_warning_on_ros1(tmp_path, target):
    from marm_setup.package.launch_xml import parse_launch
    from marm_setup.package.model import MoveItPackage
    from marm_setup.validate.rules.ros2_launch_rules import check_install_paths

    root = build_file_tree(
        tmp_path / "p",
        {
            "launch/demo.launch.xml": '<launch><include file="$(dirname)/../launch/x.xml"/></launch>',
            "config/r.urdf.xacro": '<robot><xacro:include filename="$(find p)/../../robot.urdf"/></robot>',
        },
    )
    pkg = MoveItPackage(
        root,
        str(root),
        "p",
        target,
        "marm_ros2",
        root / "r.urdf",
        "--urdf",
        launch=(parse_launch(root / "launch/demo.launch.xml", "launch/demo.launch.xml"),),
    )
    (finding,) = check_install_paths(pkg)
    assert (finding.file, finding.element, finding.severity) == (
        "config/r.urdf.xacro",
        "line 1",
        "error" if target == "ros2" else "warning",
    )


def test_empty_maps_and_lists_under_ros_parameters():
    data = {
        "/**": {"ros__parameters": {"k": {}, "a": {"b": []}, "ok": {"x": 1}, "s": ""}},
        "ns": {"node": {"ros__parameters": {"e": {}}}},
        "not_params": {"x": {}},
    }
    assert list(empty_values(data)) == [
        ("/**.ros__parameters.k", "map"),
        ("/**.ros__parameters.a.b", "list"),
        ("ns.node.ros__parameters.e", "map"),
    ]
    assert list(empty_values({"n": {"ros__parameters": {}}})) == []  # a node without parameters
