"""ros2_control's parameter file names its nodes as rcl allows: rclcpp gives a node name key
without a leading slash one (rclcpp parameter_map.cpp `parameter_map_from`, "make sure there is a
leading slash on the fully qualified node name") and matches `/**` as any namespace, so
`/controller_manager:` and `/**/controller_manager:` hold the root-namespace controller
manager's parameters just as `controller_manager:` does (the igus ReBeL's ros2_controllers.yaml,
`<namespace>/controller_manager:` with the namespace defaulting to '')."""

from __future__ import annotations

import pytest

from marm_setup.package.driver_file import read_ros2_controllers
from marm_setup.package.files import located_text
from tests.vendor_packages import ROS2_CONTROLLERS


@pytest.mark.parametrize("prefix", ["", "/", "/**/"])
def test_the_controller_manager_and_its_controllers_under_any_name_rcl_matches(prefix):
    text = ROS2_CONTROLLERS.replace("controller_manager:", f"{prefix}controller_manager:", 1).replace(
        "\nbot_arm_controller:", f"\n{prefix}bot_arm_controller:"
    )
    driver = read_ros2_controllers(located_text(text, "config/ros2_controllers.yaml"))
    assert driver.well_formed
    arm = driver.controller("bot_arm_controller")
    assert arm is not None and arm.joints == tuple(f"joint_{i}" for i in range(1, 7))
    assert dict(driver.manager_settings)["update_rate"] == 100


def test_a_manager_in_another_namespace_is_not_the_root_one():
    text = ROS2_CONTROLLERS.replace("controller_manager:", "/robot1/controller_manager:", 1)
    assert not read_ros2_controllers(located_text(text, "config/ros2_controllers.yaml")).well_formed
