"""A port gives every link one TF parent: a virtual joint MoveIt skips (its child already has a
URDF parent joint) gets no static TF in the new demo. ROS 2 demos are run through the real
launch frontend (tests/ros2_consumer.py); the ROS 1 demo is read as roslaunch reads its nodes."""

from __future__ import annotations

import json
from collections import Counter
from pathlib import Path

import pytest
from lxml import etree
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.robot.load import load_robot
from tests.ros2_consumer import harness_python, harness_report
from tests.vendor_packages import footprint_parented

runner = CliRunner()


def port(tmp_path: Path, target: list[str]) -> tuple[Path, Path, dict]:
    source, paths = footprint_parented(tmp_path / "src")
    out = tmp_path / "out"
    args = [a for p in paths for a in ("--package-path", str(p))]
    cmd = ["init", "--from-package", str(source), "--out", str(out), *target, "--no-plan"]
    result = runner.invoke(app, [*cmd, *args, "--format", "json", "--jobs", "1"])
    assert result.exit_code == 0, result.output
    return out, tmp_path / "src" / "fp_description", json.loads(result.stdout)


def tf_parents(description: Path, static_tfs: list[tuple[str, str]]) -> Counter[str]:
    """How many TF parents each frame gets: robot_state_publisher's (the URDF's joints) and the
    demo's static transforms (parent, child)."""
    robot = load_robot(description / "urdf" / "fp.urdf", {}, [description.parent])
    return Counter([j.child for j in robot.joints] + [child for _, child in static_tfs])


def ros1_static_tfs(launch: Path) -> list[tuple[str, str]]:
    """(parent, child) of each static_transform_publisher node (`x y z yaw pitch roll parent child`)."""
    nodes = etree.parse(str(launch)).iter("node")
    return [tuple(n.get("args").split()[-2:]) for n in nodes if n.get("type") == "static_transform_publisher"]


def test_the_ros1_port_gives_base_link_one_parent(tmp_path):
    source_demo = ros1_static_tfs(footprint_parented(tmp_path / "before")[0] / "launch" / "demo.launch")
    description = tmp_path / "before" / "fp_description"
    assert (
        tf_parents(description, source_demo)["base_link"] == 2
    )  # the source's demo: world and base_footprint
    out, description, doc = port(tmp_path, ["--target", "ros1"])
    for launch in ("demo.launch",):
        parents = tf_parents(description, ros1_static_tfs(out / "launch" / launch))
        assert max(parents.values()) == 1, parents
    items = {i["setting"]: i for i in doc["port"]["items"]}
    assert items["virtual_joints[world_joint].static_tf"]["status"] == "changed"
    assert "base_footprint_joint" in items["virtual_joints[world_joint].static_tf"]["detail"]
    assert "world_joint" in (out / "config" / "fp.srdf").read_text()  # the SRDF keeps it, as MoveIt reads it


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_the_ros2_port_gives_every_link_one_parent_under_the_real_launch(tmp_path, distro):
    harness_python(distro)  # skips where ../shared's harness is absent
    out, description, _ = port(tmp_path, ["--target", "ros2", "--ros-distro", distro])
    demo = "launch/demo.launch.xml"
    with harness_report(out, distro, [description], [demo]) as report:
        processes = report["launch"][demo]["processes"]
    assert any(p.get("executable") == "robot_state_publisher" for p in processes), processes
    static = [p["cmd"] for p in processes if p.get("executable") == "static_transform_publisher"]
    edges = [(cmd[cmd.index("--frame-id") + 1], cmd[cmd.index("--child-frame-id") + 1]) for cmd in static]
    parents = tf_parents(description, edges)
    assert max(parents.values()) == 1, parents
    assert (out / "config" / "moveit.rviz").read_text().count("Fixed Frame: base_footprint") == 1


def test_init_from_the_srdf_publishes_no_tf_for_a_skipped_virtual_joint(tmp_path):
    source, _ = footprint_parented(tmp_path / "src")
    urdf = tmp_path / "src" / "fp_description" / "urdf" / "fp.urdf"
    out = tmp_path / "out"
    cmd = ["init", str(urdf), "--from-srdf", str(source / "config" / "fp.srdf"), "--out", str(out)]
    result = runner.invoke(app, [*cmd, "--target", "ros2", "--trials", "100", "--jobs", "1"])
    assert result.exit_code == 0, result.output
    demo = etree.parse(str(out / "launch" / "demo.launch.xml"))
    assert [n.get("args") for n in demo.iter("node") if n.get("exec") == "static_transform_publisher"] == []
    assert "world_joint" in (out / "config" / "fp.srdf").read_text()


def description_todos(doc: dict) -> list[str]:
    return [i["detail"] for i in doc["port"]["items"] if i["setting"] == "description package fp_description"]


def test_a_catkin_description_package_is_named_for_a_ros2_port(tmp_path, monkeypatch):
    monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    _, _, doc = port(tmp_path, ["--target", "ros2", "--ros-distro", "jazzy"])
    (detail,) = description_todos(doc)
    assert detail.startswith("a catkin package: it is not built for jazzy") and "urdf/fp.urdf" in detail
    (item,) = [i for i in doc["port"]["items"] if i["setting"] == "description package fp_description"]
    assert (item["status"], item["source"]) == ("todo", str(tmp_path / "src" / "fp_description"))  # as typed


def test_a_sourced_ros2_install_lacking_the_included_urdf_is_named(tmp_path, monkeypatch):
    """The launch finds the sourced jazzy fp_description, which has no urdf/fp.urdf."""
    share = tmp_path / "jazzy" / "share" / "fp_description"
    share.mkdir(parents=True)
    (share / "package.xml").write_text(
        '<package format="3"><name>fp_description</name><buildtool_depend>ament_cmake</buildtool_depend></package>'
    )
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(tmp_path / "jazzy"))
    _, _, doc = port(tmp_path, ["--target", "ros2", "--ros-distro", "jazzy"])
    (detail,) = description_todos(doc)
    assert detail.startswith(f"the sourced jazzy install ({share}) has no urdf/fp.urdf")
    (share / "urdf").mkdir()
    (share / "urdf" / "fp.urdf").write_text("<robot/>")
    _, _, doc = port(tmp_path / "again", ["--target", "ros2", "--ros-distro", "jazzy"])
    assert description_todos(doc) == []


def test_a_catkin_description_package_is_fine_for_a_ros1_port(tmp_path, monkeypatch):
    monkeypatch.delenv("ROS_PACKAGE_PATH", raising=False)
    _, _, doc = port(tmp_path, ["--target", "ros1"])
    assert description_todos(doc) == []
