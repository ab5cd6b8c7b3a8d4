"""The port keeps move_group's own parameters (trajectory execution, controller management,
planning scene publishing) as the source's launch files set them: on the shared vendor ROS 1
packages, what real `roslaunch --dump-params` gives move_group is what the package model reads,
and the port to Humble and Jazzy writes the same value into config/moveit.yaml, or its report
names the setting (changed, dropped or todo)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest
import yaml
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.moveit_params.move_group_params import MOVE_GROUP_PARAMS
from marm_setup.package.read import read_package
from marm_setup.port.move_group import ros1_value
from tests.conftest import REALWORLD2
from tests.helpers import write_xacro_shim
from tests.integration.test_roslaunch import dump_params

# name -> (config package, launch file a user starts, folder holding its packages)
SOURCES = {
    "kinova": ("kinova-ros/kinova_moveit/robot_configs/j2n6s300_moveit_config", "j2n6s300_demo.launch", "kinova-ros"),
    "fanuc": ("fanuc/moveit_cfgs/fanuc_cr7ia_moveit_config", "demo.launch", "fanuc"),
    "ur5e": ("universal_robot/ur5e_moveit_config", "demo.launch", "universal_robot"),
    "motoman": ("motoman/motoman_sda10f_moveit_config", "demo.launch", "motoman"),
    "panda": ("../realworld/ros1/panda_moveit_config", "demo.launch", "../realworld/ros1"),
}  # fmt: skip
runner = CliRunner()


def source(name: str) -> tuple[Path, Path]:
    folder, _, root = SOURCES[name]
    pkg = REALWORLD2 / folder
    if not pkg.is_dir():
        pytest.skip(f"{pkg} absent")
    return pkg, (REALWORLD2 / root).resolve()


def port(pkg: Path, root: Path, out: Path, distro: str) -> dict:
    cmd = ["init", "--from-package", str(pkg), "--out", str(out), "--ros-distro", distro, "--no-plan"]
    result = runner.invoke(app, [*cmd, "--package-path", str(root), "--trials", "100", "--format", "json"])
    assert result.exit_code in (0, 1), result.output
    return json.loads(result.stdout)


def received(out: Path) -> dict[str, object]:
    """move_group's parameters in the new package's config/moveit.yaml, flattened with dots."""
    doc = yaml.safe_load((out / "config" / "moveit.yaml").read_text())["/**"]["ros__parameters"]
    flat = {f"trajectory_execution.{k}": v for k, v in doc.get("trajectory_execution", {}).items()}
    return {**flat, **{k: v for k, v in doc.items() if not isinstance(v, dict)}}


def source_values(pkg) -> dict[str, object]:
    """What the source's move_group holds for each parameter: its launch files' value, else MoveIt 1's default."""
    given = {p.name.removeprefix("move_group/"): ros1_value(p.value) for p in pkg.launch_params}
    return {p.name: given.get(p.ros1, p.moveit1_default) for p in MOVE_GROUP_PARAMS}


@pytest.mark.skipif(shutil.which("roslaunch") is None, reason="roslaunch not on PATH")
@pytest.mark.parametrize("name", sorted(SOURCES))
def test_the_package_model_reads_what_roslaunch_gives_move_group(tmp_path, name):
    pkg_dir, root = source(name)
    shim = write_xacro_shim(tmp_path / "pkgs" / "xacro")  # `$(find xacro)/xacro`: the shim's package
    (shim / "package.xml").write_text("<package><name>xacro</name></package>")
    dumped = dump_params(pkg_dir / "launch" / SOURCES[name][1], [root, tmp_path / "pkgs"], tmp_path)
    pkg = read_package(pkg_dir, package_paths=(root,))
    ours = {f"/{p.name}": ros1_value(p.value) for p in pkg.launch_params}
    names = [f"/move_group/{p.ros1}" for p in MOVE_GROUP_PARAMS]
    both = [k for k in names if k in dumped and k in ours]
    assert both, sorted(dumped)[:20]
    assert {k: ours[k] for k in both} == {k: dumped[k] for k in both}


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
@pytest.mark.parametrize("name", sorted(SOURCES))
def test_the_port_keeps_move_group_parameters(tmp_path, name, distro):
    pkg_dir, root = source(name)
    doc = port(pkg_dir, root, tmp_path / "out", distro)
    before, after = source_values(read_package(pkg_dir, package_paths=(root,))), received(tmp_path / "out")
    items = doc["port"]["items"]
    named = {i["setting"] for i in items if i["status"] != "carried"}
    lost = {k: (v, after.get(k)) for k, v in before.items() if after.get(k, v) != v and k not in named}
    assert lost == {}
    assert all(after.get(k, v) == v for k, v in before.items() if k.startswith("trajectory_execution."))


def test_a_kinova_arm_keeps_execution_duration_monitoring_off(tmp_path):
    """j2n6s300's move_group launch turns monitoring off (slow arm): the port keeps it off, and
    its trajectory_execution params written outside that namespace (MoveIt 1 read none) are
    reported dropped, with MoveIt 1's default scaling 1.1 kept."""
    pkg_dir, root = source("kinova")
    doc = port(pkg_dir, root, tmp_path / "out", "jazzy")
    after = received(tmp_path / "out")
    assert after["trajectory_execution.execution_duration_monitoring"] is False
    assert after["trajectory_execution.allowed_execution_duration_scaling"] == 1.1
    items = {i["setting"]: i for i in doc["port"]["items"]}
    assert items["allowed_execution_duration_scaling"]["status"] == "dropped"
    assert items["trajectory_execution.execution_duration_monitoring"]["area"] == "execution"
    assert items["capabilities[move_group/MoveGroupPickPlaceAction]"]["status"] == "dropped"
    # the changes Jazzy forces, named with their MoveIt reason, before anything that does not move the robot
    iptp = items["ompl.request_adapters[AddTimeParameterization]"]
    assert iptp["status"] == "changed" and "IPTP" in iptp["detail"] and "TOTG" in iptp["detail"]
    assert "rejection" in items["ompl.request_adapters[FixStartStateCollision]"]["detail"]
    motion = [
        i["area"] in ("limits", "scaling", "controllers", "kinematics", "planners", "execution")
        for i in doc["port"]["items"]
    ]
    assert motion == sorted(motion, reverse=True)
