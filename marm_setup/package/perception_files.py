"""Perception and teleoperation settings: MoveIt's 3D sensors (occupancy map updaters) and
MoveIt Servo.

Sensors: MoveIt 1 `sensors_3d.yaml` is `sensors: [{sensor_plugin: ..., ...}, ...]`, loaded into
move_group (sensor_manager.launch.xml); MoveIt 2 lists names, `sensors: [name, ...]`, each with
its own mapping (`<name>: {sensor_plugin: ...}`), as MoveItConfigsBuilder.sensors_3d loads it
(occupancy_map_monitor.cpp reads `sensors` then `<name>.sensor_plugin`).

Servo: the moveit_servo parameters (`move_group_name`, `command_in_type`, `publish_period`,
frames, topics, `scale.*`, ...), either at the top of a file (MoveIt 1, and the MoveIt 2 files
launch files load with `{"moveit_servo": load_yaml(...)}`) or under `moveit_servo`.
"""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.package.where import Located, Param, Where, unwrap_parameters

SERVO_KEYS = frozenset(
    {"command_in_type", "publish_period", "command_out_topic", "ee_frame_name", "planning_frame"}
)
# the frames moveit_servo looks up as robot links (noetic and humble servo_calcs.cpp
# getGlobalLinkTransform; Jazzy's servo takes its frames from the group's IK solver instead)
SERVO_FRAMES = ("planning_frame", "ee_frame_name", "robot_link_command_frame")


@dataclass(frozen=True, slots=True)
class Sensor:
    """One 3D sensor: its name (MoveIt 2) or list index, plugin and other parameters."""

    name: str
    where: Where
    plugin: str | None
    params: tuple[Param, ...]

    def param(self, key: str) -> Param | None:
        return next((p for p in self.params if p.key == key), None)


@dataclass(frozen=True, slots=True)
class SensorsFile:
    where: Where
    sensors: tuple[Sensor, ...]


def read_sensors(doc: Located) -> SensorsFile | None:
    """The sensors of a file, or None when it has no `sensors` list."""
    listed = doc.get("sensors")
    if not isinstance(listed.data, list):
        return None
    out = []
    for index, item in enumerate(listed.items_of_list()):
        if isinstance(item.data, str):  # MoveIt 2: a name, its parameters beside the list
            entry = doc.get(item.data)
            name, params = item.data, entry.params() if entry.is_mapping else ()
        elif item.is_mapping:  # MoveIt 1: the parameters in the list, named by their index
            entry, name, params = item, str(index), item.params()
        else:
            continue
        plugin = next((p.value for p in params if p.key == "sensor_plugin"), None)
        others = tuple(p for p in params if p.key != "sensor_plugin")
        out.append(Sensor(name, entry.where, None if plugin is None else str(plugin), others))
    return SensorsFile(listed.where, tuple(out))


@dataclass(frozen=True, slots=True)
class ServoConfig:
    """MoveIt Servo's parameters for one group."""

    where: Where
    params: tuple[Param, ...]

    def param(self, key: str) -> Param | None:
        return next((p for p in self.params if p.key == key), None)

    @property
    def group(self) -> str | None:
        found = self.param("move_group_name")
        return str(found.value) if found is not None and found.value else None

    @property
    def frames(self) -> tuple[Param, ...]:
        """The frames it names (planning_frame, ee_frame_name, robot_link_command_frame)."""
        return tuple(p for key in SERVO_FRAMES if (p := self.param(key)) is not None)

    @property
    def output(self) -> tuple[Param | None, Param | None]:
        """(command_out_topic, command_out_type) as written (None: absent)."""
        return self.param("command_out_topic"), self.param("command_out_type")


def read_servo(doc: Located) -> ServoConfig | None:
    """The servo parameters of a file (top level or under `moveit_servo`), or None."""
    params = unwrap_parameters(doc)
    for section in (params.get("moveit_servo"), params):
        data = section.data if isinstance(section.data, dict) else {}
        if "move_group_name" in data and SERVO_KEYS & set(data):
            return ServoConfig(section.where, section.params())
    return None
