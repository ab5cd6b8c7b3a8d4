"""The parameters of a ROS 2 package's `ros2_controllers.yaml` against what ros2_control's
controller_manager and each ros2_controllers controller declare (marm_setup/moveit_params/
driver_params.py, pinned generate_parameter_library files).

- controller.param-type: a value of another type than declared, an integer for a double included.
  A controller's ParamListener refuses it (generate_parameter_library: declare_parameter or
  as_double throws), so on_init fails and controller_manager does not load the controller: the
  spawner fails and MoveIt cannot execute on it. The controller_manager's own (`update_rate`)
  throws in ros2_control_node's constructor: nothing runs.
- controller.param-bounds: a value outside a declared validator (gt, one_of, ...): the same.

Controllers of other types, and names a file declares nowhere, are left alone (no claim).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from marm_setup.findings import Finding, error
from marm_setup.moveit_params import (
    CONTROLLER_MANAGER,
    driver_rows,
    family_of,
    type_problem,
    validator_problem,
)

if TYPE_CHECKING:
    from marm_setup.moveit_params import ParamRow
    from marm_setup.package import MoveItPackage

PARAMS = "ros__parameters"


def check_driver_parameters(pkg: MoveItPackage, distro: str | None) -> list[Finding]:
    """The findings on the controller_manager's and its controllers' parameters; with no known
    distro, only those Humble's and Jazzy's declarations agree on."""
    driver = pkg.ros2_controllers
    if driver is None:
        return []
    data = _load(pkg, driver.where.file)
    if not isinstance(data, dict):
        return []
    family = family_of(distro)
    if family in ("humble", "jazzy"):
        return _check_file(data, driver.where.file, family)
    found = [_check_file(data, driver.where.file, f) for f in ("jazzy", "humble")]
    agreed = {(f.rule, f.element) for f in found[1]}
    return [f for f in found[0] if (f.rule, f.element) in agreed]


def _load(pkg: MoveItPackage, file: str) -> Any:
    from marm_setup.bounded_read import YAML_BYTES, read_bytes
    from marm_setup.safe_yaml import load_yaml

    try:
        return load_yaml(read_bytes(pkg.path(file), YAML_BYTES).decode("utf-8"))
    except Exception:  # unreadable: the package reader's yaml.parse finding says so
        return None


def _check_file(data: dict, file: str, family: str) -> list[Finding]:
    rows = driver_rows(family)
    out: list[Finding] = []
    manager = _section(data, CONTROLLER_MANAGER)
    out += _check_node(
        manager,
        rows.get(CONTROLLER_MANAGER, ()),
        file,
        CONTROLLER_MANAGER,
        "ros2_control_node stops at start-up",
    )
    for name, entry in sorted(manager.items()):
        if not (isinstance(entry, dict) and isinstance(entry.get("type"), str)):
            continue
        does = f"controller '{name}' does not load (its parameters are refused): MoveIt cannot execute on it"
        out += _check_node(_section(data, name), rows.get(entry["type"], ()), file, name, does)
    return out


def _section(data: dict, node: str) -> dict:
    body = data.get(node)
    params = body.get(PARAMS) if isinstance(body, dict) else None
    return params if isinstance(params, dict) else {}


def _check_node(params: dict, rows: tuple[ParamRow, ...], file: str, node: str, does: str) -> list[Finding]:
    out = []
    for name, value in _leaves(params, ""):
        row = next((r for r in rows if r.pattern.fullmatch(name)), None)
        if row is None:
            continue
        element = f"{node}.{PARAMS}.{name}"
        problem = type_problem(row, value)
        if problem is not None:
            out.append(
                error("controller.param-type", file, element, f"{name}: {problem}: {does}", row.source)
            )
        elif (bound := validator_problem(row, value)) is not None:
            out.append(
                error("controller.param-bounds", file, element, f"{name}: {bound}: {does}", row.source)
            )
    return out


def _leaves(data: dict, prefix: str) -> Iterator[tuple[str, Any]]:
    """(dotted name, value) of each leaf; a non-empty mapping is a namespace, lists are values."""
    for key, value in data.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict) and value:
            yield from _leaves(value, f"{name}.")
        else:
            yield name, value
