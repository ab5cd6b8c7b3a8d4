"""MoveIt's controllers when its manager is MoveIt 2's `Ros2ControlManager`: no list of its
own, the controllers ros2_control runs are MoveIt's.

moveit2 moveit_plugins/moveit_ros_control_interface: `moveit_core_plugins.xml` registers
`moveit_ros_control_interface/Ros2ControlManager` (and its deprecated alias
`moveit_ros_control_interface/MoveItControllerManager`); `controller_manager_plugin.cpp`
`discover()` takes every controller of the controller manager whose type has an allocator
(`moveit_ros_control_interface_plugins.xml`): `joint_trajectory_controller/JointTrajectoryController`
(a FollowJointTrajectory handle on `<name>/follow_joint_trajectory`,
joint_trajectory_controller_plugin.cpp l.55), `position_controllers/`, `effort_controllers/`
(a GripperCommand handle on `<name>/gripper_cmd`, gripper_command_controller_plugin.cpp l.55) and
`parallel_gripper_action_controller/GripperActionController` (a ParallelGripperCommand handle,
parallel_gripper_command_controller_plugin.cpp l.55). None is a default controller.
"""

from __future__ import annotations

from dataclasses import replace

from marm_setup.package.controllers_file import ControllersFile, MoveItController
from marm_setup.package.driver_file import DriverFile

ROS2_CONTROL_MANAGERS = frozenset(
    {
        "moveit_ros_control_interface/Ros2ControlManager",
        "moveit_ros_control_interface/MoveItControllerManager",
    }
)
# ros2_control controller type -> (MoveIt handle type, action namespace)
ROS2_CONTROL_HANDLES = {
    "joint_trajectory_controller/JointTrajectoryController": (
        "FollowJointTrajectory",
        "follow_joint_trajectory",
    ),
    "position_controllers/GripperActionController": ("GripperCommand", "gripper_cmd"),
    "effort_controllers/GripperActionController": ("GripperCommand", "gripper_cmd"),
    # a ParallelGripperCommand handle (moveit2 jazzy on, parallel_gripper_command_controller_plugin.cpp l.55)
    "parallel_gripper_action_controller/GripperActionController": ("ParallelGripperCommand", "gripper_cmd"),
}


def managed_controllers(listed: ControllersFile, driver: DriverFile | None) -> ControllersFile:
    """`listed`, or, when its manager is Ros2ControlManager and it lists none, the driver's
    controllers MoveIt gets a handle for (each keeps the driver file's position)."""
    if listed.manager not in ROS2_CONTROL_MANAGERS or listed.controllers or driver is None:
        return listed
    found = tuple(
        MoveItController(
            c.name, ROS2_CONTROL_HANDLES[c.type][0], ROS2_CONTROL_HANDLES[c.type][1], False, c.joints, c.where
        )
        for c in driver.controllers
        if c.type in ROS2_CONTROL_HANDLES and c.joints
    )
    return replace(listed, controllers=found)
