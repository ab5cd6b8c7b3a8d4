"""A demo never drives real hardware: a description's own ros2_control switch is used only when
expanding it proves every system mock (robot/mock_switch.py), else the launch files replace the
hardware (render/hardware.py, scripts/with_mock_hardware.py); use_mock_hardware:=false gives
the vendor's real hardware. Checked by expanding with the real xacro."""

from __future__ import annotations

import dataclasses
import os
import subprocess
import sys
from pathlib import Path

import pytest

from marm_setup.errors import InputError
from marm_setup.render.hardware import description_hardware, hardware_lines, use_mock_hardware_help
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from marm_setup.robot.load import expand_xacro, load_robot, parse_xacro_args
from marm_setup.robot.mock_switch import find_mock_switch, switch_candidates
from marm_setup.robot.ros2_control import MOCK_PLUGIN, Ros2ControlSystem, on_mock_hardware, systems_in_urdf
from marm_setup.robot.ros_packages import find_packages
from marm_setup.setup.model import Ros2ControlHardware
from tests.helpers import write_xacro_shim
from tests.vendor_descriptions import NAMES, write_vendor_descriptions


def system(plugin: str) -> str:
    return f'<ros2_control name="s" type="system"><hardware><plugin>{plugin}</plugin></hardware><joint name="j"/></ros2_control>'


def urdf(*plugins: str) -> str:
    return f"<robot name='r'>{''.join(system(p) for p in plugins)}</robot>"


def test_candidates_are_boolean_switch_words_mock_and_fake_first():
    known = {
        "sim_gazebo": "false",
        "use_fake_hardware": "false",
        "robot_ip": "1.2.3.4",
        "use_mock": "maybe",
        "fake_x": "1",
    }
    assert switch_candidates(known) == ["fake_x", "use_fake_hardware", "sim_gazebo"]


@pytest.mark.parametrize(
    ("answers", "expected"),
    [
        ({"true": urdf(MOCK_PLUGIN), "false": urdf("v/Real")}, "use_mock_hardware"),
        ({"true": urdf(MOCK_PLUGIN), "false": urdf(MOCK_PLUGIN)}, None),  # mock either way: no switch
        ({"true": urdf("gz/Sim"), "false": urdf("v/Real")}, None),  # a simulator is not mock
        (
            {"true": urdf(MOCK_PLUGIN, "v/Gripper"), "false": urdf("v/Real", "v/Gripper")},
            None,
        ),  # one stays real
        ({"true": urdf(), "false": urdf("v/Real")}, None),  # no system at all is not mock
    ],
)
def test_a_switch_is_proven_by_expanding_both_ways(answers, expected):
    def expand(args):
        return answers[args["use_mock_hardware"]]

    found = find_mock_switch(expand, {}, {"use_mock_hardware": "false"})
    assert (found.arg if found else None) == expected


def test_an_expansion_that_fails_proves_nothing():
    def expand(args):
        raise InputError("boom")

    assert find_mock_switch(expand, {}, {"use_fake_hardware": "false"}) is None


def test_a_switch_to_a_mock_the_distro_lacks_is_replaced():
    """Franka's use_fake_hardware gives Humble's fake_components, which Jazzy does not have."""
    from marm_setup.robot.model import RobotModel
    from marm_setup.robot.ros2_control import MockSwitch

    real = (Ros2ControlSystem("franka", "franka_hardware/FrankaHardwareInterface", ("j1",)),)
    switch = MockSwitch(
        "use_fake_hardware", (Ros2ControlSystem("franka", "fake_components/GenericSystem", ("j1",)),), real
    )
    robot = RobotModel(
        "r", (), (), "base", urdf_xml=urdf("franka_hardware/FrankaHardwareInterface"), mock_switch=switch
    )
    assert description_hardware(robot, "humble").mode == "switch"
    jazzy = description_hardware(robot, "jazzy")
    assert jazzy.mode == "replace" and "fake_components/GenericSystem" in jazzy.why_not_switch


def test_the_mock_replacement_makes_every_system_a_mock_system():
    xml = (
        "<robot name='r'><ros2_control name='a' type='actuator'><hardware><plugin>v/A</plugin>"
        "<param name='ip'>1</param></hardware><joint name='j'/></ros2_control></robot>"
    )
    (mocked,) = systems_in_urdf(on_mock_hardware(xml))
    assert (mocked.plugin, mocked.type, mocked.joints) == (MOCK_PLUGIN, "system", ("j",))
    assert "<param" not in on_mock_hardware(xml)


def test_use_mock_hardware_says_when_false_changes_nothing():
    hw = description_hardware(dataclasses.replace(_plain_robot(), urdf_xml="<robot name='r'/>"), "humble")
    assert hw.mode == "none"
    assert "mock hardware either way" in use_mock_hardware_help(hw, Ros2ControlHardware(), True)
    (line,) = hardware_lines(hw, Ros2ControlHardware(), 3)
    assert "false nothing real: marm_setup.yaml names no hardware plugin" in line
    real = Ros2ControlHardware(plugin="acme/Arm")
    assert "false acme/Arm" in use_mock_hardware_help(hw, real, True)


def _plain_robot():
    from marm_setup.robot.model import RobotModel

    return RobotModel("r", (), (), "base")


# -- the vendor styles, end to end through xacro ----------------------------------------------------


@pytest.fixture(scope="module")
def vendors(tmp_path_factory):
    return write_vendor_descriptions(tmp_path_factory.mktemp("vendors"))


@pytest.mark.parametrize("style", NAMES)
def test_each_vendor_style_gets_its_proven_switch_or_a_replacement(vendors, style):
    vendor = vendors[style]
    robot = load_robot(vendor.urdf, parse_xacro_args(vendor.xacro_args), [vendor.root])
    assert (robot.mock_switch.arg if robot.mock_switch else None) == vendor.switch
    assert {d: description_hardware(robot, d).mode for d in ("humble", "jazzy")} == vendor.modes


def _write(vendor, distro: str, out: Path) -> Path:
    from marm_setup.flows import InitRequest, RobotInput, build_setup

    robot = load_robot(vendor.urdf, parse_xacro_args(vendor.xacro_args), [vendor.root])
    request = InitRequest(
        RobotInput.parse(vendor.urdf, xacro_args=vendor.xacro_args, package_paths=(vendor.root,)),
        out=out,
        target="ros2",
        ros_distro=distro,
    )
    apply_writes(plan_writes(render_package(build_setup(request, robot), robot), out), out)
    return out


def _description(pkg: Path, vendor, mock: str) -> str:
    """What the launch files give robot_state_publisher with use_mock_hardware:=mock: the wrapper
    through xacro, or through the generated script (run with a real-xacro `xacro` on PATH)."""
    wrapper = next((pkg / "config").glob("*.urdf.xacro"))
    script = pkg / "scripts" / "with_mock_hardware.py"
    if not script.is_file():
        packages = find_packages([vendor.root, pkg])
        return expand_xacro(wrapper, {"use_mock_hardware": mock}, packages, shown=str(wrapper))
    shims = write_xacro_shim(pkg.parent / "bin")
    env = {
        **os.environ,
        "PATH": f"{shims}{os.pathsep}{os.environ['PATH']}",
        "ROS_PACKAGE_PATH": str(vendor.root),
    }
    done = subprocess.run(
        [sys.executable, str(script), str(wrapper), f"use_mock_hardware:={mock}"],
        capture_output=True,
        text=True,
        env=env,
    )
    assert done.returncode == 0, done.stderr
    return done.stdout


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
@pytest.mark.parametrize("style", NAMES)
def test_true_is_mock_everywhere_and_false_the_vendors_hardware(vendors, tmp_path, style, distro):
    from marm_setup.robot.ros2_control import MOCK_PLUGINS

    vendor = vendors[style]
    pkg = _write(vendor, distro, tmp_path / "pkg")
    mock = systems_in_urdf(_description(pkg, vendor, "true"))
    real = systems_in_urdf(_description(pkg, vendor, "false"))
    assert mock and all(s.plugin in MOCK_PLUGINS[distro] for s in mock)
    assert {s.plugin for s in real} - {MOCK_PLUGIN} == vendor.real_plugins
    for systems in (mock, real):  # each joint in one system only
        joints = [j for s in systems for j in s.joints]
        assert len(joints) == len(set(joints))


def test_the_generated_script_and_the_static_replacement_agree(vendors, tmp_path):
    """validate's static evaluation of the demo applies on_mock_hardware where the launch file
    runs scripts/with_mock_hardware.py: both give the same systems."""
    vendor = vendors["plain_urdf_style"]
    pkg = _write(vendor, "jazzy", tmp_path / "pkg")
    by_script = systems_in_urdf(_description(pkg, vendor, "true"))
    wrapper = next((pkg / "config").glob("*.urdf.xacro"))
    expanded = expand_xacro(
        wrapper, {"use_mock_hardware": "true"}, find_packages([vendor.root, pkg]), shown="w"
    )
    assert systems_in_urdf(on_mock_hardware(expanded)) == by_script
