"""Porting real packages: the MoveIt 1 Panda to MoveIt 2 compared with the maintainers' own
MoveIt 2 port, and the vendor packages of ../shared/realworld2 to both targets."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.package.read import read_package
from marm_setup.robot.load import load_robot
from marm_setup.setup.groups import group_joints, groups_by_name
from tests.conftest import realworld
from tests.generated_packages import PORTS, shared_path

runner = CliRunner()
# The one error the source package has too (validate reports it on both upstream packages): the
# 'transport' pose puts the link5 and link7 collision meshes in contact.
INHERITED = {("pose.collision", "group_state[transport]")}
# Settings the maintainers changed by hand in their MoveIt 2 port that the MoveIt 1 package does
# not have (the port carries the MoveIt 1 values; the test checks it does).
UPSTREAM_EDITS = {
    "limit:panda_finger_joint1.acceleration",  # 0.1 -> 1.0
    *(f"limit:{j}.jerk" for j in [*(f"panda_joint{i}" for i in range(1, 8)), "panda_finger_joint1"]),
}


def _settings(pkg) -> dict[str, object]:
    """The settings the issue compares, keyed for diffing: groups (resolved joints), group
    states, end effectors, disabled pairs, kinematics, joint limits."""
    robot = load_robot(pkg.urdf, dict(pkg.xacro_args), pkg.package_paths)
    srdf = pkg.srdf
    by_name = groups_by_name(srdf.groups)
    out: dict[str, object] = {}
    for g in srdf.groups:
        out[f"group:{g.name}"] = frozenset(group_joints(g, by_name, robot))
    for s in srdf.group_states:
        out[f"state:{s.group}/{s.name}"] = tuple(sorted(s.values))
    for e in srdf.end_effectors:
        out[f"ee:{e.name}"] = (e.group, e.parent_link, e.parent_group)
    for p in srdf.disabled:
        out[f"disabled:{p.link1}|{p.link2}"] = True
    for entry in pkg.kinematics.groups:
        keys = ("kinematics_solver", "kinematics_solver_search_resolution", "kinematics_solver_timeout")
        out[f"kinematics:{entry.group}"] = tuple(p.value if (p := entry.param(k)) else None for k in keys)
    for entry in pkg.joint_limits.joints:
        for kind in ("velocity", "acceleration", "jerk"):
            flag = entry.param(f"has_{kind}_limits")
            if flag is not None and flag.value:
                out[f"limit:{entry.joint}.{kind}"] = round(float(entry.param(f"max_{kind}").value), 6)
    return out


def _diff(a: dict, b: dict) -> set[str]:
    return {k for k in a.keys() | b.keys() if a.get(k) != b.get(k)}


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_panda_ros1_to_ros2_matches_the_maintainers_port(tmp_path, distro):
    source = realworld("ros1", "panda_moveit_config")
    theirs = realworld("ros2", "panda_moveit_config")
    out = tmp_path / "panda_moveit_config"
    args = ["--package-path", str(source.parent), "--target", "ros2", "--ros-distro", distro]
    result = runner.invoke(
        app, ["init", "--from-package", str(source), "--out", str(out), *args, "--format", "json"]
    )
    doc = json.loads(result.stdout)
    errors = {(f["rule"], f["element"]) for f in doc["validation"]["findings"] if f["severity"] == "error"}
    assert errors == INHERITED, doc["validation"]
    assert result.exit_code == 1  # validation errors exit 1, even inherited ones
    items = doc["port"]["items"]
    inherited = [i for i in items if i["setting"] == "validate pose.collision"]
    assert inherited and "the source package has the same error" in inherited[0]["detail"]

    ours = _settings(read_package(out))
    src = _settings(read_package(source, package_paths=[source.parent]))
    ref = _settings(read_package(theirs, package_paths=[theirs.parent]))
    differences = _diff(ours, ref)
    reported = {i["setting"] for i in items if i["status"] in ("changed", "dropped")}
    explained = {k for k in differences if f"joint_limits[{k[6:].split('.')[0]}]" in reported}
    assert explained == {
        "limit:panda_finger_joint2.velocity",
        "limit:panda_finger_joint2.acceleration",
        "limit:panda_finger_joint2.jerk",
    }
    assert differences - explained == UPSTREAM_EDITS
    assert all(ours.get(k) == src.get(k) for k in UPSTREAM_EDITS)  # carried from MoveIt 1 as it was


# ../shared/realworld2 packages (its README), as the session ports them (tests/generated_packages.py).
VENDOR = sorted(name for name, (rel, _) in PORTS.items() if rel.startswith("realworld2/"))


@pytest.mark.parametrize("target", ["ros2", "ros1"])
@pytest.mark.parametrize("name", VENDOR)
def test_vendor_packages_port_with_no_validation_errors(tmp_path, ros2_packages, name, target):
    """Each vendor package ports to both targets and the new package validates (static rules)
    without errors, or each error has a port report line saying why. (The ros2 port is the
    session's, tests/generated_packages.py, which the ROS 2 consumer tests run too.)"""
    rel, paths = PORTS[name]
    source = shared_path(rel)
    if target == "ros2":
        port = ros2_packages.get(f"port:{name}", "humble")
        out, stdout, code = port.out, port.output, port.exit_code
    else:
        args = [arg for p in paths for arg in ("--package-path", str(shared_path(p)))]
        out = tmp_path / name
        cmd = ["init", "--from-package", str(source), "--out", str(out), "--target", target, "--no-plan"]
        result = runner.invoke(app, [*cmd, *args, "--format", "json"])
        assert result.exit_code in (0, 1), result.output
        stdout, code = result.stdout, result.exit_code
    doc = json.loads(stdout)
    errors = [f for f in doc["validation"]["findings"] if f["severity"] == "error"]
    explained = [i for i in doc["port"]["items"] if i["setting"].startswith("validate ")]
    assert len(explained) == len(errors)
    assert all("the source package has the same error" in i["detail"] for i in explained), explained
    assert code == (1 if errors else 0)
    assert (out / "marm_setup.yaml").is_file()
    _assert_moves_the_same(source, [shared_path(p) for p in paths], out, doc)


def _assert_moves_the_same(source, paths, out, doc) -> None:
    """The package model of the source and of the port hold the same joint limits, scaling
    factors, controller names and IK options, or the port report names each difference."""
    from tests.package_diff import motion_settings, unexplained

    src = read_package(source, package_paths=paths)
    robot = load_robot(src.urdf, dict(src.xacro_args), src.package_paths)
    before = motion_settings(src, robot)
    assert unexplained(before, motion_settings(read_package(out), robot), doc["port"]["items"]) == {}
    assert any(k.startswith("controller:") for k in before) and any(k.startswith("limit:") for k in before)


@pytest.mark.parametrize(("source_target", "target"), [("ros1", "ros2"), ("ros2", "ros1")])
def test_panda_ports_keep_what_moves_the_robot(tmp_path, source_target, target):
    source = realworld(source_target, "panda_moveit_config")
    out = tmp_path / "panda"
    cmd = ["init", "--from-package", str(source), "--out", str(out), "--target", target, "--no-plan"]
    result = runner.invoke(app, [*cmd, "--package-path", str(source.parent), "--format", "json"])
    _assert_moves_the_same(source, [source.parent], out, json.loads(result.stdout))


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_panda_moveit2_package_ports_to_both_targets(tmp_path, target):
    """The MoveIt 2 Panda: its config/panda.urdf.xacro wrapper gives way to the description
    .setup_assistant names (the new package's own wrapper would include itself), and the
    gripper controller of gripper_moveit_controllers.yaml joins the arm's."""
    source = realworld("ros2", "panda_moveit_config")
    out = tmp_path / "panda"
    cmd = ["init", "--from-package", str(source), "--out", str(out), "--target", target, "--no-plan"]
    result = runner.invoke(app, [*cmd, "--package-path", str(source.parent), "--format", "json"])
    doc = json.loads(result.stdout)
    errors = {(f["rule"], f["element"]) for f in doc["validation"]["findings"] if f["severity"] == "error"}
    assert errors == INHERITED, doc["validation"]
    setup = (out / "marm_setup.yaml").read_text()
    assert "panda_description/urdf/panda.urdf" in setup
    assert "name: panda_hand_controller" in setup
    notes = [i for i in doc["port"]["items"] if i["setting"] == "robot.urdf" and i["status"] == "changed"]
    assert notes and ".setup_assistant names is used" in notes[0]["detail"]


def test_panda_ros1_to_ros1_without_a_driver_says_the_driver_is_the_users(tmp_path):
    """No arbotix.yaml in the source: the new ros1 package writes no driver files, so the
    ros_control controllers are the user's to keep (not mapped to ArbotiX ones)."""
    source = realworld("ros1", "panda_moveit_config")
    out = tmp_path / "panda"
    cmd = ["init", "--from-package", str(source), "--out", str(out), "--target", "ros1", "--no-plan"]
    result = runner.invoke(app, [*cmd, "--package-path", str(source.parent), "--format", "json"])
    items = {i["setting"]: i for i in json.loads(result.stdout)["port"]["items"]}
    assert items["driver.arm_controller"]["status"] == "todo"
    assert "writes no driver files" in items["driver.arm_controller"]["detail"]
    assert items["driver"]["status"] == "todo"
    assert "arbotix" not in (out / "marm_setup.yaml").read_text()
