"""Validated means it runs: every ROS 2 package the tests generate (tests/generated_packages.py:
the marm, every description in ../shared, every synthetic fixture, the vendor-style descriptions
with their own ros2_control, the ports; Humble and Jazzy) goes through the real ROS 2 launch
frontend and rcl (../shared/ros2-consumer, tests/ros2_harness.py). Every launch file evaluates,
every parameter file parses, and the demo passes --require-mock: no ros2_control system of it
drives real hardware. Skipped where ../shared is absent.
"""

from __future__ import annotations

import pytest

from marm_setup.robot.ros2_control import MOCK_PLUGINS
from tests.generated_packages import KEYS
from tests.ros2_harness import (
    DISTROS,
    NEWER_DISTROS,
    check_package,
    harness_python,
    node_processes,
    ros2_control_of,
)
from tests.vendor_descriptions import NAMES as VENDOR_STYLES


@pytest.fixture(autouse=True)
def harness():
    """Skip before generating anything where ../shared (the harness) is absent."""
    harness_python("humble")


LAUNCH_FILES = {"launch/demo.launch.xml", "launch/move_group.launch.xml"}
DEMO = "launch/demo.launch.xml"
# what the demo starts, whatever the robot (static TF publishers only with a virtual joint)
DEMO_EXECUTABLES = {"robot_state_publisher", "move_group", "ros2_control_node", "spawner", "rviz2"}


@pytest.mark.parametrize("distro", DISTROS)
@pytest.mark.parametrize("key", KEYS)
def test_every_generated_ros2_package_passes_the_real_ros2_parsers(ros2_packages, key, distro):
    generated = ros2_packages.get(key, distro)
    report = check_package(generated.out, distro, generated.roots)
    assert report["errors"] == [], report["errors"]
    assert set(report["launch"]) >= LAUNCH_FILES  # servo.launch.xml too for a servo group
    assert all(entry["return_code"] == 0 for entry in report["launch"].values())
    processes = node_processes(report, DEMO)
    assert {p.get("executable") for p in processes} >= DEMO_EXECUTABLES
    # use_sim_time reaches every node (a set_parameter), not move_group alone
    assert all("use_sim_time" in p["parameters"] for p in processes), [p["node"] for p in processes]
    parsed = {p["file"].split(str(generated.out) + "/")[-1] for p in report["params_files"]}
    assert {"config/moveit.yaml", "config/ros2_controllers.yaml"} <= parsed
    systems = ros2_control_of(report, DEMO)
    assert systems and set(systems.values()) <= MOCK_PLUGINS[distro], systems


@pytest.mark.parametrize("distro", DISTROS)
@pytest.mark.parametrize("style", VENDOR_STYLES)
def test_use_mock_hardware_false_gives_the_vendors_real_hardware(ros2_packages, style, distro):
    """The same demo with use_mock_hardware:=false hands robot_state_publisher the vendor's own
    hardware: the switch really switches (and with true every system was mock, above)."""
    generated = ros2_packages.get(f"vendor:{style}", distro)
    vendor = ros2_packages.vendor(style)
    report = check_package(
        generated.out,
        distro,
        generated.roots,
        require_mock=False,
        launch=(DEMO,),
        args=("use_mock_hardware:=false",),
    )
    assert report["errors"] == []
    plugins = set(ros2_control_of(report, DEMO).values()) - {"mock_components/GenericSystem"}
    assert plugins == vendor.real_plugins
    replaced = (generated.out / "scripts" / "with_mock_hardware.py").is_file()
    assert ("replace" if replaced else "switch") == vendor.modes[distro]


@pytest.mark.parametrize("distro", DISTROS)
def test_use_sim_time_reaches_every_node(ros2_packages, distro):
    generated = ros2_packages.get("marm", distro)
    report = check_package(
        generated.out, distro, generated.roots, launch=(DEMO,), args=("use_sim_time:=true",)
    )
    assert report["errors"] == []
    values = {p["node"]: p["key_values"].get("use_sim_time") for p in node_processes(report, DEMO)}
    assert set(values.values()) == {True}, values


def test_kinova_gen3_robotiq_false_gives_kinova_and_robotiq_drivers(ros2_packages):
    """The shared Kinova Gen3 + Robotiq description: use_mock_hardware:=false is its own
    use_fake_hardware:=false, both vendor drivers; true (checked above) is mock."""
    generated = ros2_packages.get("shared:kinova_gen3_robotiq", "jazzy")
    report = check_package(
        generated.out,
        "jazzy",
        generated.roots,
        require_mock=False,
        launch=(DEMO,),
        args=("use_mock_hardware:=false",),
    )
    assert set(ros2_control_of(report, DEMO).values()) == {
        "kortex_driver/KortexMultiInterfaceHardware",
        "robotiq_driver/RobotiqGripperHardwareInterface",
    }


# The acceptance of Kilted and Rolling (issue 32): the marm (servo and a sensor:
# test_servo_perception.py), the shared panda and the shared Gen3 pass the real consumer with
# mock hardware, with the controllers their ros2_controllers have (no gripper_controllers).
NEWER_KEYS = ("marm", "shared:panda_ros2", "shared:kinova_gen3_robotiq")


@pytest.mark.parametrize("distro", NEWER_DISTROS)
@pytest.mark.parametrize("key", NEWER_KEYS)
def test_kilted_and_rolling_packages_pass_the_real_ros2_parsers(ros2_packages, key, distro):
    import yaml

    generated = ros2_packages.get(key, distro)
    report = check_package(generated.out, distro, generated.roots)
    assert report["errors"] == [], report["errors"]
    assert all(entry["return_code"] == 0 for entry in report["launch"].values())
    assert {p.get("executable") for p in node_processes(report, DEMO)} >= DEMO_EXECUTABLES
    systems = ros2_control_of(report, DEMO)
    assert systems and set(systems.values()) <= MOCK_PLUGINS[distro], systems
    controllers = yaml.safe_load((generated.out / "config" / "ros2_controllers.yaml").read_text())
    types = {
        v["type"]
        for k, v in controllers["controller_manager"]["ros__parameters"].items()
        if isinstance(v, dict)
    }
    assert not any(
        t.startswith(("position_controllers/GripperActionController", "gripper_controllers")) for t in types
    )
