"""The parameters a ROS 2 package hands each MoveIt node, by full name as the node sees them.

move_group gets our layout's config/moveit.yaml whole; a Setup Assistant package's files go
through MoveItConfigsBuilder (moveit_configs_utils moveit_configs_builder.py), which nests
kinematics.yaml under `robot_description_kinematics`, joint_limits.yaml and
pilz_cartesian_limits.yaml under `robot_description_planning`, each <name>_planning.yaml under
the pipeline's name, and loads moveit_controllers.yaml and sensors_3d.yaml at the top level.
A file that is itself a `<node>: ros__parameters:` file is taken at its top level. Servo's
parameters are the package's servo configurations (names below `moveit_servo`).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import yaml

from marm_setup.bounded_read import read_text
from marm_setup.errors import MarmError
from marm_setup.ros import Target
from marm_setup.safe_yaml import MAX_BYTES, load_yaml

if TYPE_CHECKING:
    from marm_setup.package.model import MoveItPackage

NESTED = {"kinematics": "robot_description_kinematics", "joint_limits": "robot_description_planning"}
TOP_LEVEL = ("moveit_controllers", "sensors", "move_group")
PILZ_LIMITS = "config/pilz_cartesian_limits.yaml"  # MoveItConfigsBuilder.pilz_cartesian_limits' default


@dataclass(frozen=True, slots=True)
class Received:
    """One parameter a node receives: its full name, value as YAML gave it, and where it is."""

    node: str  # move_group | servo
    name: str
    value: Any
    file: str
    element: str  # the key path in the file


def received_parameters(pkg: MoveItPackage) -> list[Received]:
    """Every parameter move_group and servo get from the package (ROS 2 only; else [])."""
    if pkg.target != Target.ROS2:
        return []
    out: dict[tuple[str, str, str], Received] = {}
    for file, prefix in _move_group_files(pkg):
        for r in _file_parameters(pkg, file, prefix):
            out.setdefault((r.node, r.name, r.element), r)
    for config in pkg.servo:
        for p in config.params:
            r = Received("servo", p.key, _thawed(p.value), p.where.file, p.where.element)
            out.setdefault((r.node, r.name, r.element), r)
    return list(out.values())


def _move_group_files(pkg: MoveItPackage) -> list[tuple[str, str]]:
    """(file, name prefix) of every file move_group gets, in a stable order."""
    found: dict[str, str] = {}
    for source in pkg.sources:
        kind = source.kind
        if kind.startswith("pipeline:"):
            found.setdefault(source.file, kind.split(":", 1)[1])
        elif kind in NESTED:
            found.setdefault(source.file, NESTED[kind])
        elif kind in TOP_LEVEL:
            found.setdefault(source.file, "")
    if pkg.layout == "moveit2" and PILZ_LIMITS in pkg.files:
        found.setdefault(PILZ_LIMITS, "robot_description_planning")
    return sorted(found.items())


def _file_parameters(pkg: MoveItPackage, file: str, prefix: str) -> list[Received]:
    if file not in pkg.files:
        return []
    try:
        data = load_yaml(read_text(pkg.path(file), MAX_BYTES, shown=file))
    except (OSError, yaml.YAMLError, ValueError, MarmError):
        return []  # reported by the package reader (yaml.parse)
    keys: tuple[str, ...] = ()
    if isinstance(data, dict) and len(data) == 1:
        ((node, body),) = data.items()
        if isinstance(body, dict) and isinstance(body.get("ros__parameters"), dict):
            data, keys, prefix = body["ros__parameters"], (str(node), "ros__parameters"), ""
    if not isinstance(data, dict):
        return []
    return [
        Received("move_group", ".".join(filter(None, (prefix, name))), value, file, ".".join((*keys, name)))
        for name, value in _leaves(data, "")
    ]


def _leaves(data: dict, prefix: str) -> Iterator[tuple[str, Any]]:
    """(dotted name, value) of each leaf; a non-empty mapping is a namespace, lists are values."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            yield from _leaves(value, f"{name}.")
        else:
            yield name, value


def _thawed(value: Any) -> Any:
    """A frozen Param value back as YAML gave it (tuples as lists)."""
    return [_thawed(v) for v in value] if isinstance(value, tuple) else value
