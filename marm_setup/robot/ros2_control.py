"""The `<ros2_control>` systems a robot description already declares (vendor descriptions often
do): a second system for the same joints makes the controller manager refuse the duplicate
interfaces, so a generated package adds its own system only for the joints no system covers.

Mock hardware, per ROS 2 distro (its row's `mock_plugins`, marm_setup.ros DISTROS; ros-controls/
ros2_control, hardware_interface/*_plugin_description.xml): Humble exports
`mock_components/GenericSystem` and the deprecated `fake_components/GenericSystem`; Jazzy on only
`mock_components/GenericSystem` (fake_components is gone). Both are SystemInterfaces:
the resource manager loads a `type="actuator"` or `"sensor"` element through the actuator or
sensor loader instead (humble hardware_interface/src/resource_manager.cpp l.699-720), which
does not know them, so a mocked element must also be `type="system"`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from marm_setup.ros import DISTROS, MOCK

MOCK_PLUGIN = MOCK
MOCK_PLUGINS = {name: row.mock_plugins for name, row in DISTROS.items() if row.mock_plugins}
ANY_MOCK = frozenset().union(*MOCK_PLUGINS.values())


def mock_plugins(distro: str | None) -> frozenset[str]:
    """The mock hardware plugins of `distro`'s ros2_control (any distro's when None or unknown)."""
    row = DISTROS.get(distro or "")
    return row.mock_plugins if row is not None and row.mock_plugins else ANY_MOCK


@dataclass(frozen=True, slots=True)
class JointInterfaces:
    """The `<command_interface>` and `<state_interface>` names one `<joint>` of a system lists."""

    joint: str
    command: tuple[str, ...]
    state: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class Ros2ControlSystem:
    """One `<ros2_control>` element: its name, hardware plugin and joints (document order), the
    `<param>`s of its `<hardware>` (what the plugin is configured with: address, ports...) and the
    interfaces each joint lists."""

    name: str
    plugin: str
    joints: tuple[str, ...]
    type: str = "system"
    params: tuple[tuple[str, str], ...] = ()
    interfaces: tuple[JointInterfaces, ...] = ()

    def is_mock(self, distro: str | None = None) -> bool:
        """Its plugin is mock hardware (of `distro`, or of any distro when None)."""
        return self.plugin in mock_plugins(distro)


@dataclass(frozen=True, slots=True)
class MockSwitch:
    """A xacro arg of the description that puts its own systems on mock hardware: `arg:=true`
    gives `mock` (every plugin mock), `arg:=false` gives `real` (some plugin not mock); both
    found by expanding the description (robot/mock_switch.py)."""

    arg: str
    mock: tuple[Ros2ControlSystem, ...] = field(default=())
    real: tuple[Ros2ControlSystem, ...] = field(default=())

    def works_on(self, distro: str | None) -> bool:
        """Every system of the mock side is a mock `distro` has."""
        return all(s.is_mock(distro) for s in self.mock)


@dataclass(frozen=True, slots=True)
class HardwareArg:
    """A xacro arg of the description that sets a `<param>` of a system's real hardware (and
    nothing else of the URDF): its default, and the system and parameter it sets
    (robot/hardware_args.py)."""

    name: str
    default: str
    system: str
    param: str


def systems_in_urdf(xml: str) -> tuple[Ros2ControlSystem, ...]:
    """The `<ros2_control>` elements directly under a URDF's `<robot>` (empty for unparsable XML)."""
    root = _robot_element(xml)
    if root is None:
        return ()
    systems = []
    for element in root.findall("ros2_control"):
        plugin = element.findtext("hardware/plugin") or ""
        joints = tuple(j.get("name", "") for j in element.findall("joint"))
        kind = element.get("type", "system")
        params = tuple((p.get("name", ""), (p.text or "").strip()) for p in element.findall("hardware/param"))
        interfaces = tuple(joint_interfaces(j) for j in element.findall("joint"))
        systems.append(
            Ros2ControlSystem(element.get("name", ""), plugin.strip(), joints, kind, params, interfaces)
        )
    return tuple(systems)


# The simulator plugins that run a controller manager inside Gazebo Classic (gazebo_ros2_control)
# and Gazebo / Ignition (gz_ros2_control, named ign_ros2_control on Humble), as a URDF's
# `<gazebo><plugin filename=...>` names them ("lib" prefix and ".so" suffix optional).
SIMULATOR_CONTROL_PLUGINS = frozenset(
    {"gazebo_ros2_control", "gz_ros2_control-system", "ign_ros2_control-system"}
)


def simulator_parameter_files(xml: str) -> tuple[str, ...]:
    """The parameter files a ros2_control simulator plugin of the URDF hands its controller
    manager: each `<parameters>` of the `<plugin>` (under `<gazebo>`), passed as `--params-file`
    (ros-controls/gazebo_ros2_control gazebo_ros2_control/src/gazebo_ros2_control_plugin.cpp
    l.269-277 at 3e6d3f4; ros-controls/gz_ros2_control gz_ros2_control/src/gz_ros2_control_plugin.cpp
    l.281-300 at e19b0ef), in document order; empty for unparsable XML."""
    root = _robot_element(xml)
    if root is None:
        return ()
    out = []
    for plugin in root.iterfind("gazebo/plugin"):
        name = plugin.get("filename", "").strip().rsplit("/", 1)[-1].removesuffix(".so").removeprefix("lib")
        if name in SIMULATOR_CONTROL_PLUGINS:
            out += [text for p in plugin.findall("parameters") if (text := (p.text or "").strip())]
    return tuple(dict.fromkeys(out))


def joint_interfaces(joint: Any) -> JointInterfaces:
    """The interfaces a `<joint>` element of a `<ros2_control>` lists (lxml element)."""
    return JointInterfaces(
        joint.get("name", ""),
        tuple(i.get("name", "") for i in joint.findall("command_interface")),
        tuple(i.get("name", "") for i in joint.findall("state_interface")),
    )


def on_mock_hardware(xml: str) -> str:
    """The URDF with every top-level `<ros2_control>` a mock system: its `<hardware>` (plugin and
    params) replaced by MOCK_PLUGIN and its type `system`; what the generated
    scripts/with_mock_hardware.py does on the mock path (a test holds the two to the same result)."""
    from lxml import etree

    root = etree.fromstring(xml.encode())
    for system in root.findall("ros2_control"):
        system.set("type", "system")
        for old in system.findall("hardware"):
            system.remove(old)
        hardware = etree.Element("hardware")
        etree.SubElement(hardware, "plugin").text = MOCK_PLUGIN
        system.insert(0, hardware)
    return etree.tostring(root, encoding="unicode")


def _robot_element(xml: str) -> Any:
    """The URDF's `<robot>` element, comments left out as tinyxml reads them; None for empty or
    unparsable XML."""
    if not xml:
        return None
    from lxml import etree

    from marm_setup.robot.tinyxml import tinyxml_comments

    try:
        return etree.fromstring(tinyxml_comments(xml).encode(), parser=etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError:
        return None
