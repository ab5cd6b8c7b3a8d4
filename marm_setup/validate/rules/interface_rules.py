"""A ros2_controllers.yaml JointTrajectoryController against the interfaces the robot's
ros2_control hardware offers for its joints (controller.interface-unavailable).

The controller claims `<joint>/<interface>` for each of its `command_interfaces` on each of its
`command_joints` (else `joints`), and each of its `state_interfaces` on each of `joints`
(ros2_controllers joint_trajectory_controller.cpp `command_interface_configuration` /
`state_interface_configuration`, humble l.77-115, jazzy l.200-237). The controller manager
activates it only when every one exists: Jazzy checks first ("Unable to activate controller '...'
since the command interface '...' is not available.", controller_manager.cpp jazzy l.4365-4411,
from switch_controller l.2324-2331); Humble's claim throws "does not exist" and the controller is
skipped ("Can't activate controller", controller_manager.cpp humble l.1614-1637, l.1660-1672).
The spawner fails, and MoveIt cannot execute on that controller.

What the hardware offers is what its `<ros2_control>` lists per joint, for mock_components'
GenericSystem exactly (humble hardware_interface/src/mock_components/generic_system.cpp
l.268-335; jazzy: the component's default on_export_*_interfaces from the description,
hardware_component_interface.hpp l.165-233): an error there. Another plugin may export more than
it lists (its own export_*_interfaces, jazzy's export_unlisted_*): a warning. Only joints some
`<ros2_control>` of the loaded description lists are checked: a joint no system lists, or a
description with none, is no claim of this rule.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.robot import ANY_MOCK

if TYPE_CHECKING:
    from marm_setup.package import DriverController, DriverFile
    from marm_setup.robot import Ros2ControlSystem

TRAJECTORY_CONTROLLER = "JointTrajectoryController"


@dataclass(frozen=True, slots=True)
class Offered:
    """What the hardware offers for one joint: its interfaces and whether its plugin is a mock."""

    command: frozenset[str]
    state: frozenset[str]
    mock: bool


def offered_interfaces(systems: Iterable[Ros2ControlSystem]) -> dict[str, Offered]:
    """Joint -> what its `<ros2_control>` lists (the first system naming it)."""
    out: dict[str, Offered] = {}
    for system in systems:
        for joint in system.interfaces:
            out.setdefault(
                joint.joint,
                Offered(frozenset(joint.command), frozenset(joint.state), system.plugin in ANY_MOCK),
            )
    return out


def check_controller_interfaces(driver: DriverFile, offered: dict[str, Offered]) -> list[Finding]:
    """Each JointTrajectoryController's claimed interfaces the hardware does not offer."""
    if not offered:
        return []
    out: list[Finding] = []
    for c in sorted(driver.controllers, key=lambda c: c.name):
        if c.type.rsplit("/", 1)[-1] != TRAJECTORY_CONTROLLER:
            continue
        settings = dict(c.settings)
        joints = _names(settings.get("joints"))
        commanded = _names(settings.get("command_joints")) or joints
        out += _claims(driver, c, "command", commanded, _names(settings.get("command_interfaces")), offered)
        out += _claims(driver, c, "state", joints, _names(settings.get("state_interfaces")), offered)
    return out


def _names(value: object) -> tuple[str, ...]:
    return tuple(str(v) for v in value) if isinstance(value, list | tuple) else ()


def _claims(
    driver: DriverFile,
    c: DriverController,
    kind: str,
    joints: tuple[str, ...],
    interfaces: tuple[str, ...],
    offered: dict[str, Offered],
) -> list[Finding]:
    missing = [
        (joint, name)
        for joint in joints
        if joint in offered
        for name in interfaces
        if name not in (offered[joint].command if kind == "command" else offered[joint].state)
    ]
    if not missing:
        return []
    joint = missing[0][0]
    have = offered[joint].command if kind == "command" else offered[joint].state
    claimed = ", ".join(f"{j}/{n}" for j, n in missing)
    msg = (
        f"controller '{c.name}' claims the {kind} interface(s) {claimed}, which the robot's "
        f"<ros2_control> does not offer ('{joint}' lists {', '.join(sorted(have)) or 'none'}): "
        f"controller_manager refuses to activate it ({kind} interface not available), MoveIt "
        "cannot execute on it"
    )
    hint = f"claim only listed interfaces, or add <{kind}_interface> to the joints' <ros2_control>"
    element = f"{c.name}.ros__parameters.{kind}_interfaces"
    if all(offered[j].mock for j, _ in missing):
        return [error("controller.interface-unavailable", driver.where.file, element, msg, hint)]
    msg += " (unless its hardware plugin exports interfaces its <ros2_control> does not list)"
    return [warning("controller.interface-unavailable", driver.where.file, element, msg, hint)]
