"""MoveIt's tables (`moveit_params.domain`): what we generate is what validate reads, by construction."""

from __future__ import annotations

from marm_setup.moveit_params import domain


def test_generated_ros2_controllers_are_driver_controllers_validate_knows():
    for moveit_type, plugin in domain.ROS2_CONTROLLER_TYPES.items():
        served_type, served_ns = domain.DRIVER_CONTROLLERS[plugin.rsplit("/", 1)[-1]]
        assert served_type == moveit_type
        assert domain.DRIVER_ACTION_NS["ros2", moveit_type] == domain.ROS2_ACTION_NS[moveit_type] == served_ns
    assert set(domain.ROS2_CONTROLLER_TYPES) == set(domain.MOVEIT_CONTROLLER_TYPES)


def test_defaults_are_members_of_their_tables():
    assert domain.KDL_PLUGIN in domain.KINEMATICS_PLUGINS and domain.KDL_PLUGIN in domain.CHAIN_ONLY_PLUGINS
    assert domain.DEFAULT_PLANNER in domain.OMPL_PLANNER_NAMES
    assert domain.DRIVER_ACTION_NS["arbotix", domain.GRIPPER_COMMAND] == "gripper_action"
    assert set(domain.DEFAULT_ACTION_NS) == set(domain.MOVEIT_CONTROLLER_TYPES)
