"""MoveIt's tables (`moveit_params.vocabulary`): what we generate is what validate reads, by construction."""

from __future__ import annotations

from marm_setup.moveit_params import vocabulary


def test_generated_ros2_controllers_are_driver_controllers_validate_knows():
    for moveit_type, plugin in vocabulary.ROS2_CONTROLLER_TYPES.items():
        served_type, served_ns = vocabulary.DRIVER_CONTROLLERS[plugin.rsplit("/", 1)[-1]]
        assert served_type == moveit_type
        assert (
            vocabulary.DRIVER_ACTION_NS["ros2", moveit_type]
            == vocabulary.ROS2_ACTION_NS[moveit_type]
            == served_ns
        )
    assert set(vocabulary.ROS2_CONTROLLER_TYPES) == set(vocabulary.MOVEIT_CONTROLLER_TYPES)


def test_defaults_are_members_of_their_tables():
    assert (
        vocabulary.KDL_PLUGIN in vocabulary.KINEMATICS_PLUGINS
        and vocabulary.KDL_PLUGIN in vocabulary.CHAIN_ONLY_PLUGINS
    )
    assert vocabulary.DEFAULT_PLANNER in vocabulary.OMPL_PLANNER_NAMES
    assert vocabulary.DRIVER_ACTION_NS["arbotix", vocabulary.GRIPPER_COMMAND] == "gripper_action"
    assert set(vocabulary.DEFAULT_ACTION_NS) == set(vocabulary.MOVEIT_CONTROLLER_TYPES)
