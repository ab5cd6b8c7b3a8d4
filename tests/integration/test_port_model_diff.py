"""A port keeps what changes how the robot moves: the package model of the source and of the
new package hold the same joint limits, scaling factors, controller names and IK options, or
the port report names each difference; both directions (ros1 <-> ros2), on vendor-style
packages written here (tests/vendor_packages.py) in the layouts published ones use."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.package.read import read_package
from marm_setup.robot.load import load_robot
from tests.package_diff import motion_settings, unexplained
from tests.vendor_packages import PACKAGES

runner = CliRunner()


def port(source, paths, out, target: str) -> dict:
    args = [a for p in paths for a in ("--package-path", str(p))]
    cmd = ["init", "--from-package", str(source), "--out", str(out), "--target", target, "--no-plan"]
    result = runner.invoke(app, [*cmd, *args, "--format", "json", "--jobs", "1"])
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.stdout)


def diff(source, paths, out, doc) -> tuple[dict, dict, dict]:
    src = read_package(source, package_paths=paths)
    new = read_package(out)
    robot = load_robot(src.description_file, dict(src.xacro_args), src.package_paths)
    before, after = motion_settings(src, robot), motion_settings(new, robot)
    return before, after, unexplained(before, after, doc["port"]["items"])


@pytest.mark.parametrize("target", ["ros1", "ros2"])
@pytest.mark.parametrize("name", sorted(PACKAGES))
def test_the_port_keeps_what_moves_the_robot(tmp_path, name, target):
    source, paths = PACKAGES[name](tmp_path / "src")
    doc = port(source, paths, tmp_path / "out", target)
    assert doc["validation"]["errors"] == 0, doc["validation"]
    before, after, missing = diff(source, paths, tmp_path / "out", doc)
    assert missing == {}
    assert len(before) > 10  # the source's limits, controllers and IK options were all read


def test_limits_and_controllers_the_launch_files_pick_with_an_arg(tmp_path):
    """config/$(arg dof)dof/...: 0.41 rad/s (URDF 1.0), scaling 1.0 and the vendor's controller
    names reach the new package; the report opens with them."""
    source, paths = PACKAGES["arg_selected"](tmp_path / "src")
    pkg = read_package(source, package_paths=paths)
    assert pkg.joint_limits.where.file == "config/6dof/default_joint_limits.yaml"
    assert (
        pkg.source("joint_limits").how
        == "loaded by launch/planning_context.launch into robot_description_planning"
    )
    assert pkg.srdf_path == "config/6dof/vx.srdf"
    doc = port(source, paths, tmp_path / "out", "ros2")
    setup = (tmp_path / "out" / "marm_setup.yaml").read_text()
    assert "max_velocity: 0.41" in setup and "default_velocity_scaling: 1.0" in setup
    assert "name: vx6/arm_trajectory" in setup and "name: vx6/gripper_command" in setup
    items = doc["port"]["items"]
    assert items[0]["area"] in ("limits", "scaling", "controllers", "kinematics", "planners")
    assert doc["port"]["motion_counts"]["dropped"] == 0


def test_python_launch_controllers_and_trac_ik_options(tmp_path):
    source, paths = PACKAGES["python_launch"](tmp_path / "src")
    pkg = read_package(source, package_paths=paths)
    assert pkg.moveit_controllers.where.file == "config/bot_controllers.yaml"
    assert pkg.joint_limits.where.file == "config/limits/bot_joint_limits.yaml"
    assert [p.name for p in pkg.pipelines] == ["ompl"]
    assert dict(pkg.xacro_args) == {"gripper": "true", "use_sim": "false"}  # robot_ip: no default
    port(source, paths, tmp_path / "out", "ros1")
    setup = (tmp_path / "out" / "marm_setup.yaml").read_text()
    assert "solve_type: Distance" in setup and "epsilon: 1.0e-05" in setup
    assert "name: bot_arm_controller" in setup and "name: Bot Maker" in setup
    assert "solve_type: Distance" in (tmp_path / "out" / "config" / "kinematics.yaml").read_text()


def test_position_only_ik_reaches_both_targets(tmp_path):
    source, paths = PACKAGES["position_only"](tmp_path / "src")
    for target, file in (("ros1", "config/kinematics.yaml"), ("ros2", "config/moveit.yaml")):
        port(source, paths, tmp_path / target, target)
        assert "position_only_ik: true" in (tmp_path / target / file).read_text()
        kinematics = read_package(tmp_path / target).kinematics.group("arm")
        assert kinematics.param("position_only_ik").value is True


def test_ros2_control_manager_controllers_keep_their_names(tmp_path):
    """Ros2ControlManager: MoveIt's controllers are ros2_control's; the port lists them by name."""
    source, paths = PACKAGES["ros2_control_manager"](tmp_path / "src")
    pkg = read_package(source, package_paths=paths)
    assert pkg.moveit_controllers.controllers == ()
    managed = {c.name: (c.type, c.action_ns) for c in pkg.managed_controllers.controllers}
    assert managed == {
        "rc_arm_jtc": ("FollowJointTrajectory", "follow_joint_trajectory"),
        "rc_hand": ("GripperCommand", "gripper_cmd"),
    }
    for target in ("ros1", "ros2"):
        doc = port(source, paths, tmp_path / target, target)
        setup = (tmp_path / target / "marm_setup.yaml").read_text()
        assert "name: rc_arm_jtc" in setup and "name: rc_hand" in setup
        assert not any(
            i["setting"].startswith("driver.rc_") and i["status"] == "dropped" for i in doc["port"]["items"]
        )
        items = {i["setting"]: i["status"] for i in doc["port"]["items"]}
        assert items["joint_limits[joint_6].max_velocity"] == "carried"  # none given: the URDF's stays


def test_controllers_a_python_launch_loads_by_hand(tmp_path):
    """No MoveItConfigsBuilder: the controller list a launch file names is MoveIt's."""
    source, paths = PACKAGES["hand_loaded"](tmp_path / "src")
    pkg = read_package(source, package_paths=paths)
    assert pkg.moveit_controllers.where.file == "config/hlarm_controllers.yaml"
    assert "launch/moveit.launch.py" in pkg.source("moveit_controllers").how
    assert [c.name for c in pkg.moveit_controllers.controllers] == ["hl_arm_controller", "hl_gripper"]
    port(source, paths, tmp_path / "out", "ros2")
    setup = (tmp_path / "out" / "marm_setup.yaml").read_text()
    assert "name: hl_arm_controller" in setup and "name: hl_gripper" in setup


def test_a_description_inside_the_package_is_not_named_by_the_new_package(tmp_path):
    """No .setup_assistant: the wrapper is the description. A new package of the same name would
    name itself (to ros2, its own wrapper including itself): one error line; --name another
    package name and the new package uses the source's."""
    source, paths = PACKAGES["own_wrapper"](tmp_path / "src")
    (source / ".setup_assistant").unlink()
    args = [a for p in paths for a in ("--package-path", str(p))]
    cmd = ["init", "--from-package", str(source), "--out", str(tmp_path / "same"), "--no-plan", *args]
    result = runner.invoke(app, cmd)
    assert result.exit_code == 2 and "would name itself" in result.stderr
    assert not (tmp_path / "same").exists()
    for target in ("ros1", "ros2"):
        out = tmp_path / target
        result = runner.invoke(
            app, [*cmd[:3], "--out", str(out), "--name", "wr2_moveit_config", "--target", target, *cmd[5:]]
        )
        assert result.exit_code == 0, result.output
        assert (
            "urdf: package://wr_moveit_config/config/wr.urdf.xacro" in (out / "marm_setup.yaml").read_text()
        )
