"""ROS 2 parameter files (`<node>: ros__parameters: ...`) as rcl and rclcpp read them.

`params.empty-value`: an empty map or list under ros__parameters (`robot_description_kinematics: {}`,
`controller_names: []`). rcl's YAML parser records the key as a parameter and never gives it a
value (rcl_yaml_param_parser/src/parse.c: parse_key registers the name, parse_value runs only
for scalars), and rclcpp's parameter_value_from throws InvalidParameterValueException("No
parameter value set") for it (rclcpp/src/rclcpp/parameter_map.cpp l.147, humble and jazzy),
called for the whole file when a node is constructed (detail/resolve_parameter_overrides.cpp
l.54): move_group, rviz2 and every other C++ node given the file stop at start-up.
"""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path
from typing import Any

from marm_setup.bounded_read import YAML_BYTES, FileTooLarge, read_bytes
from marm_setup.findings import Finding, error
from marm_setup.untrusted import inside

PARAMS_KEY = "ros__parameters"
SKIPPED_DIRS = {".marm_setup", ".git"}


def params_files(root: Path) -> list[Path]:
    """YAML files of the package that mention ros__parameters (every other YAML is not rcl's)."""
    out = []
    for path in sorted(root.rglob("*.yaml")):
        if SKIPPED_DIRS & set(path.relative_to(root).parts) or not path.is_file():
            continue
        if not inside(path, (root,)):  # a symlink leaving the package: package.outside says so
            continue
        try:
            if PARAMS_KEY in read_bytes(path, YAML_BYTES).decode("utf-8", errors="replace"):
                out.append(path)
        except (OSError, FileTooLarge):  # too large: yaml.parse says so where it is loaded
            continue
    return out


def check_params_files(root: Path) -> list[Finding]:
    """`params.empty-value` over every parameter file of the package."""
    from marm_setup.safe_yaml import load_yaml

    out = []
    for path in params_files(root):
        rel = path.relative_to(root).as_posix()
        try:
            data = load_yaml(read_bytes(path, YAML_BYTES).decode("utf-8"))
        except Exception:  # noqa: BLE001 - unreadable YAML has its own finding (yaml.parse)
            continue
        for element, kind in empty_values(data):
            msg = (
                f"an empty {kind}: rcl gives the parameter no value, and every C++ node given this "
                "file (move_group, rviz2, ...) stops at start-up with 'No parameter value set'"
            )
            out.append(error("params.empty-value", rel, element, msg, "leave the key out or give it a value"))
    return out


def empty_values(data: Any) -> Iterator[tuple[str, str]]:
    """(dotted element, 'map' | 'list') of each empty value under a ros__parameters key."""
    if not isinstance(data, dict):
        return
    for key, value in data.items():
        if key == PARAMS_KEY:
            yield from _empty_under(value, PARAMS_KEY)
        elif isinstance(value, dict):
            yield from ((f"{key}.{element}", kind) for element, kind in empty_values(value))


def _empty_under(value: Any, prefix: str) -> Iterator[tuple[str, str]]:
    if isinstance(value, dict):
        if not value and prefix != PARAMS_KEY:
            yield prefix, "map"
        for key, child in value.items():
            yield from _empty_under(child, f"{prefix}.{key}")
    elif isinstance(value, list) and not value:
        yield prefix, "list"
