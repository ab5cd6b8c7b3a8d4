"""`marm-setup init --from-package`: a package we generated ports back to the same
`marm_setup.yaml` (every target and distro); bad input is one error line; the report in text and
JSON accounts for every setting."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import FIXTURES, MARM_URDF

runner = CliRunner()
SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TARGETS = [("ros1", "noetic"), ("ros2", "humble"), ("ros2", "jazzy")]


def _generate(out, target: str, distro: str):
    args = ["init", str(MARM_URDF), "--out", str(out), "--setup", str(SPEC), "--trials", "300"]
    result = runner.invoke(app, [*args, "--target", target, "--ros-distro", distro])
    assert result.exit_code == 0, result.output


def _port(src, out, *args):
    return runner.invoke(app, ["init", "--from-package", str(src), "--out", str(out), "--no-plan", *args])


@pytest.mark.parametrize(("target", "distro"), TARGETS)
def test_round_trip_reproduces_marm_setup_yaml(tmp_path, target, distro):
    """Read back from the rendered files (SRDF, kinematics, limits, OMPL, controllers, ArbotiX)."""
    _generate(tmp_path / "a", target, distro)
    result = _port(tmp_path / "a", tmp_path / "b", "--target", target, "--ros-distro", distro)
    assert result.exit_code == 0, result.output
    original = (tmp_path / "a" / "marm_setup.yaml").read_text()
    assert (tmp_path / "b" / "marm_setup.yaml").read_text() == original
    assert "no findings" in result.stdout


def test_round_trip_reads_the_files_not_just_marm_setup_yaml(tmp_path):
    """A hand edit of kinematics.yaml reaches the new setup (the files are read, the yaml only
    for what no file holds)."""
    _generate(tmp_path / "a", "ros1", "noetic")
    kin = tmp_path / "a" / "config" / "kinematics.yaml"
    kin.write_text(
        kin.read_text().replace("kinematics_solver_timeout: 0.05", "kinematics_solver_timeout: 0.2")
    )
    result = _port(tmp_path / "a", tmp_path / "b", "--target", "ros1")
    assert result.exit_code == 0, result.output
    assert "timeout: 0.2" in (tmp_path / "b" / "marm_setup.yaml").read_text()
    assert "kinematics[arm].kinematics_solver_timeout: 0.2" in result.stdout


def test_ros1_to_ros2_changes_the_gripper_action_and_says_why(tmp_path):
    _generate(tmp_path / "a", "ros1", "noetic")
    result = _port(
        tmp_path / "a", tmp_path / "b", "--target", "ros2", "--ros-distro", "jazzy", "--format", "json"
    )
    assert result.exit_code == 0, result.output
    doc = json.loads(result.stdout)
    items = doc["port"]["items"]
    action = [i for i in items if i["setting"] == "controllers[gripper_controller].action_ns"]
    assert action and action[0]["status"] == "changed"
    assert "'gripper_action' -> 'gripper_cmd'" in action[0]["detail"]
    arbotix = [i for i in items if i["setting"] == "arbotix"]
    assert arbotix[0]["status"] == "dropped" and "no ArbotiX driver" in arbotix[0]["detail"]
    assert doc["port"]["counts"]["changed"] == sum(1 for i in items if i["status"] == "changed")
    assert doc["validation"]["errors"] == 0
    assert doc["port"]["target"] == "ros2" and doc["port"]["ros_distro"] == "jazzy"


def _with_sensors_file(pkg: Path, text: str) -> None:
    """config/sensors_3d.yaml and the Setup Assistant's sensor_manager.launch.xml loading it
    (move_group reads only a sensors list a launch file loads)."""
    (pkg / "config" / "sensors_3d.yaml").write_text(text)
    name = re.search(r"<name>(.+?)</name>", (pkg / "package.xml").read_text()).group(1)  # type: ignore[union-attr]
    load = f'<rosparam command="load" file="$(find {name})/config/sensors_3d.yaml"/>'
    (pkg / "launch" / "sensor_manager.launch.xml").write_text(f"<launch>\n  {load}\n</launch>\n")


def test_every_source_file_is_accounted_for(tmp_path):
    """Nothing dropped silently: each file of the source package is read or has a report line."""
    _generate(tmp_path / "a", "ros1", "noetic")
    _with_sensors_file(tmp_path / "a", "sensors: []\n")
    result = _port(tmp_path / "a", tmp_path / "b", "--format", "json")
    doc = json.loads(result.stdout)
    sources = " ".join(i["source"] for i in doc["port"]["items"])
    files = [p.relative_to(tmp_path / "a").as_posix() for p in (tmp_path / "a").rglob("*") if p.is_file()]
    assert [f for f in files if f not in sources] == []
    sensors = [i for i in doc["port"]["items"] if i["source"].startswith("config/sensors_3d.yaml")]
    assert sensors[0]["status"] == "carried" and "none configured" in sensors[0]["detail"]


def test_sensors_and_servo_settings_are_carried(tmp_path):
    """A 3D sensor and a MoveIt Servo file reach marm_setup.yaml's `sensors` and `servo` (a MoveIt
    1 sensor, unnamed, is named by its type and index); a key the setup has no place for is a line."""
    _generate(tmp_path / "a", "ros1", "noetic")
    _with_sensors_file(
        tmp_path / "a",
        "sensors:\n  - sensor_plugin: occupancy_map_monitor/PointCloudOctomapUpdater\n"
        "    point_cloud_topic: /camera/points\n    max_range: 3.0\n    mystery: 1\n",
    )
    servo = tmp_path / "a" / "config" / "arm_servo.yaml"
    servo.write_text(servo.read_text().replace("publish_period: 0.034", "publish_period: 0.02"))
    result = _port(
        tmp_path / "a", tmp_path / "b", "--target", "ros2", "--ros-distro", "humble", "--format", "json"
    )
    assert result.exit_code == 0, result.output
    items = _items(result)
    assert items["sensors[0]"][0]["status"] == "carried" and items["sensors[0]"][0]["area"] == "perception"
    assert items["sensors[0].mystery"][0]["status"] == "dropped"
    setup = (tmp_path / "b" / "marm_setup.yaml").read_text()
    assert "name: pointcloud_0" in setup and "topic: /camera/points" in setup and "max_range: 3.0" in setup
    assert "group: arm" in setup and "publish_period: 0.02" in setup
    assert "publish_period: 0.02" in (tmp_path / "b" / "config" / "arm_servo.yaml").read_text()


def test_from_package_with_a_spec_is_one_error_line(tmp_path):
    cmd = ["init", "--from-package", str(tmp_path), "--setup", str(SPEC), "--out", str(tmp_path / "o")]
    result = runner.invoke(app, cmd)
    assert result.exit_code == 2
    assert result.stderr.strip().splitlines() == [
        "error: --from-package: --from-package takes the robot from the package: drop --setup"
    ]


def test_urdf_and_xacro_args_replace_the_packages_own(tmp_path):
    """A URDF given with --from-package is the description the port uses (as validate --urdf),
    and --xacro-arg reaches it."""
    _generate(tmp_path / "a", "ros2", "jazzy")
    copy = tmp_path / "robot" / "marm.urdf.xacro"
    copy.parent.mkdir()
    copy.write_text(MARM_URDF.read_text())
    args = ["--package-path", str(FIXTURES / "marm"), "--xacro-arg", "with_gripper:=true", "--no-plan"]
    result = runner.invoke(
        app, ["init", str(copy), "--from-package", str(tmp_path / "a"), "--out", str(tmp_path / "b"), *args]
    )
    assert result.exit_code == 0, result.output
    setup = (tmp_path / "b" / "marm_setup.yaml").read_text()
    assert "urdf: ../robot/marm.urdf.xacro" in setup
    assert "xacro_args:\n    with_gripper: 'true'" in setup


def test_not_a_package_is_one_error_line_and_writes_nothing(tmp_path):
    (tmp_path / "empty").mkdir()
    result = _port(tmp_path / "empty", tmp_path / "out")
    assert result.exit_code == 2
    assert len(result.stderr.strip().splitlines()) == 1 and "not a MoveIt config package" in result.stderr
    assert "Traceback" not in result.output
    assert not (tmp_path / "out").exists()


def test_init_without_urdf_or_package_is_one_error_line(tmp_path):
    result = runner.invoke(app, ["init", "--out", str(tmp_path / "o")])
    assert result.exit_code == 2
    assert "missing: the robot's URDF (marm-setup init URDF -o DIR), or --from-package PKG" in result.stderr


def _items(result) -> dict[str, list[dict]]:
    doc = json.loads(result.stdout)
    out: dict[str, list[dict]] = {}
    for item in doc["port"]["items"]:
        out.setdefault(item["setting"], []).append(item)
    return out


def test_what_moveit_cannot_use_is_dropped_with_a_line(tmp_path):
    """A floating virtual joint off the root, KDL on a group that is no chain: MoveIt skips / cannot
    load them, so the port leaves them out and says so instead of failing or writing an error."""
    _generate(tmp_path / "a", "ros1", "noetic")
    srdf = tmp_path / "a" / "config" / "marm.srdf"
    text = srdf.read_text().replace('child_link="base_link"', 'child_link="link2"')
    srdf.write_text(text.replace('type="fixed" parent_frame="world"', 'type="floating" parent_frame="world"'))
    kin = tmp_path / "a" / "config" / "kinematics.yaml"
    kin.write_text(
        kin.read_text() + "gripper:\n  kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n"
    )
    result = _port(tmp_path / "a", tmp_path / "b", "--target", "ros2", "--format", "json")
    assert result.exit_code == 0, result.output
    items = _items(result)
    (vj,) = items["virtual_joints[virtual_joint]"]  # dropped, and never also "carried"
    assert vj["status"] == "dropped" and "is not the URDF's root link 'base_link'" in vj["detail"]
    kdl = items["kinematics[gripper].kinematics_solver"][-1]
    assert kdl["status"] == "changed" and "needs a serial chain" in kdl["detail"]
    setup = (tmp_path / "b" / "marm_setup.yaml").read_text()
    assert "virtual_joints" not in setup and "group: gripper\n  solver" not in setup
    assert json.loads(result.stdout)["validation"]["errors"] == 0


def test_a_gripper_command_of_several_joints_becomes_a_trajectory_controller_on_ros2(tmp_path):
    """ros2_control's GripperActionController drives one joint; a joint two controllers share is
    a todo line (ros2_control activates one controller per command interface)."""
    _generate(tmp_path / "a", "ros1", "noetic")
    ctl = tmp_path / "a" / "config" / "controllers.yaml"
    text = ctl.read_text().replace("      - finger_joint1\n", "      - finger_joint1\n      - joint6\n")
    ctl.write_text(text)
    result = _port(tmp_path / "a", tmp_path / "b", "--target", "ros2", "--format", "json")
    items = _items(result)
    change = items["controllers[gripper_controller].type"][0]
    assert change["status"] == "changed" and "GripperCommand -> FollowJointTrajectory" in change["detail"]
    setup = (tmp_path / "b" / "marm_setup.yaml").read_text()
    assert (
        "name: gripper_controller\n  type: FollowJointTrajectory\n  action_ns: follow_joint_trajectory"
        in setup
    )
    shared = items["controllers[arm_controller], controllers[gripper_controller]"][0]
    assert shared["status"] == "todo" and shared["detail"].startswith(
        "share joint6: ros2_control activates one"
    )


def test_report_lines_say_what_the_new_package_holds(tmp_path):
    """The projection the new package writes identically is carried; LMA ships with
    moveit_kinematics (no todo); a virtual joint srdfdom skips (no name) has its own line."""
    _generate(tmp_path / "a", "ros1", "noetic")
    srdf = tmp_path / "a" / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text().replace('name="virtual_joint" ', ""))
    kin = tmp_path / "a" / "config" / "kinematics.yaml"
    kin.write_text(
        kin.read_text().replace(
            "kdl_kinematics_plugin/KDLKinematicsPlugin", "lma_kinematics_plugin/LMAKinematicsPlugin"
        )
    )
    result = _port(tmp_path / "a", tmp_path / "b", "--target", "ros2", "--format", "json")
    assert result.exit_code == 0, result.output
    items = _items(result)
    (projection,) = items["planners[arm].projection_evaluator"]
    assert (projection["status"], projection["detail"]) == ("carried", "joints(joint1,joint2)")
    assert [i["status"] for i in items["kinematics[arm].kinematics_solver"]] == ["carried"]
    (skipped,) = [
        i for i in json.loads(result.stdout)["port"]["items"] if i["setting"].startswith("virtual_joint")
    ]
    assert skipped["status"] == "dropped" and "missing attribute 'name'" in skipped["detail"]
