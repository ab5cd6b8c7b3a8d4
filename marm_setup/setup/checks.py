"""Model checks of a SetupModel against its robot (issue 4 §2): the first problem found is an
InputError naming the file and the element by its key path (`groups[arm].chain.tip`).

The SRDF's part (names, chains, subgroup cycles, poses, end effectors, virtual and passive
joints, disabled pairs) is `setup.rules`, the rule set `validate` runs too; here are only
the checks of what `marm_setup.yaml` adds: package name, duplicate list items, groups that say
nothing, controllers the target's driver cannot serve, servo ids, a ros_distro not of the target, numbers that must be positive
(fractions in (0, 1]); MoveIt Servo (`setup.servo`) and 3D sensors (`setup.sensors`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator

from marm_setup.errors import InputError
from marm_setup.findings import Finding
from marm_setup.moveit_params import KINEMATICS_KEYS
from marm_setup.names import did_you_mean, name_problem, with_hint
from marm_setup.robot import MIN_RATE, RobotModel
from marm_setup.ros import DISTROS, Target, distros_of
from marm_setup.setup.limits import joint_limits, timing_problem
from marm_setup.setup.model import Controller, SetupModel
from marm_setup.setup.name_checks import check_setup_names
from marm_setup.setup.rules import Style, check_semantics, setup_element
from marm_setup.setup.sensors import check_sensors
from marm_setup.setup.servo import check_servos
from marm_setup.setup.srdf import setup_to_srdf

MAX_SERVO_ID = 253  # Dynamixel ids on an ArbotiX bus (254 is broadcast)
RATE_KEYS = ("scaling", "default_acceleration", "max_velocity", "max_acceleration", "max_jerk", "max_speed")


class _Checker:
    def __init__(self, model: SetupModel, robot: RobotModel, path: str | None):
        self.model, self.robot, self.path = model, robot, path
        self.group_names = tuple(g.name for g in model.groups)

    def fail(self, message: str, where: str) -> InputError:
        return InputError(message, path=self.path, element=where)

    def name(self, kind: str, name: str, known: Iterable[str], where: str) -> None:
        known = tuple(known)
        if name not in known:
            raise self.fail(with_hint(f"unknown {kind} '{name}'", did_you_mean(name, known)), where)

    def joint(self, name: str, where: str) -> None:
        self.name("joint", name, self.robot.joint_map, where)

    def group(self, name: str, where: str) -> None:
        self.name("group", name, self.group_names, where)


def check_setup(
    model: SetupModel, robot: RobotModel, path: str | None = None, style: Style = setup_element
) -> None:
    """Raise InputError for the first inconsistency between the setup and the robot; the shared
    rules name elements in `style` (`srdf_element` when the setup was imported from an SRDF)."""
    c = _Checker(model, robot, path)
    check_setup_names(model, robot, path)
    _check_names(c)
    _check_duplicates(c)
    raise_first_error(check_semantics(setup_to_srdf(model), robot, path or "", style), path)
    _check_joint_lists(c)
    _check_controller_actions(c)
    _check_ranges(c)
    _check_timing(c)
    _check_ros2_control(c)
    _check_pipelines(c)
    check_servos(model, robot, path)
    _check_file_names(c)
    check_sensors(model, path)


def raise_first_error(findings: Iterable[Finding], path: str | None) -> None:
    """The first error finding as an InputError naming `path`; warnings pass."""
    for f in findings:
        if f.is_error:
            raise as_input_error(f, path)


def as_input_error(f: Finding, path: str | None = None) -> InputError:
    """A finding as the one-line input error (its hint in parentheses), naming `path` or its file."""
    return InputError(
        with_hint(f.message, f.hint), path=f.file if path is None else path, element=f.element or None
    )


def _check_names(c: _Checker) -> None:
    problem = package_name_problem(c.model.package_name)
    if problem:
        raise c.fail(problem, "package_name")
    problem = distro_problem(c.model.target, c.model.ros_distro)
    if problem:
        raise c.fail(problem, "ros_distro")
    _check_author(c)


def _check_author(c: _Checker) -> None:
    """The maintainer as catkin_pkg reads package.xml (Person.validate: an email it rejects makes
    the whole package.xml invalid to catkin and to `validate`)."""
    from catkin_pkg.package import InvalidPackage, Person

    author = c.model.author
    try:
        Person(author.name, author.email).validate()
    except InvalidPackage as exc:
        raise c.fail(f"{exc}: catkin_pkg rejects package.xml with it", "author.email") from None


def distro_problem(target: Target, distro: str | None) -> str | None:
    """Why `distro` is not one the target is written for (None: it is, or none is given)."""
    distros = distros_of(target)
    if distro is None or distro in distros:
        return None
    return f"'{distro}' is not a {target} distro (valid: {', '.join(distros)})"


def _check_pipelines(c: _Checker) -> None:
    """Known pipelines, each once, that the package's distro can run (STOMP on Humble built from
    source: a warning, `setup_warnings`); their parameters (`_check_pipeline_parameters`)."""
    from marm_setup.moveit_params import PIPELINES

    names = c.model.planning_pipelines
    if not names:
        raise c.fail("no planning pipeline: move_group could not plan", "planning_pipelines")
    for i, name in enumerate(names):
        where = f"planning_pipelines[{i}]"
        c.name("planning pipeline", name, PIPELINES, where)
        if name in names[:i]:
            raise c.fail(f"'{name}' is listed twice", where)
        row = c.model.row
        if name not in row.planners + row.planners_from_source:
            shipped = ", ".join(
                r.name for r in DISTROS.values() if name in r.planners + r.planners_from_source
            )
            raise c.fail(f"'{name}' is not in MoveIt's {row.name} binaries (only {shipped})", where)
    _check_pipeline_parameters(c)
    for name, value in c.model.move_group_parameters:
        from marm_setup.moveit_params import move_group_problem

        problem = move_group_problem(name, value)
        if problem:
            raise c.fail(problem, f"move_group_parameters.{name}")


def _check_pipeline_parameters(c: _Checker) -> None:
    """Each pipeline's parameters: one of the setup's pipelines, a name some ROS 2 distro's
    MoveIt reads there (one only the other distro reads: a warning), a value of its type."""
    from marm_setup.moveit_params import parameter_problem

    model = c.model
    if model.pipeline_parameters and model.target != Target.ROS2:
        raise c.fail(
            f"written for ROS 2 ({', '.join(distros_of(Target.ROS2))}) only: noetic's pipeline launch files keep MoveIt's defaults",
            "pipeline_parameters",
        )
    for pipeline, params in model.pipeline_parameters:
        if pipeline not in model.planning_pipelines:
            listed = ", ".join(model.planning_pipelines)
            raise c.fail(
                f"'{pipeline}' is not in planning_pipelines ({listed})", f"pipeline_parameters.{pipeline}"
            )
        for name, value in params:
            problem = parameter_problem(pipeline, model.distro, name, value)
            if problem:
                raise c.fail(problem, f"pipeline_parameters.{pipeline}.{name}")


def setup_warnings(model: SetupModel) -> tuple[str, ...]:
    """`warning: ...` lines for what a setup asks that its distro's MoveIt binaries cannot do
    alone (STOMP on Humble) or do not read (a parameter of the other distro: left out)."""
    from marm_setup.moveit_params import PIPELINES, other_distros_reading, parameter

    distro, out = model.distro, []
    for i, name in enumerate(model.planning_pipelines):
        pipeline = PIPELINES.get(name)
        if pipeline is not None and name in model.row.planners_from_source:
            out.append(
                f"warning: planning_pipelines[{i}]: '{name}' is not in MoveIt's {distro} binaries (moveit2's "
                f"{distro} branch has no moveit_planners/{name}): build {pipeline.package} from moveit2's "
                f"source (Iron or later) into your workspace, else move_group cannot load {pipeline.plugin_ros2} "
                "(moveit/moveit2#2550, #2742)"
            )
    for pipeline_name, params in model.pipeline_parameters:
        for name, _ in params:
            others = other_distros_reading(pipeline_name, distro, name)
            if parameter(pipeline_name, distro, name) is None and others:
                out.append(
                    f"warning: pipeline_parameters.{pipeline_name}.{name}: {distro}'s MoveIt does not read it "
                    f"({', '.join(others)}'s does): left out of config/moveit.yaml"
                )
    return tuple(out)


def _check_ros2_control(c: _Checker) -> None:
    """joint_trajectory_controller needs a command interface and a position state of each joint
    (and joint_state_broadcaster publishes positions), so the hardware must offer them."""
    hardware = c.model.ros2_control
    if hardware is None:
        return
    if not hardware.plugin:
        raise c.fail("the hardware plugin is empty", "ros2_control.plugin")
    if not hardware.command_interfaces:
        raise c.fail(
            "no command interface: the trajectory controllers could not command",
            "ros2_control.command_interfaces",
        )
    if "position" not in hardware.state_interfaces:
        raise c.fail(
            "needs a 'position' state interface (joint states, trajectory control)",
            "ros2_control.state_interfaces",
        )


def package_name_problem(name: str) -> str | None:
    """Why `name` cannot name a ROS package (REP 144), or None."""
    return name_problem("package", name)


def _check_duplicates(c: _Checker) -> None:
    """Items of the setup's lists named twice (duplicate groups are a rule of `setup.rules`)."""
    m = c.model
    lists = {
        "group_states": [f"{s.group}/{s.name}" for s in m.group_states],
        "start_poses": [s.group for s in m.start_poses or ()],
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


def per_item_files(model: SetupModel) -> list[tuple[str, str]]:
    """(element, path) of each file named after an item of the setup: a servo group's config
    (render/package.py servo_and_sensor_templates)."""
    return [(f"servo[{s.group}]", f"config/{s.group}_servo.yaml") for s in model.servo or ()]


def _check_file_names(c: _Checker) -> None:
    """Two generated files whose paths differ only in case (groups `arm` and `Arm`): on a
    case-insensitive file system (macOS, Windows) the second overwrites the first."""
    seen: dict[str, str] = {}
    for where, path in per_item_files(c.model):
        other = seen.setdefault(path.casefold(), path)
        if other != path:
            raise c.fail(
                f"writes {path}, which differs from {other} only in case (one would overwrite "
                "the other on a case-insensitive file system); rename one of the groups",
                where,
            )


def _check_joint_lists(c: _Checker) -> None:
    m = c.model
    for ctl in m.controllers:
        _check_controller_joints(c, ctl)
        if ctl.group is not None:
            c.group(ctl.group, f"controllers[{ctl.name}].group")
    for k in m.kinematics:
        c.group(k.group, f"kinematics[{k.group}].group")
        for key, _ in k.options:
            if not key or key in KINEMATICS_KEYS:
                what = "an empty key" if not key else f"'{key}' has a field of its own in kinematics"
                raise c.fail(f"{what}: not a solver option", f"kinematics[{k.group}].options.{key}")
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
        if (
            lim.min_position is not None
            and lim.max_position is not None
            and lim.min_position > lim.max_position
        ):
            message = f"min_position {lim.min_position:g} is above max_position {lim.max_position:g}"
            raise c.fail(message, f"joint_limits[{lim.joint}].min_position")
    for start in m.start_poses or ():
        c.group(start.group, f"start_poses[{start.group}].group")
        poses = [s.name for s in m.group_states if s.group == start.group]
        c.name(f"pose of group '{start.group}'", start.pose, poses, f"start_poses[{start.group}].pose")


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
    driver = c.model.driver_key
    for ctl in c.model.controllers:
        served = c.model.served_action_ns(ctl.type)
        if served is not None and ctl.action_ns != served:
            raise c.fail(
                f"'{ctl.action_ns}' is not served by the {driver} driver: a {ctl.type} controller "
                f"serves '{ctl.name}/{served}' (set action_ns: {served})",
                f"controllers[{ctl.name}].action_ns",
            )


def _check_ranges(c: _Checker) -> None:
    """Numbers MoveIt / the drivers need positive, and fractions in (0, 1]; a seed >= 0."""
    if c.model.collision.seed < 0:
        raise c.fail(f"must be >= 0, got {c.model.collision.seed}", "collision.seed")
    for i, unproved in enumerate(c.model.collision.unproved):
        if not 0.0 <= unproved.proved_fraction <= 1.0:
            raise c.fail(
                f"must be in [0, 1], got {unproved.proved_fraction:g}",
                f"collision.unproved[{i}].proved_fraction",
            )
    for where, value, upper in _ranged_values(c.model):
        if value is not None and not 0 < value <= upper:
            bound = "> 0" if upper == math.inf else f"in (0, {upper:g}]"
            raise c.fail(f"must be {bound}, got {value:g}", where)
        if value is not None and where.endswith(RATE_KEYS) and value < MIN_RATE:
            raise c.fail(
                f"must be at least {MIN_RATE:g} (no trajectory could be timed), got {value:g}", where
            )


def _check_timing(c: _Checker) -> None:
    """The limits the package will give MoveIt pass the timing rule validate runs too
    (setup/limits.py): a rate fine alone but not scaled is blamed on the scaling factor, a URDF
    velocity on the URDF's element (naming the setup key that overrides it); a setup value is
    checked by `_check_ranges`."""
    m = c.model
    overridden = {o.joint for o in m.joint_limits if o.max_velocity is not None}
    scalings = {"velocity": m.default_velocity_scaling, "acceleration": m.default_acceleration_scaling}
    for limit in joint_limits(m, c.robot):
        for kind, scaling in scalings.items():
            key, rate = f"max_{kind}", getattr(limit, f"max_{kind}")
            problem = timing_problem(limit.joint, key, rate, scaling)
            if not problem:
                continue
            if rate >= MIN_RATE:
                raise c.fail(problem, f"default_{kind}_scaling")
            if kind == "velocity" and limit.joint not in overridden:
                raise InputError(
                    f"{problem}; override it with joint_limits[{limit.joint}].{key}",
                    path=c.robot.source or None,
                    element=f"joint[{limit.joint}]/limit@velocity",
                    needs="--setup",
                )
            raise c.fail(problem, f"joint_limits[{limit.joint}].{key}")


def _ranged_values(m: SetupModel) -> Iterator[tuple[str, float | None, float]]:
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
