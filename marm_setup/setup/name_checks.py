"""Every name a setup holds, checked against its kind's rule (`marm_setup.names`).

Runs wherever a setup is read (setup file, SRDF import, inference, `render`), before anything
is rendered, so a name can neither break a generated file nor turn into code in one.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator

from marm_setup.errors import InputError
from marm_setup.names import name_problem
from marm_setup.robot import RobotModel
from marm_setup.setup.model import SetupModel


def check_setup_names(model: SetupModel, robot: RobotModel | None, path: str | None) -> None:
    """Raise InputError for the first name that is not valid for its kind (the URDF's own
    first: a bad joint name is the URDF's to fix, wherever the setup repeats it)."""
    if robot is not None:
        check_robot_names(robot)
    for kind, name, where in setup_names(model):
        problem = name_problem(kind, name)
        if problem:
            raise InputError(problem, path=path, element=where)


def check_robot_names(robot: RobotModel) -> None:
    """The URDF's link and joint names: they reach generated files through groups and controllers."""
    for kind, names in (("link", robot.link_map), ("joint", robot.joint_map)):
        for name in names:
            problem = name_problem(kind, name)
            if problem:
                raise InputError(problem, path=robot.source or None, element=f"{kind}[{name!r}]")


def setup_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    """(kind, name, key path) of every name in the setup, in file order."""
    yield "package", m.package_name, "package_name"
    yield "robot", m.robot_name, "robot_name"
    yield "property", m.author.name, "author.name"
    yield "property", m.author.email, "author.email"
    for vj in m.virtual_joints:
        w = f"virtual_joints[{vj.name}]"
        yield from (("virtual joint", vj.name, w), ("frame", vj.parent_frame, f"{w}.parent_frame"))
        yield "link", vj.child_link, f"{w}.child_link"
    yield from _group_names(m)
    yield from _end_effector_names(m)
    yield from _listed("joint", m.passive_joints, "passive_joints")
    for i, pair in enumerate(m.collision.disabled):
        yield from _listed("link", (pair.link1, pair.link2), f"collision.disabled[{i}]")
    for i, unproved in enumerate(m.collision.unproved):
        yield from _listed("link", unproved.pair, f"collision.unproved[{i}]")
    for k in m.kinematics:
        yield from (
            ("group", k.group, f"kinematics[{k.group}]"),
            ("property", k.solver, f"kinematics[{k.group}].solver"),
        )
    for p in m.planners:
        yield "group", p.group, f"planners[{p.group}]"
    yield from _controller_names(m)
    for a in m.arbotix_joints:
        yield "joint", a.joint, f"arbotix_joints[{a.joint}]"
    for lim in m.joint_limits:
        yield "joint", lim.joint, f"joint_limits[{lim.joint}]"
    yield from _extras_names(m)
    yield from _ros2_control_names(m)
    yield from _servo_and_sensor_names(m)


def _listed(kind: str, names: Iterable[str], where: str) -> Iterator[tuple[str, str, str]]:
    for i, name in enumerate(names):
        yield kind, name, f"{where}[{i}]"


def _group_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    for g in m.groups:
        w = f"groups[{g.name}]"
        yield "group", g.name, w
        if g.chain is not None:
            yield from (("link", g.chain.base, f"{w}.chain.base"), ("link", g.chain.tip, f"{w}.chain.tip"))
        yield from _listed("joint", g.joints, f"{w}.joints")
        yield from _listed("link", g.links, f"{w}.links")
        yield from _listed("group", g.subgroups, f"{w}.subgroups")
    for s in m.group_states:
        w = f"group_states[{s.name}]"
        yield from (("pose", s.name, w), ("group", s.group, f"{w}.group"))
        for joint, _ in s.values:
            yield "joint", joint, f"{w}.values"


def _end_effector_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    for ee in m.end_effectors:
        w = f"end_effectors[{ee.name}]"
        yield from (("end effector", ee.name, w), ("group", ee.group, f"{w}.group"))
        yield "link", ee.parent_link, f"{w}.parent_link"
        if ee.parent_group is not None:
            yield "group", ee.parent_group, f"{w}.parent_group"


def _controller_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    for c in m.controllers:
        w = f"controllers[{c.name}]"
        yield from (("controller", c.name, w), ("action_ns", c.action_ns, f"{w}.action_ns"))
        yield from _listed("joint", c.joints, f"{w}.joints")
        if c.group is not None:
            yield "group", c.group, f"{w}.group"


def _extras_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    extras = m.srdf_extras
    for i, pair in enumerate(extras.enable_collisions):
        yield from _listed("link", (pair.link1, pair.link2), f"srdf_extras.enable_collisions[{i}]")
        yield "property", pair.reason or "-", f"srdf_extras.enable_collisions[{i}].reason"
    yield from _listed("link", extras.disable_default_collisions, "srdf_extras.disable_default_collisions")
    for i, prop in enumerate(extras.joint_properties):
        w = f"srdf_extras.joint_properties[{i}]"
        yield from (("joint", prop.joint, f"{w}.joint"), ("property", prop.property, f"{w}.property"))
        yield "property", prop.value or "-", f"{w}.value"
    for approx in extras.link_sphere_approximations:
        yield "link", approx.link, f"srdf_extras.link_sphere_approximations[{approx.link}]"


def _ros2_control_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    hardware = m.ros2_control
    if hardware is None:
        return
    yield "plugin", hardware.plugin, "ros2_control.plugin"
    yield from _listed("interface", hardware.command_interfaces, "ros2_control.command_interfaces")
    yield from _listed("interface", hardware.state_interfaces, "ros2_control.state_interfaces")
    for key, _ in hardware.parameters:
        yield "parameter", key, f"ros2_control.parameters.{key}"


def _servo_and_sensor_names(m: SetupModel) -> Iterator[tuple[str, str, str]]:
    for servo in m.servo or ():
        w = f"servo[{servo.group}]"
        yield "group", servo.group, f"{w}.group"
        if servo.controller is not None:
            yield "controller", servo.controller, f"{w}.controller"
        for key in ("planning_frame", "ee_frame", "command_frame"):
            if getattr(servo, key) is not None:
                yield "link", getattr(servo, key), f"{w}.{key}"
    for sensor in m.sensors:
        yield "sensor", sensor.name, f"sensors[{sensor.name}]"
    if m.octomap_frame is not None:
        yield "frame", m.octomap_frame, "octomap_frame"
