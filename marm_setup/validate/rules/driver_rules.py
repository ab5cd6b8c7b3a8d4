"""Controllers, the driver's side: MoveIt's controllers against ROS 2 `ros2_controllers.yaml`
(controller_manager), ROS 1 ros_control `ros_controllers.yaml`, and ArbotiX `arbotix.yaml` plus
the `gripper_controller` nodes of the launch files."""

from __future__ import annotations

from collections.abc import Mapping

from marm_setup.findings import Finding, error, warning
from marm_setup.moveit_params import (
    DRIVER_CONTROLLER_TYPES,
    DRIVER_CONTROLLERS,
    FOLLOW_JOINT_TRAJECTORY,
    FOLLOW_JOINT_TRAJECTORY_NS,
    GRIPPER_COMMAND,
    JOINT_DRIVER_CONTROLLERS,
    MOVEIT_HANDLE_TYPES,
)
from marm_setup.package import ArbotixFile, ControllersFile, DriverController, DriverFile, MoveItController
from marm_setup.robot import RobotModel

# Controller classes that serve no action MoveIt sends: joint state publishers and the forward
# command controllers (a topic, no action server).
NO_ACTION_CONTROLLERS = frozenset(
    {*JOINT_DRIVER_CONTROLLERS - set(DRIVER_CONTROLLERS), "JointStateController", "JointStateBroadcaster"}
)


def check_driver_controllers(
    moveit: ControllersFile,
    driver: DriverFile,
    robot: RobotModel,
    *,
    ros1: bool = False,
    simulated: tuple[DriverFile, ...] = (),
) -> list[Finding]:
    """MoveIt's controllers exist in the driver file with a matching type, joints and action;
    one the driver file lacks is checked against the files the robot description's ros2_control
    simulator plugin loads (`simulated`), where the controller manager that runs in simulation
    finds it (gazebo_ros2_control_plugin.cpp l.269-277: each `<parameters>` is a --params-file).

    A driver file without controllers (the Setup Assistant's ROS 1 `ros_controllers.yaml` with
    only `hardware_interface` / `generic_hw_control_loop`, moveit/moveit `moveit_setup_assistant/
    src/tools/moveit_config_data.cpp` l.1063-1074) is nothing to check: the spawner starts only
    the controllers named in its args (`templates/moveit_config_pkg_template/launch/
    ros_controllers.launch` l.8-9, `[ROS_CONTROLLERS]`, empty then), so nothing loads a
    controller from the file and nothing fails; MoveIt's controllers come from elsewhere.

    So is a ROS 1 (`ros1`) file whose controllers serve no action MoveIt sends (only a
    `joint_state_controller`, as the Setup Assistant's template lists it beside a hardware
    interface): the action servers MoveIt connects to are another package's (a vendor driver,
    ROS-Industrial's `joint_trajectory_action`), which no rule here can see. ROS 2 keeps the
    check: its spawners start MoveIt's controllers from this file."""
    file = driver.where.file
    if not driver.well_formed:
        return [error("controller.driver-malformed", file, "", "expected a mapping of controllers")]
    if not driver.controllers:
        return []
    out: list[Finding] = []
    for d in sorted(driver.controllers, key=lambda d: d.name):
        if d.type.rsplit("/", 1)[-1] not in JOINT_DRIVER_CONTROLLERS:
            continue  # e.g. a twist controller's `joint` names a Cartesian frame, not a URDF joint
        for joint in d.joints or ():
            if joint not in robot.joint_map:
                out.append(error("controller.unknown-joint", file, d.element, f"unknown joint '{joint}'"))
    if ros1 and not any(_may_serve_action(d) for d in driver.controllers):
        return out
    for c in moveit.controllers:
        sim = next((f for f in simulated if f.controller(c.name) is not None), None)
        if driver.controller(c.name) is None and sim is not None:
            out += _check_against_driver(moveit, sim, c)
        else:
            out += _check_against_driver(moveit, driver, c, simulated)
    return out


def _may_serve_action(d: DriverController) -> bool:
    """`d` may be an action server MoveIt connects to (a trajectory or gripper action
    controller, or a type we do not know)."""
    return d.type.rsplit("/", 1)[-1] not in NO_ACTION_CONTROLLERS


def _check_against_driver(
    moveit: ControllersFile, driver: DriverFile, c: MoveItController, simulated: tuple[DriverFile, ...] = ()
) -> list[Finding]:
    file = driver.where.file
    d: DriverController | None = driver.controller(c.name)
    if d is None:
        return [_missing(moveit, driver, c, simulated)]
    suffix = d.type.rsplit("/", 1)[-1]
    served = DRIVER_CONTROLLER_TYPES.get(d.type) or DRIVER_CONTROLLERS.get(suffix)
    if served is None:
        return []  # a driver type we do not know: no claim either way
    expected_type, served_ns = served
    out = []
    if c.type in MOVEIT_HANDLE_TYPES and c.type != expected_type:
        msg = f"MoveIt expects a {c.type} action but '{c.name}' is a {d.type}"
        out.append(error("controller.driver-type", file, d.element, msg))
    elif c.action != f"{c.name}/{served_ns}":
        msg = f"{d.type} serves '{c.name}/{served_ns}', MoveIt connects to '{c.action}'"
        out.append(error("controller.driver-action", file, d.element, msg, f"set action_ns: {served_ns}"))
    if d.joints is None:
        msg = f"'{c.name}' names no joints ({d.type} needs them; MoveIt's has {list(c.joints)})"
        out.append(error("controller.driver-joints", file, d.element, msg))
    elif set(d.joints) != set(c.joints):
        msg = f"joints {list(d.joints)} differ from MoveIt's {list(c.joints)} for '{c.name}'"
        out.append(error("controller.driver-joints", file, d.element, msg))
    return out


def _missing(
    moveit: ControllersFile, driver: DriverFile, c: MoveItController, simulated: tuple[DriverFile, ...] = ()
) -> Finding:
    """MoveIt's controller `c` is not in the driver file. MoveIt's simple controller manager
    connects to the action `<name>/<action_ns>` whoever serves it (moveit2 humble
    `moveit_simple_controller_manager/src/moveit_simple_controller_manager.cpp` l.111-182: one
    action client per listed controller, no controller_manager asked). An error when a
    controller of the file that may serve an action may drive one of `c`'s joints: ros2_control
    moves those joints under another name, so nothing serves the action MoveIt connects to (a
    renamed or misspelled controller). When no controller of the file may drive any of its
    joints (a broadcaster drives none), they are moved outside this file (a gripper driver's
    own action server, e.g. franka_gripper's `<name>/gripper_action` started by another
    package's launch file), which validate cannot see: a warning."""
    known = ", ".join(sorted(x.name for x in driver.controllers)) or "none"
    msg = f"controller '{c.name}' is not in {driver.where.file} (has: {known})"
    if simulated:
        msg += f" nor in {', '.join(f.where.file for f in simulated)}, which the simulator plugin loads"
    joints = set(c.joints)
    if any(_may_drive(d, joints) for d in driver.controllers):
        return error("controller.driver-missing", moveit.where.file, c.element, msg)
    msg += (
        f", and none of its controllers drives {sorted(joints)}: the action '{c.action}' must come "
        "from another node (a vendor driver), which validate cannot see"
    )
    fix = f"start the node serving '{c.action}', or add '{c.name}' to {driver.where.file}"
    return warning("controller.driver-missing", moveit.where.file, c.element, msg, fix)


def _may_drive(d: DriverController, joints: set[str]) -> bool:
    """`d` may serve an action and drive some of `joints`: it names one of them, or it is a
    trajectory or gripper action controller whose joints the file does not give (they may be
    any)."""
    if not _may_serve_action(d):
        return False
    if d.joints is not None:
        return bool(joints & set(d.joints))
    return d.type in DRIVER_CONTROLLER_TYPES or d.type.rsplit("/", 1)[-1] in DRIVER_CONTROLLERS


# -- ArbotiX ---------------------------------------------------------------------------------------


def check_arbotix(
    arbotix: ArbotixFile,
    moveit: ControllersFile,
    robot: RobotModel,
    gripper_nodes: Mapping[str, tuple[str, str]],
) -> list[Finding]:
    """arbotix.yaml joints exist; FollowJointTrajectory controllers match `controllers` by
    name, action_name and joints; GripperCommand controllers match a gripper_controller node
    (`gripper_nodes`: node name -> (launch file, its `joint` param))."""
    file = arbotix.where.file
    out: list[Finding] = []
    for servo in sorted(arbotix.servos, key=lambda s: s.joint):
        if servo.joint not in robot.joint_map:
            out.append(
                error(
                    "controller.unknown-joint",
                    file,
                    f"joints.{servo.joint}",
                    f"unknown joint '{servo.joint}'",
                )
            )
    for c in moveit.controllers:
        if c.type == GRIPPER_COMMAND:
            out += _check_gripper_node(file, c, gripper_nodes)
        elif c.type == FOLLOW_JOINT_TRAJECTORY:
            out += _check_arbotix_follow(arbotix, c)
    return out


def _check_arbotix_follow(arbotix: ArbotixFile, c: MoveItController) -> list[Finding]:
    file = arbotix.where.file
    entry = arbotix.controller(c.name)
    where = f"controllers.{c.name}"
    if entry is None:
        known = ", ".join(sorted(x.name for x in arbotix.controllers)) or "none"
        return [
            error(
                "controller.driver-missing",
                file,
                "controllers",
                f"no ArbotiX controller '{c.name}' (has: {known})",
            )
        ]
    out = []
    action = entry.action_name.value if entry.action_name is not None else FOLLOW_JOINT_TRAJECTORY_NS
    if action != c.action:
        msg = f"action_name '{action}' differs from MoveIt's '{c.action}'"
        out.append(
            error(
                "controller.driver-action", file, f"{where}.action_name", msg, f"set action_name: {c.action}"
            )
        )
    joints = entry.joints.value if entry.joints is not None else None
    if isinstance(joints, tuple) and set(map(str, joints)) != set(c.joints):
        msg = f"joints {list(joints)} differ from MoveIt's {list(c.joints)}"
        out.append(error("controller.driver-joints", file, f"{where}.joints", msg))
    return out


def _check_gripper_node(
    file: str, c: MoveItController, nodes: Mapping[str, tuple[str, str]]
) -> list[Finding]:
    if c.name not in nodes:
        known = ", ".join(sorted(nodes)) or "none"
        msg = f"no gripper_controller node named '{c.name}' in the launch files (found: {known})"
        return [error("controller.driver-missing", file, "controllers", msg)]
    launch, joint = nodes[c.name]
    if joint and joint not in c.joints:
        msg = (
            f"gripper_controller '{c.name}' drives joint '{joint}', MoveIt's controller has {list(c.joints)}"
        )
        return [error("controller.gripper-joint", launch, f"node[{c.name}]", msg)]
    return []
