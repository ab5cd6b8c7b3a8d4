"""load_robot on the real fixtures, the shared panda, and inline URDFs."""

from __future__ import annotations

import pytest

from marm_setup.errors import InputError
from marm_setup.robot.load import load_robot, parse_xacro_args
from marm_setup.robot.model import Box, Cylinder, Mesh
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.helpers import TWO_BOXES, build_file_tree, urdf

MARM_JOINTS = ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "finger_joint1")


def test_marm_fixture_matches_the_course_robot():
    robot = load_robot(MARM_URDF)
    assert robot.name == "marm" and robot.root == "base_link"
    assert robot.active_joint_names == MARM_JOINTS
    assert robot.joint("finger_joint2").mimic.joint == "finger_joint1"
    assert robot.joint("finger_joint2").mimic.multiplier == -1.0
    assert not robot.link("grasping_frame").has_geometry
    assert robot.link("bottom_link").collisions[0].geometry == Box((1.0, 1.0, 0.02))
    assert robot.link("link3").collisions[0].geometry == Cylinder(0.03, 0.22)
    limits = [robot.joint(f"joint{i}").upper for i in range(1, 7)]
    assert limits == [2.96, 2.35, 2.62, 2.62, 2.62, 6.28]


def test_package_uri_resolves_to_the_fixture_mesh():
    mesh = load_robot(MARM_URDF).link("link6").collisions[0].geometry
    assert isinstance(mesh, Mesh)
    assert mesh.uri == "package://marm_description/meshes/link6.stl"
    assert mesh.path == str((FIXTURES / "marm" / "meshes" / "link6.stl").resolve())


def test_xacro_args_change_the_robot():
    path = FIXTURES / "two_link" / "urdf" / "two_link.urdf.xacro"
    full = load_robot(path)
    bare = load_robot(path, {"with_tool": "false", "length": "0.5"})
    assert "tool" in full.link_map and "tool" not in bare.link_map
    assert bare.joint("elbow").origin.xyz == (0.0, 0.0, 0.5)
    assert bare.joint("elbow").bounds == pytest.approx((-3.141592653589793, 3.141592653589793))


def test_marm_without_gripper():
    robot = load_robot(MARM_URDF, {"with_gripper": "false"})
    assert "finger_joint1" not in robot.joint_map
    assert robot.active_joint_names == MARM_JOINTS[:-1]


def test_adjacency_sees_through_geometry_less_links(tmp_path):
    body = """
    <link name="a"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="m1"/><link name="m2"/>
    <link name="b"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="j1" type="fixed"><parent link="a"/><child link="m1"/></joint>
    <joint name="j2" type="revolute"><parent link="m1"/><child link="m2"/>
      <limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
    <joint name="j3" type="fixed"><parent link="m2"/><child link="b"/></joint>
    """
    build_file_tree(tmp_path, {"r.urdf": urdf(body)})
    robot = load_robot(tmp_path / "r.urdf")
    assert robot.adjacent_geometry_pairs() == {("a", "b")}


def test_panda_ros1_xacro_with_package_path():
    root = realworld("ros1")
    robot = load_robot(root / "panda_description/urdf/panda_arm_hand.urdf.xacro", package_paths=[root])
    assert robot.root == "panda_link0"
    assert len(robot.active_joints) == 8
    assert robot.joint("panda_finger_joint2").mimic.joint == "panda_finger_joint1"
    assert all(isinstance(c.geometry, Mesh) for c in robot.link("panda_link3").collisions)


def test_panda_ros2_urdf_resolves_meshes_around_the_file():
    robot = load_robot(realworld("ros2", "panda_description/urdf/panda.urdf"))
    assert len(robot.geometry_links) == 11


def test_soft_limits_narrow_the_bounds(tmp_path):
    body = TWO_BOXES.replace(
        '<limit lower="-1" upper="1" velocity="1" effort="1"/>',
        '<limit lower="-1" upper="1" velocity="1" effort="1"/>'
        '<safety_controller soft_lower_limit="-0.5" soft_upper_limit="2" k_velocity="1"/>',
    )
    build_file_tree(tmp_path, {"r.urdf": body})
    assert load_robot(tmp_path / "r.urdf").joint("j").bounds == (-0.5, 1.0)


def test_parse_xacro_args_rejects_malformed_items():
    assert parse_xacro_args(["a:=1", "b:=x:=y"]) == {"a": "1", "b": "x:=y"}
    with pytest.raises(InputError, match="NAME:=VALUE"):
        parse_xacro_args(["a=1"])


STL_TRIANGLE = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 0.1 0 0\nvertex 0 0.1 0\nendloop\nendfacet\nendsolid t\n"


def _folder_named_package(tmp_path):
    """A pip `share/`-style tree: folder `my_robot_description` whose package.xml says another name."""
    mesh_link = (
        '<link name="m"><collision><geometry><mesh filename="package://my_robot_description/meshes/t.stl"/>'
        '</geometry></collision></link><joint name="jm" type="fixed"><parent link="b"/><child link="m"/></joint>'
    )
    return build_file_tree(
        tmp_path,
        {
            "share/my_robot_description/package.xml": "<package><name>vendor_robot</name></package>",
            "share/my_robot_description/meshes/t.stl": STL_TRIANGLE,
            "share/my_robot_description/urdf/arm.xacro": '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
            + TWO_BOXES.split("\n", 2)[2].replace("</robot>", "")
            + mesh_link
            + "</robot>",
            "work/r.urdf.xacro": '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<xacro:include filename="$(find my_robot_description)/urdf/arm.xacro"/></robot>',
        },
    )


def test_package_found_by_folder_name_for_find_and_meshes(tmp_path):
    root = _folder_named_package(tmp_path)
    robot = load_robot(root / "work/r.urdf.xacro", package_paths=[root / "share"])
    folder = root / "share/my_robot_description"
    assert robot.link("m").collisions[0].geometry.path == str((folder / "meshes/t.stl").resolve())
    assert robot.packages == (("my_robot_description", str(folder.resolve()), "folder name"),)


def test_package_xml_name_wins_over_a_folder_name(tmp_path):
    root = _folder_named_package(tmp_path)
    build_file_tree(
        root, {"share/other/my_robot_description/package.xml": "<package><name>x</name></package>"}
    )
    build_file_tree(
        root,
        {
            "share/real/package.xml": "<package><name>my_robot_description</name></package>",
            "share/real/urdf/arm.xacro": (root / "share/my_robot_description/urdf/arm.xacro").read_text(),
            "share/real/meshes/t.stl": STL_TRIANGLE,
        },
    )
    robot = load_robot(root / "work/r.urdf.xacro", package_paths=[root / "share"])
    assert robot.packages == (("my_robot_description", str((root / "share/real").resolve()), "package.xml"),)


def test_folder_fallback_next_to_the_urdf(tmp_path):
    """Without --package-path: a folder of the package's name enclosing the URDF."""
    root = _folder_named_package(tmp_path)
    body = (root / "share/my_robot_description/urdf/arm.xacro").read_text()
    build_file_tree(
        root, {"share/my_robot_description/urdf/arm.urdf": body.replace("xmlns:xacro", 'name="r" x')}
    )
    robot = load_robot(root / "share/my_robot_description/urdf/arm.urdf")
    assert robot.packages[0][2] == "folder name"


def _unnamed_package_urdf(tmp_path, uri: str):
    mesh_link = (
        f'<link name="m"><collision><geometry><mesh filename="{uri}"/></geometry></collision></link>'
        '<joint name="jm" type="fixed"><parent link="b"/><child link="m"/></joint>'
    )
    return build_file_tree(
        tmp_path,
        {
            "share/robots_data/robots/talos/meshes/t.stl": STL_TRIANGLE,
            "share/robots_data/robots/talos/robots/r.urdf": TWO_BOXES.replace(
                "</robot>", mesh_link + "</robot>"
            ),
        },
    )


def test_a_package_uri_without_a_name_reads_as_pinocchio_reads_it(tmp_path):
    """`package:///a/b` (example-robot-data's talos_full_v2): the path below a package search
    root, or below a folder enclosing the URDF."""
    root = _unnamed_package_urdf(tmp_path, "package:///robots_data/robots/talos/meshes/t.stl")
    urdf_path = root / "share/robots_data/robots/talos/robots/r.urdf"
    mesh = (root / "share/robots_data/robots/talos/meshes/t.stl").resolve()
    assert load_robot(urdf_path).link("m").collisions[0].geometry.path == str(mesh)
    assert load_robot(urdf_path, package_paths=[root / "share"]).link("m").collisions[0].geometry.path == str(
        mesh
    )


def test_a_package_uri_without_a_name_that_no_folder_holds(tmp_path):
    root = _unnamed_package_urdf(tmp_path, "package:///elsewhere/t.stl")
    with pytest.raises(InputError, match=r"mesh 'package:///elsewhere/t.stl' not found \(looked at "):
        load_robot(root / "share/robots_data/robots/talos/robots/r.urdf")


def test_a_xacro_records_the_unset_environment_variables_it_reads_with_optenv(tmp_path, monkeypatch):
    """kinova-movo's description builds its arms only where MOVO_HAS_KINOVA_ARM is set: the
    robot says which variables it took the defaults of (validate's summary names them)."""
    monkeypatch.delenv("MARM_TEST_ARM", raising=False)
    monkeypatch.delenv("MARM_TEST_SIDE", raising=False)
    monkeypatch.setenv("MARM_TEST_SET", "1")
    path = tmp_path / "r.urdf.xacro"
    path.write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <link name="a"/>\n'
        '  <xacro:if value="$(optenv MARM_TEST_ARM false)"><link name="arm"/>\n'
        '    <joint name="ja" type="fixed"><parent link="a"/><child link="arm"/></joint></xacro:if>\n'
        '  <link name="$(optenv MARM_TEST_SIDE left)_b"/>\n'
        '  <link name="c$(optenv MARM_TEST_SET 0)"/>\n'
        '  <joint name="j" type="fixed"><parent link="a"/><child link="left_b"/></joint>\n'
        '  <joint name="k" type="fixed"><parent link="a"/><child link="c1"/></joint>\n'
        "</robot>\n",
        encoding="utf-8",
    )
    robot = load_robot(path)
    assert robot.env_defaults == ("MARM_TEST_ARM", "MARM_TEST_SIDE")
    assert "arm" not in robot.link_map
    monkeypatch.setenv("MARM_TEST_ARM", "true")
    assert load_robot(path).env_defaults == ("MARM_TEST_SIDE",)


def test_a_folder_of_the_package_name_holding_other_packages_is_not_that_package(tmp_path):
    """A repository folder named like a package (prbt_robot/ holding prbt_description/ and
    prbt_robot_support/) is no package: packages do not nest (catkin_pkg find_package_paths stops
    at a package.xml; rospack likewise), so $(find prbt_robot) finds no package there."""
    from marm_setup.robot.ros_packages import find_packages

    root = build_file_tree(
        tmp_path,
        {
            "ws/prbt_robot/prbt_description/package.xml": "<package><name>prbt_description</name></package>",
            "ws/prbt_robot/prbt_robot_support/package.xml": "<package><name>prbt_robot_support</name></package>",
            "ws/prbt_robot/README.md": "repository",
            "ws/plain_description/urdf/a.urdf": "<robot name='a'/>",
        },
    )
    index = find_packages([root / "ws"], environ={})
    assert index.lookup("prbt_robot") is None
    assert index.lookup("prbt_description") == (root / "ws/prbt_robot/prbt_description").resolve()
    assert (
        index.lookup("plain_description") == (root / "ws/plain_description").resolve()
    )  # the fallback stays
