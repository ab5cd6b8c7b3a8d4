"""Controllers, MoveIt's side: the controller list vs the robot and the groups (MoveIt's own
controller selection), and MoveIt 1's fake controllers. The driver side is `driver_rules`."""

from __future__ import annotations

from collections.abc import Collection, Sequence
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, Location, error, warning
from marm_setup.moveit_params import (
    ARBOTIX_GRIPPER_ACTION_NS,
    FOLLOW_JOINT_TRAJECTORY,
    FOLLOW_JOINT_TRAJECTORY_NS,
    GRIPPER_CMD_NS,
    MOVEIT_HANDLE_TYPES,
    load_table,
)
from marm_setup.package import (
    ROS2_CONTROL_HANDLES,
    SIMPLE_MANAGER,
    ControllersFile,
    DriverFile,
    MoveItController,
    MoveItPackage,
    SkippedController,
)
from marm_setup.robot import RobotModel
from marm_setup.setup import active_group_joints, groups_by_name
from marm_setup.validate.rules.controller_selection import select_controllers

if TYPE_CHECKING:
    from marm_setup.setup import Srdf


def skipped_reason(skipped: SkippedController) -> tuple[str, str]:
    """(message, hint) for an entry the manager skips (the port reports it the same way)."""
    if skipped.missing == ("action_ns",):
        msg = "no action_ns: MoveIt skips this controller (an empty action_ns is allowed)"
        return msg, f"add action_ns: {FOLLOW_JOINT_TRAJECTORY_NS}"
    return (
        f"MoveIt skips this controller: a key it needs is missing or empty ({', '.join(skipped.missing)})",
        "",
    )


def check_listed(controllers: ControllersFile) -> list[Finding]:
    """The list exists, and each entry the manager would skip."""
    file = controllers.where.file
    if controllers.form is None:
        return [
            error(
                "controller.malformed",
                file,
                controllers.where.element,
                "no controller_list / controller_names",
            )
        ]
    out = []
    for skipped in controllers.skipped:
        msg, hint = skipped_reason(skipped)
        rule = "controller.missing-action-ns" if skipped.missing == ("action_ns",) else "controller.malformed"
        out.append(error(rule, file, skipped.where.element, msg, hint))
    return out


def check_ros2_namespace(controllers: ControllersFile) -> list[Finding]:
    """MoveIt 2: the simple controller manager reads `moveit_simple_controller_manager.controller_names`
    (moveit2 moveit_simple_controller_manager.cpp `initialize` l.105-108 at 8fcb5d2: PARAM_BASE_NAME
    prefix, "No controller_names specified" otherwise). Where the list lands is the key a launch
    puts the file under (`{"moveit_simple_controller_manager": load_yaml(...)}` in a Python
    launch: `loaded_into`) followed by the file's own keys; MoveItConfigsBuilder.trajectory_execution
    hands the file over as it is (moveit_configs_builder.py l.343-382 at jazzy 4d84106), so there
    top-level `controller_names` give MoveIt no controllers, and so does a file that names the
    namespace again under a launch that already adds it. Ros2ControlManager asks ros2_control for
    its controllers instead and needs no list.

    When no launch file of the package loads the list (`load_unknown`: a config package whose
    move_group is launched by another package, as a bringup's `{"moveit_simple_controller_manager":
    load_yaml(...)}` does), the key it lands under is that other launch file's to say: top-level
    `controller_names` is then a warning, not an error."""
    if controllers.form != "controller_names" or "Ros2ControlManager" in controllers.manager:
        return []
    in_file = (SIMPLE_MANAGER,) if controllers.namespaced else ()
    landed = (*((controllers.loaded_into,) if controllers.loaded_into else ()), *in_file)
    if landed == (SIMPLE_MANAGER,):
        return []
    file = controllers.where.file
    if not landed:
        msg = f"controller_names is not under '{SIMPLE_MANAGER}': MoveIt 2 finds no controllers"
        hint = f"indent controller_names and the controllers under '{SIMPLE_MANAGER}:'"
        if controllers.load_unknown:
            msg += (
                " unless the launch file that loads it (no launch file of this package does) puts it "
                f"under '{SIMPLE_MANAGER}'"
            )
            return [warning("controller.no-namespace", file, "controller_names", msg, hint)]
        return [error("controller.no-namespace", file, "controller_names", msg, hint)]
    msg = (
        f"the launch puts this file under '{controllers.loaded_into}', so controller_names lands at "
        f"'{'.'.join(landed)}.controller_names', not '{SIMPLE_MANAGER}.controller_names': MoveIt 2 finds no controllers"
    )
    hint = f"drop the file's own '{SIMPLE_MANAGER}:' level" if controllers.namespaced else ""
    return [error("controller.no-namespace", file, "controller_names", msg, hint)]


def check_ros1_namespace(controllers: ControllersFile) -> list[Finding]:
    """MoveIt 1: the simple controller manager reads `controller_list` from move_group's private
    namespace (moveit/moveit moveit_plugins/moveit_simple_controller_manager/src/
    moveit_simple_controller_manager.cpp l.56-61 at fdb79ac: `node_handle_("~")`,
    `hasParam("controller_list")`, else "No controller_list specified." and no controllers). A
    list the launch files load only under another namespace (`<rosparam ns=...>`, a ros_control
    namespace, outside move_group's) is one MoveIt never reads: one error at the first such load
    (package/layout.py `_ros1_controllers` decides, from every load's resolved namespace)."""
    if not controllers.elsewhere:
        return []
    first, others = controllers.elsewhere[0], controllers.elsewhere[1:]
    read_at = " or ".join(f"'/{ns}/controller_list'" for ns in controllers.read_at)
    more = f" (and {len(others)} more load(s), none there either)" if others else ""
    msg = (
        f"loads {controllers.where.file}'s controller_list into '/{first.ns}' ('{_list_at(first.ns)}'){more}, "
        f"but move_group's simple controller manager reads {read_at} and no launch file loads one there: "
        "MoveIt logs 'No controller_list specified.' and has no controllers to execute with"
    )
    hint = (
        f"load {controllers.where.file} in move_group's namespace ('/{controllers.read_at[0]}'): "
        '<rosparam file=...> without ns=, in the launch file move_group.launch includes with ns="move_group"'
    )
    element = f"line {first.line}: <rosparam>" if first.line else "rosparam"
    return [error("controller.list-namespace", first.launch, element, msg, hint)]


def check_ros1_list_loaded(pkg: MoveItPackage) -> list[Finding]:
    """MoveIt 1: a launch file makes the simple controller manager move_group's manager, but no
    launch file of the package loads a `controller_list` anywhere: MoveIt reads none ("No
    controller_list specified.", moveit_simple_controller_manager.cpp l.56-61 at fdb79ac) unless a
    launch file outside the package loads one into move_group's namespace (a warning: that is
    the user's to know)."""
    launch = pkg.controller_list_unloaded
    if not launch:
        return []
    listed = pkg.moveit_controllers
    named = f" ({listed.where.file} is never loaded)" if listed is not None else ""
    msg = (
        "sets move_group's moveit_controller_manager to the simple controller manager, but no launch "
        f"file of the package loads a controller_list{named}: MoveIt logs 'No controller_list "
        "specified.' and cannot execute, unless a launch file elsewhere loads one into move_group's namespace"
    )
    hint = "load the controller list (<rosparam file=.../simple_moveit_controllers.yaml/>) beside that param"
    return [warning("controller.list-not-loaded", launch, "moveit_controller_manager", msg, hint)]


def check_ros1_manager_plugins(pkg: MoveItPackage) -> list[Finding]:
    """MoveIt 1: a `moveit_controller_manager` class (set on a branch the launch defaults take)
    that no MoveIt package nor a known third-party one exports, as declared_param_rules judges a
    ROS 2 plugin class (params.plugin). pluginlib throws, and the trajectory execution manager
    logs "Exception while loading controller manager" and executes nothing
    (trajectory_execution_manager.cpp noetic l.160-169 at fdb79ac)."""
    from marm_setup.package import Received
    from marm_setup.validate.rules.declared_param_rules import (
        check_plugin_param,
        exported_classes,
        package_finder,
    )

    table, built, exported = load_table("noetic"), package_finder(pkg), exported_classes(pkg)
    out: list[Finding] = []
    for launch, value in dict.fromkeys((p.launch, p.value.strip()) for p in pkg.controller_managers):
        if value and "$(" not in value:
            param = Received(
                "move_group", "moveit_controller_manager", value, launch, "moveit_controller_manager"
            )
            out += check_plugin_param(param, table, built, exported)
    return out


def _list_at(ns: str) -> str:
    return f"/{ns}/controller_list" if ns else "/controller_list"


def check_moveit_controllers(
    controllers: ControllersFile, robot: RobotModel | None, real: bool = True, virtual: Collection[str] = ()
) -> list[Finding]:
    """Joints exist (when the robot is known; `virtual`: the SRDF's virtual joints, joints of
    MoveIt's model too); for real (non-fake) controllers: known type, action_ns present and
    plausible."""
    out: list[Finding] = []
    file = controllers.where.file
    for c in controllers.controllers:
        for joint in c.joints:
            if robot is not None and joint not in robot.joint_map and joint not in virtual:
                out.append(error("controller.unknown-joint", file, c.element, f"unknown joint '{joint}'"))
        if real:
            out += _check_type(file, c)
    return out


def _check_type(file: str, c: MoveItController) -> list[Finding]:
    if c.type not in MOVEIT_HANDLE_TYPES:
        msg = f"type '{c.type}' is not one MoveIt's simple controller manager knows ({', '.join(MOVEIT_HANDLE_TYPES)})"
        return [error("controller.unknown-type", file, c.element, msg)]
    if c.action_ns and _implausible(c.type, c.action_ns):
        msg = f"action_ns '{c.action_ns}' is implausible for a {c.type} controller"
        hint = (
            FOLLOW_JOINT_TRAJECTORY_NS
            if c.type == FOLLOW_JOINT_TRAJECTORY
            else f"{GRIPPER_CMD_NS} (ros2_control) or {ARBOTIX_GRIPPER_ACTION_NS} (ArbotiX)"
        )
        return [warning("controller.action-ns", file, c.element, msg, f"usually {hint}")]
    return []


def _implausible(type_: str, action_ns: str) -> bool:
    """A trajectory controller on a gripper namespace, or a gripper on a trajectory namespace."""
    if type_ == FOLLOW_JOINT_TRAJECTORY:
        return "gripper" in action_ns
    return FOLLOW_JOINT_TRAJECTORY_NS in action_ns


def check_coverage(
    controllers: ControllersFile, srdf: Srdf, robot: RobotModel, alternatives: Sequence[ControllersFile] = ()
) -> list[Finding]:
    """Every active group joint is in some controller, and each group's joints can be executed
    by MoveIt's own controller selection (see `controller_selection`)."""
    out: list[Finding] = []
    ctrls = controllers.controllers
    covered = {j for c in ctrls for j in c.joints}
    for joint, groups in sorted(_group_joints(srdf, robot).items()):
        if joint not in covered:
            label = f"joint '{joint}' (group {', '.join(groups)})"
            out.append(_uncovered(controllers, label, joint, alternatives))
    by_name = groups_by_name(srdf.groups)
    for group in srdf.groups:
        joints = active_group_joints(group, by_name, robot, tuple(srdf.passive_joints))
        if joints and set(joints) <= covered:
            out += _check_selection(controllers, group.name, joints)
    return out


def _check_selection(controllers: ControllersFile, group: str, joints: Sequence[str]) -> list[Finding]:
    file, where = controllers.where.file, controllers.where.child(f"group[{group}]").element
    pick = select_controllers(joints, controllers.controllers)
    if pick is None:
        msg = (
            f"no set of controllers without shared joints covers group '{group}': MoveIt cannot "
            "execute its motions ('Unable to identify any set of controllers')"
        )
        return [error("controller.no-combination", file, where, msg)]
    if pick.tied:
        options = " or ".join("+".join(repr(n) for n in o) for o in (pick.chosen, *pick.tied))
        msg = (
            f"MoveIt picks arbitrarily between {options} for group '{group}' (same defaults and joint count)"
        )
        return [warning("controller.ambiguous", file, where, msg, "set default: true on the one to use")]
    return []


def _uncovered(
    controllers: ControllersFile, label: str, joint: str, alternatives: Sequence[ControllersFile]
) -> Finding:
    file, where = controllers.where.file, controllers.where.child(f"joint[{joint}]").element
    for alt in alternatives:
        if any(joint in c.joints for c in alt.controllers):
            msg = f"{label} has no controller here; only {alt.where.file} covers it"
            hint = f"launch with {alt.where.file} to execute it"
            return warning("controller.uncovered-joint", file, where, msg, hint)
    msg = f"{label} has no controller: MoveIt cannot execute motions of it"
    return error("controller.uncovered-joint", file, where, msg, "add it to a controller's joints")


def _group_joints(srdf: Srdf, robot: RobotModel) -> dict[str, list[str]]:
    by_name = groups_by_name(srdf.groups)
    out: dict[str, list[str]] = {}
    for group in srdf.groups:
        for joint in active_group_joints(group, by_name, robot, tuple(srdf.passive_joints)):
            out.setdefault(joint, []).append(group.name)
    return out


# -- fake controllers (MoveIt 1) ----------------------------------------------------------------------


def check_fake_controllers(fake: ControllersFile, srdf: Srdf, robot: RobotModel) -> list[Finding]:
    """Joints exist, every group's active joints are covered, `initial` poses exist. The SRDF's
    virtual joint is a joint of MoveIt's model (its root joint), which the Setup Assistant lists
    when a group holds it (moveit_config_data.cpp outputFakeControllersYAML l.551-567) and the
    fake controller manager takes like any name (moveit_fake_controller_manager.cpp l.83-122); robot_model.cpp buildJointModel l.932-960 makes it the root joint."""
    virtual = {v.name for v in srdf.virtual_joints}
    out = check_listed(fake) + check_moveit_controllers(fake, robot, real=False, virtual=virtual)
    covered = {j for c in fake.controllers for j in c.joints}
    for joint, groups in sorted(_group_joints(srdf, robot).items()):
        if joint not in covered:
            msg = f"joint '{joint}' (group {', '.join(groups)}) is in no fake controller"
            where = fake.where.child(f"joint[{joint}]").element
            out.append(error("controller.fake-uncovered", fake.where.file, where, msg))
    return out + _check_initial(fake, srdf)


def _check_initial(fake: ControllersFile, srdf: Srdf) -> list[Finding]:
    file = fake.where.file
    if fake.initial_malformed:
        return [
            error(
                "controller.fake-initial-pose", file, fake.where.child("initial").element, "expected a list"
            )
        ]
    groups = {g.name for g in srdf.groups}
    states = {(s.group, s.name) for s in srdf.group_states}
    out = []
    for item in fake.initial or ():
        where = item.where.element
        if item.group not in groups:
            at = Location("fake_controllers.initial", item.group, ("group", item.group))
            out.append(
                error("controller.fake-initial-pose", file, where, f"unknown group '{item.group}'", at=at)
            )
        elif (item.group, item.pose) not in states:
            msg = f"group '{item.group}' has no pose '{item.pose}'"
            out.append(error("controller.fake-initial-pose", file, where, msg))
    return out


# -- moveit_ros_control_interface: controllers found at run time ------------------------------------

ROS_CONTROL_INTERFACE = "moveit_ros_control_interface/"
# The controller types moveit_ros_control_interface has a handle for (the package model's
# table, package.control_manager, from moveit_ros_control_interface_plugins.xml); the
# admittance controller's handle is empty (it executes nothing).
EXECUTING_TYPES = frozenset(ROS2_CONTROL_HANDLES)


def uses_ros_control_interface(controllers: ControllersFile) -> bool:
    """The manager is moveit_ros_control_interface's (`Ros2ControlManager`, MoveIt 1's
    `MoveItControllerManager`): it asks the controller manager for its controllers."""
    return controllers.manager.startswith(ROS_CONTROL_INTERFACE)


def check_ros_control_coverage(
    controllers: ControllersFile, driver: DriverFile | None, srdf: Srdf, robot: RobotModel
) -> list[Finding]:
    """moveit_ros_control_interface needs no controller list: it lists ros2_control's
    controllers at run time (moveit/moveit2 moveit_plugins/moveit_ros_control_interface/src/
    controller_manager_plugin.cpp l.184-260, `discover` calls list_controllers and makes a handle
    for each type it has a plugin for). Which controllers run is decided by the spawners of the
    launch files, which validate does not run: a group joint no executing controller of the
    driver file drives, or no driver file at all, is a warning saying what could not be read."""
    file = controllers.where.file
    if driver is None:
        msg = (
            f"{controllers.manager} takes MoveIt's controllers from the controller manager at run "
            "time and no ros2_controllers.yaml was found: which joints they drive was not checked"
        )
        return [warning("controller.not-checked", file, "moveit_controller_manager", msg)]
    covered = {j for d in driver.controllers if d.type in EXECUTING_TYPES for j in d.joints or ()}
    out = []
    for joint, groups in sorted(_group_joints(srdf, robot).items()):
        if joint not in covered:
            msg = (
                f"joint '{joint}' (group {', '.join(groups)}) is in no trajectory or gripper "
                f"controller of {driver.where.file}: MoveIt cannot execute its motions unless another "
                "controller manager's file provides one"
            )
            where = controllers.where.child(f"joint[{joint}]").element
            out.append(warning("controller.uncovered-joint", file, where, msg))
    return out
