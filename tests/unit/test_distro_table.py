"""Every distro is one row of marm_setup.ros DISTROS (issue 32): a new distro is one row, an
unknown distro is one `error:` line naming the known ones."""

from __future__ import annotations

import dataclasses

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.errors import InputError
from marm_setup.ros import DISTROS, Target, distro_row, distros_of
from tests.conftest import FIXTURES
from tests.render_helpers import marm_with, rendered_files


def test_a_new_distro_is_one_row(monkeypatch):
    """A fake distro of Jazzy's capabilities renders what Jazzy renders, but for its name."""
    monkeypatch.setitem(DISTROS, "fakedistro", dataclasses.replace(DISTROS["jazzy"], name="fakedistro"))
    assert "fakedistro" in distros_of(Target.ROS2)
    model, robot = marm_with("ros2", "jazzy")
    jazzy = rendered_files(model, robot)
    fake = rendered_files(dataclasses.replace(model, ros_distro="fakedistro"), robot)
    assert fake.keys() == jazzy.keys()
    assert "ros_distro: fakedistro" in fake["marm_setup.yaml"]
    for path, text in fake.items():
        assert text.replace("fakedistro", "jazzy").replace("Fakedistro", "Jazzy") == jazzy[path], path


def test_kilted_and_rolling_read_jazzy_tables_with_their_own_controllers():
    for name in ("kilted", "rolling"):
        row = distro_row(name, Target.ROS2)
        assert row.params == "jazzy" and row.launch_frontend == "jazzy"
        gripper = row.controller("GripperCommand")
        assert gripper.type == "parallel_gripper_action_controller/GripperActionController"
        assert gripper.moveit_type == "ParallelGripperCommand"
    assert distro_row("rolling").controller("forward_position").interface_name == "position"
    assert distro_row("kilted").controller("forward_position").type.startswith("position_controllers/")


def test_a_missing_capability_names_the_known_ones():
    with pytest.raises(InputError, match="noetic has no GripperCommand controller"):
        distro_row("noetic").controller("GripperCommand")


def test_an_unknown_distro_is_one_error_line(tmp_path):
    out = tmp_path / "pkg"
    urdf = FIXTURES / "marm" / "urdf" / "marm.urdf.xacro"
    result = CliRunner().invoke(app, ["init", str(urdf), "--out", str(out), "--ros-distro", "iron"])
    assert result.exit_code == 2
    assert result.stderr.strip() == (
        "error: --ros-distro: 'iron' is not a ros2 distro (valid: humble, jazzy, kilted, rolling)"
    )
    assert not out.exists()
    with pytest.raises(InputError, match=r"'iron' is not a known distro \(valid: noetic, humble, jazzy"):
        distro_row("iron")
