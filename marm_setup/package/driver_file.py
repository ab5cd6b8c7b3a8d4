"""The driver side of the controller wiring: ros2_control's `ros2_controllers.yaml` (the
controller_manager's parameter file), ROS 1 ros_control's `ros_controllers.yaml`, the ArbotiX
driver's `arbotix.yaml` and ros2_control's `initial_positions.yaml`."""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from marm_setup.moveit_params import flatten
from marm_setup.package.where import Located, Param, Where, freeze

if TYPE_CHECKING:
    from marm_setup.robot import Ros2ControlSystem

# (dotted name, value as YAML gave it) of every parameter of one node
Settings = tuple[tuple[str, Any], ...]

OWN_KEYS = ("type", "joints", "joint")


@dataclass(frozen=True, slots=True)
class DriverController:
    """A controller the driver runs: its plugin type, its joints (None when it names none) and
    the names of its other parameters (gains, tolerances, ...)."""

    name: str
    type: str
    joints: tuple[str, ...] | None
    where: Where
    parameters: tuple[str, ...] = ()
    settings: Settings = field(default=(), compare=False)  # ROS 2: its ros__parameters, flattened

    @property
    def element(self) -> str:
        return self.where.element


@dataclass(frozen=True, slots=True)
class DriverFile:
    where: Where
    controllers: tuple[DriverController, ...]
    well_formed: bool = True  # the controllers' mapping is one (ROS 2: controller_manager.ros__parameters)
    manager_settings: Settings = field(default=(), compare=False)  # ROS 2: controller_manager's own

    def controller(self, name: str) -> DriverController | None:
        return next((c for c in self.controllers if c.name == name), None)


def read_ros2_controllers(doc: Located) -> DriverFile:
    """`controller_manager.ros__parameters.<name>.type`, each controller's own parameters under
    `<name>.ros__parameters` (ros2_control controller_manager); each node under any key rcl
    matches to it in the root namespace (`node_entry`)."""
    manager = node_entry(doc, "controller_manager").get("ros__parameters")
    out = []
    for name, entry in manager.items():
        if entry.is_mapping and "type" in entry.data:
            params = node_entry(doc, str(name)).get("ros__parameters")
            joints, others = _joints(params), _others(params)
            out.append(
                DriverController(
                    name, str(entry.data["type"]), joints, entry.where, others, _settings(params)
                )
            )
    return DriverFile(doc.where, tuple(out), manager.is_mapping, _settings(manager))


def node_entry(doc: Located, name: str) -> Located:
    """The entry of a ROS 2 parameter file for the root-namespace node `name`: under `name`,
    `/name` or `/**/name` (rclcpp parameter_map.cpp `parameter_map_from` gives a key without a
    leading slash one, and matches `/**` as any namespace), the first present."""
    for key in (name, f"/{name}", f"/**/{name}"):
        entry = doc.get(key)
        if entry.data is not None:
            return entry
    return doc.get(name)


def read_ros_controllers(doc: Located) -> DriverFile:
    """ros_control: one top-level entry with a `type` per controller."""
    out = [
        DriverController(name, str(entry.data["type"]), _joints(entry), entry.where, _others(entry))
        for name, entry in doc.items()
        if entry.is_mapping and "type" in entry.data
    ]
    return DriverFile(doc.where, tuple(out), doc.is_mapping)


def _joints(params: Located) -> tuple[str, ...] | None:
    data = params.data if isinstance(params.data, dict) else {}
    if isinstance(data.get("joints"), list):
        return tuple(str(j) for j in data["joints"])
    if data.get("joint"):
        return (str(data["joint"]),)
    return None


def _settings(params: Located) -> Settings:
    return tuple(flatten(params.data)) if isinstance(params.data, dict) else ()


def _others(params: Located) -> tuple[str, ...]:
    data = params.data if isinstance(params.data, dict) else {}
    return tuple(sorted(str(k) for k in data if k not in OWN_KEYS))


# -- ArbotiX -------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True)
class ArbotixServo:
    """An `arbotix.yaml` joint: servo id, max_speed [deg/s], and its other keys."""

    joint: str
    where: Where
    params: tuple[Param, ...]

    def param(self, key: str) -> Param | None:
        return next((p for p in self.params if p.key == key), None)


@dataclass(frozen=True, slots=True)
class ArbotixController:
    """An `arbotix.yaml` controller: its action_name and joints (as written)."""

    name: str
    where: Where
    action_name: Param | None
    joints: Param | None


@dataclass(frozen=True, slots=True)
class ArbotixFile:
    where: Where
    servos: tuple[ArbotixServo, ...]
    controllers: tuple[ArbotixController, ...]
    settings: tuple[Param, ...]  # every other top-level key (port, baud, rate, ...)

    def controller(self, name: str) -> ArbotixController | None:
        return next((c for c in self.controllers if c.name == name), None)


def read_arbotix(doc: Located) -> ArbotixFile:
    joints = doc.get("joints")
    servos = tuple(
        ArbotixServo(name, entry.where, entry.params() if entry.is_mapping else ())
        for name, entry in joints.items()
    )
    controllers = tuple(
        ArbotixController(name, entry.where, entry.param("action_name"), entry.param("joints"))
        for name, entry in doc.get("controllers").items()
        if entry.is_mapping
    )
    settings = tuple(
        Param(key, freeze(value.data), value.where)
        for key, value in doc.items()
        if key not in ("joints", "controllers")
    )
    return ArbotixFile(doc.where, servos, controllers, settings)


# -- initial positions (ros2_control's mock hardware start) ----------------------------------------


@dataclass(frozen=True, slots=True)
class InitialPositions:
    """`initial_positions: {joint: value}` (or the mapping itself); `values` None when it is no
    mapping. `where` names the `initial_positions` key, as findings do."""

    where: Where
    values: tuple[Param, ...] | None


def read_initial_positions(doc: Located) -> InitialPositions:
    named = Where(doc.where.file, (*doc.where.keys, "initial_positions"))
    if not doc.is_mapping:
        return InitialPositions(named, ())
    inner = doc.get("initial_positions") if "initial_positions" in doc.data else doc
    if not inner.is_mapping:
        return InitialPositions(named, None)
    values = tuple(
        Param(key, freeze(value.data), named.child(key, line=value.where.line))
        for key, value in inner.items()
    )
    return InitialPositions(named, values)


# -- ros2_control hardware descriptions (`config/*.ros2_control.xacro`) ------------------------------


@dataclass(frozen=True, slots=True)
class Ros2ControlFile:
    """A package's ros2_control xacro: the joints its `<ros2_control>` systems name literally
    (a `${...}` name is only known once xacro runs), and those systems with the interfaces each
    literally named joint lists (`plugin` '' unless one literal plugin is all it can load)."""

    file: str
    joints: tuple[str, ...]
    systems: tuple[Ros2ControlSystem, ...] = ()


def read_ros2_control(file: str, text: str) -> Ros2ControlFile:
    from lxml import etree

    from marm_setup.robot import Ros2ControlSystem, joint_interfaces

    try:
        root = etree.fromstring(text.encode(), parser=etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError:
        return Ros2ControlFile(file, ())
    names = [j.get("name", "") for system in root.iter("ros2_control") for j in system.findall("joint")]
    systems = []
    for system in root.iter("ros2_control"):
        plugins = {(p.text or "").strip() for p in system.iter("plugin")}
        plugin = next(iter(plugins)) if len(plugins) == 1 and "${" not in next(iter(plugins)) else ""
        found = tuple(
            interfaces
            for j in system.findall("joint")
            if "${" not in (interfaces := joint_interfaces(j)).joint
            and not any("${" in n for n in (*interfaces.command, *interfaces.state))
        )
        joints = tuple(i.joint for i in found)
        systems.append(Ros2ControlSystem(system.get("name", ""), plugin, joints, interfaces=found))
    return Ros2ControlFile(file, tuple(n for n in names if n and "${" not in n), tuple(systems))


def read_simulator_drivers(files: tuple[str, ...], root: Path) -> tuple[DriverFile, ...]:
    """The controller_manager parameter files a ros2_control simulator plugin of the robot
    description names (`simulator_parameter_files`), read as `ros2_controllers.yaml` and shown
    relative to the package at `root`; a file that is not absolute (rcl resolves it against the
    simulator's working directory), absent, unreadable (--untrusted) or not YAML is left out."""
    import yaml

    from marm_setup.bounded_read import YAML_BYTES, FileTooLarge, read_text
    from marm_setup.package.files import located_text
    from marm_setup.untrusted import readable

    out = []
    for file in files:
        path = Path(file)
        if not path.is_absolute() or not path.is_file() or not readable(path):
            continue
        shown = Path(os.path.relpath(path, root)).as_posix()
        try:
            doc = located_text(read_text(path, YAML_BYTES, shown=shown), shown)
        except (OSError, UnicodeDecodeError, FileTooLarge, yaml.YAMLError):
            continue
        out.append(read_ros2_controllers(doc))
    return tuple(out)
