"""package_discovery: URDF, target, SRDF and config files of MoveIt 1, MoveIt 2 and marm layouts."""

from __future__ import annotations

import shutil

import pytest

from marm_setup.errors import InputError
from marm_setup.package.read import read_package
from tests.validate_helpers import generate_marm, panda


def test_moveit1_setup_assistant_package():
    good = panda("ros1")
    pkg = read_package(good.path, package_paths=good.package_paths)
    assert (pkg.target, pkg.layout) == ("ros1", "moveit1")
    assert pkg.urdf_origin == "robot_description in launch/planning_context.launch"
    assert pkg.name == "moveit_resources_panda_moveit_config"
    assert pkg.urdf.name == "panda_arm_hand.urdf.xacro"
    assert pkg.srdf_path == "config/panda.srdf" and pkg.srdf.robot_name == "panda"
    assert pkg.moveit_controllers.where.file == "config/simple_moveit_controllers.yaml"
    assert pkg.fake_controllers.where.file == "config/fake_controllers.yaml"
    assert pkg.ros_controllers.where.file == "config/ros_controllers.yaml"
    assert "launch/demo.launch" in pkg.launch_files
    assert pkg.problems == ()


def test_moveit2_setup_assistant_package():
    good = panda("ros2")
    pkg = read_package(good.path, package_paths=good.package_paths)
    assert (pkg.target, pkg.layout) == ("ros2", "moveit2")
    assert pkg.urdf_origin == "config/<robot>.urdf.xacro"
    assert pkg.srdf_path == "config/panda_arm_hand.srdf.xacro"  # what .setup_assistant names
    assert [g.name for g in pkg.srdf.groups] == ["panda_arm", "hand", "panda_arm_hand"]
    assert (pkg.moveit_controllers.where.file, pkg.moveit_controllers.where.element) == (
        "config/moveit_controllers.yaml",
        "moveit_simple_controller_manager",
    )
    assert [s.where.file for s in pkg.alt_moveit_controllers] == ["config/gripper_moveit_controllers.yaml"]
    assert pkg.ros2_controllers.where.file == "config/ros2_controllers.yaml"
    assert {p.key: p.value for p in pkg.initial_positions.values}["panda_joint4"] == -2.356


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_marm_packages(tmp_path, target):
    pkg = read_package(generate_marm(tmp_path, target))
    assert pkg.target == target and pkg.urdf_origin == "marm_setup.yaml"
    assert pkg.urdf.resolve().name == "marm.urdf.xacro"
    assert pkg.srdf_path == "config/marm.srdf"
    if target == "ros2":
        assert pkg.layout == "marm_ros2"
        kinds = (pkg.kinematics, pkg.joint_limits, pkg.ompl, pkg.moveit_controllers)
        assert {s.where.file for s in kinds} == {"config/moveit.yaml"}
        assert (
            pkg.kinematics.group("arm").where.element
            == "/**.ros__parameters.robot_description_kinematics.arm"
        )
    else:
        assert pkg.arbotix.where.file == "config/arbotix.yaml"
        assert pkg.moveit_controllers.where.file == "config/controllers.yaml"


def test_the_description_package_no_path_holds_is_a_finding(tmp_path):
    good = panda("ros1")
    copy = tmp_path / "panda_moveit_config"
    shutil.copytree(good.path, copy)
    pkg = read_package(copy)
    assert pkg.urdf is None
    assert [(f.rule, f.file) for f in pkg.problems] == [
        ("urdf.package-missing", "launch/planning_context.launch")
    ]
    assert "moveit_resources_panda_description" in pkg.problems[0].message
    assert read_package(copy, package_paths=good.package_paths).urdf.is_file()


def test_not_a_package(tmp_path):
    with pytest.raises(InputError, match="not a folder"):
        read_package(tmp_path / "missing")
    with pytest.raises(InputError, match="not a MoveIt config package"):
        read_package(tmp_path)


def test_no_robot_description(tmp_path):
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "a.srdf").write_text('<robot name="a"/>', encoding="utf-8")
    with pytest.raises(InputError, match="cannot find the robot description") as info:
        read_package(tmp_path)
    assert (info.value.element, info.value.needs) == ("robot description", "--urdf")


def test_marm_setup_yaml_xacro_args_and_package_paths(tmp_path):
    from typer.testing import CliRunner

    from marm_setup.cli.app import app
    from tests.conftest import FIXTURES, MARM_URDF

    out = tmp_path / "pkg"
    args = [
        "init",
        str(MARM_URDF),
        "--out",
        str(out),
        "--xacro-arg",
        "with_gripper:=false",
        "--package-path",
        str(FIXTURES),
    ]
    assert CliRunner().invoke(app, args).exit_code == 0
    pkg = read_package(out)
    assert pkg.xacro_args == (("with_gripper", "false"),)
    assert FIXTURES.resolve() in pkg.package_paths
    assert pkg.package_paths[0] == out.resolve()  # $(find <itself>) is this copy


@pytest.mark.parametrize(
    ("text", "reason"),
    [
        ("moveit_setup_assistant_config: [\n", ".setup_assistant is not readable YAML"),
        ("moveit_setup_assistant_config:\n  SRDF: {relative_path: config/a.srdf}\n", "gives no URDF package"),
    ],
)
def test_no_robot_description_names_the_broken_setup_assistant(tmp_path, text, reason):
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "a.srdf").write_text('<robot name="a"/>', encoding="utf-8")
    (tmp_path / ".setup_assistant").write_text(text, encoding="utf-8")
    with pytest.raises(InputError, match=reason) as info:
        read_package(tmp_path)
    assert (info.value.element, info.value.needs) == ("robot description", "--urdf")
