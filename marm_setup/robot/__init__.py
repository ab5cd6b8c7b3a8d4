"""The robot: URDF/xacro loading, ROS package lookup, meshes, the frozen RobotModel,
batched forward kinematics, and its text description.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "load": "load_robot parse_xacro_args",
        "xacro_expand": "expand_xacro run_xacro check_xacro_args",
        "model": "RobotModel Link Joint",
        "kinematics": "forward_kinematics sample_configurations default_configuration",
        "meshes": "load_mesh",
        "ros_packages": "find_packages find_package resolve_uri",
        "describe": "describe_robot format_tree",
        "ros2_control": "Ros2ControlSystem described_systems described_joints",
    },
)
