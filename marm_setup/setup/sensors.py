"""3D perception: the setup's `sensors` resolved into MoveIt's occupancy map updater parameters,
and their checks.

move_group's planning scene monitor starts an occupancy map monitor that reads `sensors` and,
per sensor, `<name>.sensor_plugin` (MoveIt 2: moveit2 humble/jazzy occupancy_map_monitor
occupancy_map_monitor_middleware_handle.cpp l.90-118) or a list of parameter structs (MoveIt 1:
noetic occupancy_map_monitor.cpp l.105-160), loads each updater plugin and hands it its
parameters (`setParams`). It builds the octomap in the planning frame it is given (the
planning scene's: planning_scene_monitor.cpp, `OccupancyMapMonitor(..., getPlanningFrame())`),
reading `octomap_frame` only when it is given none, and `octomap_resolution` (else 0.1 with a
warning).
"""

from __future__ import annotations

import dataclasses

from marm_setup.errors import InputError
from marm_setup.moveit_params import DEFAULT_OCTOMAP_RESOLUTION, SENSOR_TYPES
from marm_setup.names import name_problem
from marm_setup.robot import RobotModel
from marm_setup.setup.model import Sensor, SetupModel

# Sensor fields that are no updater parameter of their own (the topic goes in the type's key).
_COMMON = ("name", "type", "topic", "ns")
# move_group's own parameter namespaces in moveit.yaml: a sensor named so would merge into them.
RESERVED_SENSOR_NAMES = frozenset(
    {
        "sensors",
        "planning_pipelines",
        "robot_description",
        "robot_description_semantic",
        "robot_description_kinematics",
        "robot_description_planning",
        "moveit_simple_controller_manager",
        "trajectory_execution",
        "ompl",
        "chomp",
        "stomp",
        "pilz_industrial_motion_planner",
    }
)


@dataclasses.dataclass(frozen=True, slots=True)
class SensorPlan:
    """One sensor as MoveIt reads it: its name, plugin and (parameter, value) pairs in the order
    the plugin reads them, the topic first."""

    name: str
    plugin: str
    parameters: tuple[tuple[str, float | int | str], ...]


@dataclasses.dataclass(frozen=True, slots=True)
class Perception:
    """The octomap's resolution [m] and frame, and the sensors feeding it."""

    resolution: float
    frame: str
    sensors: tuple[SensorPlan, ...]


def plan_perception(model: SetupModel, robot: RobotModel) -> Perception | None:
    """The perception settings to write, or None when the setup has no sensors."""
    if not model.sensors:
        return None
    frame = model.octomap_frame or (
        model.virtual_joints[0].parent_frame if model.virtual_joints else robot.root
    )
    resolution = model.octomap_resolution or DEFAULT_OCTOMAP_RESOLUTION
    return Perception(resolution, frame, tuple(plan_sensor(s) for s in model.sensors))


def plan_sensor(sensor: Sensor) -> SensorPlan:
    kind = SENSOR_TYPES[sensor.type]
    values: list[tuple[str, float | int | str]] = [(kind.topic_key, sensor.topic)]
    for key, default in kind.defaults:
        given = getattr(sensor, key)
        values.append((key, default if given is None else given))
    if sensor.ns is not None:
        values.append(("ns", sensor.ns))
    return SensorPlan(sensor.name, kind.plugin, tuple(values))


def check_sensors(model: SetupModel, path: str | None) -> None:
    """Raise InputError for the first sensor MoveIt could not load as written."""
    seen: set[str] = set()
    for sensor in model.sensors:
        where = f"sensors[{sensor.name}]"
        if sensor.name in seen:
            raise InputError(f"duplicate sensor name '{sensor.name}'", path=path, element=where)
        seen.add(sensor.name)
        if sensor.name in RESERVED_SENSOR_NAMES:
            raise InputError(
                f"'{sensor.name}' is one of move_group's own parameter namespaces: name the sensor otherwise",
                path=path,
                element=where,
            )
        _check_type_keys(sensor, path, where)
        _check_sensor_values(sensor, path, where)
    if model.octomap_resolution is not None and model.octomap_resolution <= 0:
        raise InputError(
            f"must be > 0, got {model.octomap_resolution:g}", path=path, element="octomap_resolution"
        )


def _check_type_keys(sensor: Sensor, path: str | None, where: str) -> None:
    """Only the parameters the sensor's updater reads."""
    kind = SENSOR_TYPES[sensor.type]
    own = {key for key, _ in kind.defaults}
    for field in dataclasses.fields(Sensor):
        if field.name in _COMMON or field.name in own or getattr(sensor, field.name) is None:
            continue
        others = [t for t, k in SENSOR_TYPES.items() if field.name in {key for key, _ in k.defaults}]
        raise InputError(
            f"a {sensor.type} sensor has no '{field.name}' ({kind.plugin} does not read it; "
            f"a {' or '.join(others)} sensor does)",
            path=path,
            element=f"{where}.{field.name}",
        )


def _check_sensor_values(sensor: Sensor, path: str | None, where: str) -> None:
    """Topics are ROS names; distances, rates and counts are not negative, the range and the
    subsampling step positive, the near clipping plane before the far one."""
    for key in ("topic", "filtered_cloud_topic"):
        value = getattr(sensor, key)
        if value is not None and (key == "topic" or value) and (problem := name_problem("topic", value)):
            raise InputError(problem, path=path, element=f"{where}.{key}")
    if sensor.ns and (problem := name_problem("topic", sensor.ns)):
        raise InputError(problem, path=path, element=f"{where}.ns")
    plan = dict(plan_sensor(sensor).parameters)
    for key, value in plan.items():
        if isinstance(value, int | float) and value < 0:
            raise InputError(f"must be >= 0, got {value:g}", path=path, element=f"{where}.{key}")
    for key in ("max_range", "point_subsample", "queue_size"):
        if key in plan and plan[key] == 0:
            raise InputError("must be > 0, got 0", path=path, element=f"{where}.{key}")
    near, far = plan.get("near_clipping_plane_distance"), plan.get("far_clipping_plane_distance")
    if isinstance(near, float) and isinstance(far, float) and near >= far:
        raise InputError(
            f"the near clipping plane ({near:g} m) must be before the far one ({far:g} m)",
            path=path,
            element=f"{where}.near_clipping_plane_distance",
        )
