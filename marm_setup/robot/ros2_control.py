"""The `<ros2_control>` systems a robot description already declares (vendor descriptions often
do): a second system for the same joints makes the controller manager refuse the duplicate
interfaces, so a generated package adds its own system only for the joints no system covers."""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.robot.model import RobotModel


@dataclass(frozen=True, slots=True)
class Ros2ControlSystem:
    """One `<ros2_control>` element: its name, hardware plugin and joints (document order)."""

    name: str
    plugin: str
    joints: tuple[str, ...]


def described_systems(robot: RobotModel) -> tuple[Ros2ControlSystem, ...]:
    """The `<ros2_control>` elements directly under the (expanded) URDF's `<robot>`."""
    if not robot.urdf_xml:
        return ()
    from lxml import etree

    root = etree.fromstring(robot.urdf_xml.encode(), parser=etree.XMLParser(remove_comments=True))
    systems = []
    for element in root.findall("ros2_control"):
        plugin = element.findtext("hardware/plugin") or ""
        joints = tuple(j.get("name", "") for j in element.findall("joint"))
        systems.append(Ros2ControlSystem(element.get("name", ""), plugin.strip(), joints))
    return tuple(systems)


def described_joints(robot: RobotModel) -> frozenset[str]:
    """Joints some `<ros2_control>` of the description already drives or reports."""
    return frozenset(j for system in described_systems(robot) for j in system.joints)
