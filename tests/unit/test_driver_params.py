"""ros2_control's declared parameters (moveit_params/driver_params.py, data/drivers_<family>.yaml)
and validate's check of a package's ros2_controllers.yaml against them: a fresh package passes,
each one-line edit that stops ros2_control_node or keeps a controller from loading is one error."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from marm_setup.moveit_params import CONTROLLER_MANAGER, driver_rows
from marm_setup.package import read_package
from marm_setup.validate.rules.driver_param_rules import check_driver_parameters
from tests.render_helpers import written_ros2_marms
from tests.validate_helpers import replace_text

CONTROLLERS = "config/ros2_controllers.yaml"
JTC = "joint_trajectory_controller/JointTrajectoryController"


@pytest.fixture(scope="module")
def fresh(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """A generated ROS 2 marm package per distro, made once."""
    return written_ros2_marms(tmp_path_factory)


def edited(fresh: dict[str, Path], tmp_path: Path, distro: str, old: str, new: str) -> Path:
    pkg = tmp_path / "marm_moveit_config"
    shutil.copytree(fresh[distro], pkg)
    replace_text(pkg, CONTROLLERS, old, new)
    return pkg


def findings(pkg: Path, distro: str | None) -> list[tuple[str, str, str]]:
    return [(f.rule, f.file, f.element) for f in check_driver_parameters(read_package(pkg), distro)]


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_a_generated_package_passes(fresh, distro):
    assert findings(fresh[distro], distro) == []


@pytest.mark.parametrize("distro", ["humble", "jazzy", None])
def test_a_double_update_rate_stops_ros2_control_node(fresh, tmp_path, distro):
    pkg = edited(fresh, tmp_path, distro or "jazzy", "update_rate: 100", "update_rate: 100.0")
    element = "controller_manager.ros__parameters.update_rate"
    assert findings(pkg, distro) == [("controller.param-type", CONTROLLERS, element)]
    found = check_driver_parameters(read_package(pkg), distro)[0]
    assert "ros2_control_node stops" in found.message
    assert "controller_manager" in found.hint


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_an_integer_for_a_bool_keeps_the_trajectory_controller_from_loading(fresh, tmp_path, distro):
    key = "allow_nonzero_velocity_at_trajectory_end"
    pkg = edited(fresh, tmp_path, distro, f"{key}: true", f"{key}: 1")
    assert findings(pkg, distro) == [
        ("controller.param-type", CONTROLLERS, f"arm_controller.ros__parameters.{key}")
    ]
    assert "MoveIt cannot execute" in check_driver_parameters(read_package(pkg), distro)[0].message


def test_a_value_outside_a_declared_validator_is_an_error(fresh, tmp_path):
    old = "allow_nonzero_velocity_at_trajectory_end: true"
    pkg = edited(fresh, tmp_path, "jazzy", old, old + "\n    interpolation_method: cubic")
    element = "arm_controller.ros__parameters.interpolation_method"
    assert findings(pkg, "jazzy") == [("controller.param-bounds", CONTROLLERS, element)]


def test_gains_per_joint_are_matched_through_the_joint_placeholder(fresh, tmp_path):
    old = "allow_nonzero_velocity_at_trajectory_end: true"
    pkg = edited(fresh, tmp_path, "jazzy", old, old + "\n    gains:\n      joint1:\n        p: 10")
    element = "arm_controller.ros__parameters.gains.joint1.p"
    assert findings(pkg, "jazzy") == [("controller.param-type", CONTROLLERS, element)]


def test_a_controller_of_a_type_not_in_the_tables_is_left_alone(fresh, tmp_path):
    pkg = edited(fresh, tmp_path, "jazzy", JTC, "my_controllers/MyTrajectoryController")
    text = (pkg / CONTROLLERS).read_text(encoding="utf-8")
    (pkg / CONTROLLERS).write_text(
        text.replace(
            "allow_nonzero_velocity_at_trajectory_end: true", "allow_nonzero_velocity_at_trajectory_end: 1"
        )
    )
    assert findings(pkg, "jazzy") == []


@pytest.mark.parametrize("family", ["humble", "jazzy"])
def test_the_tables_hold_the_manager_and_the_controllers_marm_setup_writes(family):
    rows = driver_rows(family)
    assert [r.type for r in rows[CONTROLLER_MANAGER] if r.name == "update_rate"] == ["int"]
    assert {r.name for r in rows[JTC]} >= {"joints", "command_interfaces", "state_interfaces"}
    assert all(":" in r.source for node in rows.values() for r in node)


@pytest.mark.skipif(
    "MARM_ROS2_CONTROL_CHECKOUT" not in os.environ, reason="needs ros2_control git repositories"
)
def test_regenerating_reproduces_the_committed_driver_tables():
    from marm_setup.moveit_params.regenerate import render_drivers

    control, controllers = (
        Path(os.environ[k]) for k in ("MARM_ROS2_CONTROL_CHECKOUT", "MARM_ROS2_CONTROLLERS_CHECKOUT")
    )
    for path, text in render_drivers(control, controllers).items():
        assert text == path.read_text(encoding="utf-8"), path.name
