"""A port keeps a package's 3D sensors and MoveIt Servo configurations (issue 25): the package
model of the source and of the port hold the same sensors (plugin, topic, every parameter) and
servos (group, frames where the target's servo reads them, scales, output message type and the
controller the output reaches), or the port report names each difference; ros1 -> ros2,
ros2 -> ros1 and humble -> jazzy, on the marm with a point cloud and a depth camera."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.package.read import read_package
from marm_setup.validate.runner import validate
from tests.conftest import FIXTURES
from tests.integration.test_servo_perception import write_marm

runner = CliRunner()
SENSORS = """- {name: depth_camera, type: depth_image, topic: /camera/depth/image_raw, padding_scale: 3.0}
octomap_resolution: 0.05
"""
SERVO_READ = ("move_group_name", "command_out_type", "scale.linear", "scale.rotational", "scale.joint")
FRAMES = ("planning_frame", "ee_frame_name", "robot_link_command_frame")  # noetic and humble only


def perception(pkg_dir: Path, distro: str) -> tuple[list[tuple[str, dict]], dict[str, dict]]:
    """(sensors in order: (source name, parameters), servos by group: what the distro's servo reads)."""
    pkg = read_package(pkg_dir)
    sensors = [
        (s.name, {"plugin": s.plugin, **{p.key: p.value for p in s.params}})
        for s in (pkg.sensors.sensors if pkg.sensors else ())
    ]
    keys = SERVO_READ + (FRAMES if distro != "jazzy" else ())
    servos = {}
    for servo in pkg.servo:
        values = {k: p.value for k in keys if (p := servo.param(k)) is not None}
        topic = servo.param(
            "command_out_topic"
        )  # /<controller>/joint_trajectory, /<controller>/commands, ...
        values["controller"] = str(topic.value).strip("/").split("/")[0] if topic is not None else None
        servos[servo.group] = values
    return sensors, servos


def port(source: Path, out: Path, target: str, distro: str) -> list[dict]:
    argv = ["init", "--from-package", str(source), "--out", str(out), "--target", target, "--no-plan"]
    argv += [
        "--ros-distro",
        distro,
        "--format",
        "json",
        "--jobs",
        "1",
        "--package-path",
        str(FIXTURES / "marm"),
    ]
    made = runner.invoke(app, argv)
    assert made.exit_code in (0, 1), made.output
    return json.loads(made.stdout)["port"]["items"]


def unexplained(before, after, items: list[dict]) -> dict[str, object]:
    """Every sensor or servo value of the source the port changes without a changed/dropped line."""
    said = {i["setting"] for i in items if i["status"] in ("changed", "dropped")}
    missing: dict[str, object] = {}
    (src_sensors, src_servos), (new_sensors, new_servos) = before, after
    for i, (name, params) in enumerate(src_sensors):
        kept = new_sensors[i][1] if i < len(new_sensors) else {}
        for key, value in params.items():
            if kept.get(key) != value and not {f"sensors[{name}]", f"sensors[{name}].{key}"} & said:
                missing[f"sensors[{name}].{key}"] = value
    for group, values in src_servos.items():
        kept = new_servos.get(group, {})
        for key, value in values.items():
            explained = {f"servo[{group}]", f"servo[{group}].{key}", f"servo[{group}].command_out_type"}
            if kept.get(key) != value and not explained & said:
                missing[f"servo[{group}].{key}"] = value
    return missing


@pytest.mark.parametrize(
    ("source", "command_out", "target", "distro"),
    [
        ("noetic", "trajectory", "ros2", "humble"),
        ("humble", "trajectory", "ros1", "noetic"),
        ("humble", "position", "ros1", "noetic"),
        ("humble", "position", "ros2", "jazzy"),
        ("jazzy", "position", "ros2", "humble"),
    ],
)
def test_the_port_keeps_sensors_and_servo(tmp_path, source, command_out, target, distro):
    servo = f"servo:\n- {{group: arm, command_out: {command_out}, scale: {{linear: 0.25, joint: 0.7}}}}\n"
    (tmp_path / "src").mkdir()
    src = write_marm(tmp_path / "src", "ros1" if source == "noetic" else "ros2", source, SENSORS + servo)
    items = port(src, tmp_path / "out" / "marm_moveit_config", target, distro)
    before = perception(src, distro)
    after = perception(tmp_path / "out" / "marm_moveit_config", distro)
    assert len(before[0]) == 2 and before[1]["arm"]["scale.linear"] == 0.25  # both sensors and the servo read
    assert unexplained(before, after, items) == {}
    assert [s[1] for s in after[0]] == [s[1] for s in before[0]]  # sensors: every parameter as it was
    found = validate(tmp_path / "out" / "marm_moveit_config", plan=False).findings
    assert not [f for f in found if f.rule.startswith(("servo.", "sensors.")) and f.is_error]
    if target == "ros1" and command_out == "position":
        assert after[1]["arm"]["command_out_type"] == "trajectory_msgs/JointTrajectory"
        assert after[1]["arm"]["controller"] == "arm_controller"
    else:
        # a Jazzy source names no frames (its servo reads none): a Humble port writes the group's own
        assert {k: after[1]["arm"].get(k) for k in before[1]["arm"]} == before[1]["arm"]
