"""Model checks of a SetupModel against its robot (issue 4 §2): the first problem found is an
InputError naming the file and the element by its key path (`groups[arm].chain.tip`).

Checks: unknown joint/link/group names (with close matches), duplicate names, chain tip not
below its base, subgroup cycles, poses missing a joint of their group or outside its limits,
end effectors whose parent link is inside their own group, virtual joints not at the root,
controller action namespaces the target's driver does not serve, package names ROS rejects,
a robot_name other than the URDF's, a ros_distro not of the target, numbers that must be positive (fractions in (0, 1]).
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Iterable

from marm_setup.errors import InputError
from marm_setup.names import name_problem
from marm_setup.robot.model import RobotModel
from marm_setup.setup.groups import active_group_joints, group_joints, group_links, groups_by_name
from marm_setup.setup.model import DRIVER_ACTION_NS, ROS_DISTROS, Controller, Group, SetupModel
from marm_setup.setup.name_checks import check_setup_names

LIMIT_TOLERANCE = 1e-9  # [rad] or [m]: values written with full precision sit on the limit
MAX_SERVO_ID = 253  # Dynamixel ids on an ArbotiX bus (254 is broadcast)


class _Checker:
    def __init__(self, model: SetupModel, robot: RobotModel, path: str | None):
        self.model, self.robot, self.path = model, robot, path
        self.group_names = tuple(g.name for g in model.groups)

    def fail(self, message: str, where: str) -> InputError:
        return InputError(message, path=self.path, element=where)

    def name(self, kind: str, name: str, known: Iterable[str], where: str) -> None:
        known = tuple(known)
        if name not in known:
            raise self.fail(f"unknown {kind} '{name}'{_close(name, known)}", where)

    def joint(self, name: str, where: str) -> None:
        self.name("joint", name, self.robot.joint_map, where)

    def link(self, name: str, where: str) -> None:
        self.name("link", name, self.robot.link_map, where)

    def group(self, name: str, where: str) -> None:
        self.name("group", name, self.group_names, where)


def check_setup(model: SetupModel, robot: RobotModel, path: str | None = None) -> None:
    """Raise InputError for the first inconsistency between the setup and the robot."""
    c = _Checker(model, robot, path)
    check_setup_names(model, robot, path)
    _check_names(c)
    _check_duplicates(c)
    _check_virtual_joints(c)
    _check_groups(c)
    _check_subgroup_cycles(c)
    _check_states(c)
    _check_end_effectors(c)
    _check_joint_lists(c)
    _check_controller_actions(c)
    _check_ranges(c)
    _check_collision_pairs(c)


def _check_names(c: _Checker) -> None:
    problem = package_name_problem(c.model.package_name)
    if problem:
        raise c.fail(problem, "package_name")
    if c.model.robot_name != c.robot.name:
        raise c.fail(f"'{c.model.robot_name}' is not the URDF's robot name '{c.robot.name}'", "robot_name")
    distros = ROS_DISTROS.get(c.model.target, ())
    if c.model.ros_distro is not None and c.model.ros_distro not in distros:
        valid = ", ".join(distros)
        raise c.fail(
            f"'{c.model.ros_distro}' is not a {c.model.target} distro (valid: {valid})", "ros_distro"
        )


def package_name_problem(name: str) -> str | None:
    """Why `name` cannot name a ROS package (REP 144), or None."""
    return name_problem("package", name)


def _close(name: str, known: tuple[str, ...]) -> str:
    matches = difflib.get_close_matches(name, known, n=3, cutoff=0.6)
    if matches:
        return f" (close: {', '.join(matches)})"
    if len(known) <= 8:
        return f" (known: {', '.join(known) or 'none'})"
    return ""


def _check_duplicates(c: _Checker) -> None:
    m = c.model
    lists = {
        "groups": [g.name for g in m.groups],
        "group_states": [f"{s.group}/{s.name}" for s in m.group_states],
        "end_effectors": [e.name for e in m.end_effectors],
        "virtual_joints": [v.name for v in m.virtual_joints],
        "controllers": [x.name for x in m.controllers],
        "kinematics": [k.group for k in m.kinematics],
        "planners": [p.group for p in m.planners],
        "passive_joints": list(m.passive_joints),
        "arbotix_joints": [a.joint for a in m.arbotix_joints],
        "joint_limits": [j.joint for j in m.joint_limits],
    }
    for key, names in lists.items():
        seen: set[str] = set()
        for name in names:
            if name in seen:
                group, _, short = name.rpartition("/")
                where = f" in group '{group}'" if group else ""
                raise c.fail(f"duplicate name '{short}'{where}", f"{key}[{short}]")
            seen.add(name)


def _check_virtual_joints(c: _Checker) -> None:
    for vj in c.model.virtual_joints:
        where = f"virtual_joints[{vj.name}].child_link"
        c.link(vj.child_link, where)
        if vj.child_link != c.robot.root:
            raise c.fail(
                f"child link '{vj.child_link}' is not the robot's root link '{c.robot.root}' "
                "(MoveIt skips such a virtual joint)",
                where,
            )


def _check_groups(c: _Checker) -> None:
    for g in c.model.groups:
        where = f"groups[{g.name}]"
        if g.chain is None and not (g.joints or g.links or g.subgroups):
            raise c.fail("empty group: give a chain, joints, links or subgroups", where)
        if g.chain is not None:
            c.link(g.chain.base, f"{where}.chain.base")
            c.link(g.chain.tip, f"{where}.chain.tip")
            if c.robot.chain(g.chain.base, g.chain.tip) is None or g.chain.base == g.chain.tip:
                raise c.fail(
                    f"chain tip '{g.chain.tip}' is not below base '{g.chain.base}'", f"{where}.chain.tip"
                )
        for i, j in enumerate(g.joints):
            c.joint(j, f"{where}.joints[{i}]")
        for i, link in enumerate(g.links):
            c.link(link, f"{where}.links[{i}]")
        for i, sub in enumerate(g.subgroups):
            c.group(sub, f"{where}.subgroups[{i}]")


def _check_subgroup_cycles(c: _Checker) -> None:
    by_name = groups_by_name(c.model.groups)
    for g in c.model.groups:
        cycle = _find_cycle(g.name, by_name, [])
        if cycle:
            raise c.fail(f"subgroup cycle: {' -> '.join(cycle)}", f"groups[{g.name}].subgroups")


def _find_cycle(name: str, by_name: dict[str, Group], trail: list[str]) -> list[str] | None:
    if name in trail:
        return [*trail[trail.index(name) :], name]
    for sub in by_name[name].subgroups:
        found = _find_cycle(sub, by_name, [*trail, name])
        if found:
            return found
    return None


def _check_states(c: _Checker) -> None:
    by_name = groups_by_name(c.model.groups)
    for s in c.model.group_states:
        where = f"group_states[{s.name}]"
        c.group(s.group, f"{where}.group")
        group = by_name[s.group]
        members = group_joints(group, by_name, c.robot)
        for joint, value in s.values:
            c.joint(joint, f"{where}.values.{joint}")
            if joint not in members:
                raise c.fail(f"joint '{joint}' is not in group '{s.group}'", f"{where}.values.{joint}")
            _check_limit(c, joint, value, f"{where}.values.{joint}")
        given = {j for j, _ in s.values}
        missing = [
            j for j in active_group_joints(group, by_name, c.robot, c.model.passive_joints) if j not in given
        ]
        if missing:
            raise c.fail(f"missing joint(s) of group '{s.group}': {', '.join(missing)}", f"{where}.values")


def _check_limit(c: _Checker, joint: str, value: float, where: str) -> None:
    j = c.robot.joint(joint)
    if j.type == "continuous" or not j.is_actuated:
        return
    lo, hi = j.bounds
    if not lo - LIMIT_TOLERANCE <= value <= hi + LIMIT_TOLERANCE:
        raise c.fail(f"value {value:g} is outside the limits [{lo:g}, {hi:g}]", where)


def _check_end_effectors(c: _Checker) -> None:
    by_name = groups_by_name(c.model.groups)
    for ee in c.model.end_effectors:
        where = f"end_effectors[{ee.name}]"
        c.group(ee.group, f"{where}.group")
        c.link(ee.parent_link, f"{where}.parent_link")
        if ee.parent_group is not None:
            c.group(ee.parent_group, f"{where}.parent_group")
        if ee.parent_link in group_links(by_name[ee.group], by_name, c.robot):
            raise c.fail(
                f"parent link '{ee.parent_link}' is inside the end effector's own group '{ee.group}'",
                f"{where}.parent_link",
            )


def _check_joint_lists(c: _Checker) -> None:
    m = c.model
    for i, j in enumerate(m.passive_joints):
        c.joint(j, f"passive_joints[{i}]")
    for ctl in m.controllers:
        _check_controller_joints(c, ctl)
        if ctl.group is not None:
            c.group(ctl.group, f"controllers[{ctl.name}].group")
    for k in m.kinematics:
        c.group(k.group, f"kinematics[{k.group}].group")
    for p in m.planners:
        c.group(p.group, f"planners[{p.group}].group")
    servo_ids: dict[int, str] = {}
    for a in m.arbotix_joints:
        c.joint(a.joint, f"arbotix_joints[{a.joint}].joint")
        if not 0 <= a.id <= MAX_SERVO_ID:
            raise c.fail(f"servo id {a.id} is outside 0..{MAX_SERVO_ID}", f"arbotix_joints[{a.joint}].id")
        if a.id in servo_ids:
            raise c.fail(f"servo id {a.id} is also {servo_ids[a.id]}'s", f"arbotix_joints[{a.joint}].id")
        servo_ids[a.id] = a.joint
    for lim in m.joint_limits:
        c.joint(lim.joint, f"joint_limits[{lim.joint}].joint")


def _check_controller_joints(c: _Checker, ctl: Controller) -> None:
    """At least one joint, each a variable of its own (mimic and fixed joints take no commands)."""
    if not ctl.joints:
        raise c.fail("a controller needs at least one joint", f"controllers[{ctl.name}].joints")
    for i, name in enumerate(ctl.joints):
        where = f"controllers[{ctl.name}].joints[{i}]"
        c.joint(name, where)
        joint = c.robot.joint(name)
        if joint.mimic is not None:
            raise c.fail(f"'{name}' mimics '{joint.mimic.joint}': command that joint instead", where)
        if not joint.is_actuated:
            raise c.fail(f"'{name}' is a {joint.type} joint: nothing to command", where)


def _check_controller_actions(c: _Checker) -> None:
    """MoveIt's `<name>/<action_ns>` must be the action the target's driver serves."""
    target = c.model.target
    for ctl in c.model.controllers:
        served = DRIVER_ACTION_NS.get((target, ctl.type))
        if served is not None and ctl.action_ns != served:
            raise c.fail(
                f"'{ctl.action_ns}' is not served by the {target} driver: a {ctl.type} controller "
                f"serves '{ctl.name}/{served}' (set action_ns: {served})",
                f"controllers[{ctl.name}].action_ns",
            )


def _check_ranges(c: _Checker) -> None:
    """Numbers MoveIt / the drivers need positive, and fractions in (0, 1]; a seed >= 0."""
    if c.model.collision.seed < 0:
        raise c.fail(f"must be >= 0, got {c.model.collision.seed}", "collision.seed")
    for where, value, upper in _ranged_values(c.model):
        if value is not None and not 0 < value <= upper:
            bound = "> 0" if upper == math.inf else f"in (0, {upper:g}]"
            raise c.fail(f"must be {bound}, got {value:g}", where)


def _ranged_values(m: SetupModel):
    """(key path, value, upper bound) of every number with a lower bound of 0 (exclusive)."""
    inf = math.inf
    yield "default_velocity_scaling", m.default_velocity_scaling, 1.0
    yield "default_acceleration_scaling", m.default_acceleration_scaling, 1.0
    yield "default_acceleration", m.default_acceleration, inf
    yield "collision.trials", m.collision.trials, inf
    yield "collision.min_collision_fraction", m.collision.min_collision_fraction, 1.0
    for k in m.kinematics:
        for name in ("search_resolution", "timeout", "attempts"):
            yield f"kinematics[{k.group}].{name}", getattr(k, name), inf
    for p in m.planners:
        yield f"planners[{p.group}].longest_valid_segment_fraction", p.longest_valid_segment_fraction, 1.0
    for lim in m.joint_limits:
        for name in ("max_velocity", "max_acceleration", "max_jerk"):
            yield f"joint_limits[{lim.joint}].{name}", getattr(lim, name), inf
    for a in m.arbotix_joints:
        yield f"arbotix_joints[{a.joint}].max_speed", a.max_speed, inf


def _check_collision_pairs(c: _Checker) -> None:
    for i, pair in enumerate(c.model.collision.disabled):
        c.link(pair.link1, f"collision.disabled[{i}].link1")
        c.link(pair.link2, f"collision.disabled[{i}].link2")
