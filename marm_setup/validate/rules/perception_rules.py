"""MoveIt Servo configurations and 3D sensors of any package, as moveit_servo and the occupancy
map monitor read them (sources: moveit/moveit noetic-devel, moveit/moveit2 humble and jazzy).

Servo:
- servo.unknown-group (error): moveit_servo looks its move_group_name up in the robot model:
  humble servo_calcs.cpp l.89-94 throws "Invalid move group name", jazzy servo.cpp l.189-196
  refuses the parameters, noetic servo_calcs.cpp l.97-98 dereferences the null group.
- servo.unknown-frame (error; noetic and humble): planning_frame, ee_frame_name and
  robot_link_command_frame are looked up with getGlobalLinkTransform (noetic servo_calcs.cpp
  l.197-199, humble l.241-245): a name that is no link of the robot gives no transform. The model
  frame (a virtual joint's parent) is taken as well. Jazzy's servo reads no such frames (it takes
  the IK solver's, servo.cpp l.403-436): not checked for a package marm_setup.yaml says is Jazzy.
- servo.output-type (error): a command_out_type other than trajectory_msgs/JointTrajectory or
  std_msgs/Float64MultiArray publishes nothing (noetic servo_calcs.cpp l.125-128, humble
  l.134-140; jazzy servo_parameters.yaml l.157-165 refuses it).
- servo.no-controller: the output topic must be a controller's command topic with the same
  message type (a publisher of another type never connects): ros2_control's
  joint_trajectory_controller subscribes `<name>/joint_trajectory` (JointTrajectory), the
  forward command controllers `<name>/commands` (Float64MultiArray); ros_control's
  JointTrajectoryController and JointGroup*Controller, and ArbotiX's follow_controller,
  `<name>/command`. An error when the package's controller files define no controller there (the
  robot does not move); a warning when the package has no controller file (its driver may run
  one elsewhere), unless the topic is that of a FollowJointTrajectory controller of MoveIt's own
  controller list (the trajectory controller a driver runs for MoveIt subscribes it too).
Sensors (occupancy map monitor; the Setup Assistant's updaters, pluginlib names in
moveit_ros/perception/*_plugin_description.xml, identical on the three branches):
- sensors.unknown-plugin (error): no sensor_plugin, or an `occupancy_map_monitor/` plugin that is
  none of MoveIt's: the sensor is not loaded (noetic occupancy_map_monitor.cpp l.119-123 and
  l.148-155; humble l.103-111, jazzy l.101-109). MoveIt skips an empty or `~` plugin on purpose
  with an info line (noetic l.126-128; humble occupancy_map_monitor_middleware_handle.cpp
  l.109-112, jazzy l.108-112); a plugin of another namespace may be the user's own: neither is
  checked.
- sensors.empty (warning): an entry with nothing in it, as MoveIt 1's Setup Assistant writes when
  no sensor was chosen (`sensors: - {}`, moveit_config_data.cpp output3DSensorPluginYAML), or an
  empty MoveIt 2 name (`sensors: [""]`): MoveIt logs "No sensor plugin specified for octomap
  updater ...; ignoring." and goes on (noetic occupancy_map_monitor.cpp l.119-123 at 5555c3d;
  moveit2 jazzy occupancy_map_monitor_middleware_handle.cpp l.103-112 at 4d84106, humble
  l.104-112): no sensor was meant, none is lost.
- sensors.no-topic (error): PointCloudOctomapUpdater::setParams fails without point_cloud_topic
  (noetic pointcloud_octomap_updater.cpp l.73-74; humble l.78-88, jazzy l.75-85) and an empty
  topic subscribes nothing; the DepthImage updater reads image_topic (noetic
  depth_image_octomap_updater.cpp l.92-93, humble l.90-106, jazzy l.92-108).
- sensors.missing-parameter (ROS 2): the PointCloud updater's setParams returns false when one of
  its parameters is unset: "Failed to configure updater", the sensor is skipped (error; humble
  occupancy_map_monitor.cpp l.121-125, jazzy l.119-123). The DepthImage updater stops reading at
  the first unset one and keeps its built-in values for the rest (a warning).
- sensors.parameter-type (error): ROS 2's typed get_parameter throws on a value of another type
  (an integer for a double): the DepthImage updater then fails (humble l.108-111), the
  PointCloud one does not catch it. MoveIt 1's readXmlParam takes an integer for a double but
  casts an unsigned int parameter from an int only (noetic occupancy_map_updater.cpp l.56-71):
  XmlRpc throws, setParams fails.
"""

from __future__ import annotations

from collections.abc import Iterable

from marm_setup.findings import Finding, Location, error, warning
from marm_setup.moveit_params import SENSOR_TYPES
from marm_setup.package import MoveItPackage, Param, Sensor, ServoConfig
from marm_setup.robot import RobotModel
from marm_setup.ros import DISTROS, Target

TRAJECTORY, FORWARD = "trajectory_msgs/JointTrajectory", "std_msgs/Float64MultiArray"
ROS2_FORWARD = (
    "forward_command_controller/ForwardCommandController",
    "forward_command_controller/MultiInterfaceForwardCommandController",
    "position_controllers/JointGroupPositionController",
    "velocity_controllers/JointGroupVelocityController",
    "effort_controllers/JointGroupEffortController",
)
PLUGIN_PREFIX = "occupancy_map_monitor/"


def controller_topics(pkg: MoveItPackage) -> dict[str, tuple[str, str]]:
    """Command topic (no leading slash) -> (message type, controller) of every controller the
    package's controller files define."""
    out: dict[str, tuple[str, str]] = {}
    if pkg.ros2_controllers is not None:
        for c in pkg.ros2_controllers.controllers:
            if c.type == "joint_trajectory_controller/JointTrajectoryController":
                out[f"{c.name}/joint_trajectory"] = (TRAJECTORY, c.name)
            elif c.type in ROS2_FORWARD:
                out[f"{c.name}/commands"] = (FORWARD, c.name)
    if pkg.ros_controllers is not None:
        for c in pkg.ros_controllers.controllers:
            if c.type.endswith("/JointTrajectoryController"):
                out[f"{c.name}/command"] = (TRAJECTORY, c.name)
            elif c.type.rsplit("/", 1)[-1].startswith("JointGroup"):
                out[f"{c.name}/command"] = (FORWARD, c.name)
    for a in pkg.arbotix.controllers if pkg.arbotix is not None else ():
        out[f"{a.name}/command"] = (TRAJECTORY, a.name)
    return out


def check_servos(pkg: MoveItPackage, robot: RobotModel) -> list[Finding]:
    assert pkg.srdf is not None
    groups = {g.name for g in pkg.srdf.groups}
    frames = {link.name for link in robot.links} | {v.parent_frame for v in pkg.srdf.virtual_joints}
    topics = controller_topics(pkg)
    out: list[Finding] = []
    for servo in pkg.servo:
        out += _group(servo, groups)
        row = DISTROS.get(pkg.ros_distro or "")
        if row is None or not row.servo_needs_kinematics:  # else servo takes its frames from IK
            out += _frames(servo, frames)
        out += _output(servo, topics, pkg)
    return out


def _group(servo: ServoConfig, groups: set[str]) -> list[Finding]:
    found = servo.param("move_group_name")
    if found is None or str(found.value) in groups:
        return []
    known = ", ".join(sorted(groups)) or "none"
    msg = f"unknown group '{found.value}' (groups: {known}): moveit_servo stops on it"
    at = Location("servo", str(found.value), ("group", str(found.value)))
    return [error("servo.unknown-group", found.where.file, found.where.element, msg, at=at)]


def _frames(servo: ServoConfig, frames: set[str]) -> list[Finding]:
    return [
        error(
            "servo.unknown-frame",
            p.where.file,
            p.where.element,
            f"'{p.value}' is no link of the robot: moveit_servo finds no transform for it",
            f"a link: {', '.join(sorted(frames)[:8])}{', ...' if len(frames) > 8 else ''}",
        )
        for p in servo.frames
        if str(p.value) not in frames
    ]


def _output(servo: ServoConfig, topics: dict[str, tuple[str, str]], pkg: MoveItPackage) -> list[Finding]:
    topic, kind = servo.output
    if kind is not None and kind.value not in (TRAJECTORY, FORWARD):
        msg = f"'{kind.value}' is not one of: {TRAJECTORY}, {FORWARD}: moveit_servo publishes nothing"
        return [error("servo.output-type", kind.where.file, kind.where.element, msg)]
    if topic is None or not isinstance(topic.value, str):
        return []
    out_type = str(kind.value) if kind is not None else TRAJECTORY
    name = topic.value.strip("/")
    match = next((v for t, v in topics.items() if name == t or name.endswith(f"/{t}")), None)
    file, element = topic.where.file, topic.where.element
    if match is None:
        return [] if _moveit_drives(name, out_type, pkg) else [_no_controller(topic, out_type, pkg, topics)]
    if match[0] != out_type:
        msg = f"{match[1]} takes {match[0]} on {topic.value}, moveit_servo publishes {out_type}: they never connect"
        return [error("servo.no-controller", file, element, msg, "set command_out_type or command_out_topic")]
    return []


# what a trajectory controller `<name>` subscribes beside the `<name>/follow_joint_trajectory`
# action MoveIt sends: ros_control's JointTrajectoryController `command` (ros_controllers
# joint_trajectory_controller_impl.h, init(): subscribe("command") and ActionServer
# "follow_joint_trajectory" in the controller's namespace), ros2_control's `~/joint_trajectory`
# (ros2_controllers joint_trajectory_controller.cpp on_configure)
TRAJECTORY_TOPIC = {Target.ROS1: "command", Target.ROS2: "joint_trajectory"}


def _moveit_drives(topic: str, out_type: str, pkg: MoveItPackage) -> bool:
    """Whether `topic` (no leading slash) is the trajectory topic of a controller MoveIt's own
    controller list drives through `<name>/follow_joint_trajectory` while the package defines no
    controller: the driver must run that controller for MoveIt anyway, and servo reaches it."""
    if out_type != TRAJECTORY or pkg.moveit_controllers is None or _driver_files(pkg):
        return False
    suffix = TRAJECTORY_TOPIC[pkg.target]
    return any(
        c.type == "FollowJointTrajectory"
        and c.action_ns == "follow_joint_trajectory"
        and topic in (f"{c.name}/{suffix}", f"{c.name.strip('/')}/{suffix}")
        for c in pkg.moveit_controllers.controllers
    )


def _driver_files(pkg: MoveItPackage) -> list[str]:
    return [f.where.file for f in (pkg.ros2_controllers, pkg.ros_controllers, pkg.arbotix) if f is not None]


def _no_controller(topic: Param, out_type: str, pkg: MoveItPackage, topics: dict) -> Finding:
    files = _driver_files(pkg)
    wanted = "joint_trajectory_controller" if out_type == TRAJECTORY else "forward command controller"
    if not files:
        msg = f"no controller file of the package defines a {wanted} on {topic.value}"
        return warning(
            "servo.no-controller", topic.where.file, topic.where.element, msg, "make sure the driver runs one"
        )
    offered = ", ".join(f"/{t}" for t, (kind, _) in sorted(topics.items()) if kind == out_type) or "none"
    msg = f"no controller of {', '.join(files)} subscribes {topic.value} ({out_type} topics: {offered}): the robot does not move"
    return error("servo.no-controller", topic.where.file, topic.where.element, msg)


def check_sensors(pkg: MoveItPackage) -> list[Finding]:
    out: list[Finding] = []
    by_plugin = {kind.plugin: kind for kind in SENSOR_TYPES.values()}
    for sensor in pkg.sensors.sensors if pkg.sensors is not None else ():
        kind = by_plugin.get(sensor.plugin or "")
        if kind is None:
            out += _unknown_plugin(sensor, sorted(by_plugin))
            continue
        out += _sensor(sensor, kind.topic_key, dict(kind.defaults), pkg.target)
    return out


def _unknown_plugin(sensor: Sensor, valid: list[str]) -> list[Finding]:
    plugin = sensor.plugin
    if plugin is None and not sensor.params and (sensor.name.isdigit() or not sensor.name):
        msg = "an empty sensor entry: MoveIt logs 'No sensor plugin specified' and ignores it"
        return [warning("sensors.empty", sensor.where.file, sensor.where.element, msg, "remove the entry")]
    skipped = plugin is not None and (not plugin or plugin.startswith("~"))
    if skipped or (plugin and not plugin.startswith(PLUGIN_PREFIX)):
        return []
    said = f"sensor_plugin '{plugin}' is none of MoveIt's updaters" if plugin else "no sensor_plugin"
    msg = f"{said} ({', '.join(valid)}): the sensor is not loaded"
    return [error("sensors.unknown-plugin", sensor.where.file, sensor.where.element, msg)]


def _sensor(sensor: Sensor, topic_key: str, defaults: dict, target: Target) -> list[Finding]:
    file, element = sensor.where.file, sensor.where.element
    topic = sensor.param(topic_key)
    out = []
    if topic is None or not str(topic.value or "").strip():
        msg = f"no {topic_key}: the updater subscribes to nothing (MoveIt fails to configure it)"
        out.append(error("sensors.no-topic", file, element, msg, f"set {topic_key}"))
    missing = [key for key in defaults if sensor.param(key) is None]
    if target == Target.ROS2 and missing:
        out.append(_missing(sensor, missing, defaults, topic_key))
    for key, default in defaults.items():
        found = sensor.param(key)
        if found is not None:
            out += _typed(found, default, target)
    return out


def _missing(sensor: Sensor, missing: list[str], defaults: dict, topic_key: str) -> Finding:
    file, element = sensor.where.file, sensor.where.element
    hint = ", ".join(f"{k}: {defaults[k]}" for k in missing)
    if topic_key == "point_cloud_topic":
        msg = f"no {', '.join(missing)}: MoveIt 2's PointCloud updater fails to configure without it and skips the sensor"
        return error("sensors.missing-parameter", file, element, msg, hint)
    msg = f"no {missing[0]}: MoveIt 2's DepthImage updater stops reading there (the parameters after it keep its built-in values)"
    return warning("sensors.missing-parameter", file, element, msg, hint)


def _typed(found: Param, default: object, target: Target) -> Iterable[Finding]:
    value = found.value
    number = isinstance(value, int | float) and not isinstance(value, bool)
    if isinstance(default, str):
        ok = isinstance(value, str)
    elif target == Target.ROS1 and isinstance(default, float):
        ok = number
    else:
        ok = number and type(value) is type(default)
    if ok:
        return []
    want = {str: "a string", int: "an integer", float: "a double"}[type(default)]
    msg = f"expected {want}, got {value!r}: the updater fails to load"
    return [error("sensors.parameter-type", found.where.file, found.where.element, msg)]
