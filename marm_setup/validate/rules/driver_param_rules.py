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

from typing import TYPE_CHECKING

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
    from marm_setup.package import DriverFile, MoveItPackage, Settings

PARAMS = "ros__parameters"


def check_driver_parameters(pkg: MoveItPackage, distro: str | None) -> list[Finding]:
    """The findings on the controller_manager's and its controllers' parameters; with no known
    distro, only those Humble's and Jazzy's declarations agree on."""
    driver = pkg.ros2_controllers
    if driver is None:
        return []
    family = family_of(distro)
    if family in ("humble", "jazzy"):
        return _check_file(driver, family)
    found = [_check_file(driver, f) for f in ("jazzy", "humble")]
    agreed = {(f.rule, f.element) for f in found[1]}
    return [f for f in found[0] if (f.rule, f.element) in agreed]


def _check_file(driver: DriverFile, family: str) -> list[Finding]:
    rows, file = driver_rows(family), driver.where.file
    stops = "ros2_control_node stops at start-up"
    out = _check_node(
        driver.manager_settings, rows.get(CONTROLLER_MANAGER, ()), file, CONTROLLER_MANAGER, stops
    )
    for c in sorted(driver.controllers, key=lambda c: c.name):
        does = (
            f"controller '{c.name}' does not load (its parameters are refused): MoveIt cannot execute on it"
        )
        out += _check_node(c.settings, rows.get(c.type, ()), file, c.name, does)
    return out


def _check_node(
    settings: Settings, rows: tuple[ParamRow, ...], file: str, node: str, does: str
) -> list[Finding]:
    out = []
    for name, value in settings:
        row = next((r for r in rows if r.pattern.fullmatch(name)), None)
        if row is None:
            continue
        element = f"{node}.{PARAMS}.{name}"
        if (problem := type_problem(row, value)) is not None:
            out.append(
                error("controller.param-type", file, element, f"{name}: {problem}: {does}", row.source)
            )
        elif (bound := validator_problem(row, value)) is not None:
            out.append(
                error("controller.param-bounds", file, element, f"{name}: {bound}: {does}", row.source)
            )
    return out
