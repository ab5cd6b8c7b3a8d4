"""The robot: URDF/xacro loading, ROS package lookup, meshes, the frozen RobotModel,
batched forward kinematics, and its text description.

Public API below (name -> module); names load on first use (see `marm_setup.exports`).
"""

from __future__ import annotations

from typing import Any

from marm_setup.exports import load_export

_API = {
    "load_robot": "load",
    "parse_xacro_args": "load",
    "expand_xacro": "load",
    "RobotModel": "model",
    "Link": "model",
    "Joint": "model",
    "forward_kinematics": "kinematics",
    "sample_configurations": "kinematics",
    "default_configuration": "kinematics",
    "load_mesh": "meshes",
    "find_packages": "ros_packages",
    "find_package": "ros_packages",
    "resolve_uri": "ros_packages",
    "describe_robot": "describe",
    "format_tree": "describe",
}
__all__ = sorted(_API)


def __getattr__(name: str) -> Any:
    return load_export(__name__, _API, name)


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})
