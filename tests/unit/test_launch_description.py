"""validate loads the robot MoveIt 1 loads: `robot_description` and its `_semantic` as the
package's launch files set them (xacro command lines read as xacro reads them, `textfile=`, a
`.srdf.xacro` in the description package), before `.setup_assistant`, which MoveIt never reads."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from marm_setup.package.read import read_package
from marm_setup.robot.xacro_cli import parse_xacro_command
from marm_setup.robot.xacro_command import main as xacro_main
from marm_setup.validate.runner import validate
from tests.helpers import build_file_tree
from tests.vendor_packages import AMENT, CATKIN, _arm_urdf, _srdf


@pytest.mark.parametrize(
    ("command", "file", "args"),
    [
        ("xacro FILE", "FILE", ()),
        ("/opt/ros/share/xacro/xacro --inorder ns:=x FILE a:=b", "FILE", (("a", "b"), ("ns", "x"))),
        ("rosrun xacro xacro 'FILE' -o out.urdf", "FILE", ()),
        ("python3 /x/xacro.py --verbosity 2 FILE __name:=n _private:=p", "FILE", (("__name", "n"),)),
        ("xacro --root-dir /r -i  FILE", "FILE", ()),
    ],
)
def test_xacro_command_lines_are_read_as_xacro_reads_them(command, file, args):
    call = parse_xacro_command(command)
    assert call is not None and (call.file, call.args) == (file, args)


def test_a_command_that_is_not_xacro_names_no_file():
    assert parse_xacro_command("cat robot.urdf") is None


def test_the_fallback_xacro_takes_mappings_before_the_file(tmp_path, capsys):
    robot = tmp_path / "r.urdf.xacro"
    robot.write_text(
        '<robot name="$(arg n)" xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:arg name="n" default="d"/>'
        '<link name="a"/></robot>'
    )
    assert xacro_main(["--inorder", "n:=given", str(robot)]) == 0
    assert 'name="given"' in capsys.readouterr().out


PLANNING_CONTEXT = """<launch>
  <arg name="load_robot_description" default="false"/>
  <arg name="robot_description" default="robot_description"/>
  <arg name="prefix" default="left_"/>
  <param if="$(arg load_robot_description)" name="$(arg robot_description)"
         {description}/>
  <param name="$(arg robot_description)_semantic" {semantic}/>
</launch>
"""
DEMO = """<launch>
  <include file="$(dirname)/planning_context.launch">
    <arg name="load_robot_description" value="true"/>
  </include>
</launch>
"""
XACRO_ROBOT = """<?xml version="1.0"?>
<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="prefix" default=""/>
  <xacro:arg name="limited" default="false"/>
  <xacro:include filename="$(find vd_description)/urdf/arm.urdf"/>
</robot>
"""


def vendor(root: Path, description: str, semantic: str, *, with_description: bool = True) -> Path:
    """A MoveIt 1 config package whose launch files load the robot from `vd_description`, and a
    stale `.setup_assistant` naming another robot's file."""
    files = {
        "vd_moveit_config/package.xml": CATKIN.format(name="vd_moveit_config"),
        "vd_moveit_config/launch/planning_context.launch": PLANNING_CONTEXT.format(
            description=description, semantic=semantic
        ),
        "vd_moveit_config/launch/demo.launch": DEMO,
        "vd_moveit_config/config/vd.srdf": _srdf("vd", 6, False),
        "vd_moveit_config/.setup_assistant": (
            "moveit_setup_assistant_config:\n  URDF:\n    package: other_description\n"
            "    relative_path: urdf/other.urdf\n  SRDF:\n    relative_path: config/vd.srdf\n"
        ),
        "other_description/package.xml": CATKIN.format(name="other_description"),
        "other_description/urdf/other.urdf": _arm_urdf("other", 3, False),
    }
    if with_description:
        files |= {
            "vd_description/package.xml": CATKIN.format(name="vd_description"),
            "vd_description/urdf/arm.urdf": _links_only(_arm_urdf("vd", 6, False)),
            "vd_description/urdf/vd.urdf.xacro": XACRO_ROBOT.format(name="vd"),
            "vd_description/urdf/vd.urdf": _arm_urdf("vd", 6, False),
            "vd_description/srdf/vd.srdf.xacro": _srdf("vd", 6, False),
        }
    build_file_tree(root, files)
    return root / "vd_moveit_config"


def _links_only(urdf: str) -> str:
    """A URDF's links and joints, wrapped for inclusion by a xacro."""
    body = urdf.split(">", 2)[2].rsplit("</robot>", 1)[0] if urdf.startswith("<?xml") else urdf
    return f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{body}</robot>'


XACRO_COMMAND = (
    """command="$(find xacro)/xacro --inorder prefix:=$(arg prefix) '$(find vd_description)/urdf/vd.urdf.xacro' """
    """limited:=true" """
)
TEXTFILE_SRDF = 'textfile="$(find vd_moveit_config)/config/vd.srdf"'


def test_the_description_is_the_one_the_launch_files_load(tmp_path):
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF)
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
    assert pkg.urdf_origin == "robot_description in launch/planning_context.launch"
    assert dict(pkg.xacro_args) == {"prefix": "left_", "limited": "true"}
    assert pkg.srdf_path == "config/vd.srdf"


def test_the_summary_names_the_description_srdf_and_args(tmp_path):
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF)
    result = validate(root, plan=False)
    assert result.robot == "vd"
    described = result.describe()
    assert (
        "vd.urdf.xacro limited:=true prefix:=left_ (robot_description in launch/planning_context.launch)"
        in described
    )
    assert (
        "SRDF config/vd.srdf (set as the semantic description by launch/planning_context.launch)" in described
    )
    assert result.as_dict()["xacro_args"] == {"limited": "true", "prefix": "left_"}


def test_a_textfile_description_and_an_srdf_xacro_in_the_description_package(tmp_path):
    semantic = "command=\"xacro '$(find vd_description)/srdf/vd.srdf.xacro'\""
    root = vendor(tmp_path, 'textfile="$(find vd_description)/urdf/vd.urdf"', semantic)
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf").resolve()
    assert pkg.srdf_path == "../vd_description/srdf/vd.srdf.xacro"
    assert validate(root, plan=False).robot == "vd"


def test_a_description_package_no_path_holds_is_a_finding_not_exit_2(tmp_path):
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF, with_description=False)
    result = validate(root, plan=False)
    missing = [f for f in result.findings if f.rule == "urdf.package-missing"]
    assert [(f.severity, f.file, f.element) for f in missing] == [
        ("warning", "launch/planning_context.launch", "robot_description")
    ]
    assert "--package-path DIR (the folder holding vd_description)" in missing[0].hint
    assert result.robot is None  # never the stale .setup_assistant's robot
    assert any("every rule needing the robot" in s for s in result.skipped)


def test_a_description_file_the_launch_names_but_nobody_ships_is_an_error(tmp_path):
    command = "command=\"xacro '$(find vd_description)/urdf/gone.urdf.xacro'\""
    root = vendor(tmp_path, command, TEXTFILE_SRDF)
    result = validate(root, plan=False)
    found = [f for f in result.findings if f.rule in ("urdf.missing", "launch.missing-file")]
    assert [(f.rule, f.severity, f.file) for f in found] == [
        ("urdf.missing", "error", "launch/planning_context.launch")
    ]
    assert result.robot is None and not [f for f in result.findings if f.rule == "urdf.runtime-only"]


def test_setup_assistant_only_when_no_launch_file_names_a_description(tmp_path):
    root = vendor(tmp_path, 'value=""', TEXTFILE_SRDF)
    (tmp_path / "other_description/urdf/other.urdf").write_text(_arm_urdf("vd", 6, False))
    pkg = read_package(root)
    assert pkg.urdf_origin.startswith(".setup_assistant (no launch file names")


ROS2_LAUNCH = """<launch>
  <arg name="prefix" default="right_"/>
  <node pkg="moveit_ros_move_group" exec="move_group">
    <param name="robot_description"
           value="$(command 'xacro $(find-pkg-share vd_description)/urdf/vd.urdf.xacro prefix:=$(var prefix)')"/>
    <param name="robot_description_semantic" value="$(command 'cat $(find-pkg-share vd_moveit_config)/config/vd.srdf')"/>
  </node>
</launch>
"""


def ros2_vendor(tmp_path: Path, launch: str, text: str) -> Path:
    """The vendor package made a ROS 2 one: its ROS 1 entry launch files replaced by `launch`."""
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF)
    for rel in ("launch/planning_context.launch", "launch/demo.launch"):
        (root / rel).unlink()
    (root / launch).write_text(text)
    (root / "package.xml").write_text(AMENT.format(name="vd_moveit_config"))
    return root


def test_a_ros2_xml_launch_gives_move_group_its_description(tmp_path):
    root = ros2_vendor(tmp_path, "launch/move_group.launch.xml", ROS2_LAUNCH)
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
    assert (pkg.urdf_origin, dict(pkg.xacro_args)) == (
        "robot_description in launch/move_group.launch.xml",
        {"prefix": "right_"},
    )
    assert pkg.srdf_path == "config/vd.srdf"


def test_a_missing_description_file_only_a_non_default_branch_loads_is_a_warning(tmp_path):
    """sawyer_moveit_config's case: planning_context.launch loads the URDF only with
    load_robot_description:=true, and no launch of the package sets it (the robot publishes
    robot_description): a missing file there stops roslaunch only when a user sets it."""
    command = "command=\"xacro '$(find vd_description)/urdf/gone.urdf.xacro'\""
    root = vendor(tmp_path, command, TEXTFILE_SRDF)
    (root / "launch/demo.launch").write_text(
        '<launch>\n  <include file="$(dirname)/planning_context.launch"/>\n</launch>\n', encoding="utf-8"
    )
    found = [f for f in validate(root, plan=False).findings if f.rule == "urdf.missing"]
    assert [(f.severity, f.file) for f in found] == [("warning", "launch/planning_context.launch")]
    assert "only other args take" in found[0].message


UPLOAD_LAUNCH = """<launch>
  <arg name="prefix" default="up_"/>
  <param name="robot_description" {description}/>
  <rosparam command="load" file="$(find vd_description)/config/other.yaml"/>
</launch>
"""
INCLUDING_CONTEXT = """<launch>
  <arg name="load_robot_description" default="false"/>
  <arg name="prefix" default="left_"/>
  <include if="$(arg load_robot_description)" file="$(find vd_description)/launch/upload.launch">
    <arg name="prefix" value="$(arg prefix)"/>
  </include>
  <param name="robot_description_semantic" {semantic}/>
</launch>
"""


def test_a_description_loaded_by_another_packages_launch_file_is_the_robot(tmp_path):
    """iiwa_moveit's case: planning_context.launch includes `$(find x_description)/launch/
    upload.launch`, which sets robot_description; roslaunch includes files of any package
    (xmlloader.py _include_tag), so that is the URDF move_group reads, not .setup_assistant's."""
    root = vendor(tmp_path, 'value=""', TEXTFILE_SRDF)
    build_file_tree(
        tmp_path,
        {
            "vd_moveit_config/launch/planning_context.launch": INCLUDING_CONTEXT.format(
                semantic=TEXTFILE_SRDF
            ),
            "vd_description/launch/upload.launch": UPLOAD_LAUNCH.format(description=XACRO_COMMAND),
        },
    )
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
    assert pkg.urdf_origin == "robot_description in ../vd_description/launch/upload.launch"
    assert dict(pkg.xacro_args) == {"prefix": "left_", "limited": "true"}
    assert validate(root, plan=False).robot == "vd"


def test_the_packages_own_description_load_comes_before_another_packages(tmp_path):
    """A demo.launch that includes another package's upload.launch and then sets robot_description
    itself: roslaunch's later param wins (a param set twice keeps the last value), so the
    package's own load, as before other packages' launch files were read, is the robot."""
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF)
    build_file_tree(
        tmp_path,
        {
            "vd_description/launch/upload.launch": UPLOAD_LAUNCH.format(
                description='textfile="$(find other_description)/urdf/other.urdf"'
            ),
            "vd_moveit_config/launch/demo.launch": DEMO.replace(
                "<launch>\n", '<launch>\n  <include file="$(find vd_description)/launch/upload.launch"/>\n'
            ),
        },
    )
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
    assert pkg.urdf_origin == "robot_description in launch/planning_context.launch"


XACRO_API_LAUNCH = """import os
import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    xacro_file = os.path.join(get_package_share_directory("vd_description"), "urdf", "vd.urdf.xacro")
    {make}
    robot_description = {{"robot_description": doc.toxml()}}
    return LaunchDescription([Node(package="moveit_ros_move_group", executable="move_group",
                                   parameters=[robot_description])])
"""


@pytest.mark.parametrize(
    "make",
    [
        'doc = xacro.process_file(xacro_file, mappings={"prefix": "right_"})',
        'doc = xacro.parse(open(xacro_file))\n    xacro.process_doc(doc, mappings={"prefix": "right_"})',
    ],
)
def test_a_python_launch_running_xacros_python_api_gives_move_group_its_description(tmp_path, make):
    """IFRA-Cranfield's ros2_RobotSimulation packages expand the description with xacro's
    Python API (xacro/__init__.py process_file; parse + process_doc) inside the launch file."""
    root = ros2_vendor(tmp_path, "launch/move_group.launch.py", XACRO_API_LAUNCH.format(make=make))
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
    assert (pkg.urdf_origin, dict(pkg.xacro_args)) == (
        "xacro command in launch/move_group.launch.py",
        {"prefix": "right_"},
    )


def test_the_summary_says_what_to_set_when_an_optenv_robot_lacks_the_names_found():
    """A robot built with $(optenv) defaults that lacks the joints the package names: the summary
    says to set the variables; with no such finding it only names them."""
    from marm_setup.findings import error
    from marm_setup.ros import Target
    from marm_setup.validate.runner import Validation

    lacking = (
        error("pose.unknown-joint", "config/r.srdf", "group_state[home]", "unknown joint 'arm_j1'"),
        error("srdf.unknown-link", "config/r.srdf", "group[arm]", "unknown link 'arm_l1'"),
        error("ompl.unknown-group", "config/ompl_planning.yaml", "arm", "unknown group"),
    )
    found = Validation(
        lacking, "r_moveit_config", Target.ROS1, "moveit1", "r.urdf.xacro", "launch", "r", None
    )
    found = dataclasses.replace(found, env_defaults=("R_HAS_ARM", "R_SIDE"))
    described = found.describe()
    assert "$(optenv): R_HAS_ARM, R_SIDE (2 findings name joints or links it lacks:" in described
    assert "R_HAS_ARM=... marm-setup validate ..." in described
    assert "lacks" not in dataclasses.replace(found, findings=lacking[2:]).describe()


def test_a_launch_wrapping_the_demo_with_its_own_description_does_not_choose_the_robot(tmp_path):
    """The Setup Assistant's demo_gazebo.launch (MoveIt 1, moveit_setup_assistant templates/
    moveit_config_pkg_template/launch/demo_gazebo.launch l.13-20) includes gazebo.launch, which
    sets robot_description to the gazebo copy of the URDF, and demo.launch with
    load_robot_description:=false. demo.launch is then included by another file, yet it is the
    demo a user starts, and its planning_context.launch gives move_group the package's URDF:
    a launch starting move_group that another launch starting move_group includes is walked
    first for the robot description; the wrapper is a variant of it. demo_gazebo.launch sorted
    before every other entry and the gazebo copy was validated (khi_rs030n_moveit_config)."""
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF)
    node = '  <node pkg="moveit_ros_move_group" type="move_group" name="move_group"/>\n</launch>'
    build_file_tree(
        tmp_path,
        {
            "vd_moveit_config/launch/demo.launch": DEMO.replace("</launch>", node),
            "vd_moveit_config/launch/gazebo.launch": (
                '<launch>\n  <param name="robot_description" textfile="$(find other_description)/urdf/other.urdf"/>\n'
                "</launch>\n"
            ),
            "vd_moveit_config/launch/demo_gazebo.launch": (
                '<launch>\n  <include file="$(dirname)/gazebo.launch"/>\n'
                '  <include file="$(dirname)/demo.launch">\n'
                '    <arg name="load_robot_description" value="false"/>\n  </include>\n</launch>\n'
            ),
        },
    )
    demo = (root / "launch/demo.launch").read_text()
    (root / "launch/demo.launch").write_text(
        demo.replace(
            "<launch>\n", '<launch>\n  <arg name="load_robot_description" default="true"/>\n'
        ).replace(
            '<arg name="load_robot_description" value="true"/>',
            '<arg name="load_robot_description" value="$(arg load_robot_description)"/>',
        )
    )
    pkg = read_package(root)
    assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
    assert pkg.urdf_origin == "robot_description in launch/planning_context.launch"


@pytest.mark.parametrize(("where", "found"), [("move_group", True), ("robot_state_publisher", False)])
def test_a_description_remapped_for_move_group_is_the_robot(tmp_path, where, found):
    """move_group started with `<remap from="robot_description" to="vd_robot"/>` reads its URDF
    from vd_robot and its SRDF from vd_robot_semantic (moveit rdf_loader.cpp: searchParam
    applies the node's remappings), the names planning_context.launch loads under its
    robot_description arg: that load is the robot, not the stale `.setup_assistant`'s file
    (human_moveit_config). A remap on another node says nothing about move_group."""
    root = vendor(tmp_path, XACRO_COMMAND, TEXTFILE_SRDF)
    context = root / "launch/planning_context.launch"
    context.write_text(context.read_text().replace('default="robot_description"', 'default="vd_robot"'))
    node = f'  <node pkg="x" type="{where}" name="n">\n    <remap from="robot_description" to="vd_robot"/>\n  </node>\n'
    if where != "move_group":
        node += '  <node pkg="moveit_ros_move_group" type="move_group" name="move_group"/>\n'
    (root / "launch/demo.launch").write_text(DEMO.replace("</launch>", node + "</launch>"))
    pkg = read_package(root)
    if found:
        assert pkg.urdf == (tmp_path / "vd_description/urdf/vd.urdf.xacro").resolve()
        assert pkg.urdf_origin.endswith(" in launch/planning_context.launch")
    else:
        assert pkg.urdf == (tmp_path / "other_description/urdf/other.urdf").resolve()


NO_DESCRIPTION = """<launch>
  <arg name="load_robot_description" default="false"/>
  <!--param if="$(arg load_robot_description)" name="robot_description" textfile="$(find vd_description)/urdf/vd.urdf"/-->
  <param name="robot_description_semantic" textfile="$(find vd_moveit_config)/config/vd.srdf"/>
</launch>
"""


@pytest.mark.parametrize("urdf_package", ['""', "'\"\"'"])  # empty, and the two quotes it checks for
def test_a_setup_assistant_naming_no_package_and_launch_files_loading_no_description_is_runtime_only(
    tmp_path, urdf_package
):
    """The MoveIt 1 Setup Assistant takes relative_path itself when package is empty (a file
    outside any package); move_group takes /robot_description as something else loads it."""
    build_file_tree(
        tmp_path,
        {
            "vd_moveit_config/package.xml": CATKIN.format(name="vd_moveit_config"),
            "vd_moveit_config/launch/planning_context.launch": NO_DESCRIPTION,
            "vd_moveit_config/launch/demo.launch": DEMO,
            "vd_moveit_config/config/vd.srdf": _srdf("vd", 6, False),
            "vd_moveit_config/.setup_assistant": (
                f"moveit_setup_assistant_config:\n  URDF:\n    package: {urdf_package}\n"
                "    relative_path: /home/someone/ws/src/vd/vd.urdf\n  SRDF:\n    relative_path: config/vd.srdf\n"
            ),
        },
    )
    result = validate(tmp_path / "vd_moveit_config", plan=False)
    assert result.robot is None
    runtime = [f for f in result.findings if f.rule == "urdf.runtime-only"]
    assert [(f.severity, f.file, f.element) for f in runtime] == [
        ("warning", "launch/*.launch", "robot_description")
    ]
    assert ".setup_assistant names no package" in runtime[0].message
    assert not [f for f in result.findings if f.severity == "error"]


def test_a_ros2_package_whose_setup_assistant_names_no_package_stays_exit_2(tmp_path):
    """MoveItConfigsBuilder looks the empty package up in the ament index and stops the launch:
    no run time description to wait for."""
    from marm_setup.errors import InputError

    build_file_tree(
        tmp_path,
        {
            "vd_moveit_config/package.xml": AMENT.format(name="vd_moveit_config"),
            "vd_moveit_config/launch/demo.launch.py": "from moveit_configs_utils import MoveItConfigsBuilder\n",
            "vd_moveit_config/config/vd.srdf": _srdf("vd", 6, False),
            "vd_moveit_config/.setup_assistant": (
                "moveit_setup_assistant_config:\n  urdf:\n    package: ''\n"
                "    relative_path: /home/someone/vd.urdf\n  srdf:\n    relative_path: config/vd.srdf\n"
            ),
        },
    )
    with pytest.raises(InputError, match="gives no URDF package"):
        read_package(tmp_path / "vd_moveit_config")


LOAD_FILE_LAUNCH = """import os
from ament_index_python.packages import get_package_share_directory
from launch_ros.actions import Node


def load_file(package_name, file_path):
    with open(os.path.join(get_package_share_directory(package_name), file_path)) as f:
        return f.read()


def generate_launch_description():
    robot_description = {"robot_description": load_file("vd_description", "urdf/vd.urdf")}
    semantic = load_file("vd_moveit_config", "config/vd.srdf")
    return LaunchDescription([Node(package="moveit_ros_move_group", executable="move_group",
        parameters=[robot_description, {"robot_description_semantic": semantic}])])
"""


def test_a_plain_urdf_and_srdf_a_launch_reads_with_load_file_are_what_move_group_gets(tmp_path):
    """MoveIt 2's early tutorials' `load_file(pkg, path)` (the file's text, handed over as it is):
    its URDF and SRDF are the ones validate takes; a .xacro read so is not (it would reach MoveIt
    unexpanded)."""
    from marm_setup.package.launch_python import read_python_launch

    root = tmp_path / "vd_moveit_config"
    (root / "launch").mkdir(parents=True)
    (root / "launch/move_group.launch.py").write_text(LOAD_FILE_LAUNCH)
    shares = {"vd_description": "/share/vd_description", "vd_moveit_config": str(root)}
    launch = read_python_launch(root, ("launch/move_group.launch.py",), shares.get)
    assert {c.parameter: c.file for c in launch.commands} == {
        "robot_description": "/share/vd_description/urdf/vd.urdf",
        "robot_description_semantic": str(root / "config/vd.srdf"),
    }
    (root / "launch/move_group.launch.py").write_text(LOAD_FILE_LAUNCH.replace("vd.urdf", "vd.urdf.xacro"))
    launch = read_python_launch(root, ("launch/move_group.launch.py",), shares.get)
    assert [c.parameter for c in launch.commands] == ["robot_description_semantic"]
