"""What a planning query needs from a config package: a group's joints, named poses, limits, checker.

Read from a `MoveItPackage` (ours or the Setup Assistant's): the SRDF gives groups, named poses,
passive joints and the disabled pairs; the joint limits file (`robot_description_planning`), as
MoveIt reads it (`package.limits`), the limits and default scaling factors. Joints outside the group sit at the robot's
default state (0, or mid-range), as MoveIt's default start state does. Continuous joints are
wrapped into [-pi, pi), as MoveIt's enforceBounds does (a pose may say 4.0 rad).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.errors import InputError
from marm_setup.names import did_you_mean, with_hint
from marm_setup.package import LoadedLimit, MoveItPackage, Param, effective_limits, package_start_values
from marm_setup.plan.execution import ExecutionOptions, ExecutionReport, fake_execute
from marm_setup.plan.planner import (
    PlanFailed,
    PlanFound,
    PlannerOptions,
    ValidityChecker,
    group_space,
    plan_joint_path,
)
from marm_setup.plan.timing import JointLimits, TimedTrajectory, limits_from_config, time_parameterize
from marm_setup.robot import RobotModel, onto_bounds, wrap_continuous
from marm_setup.ros import Target
from marm_setup.setup import (
    active_group_joints,
    allowed_pairs,
    groups_by_name,
    pose_configuration,
    start_configuration,
    timing_problem,
)

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene


@dataclass(frozen=True, eq=False)
class PlanningProblem:
    """One group of one package: joints, named poses (full configurations), limits, checker."""

    group: str
    joint_names: tuple[str, ...]
    poses: dict[str, np.ndarray]
    limits: JointLimits  # the hard limits
    velocity_scaling: float
    acceleration_scaling: float
    check: ValidityChecker


@dataclass(frozen=True, eq=False)
class Executed:
    """A plan between two poses, its timed trajectory and its fake execution."""

    plan: PlanFound
    trajectory: TimedTrajectory
    execution: ExecutionReport


def initial_configuration(package: MoveItPackage, robot: RobotModel) -> np.ndarray:
    """The active configuration the package's demo starts in (`setup.start_state`)."""
    return start_configuration(robot, package_start_values(package, robot))


def _limits_section(package: MoveItPackage) -> tuple[dict[str, LoadedLimit], float, float]:
    """The joints' limits as MoveIt reads the file, and the default scaling factors."""
    limits = package.joint_limits
    entries = effective_limits(limits, package.target == Target.ROS2)
    if limits is None:
        return entries, 1.0, 1.0
    return entries, _scaling(limits.velocity_scaling), _scaling(limits.acceleration_scaling)


def _scaling(param: Param | None) -> float:
    """A default scaling factor in (0, 1]; 1 (MoveIt's default) when absent or unusable."""
    value = param.number if param is not None else None
    return value if value is not None and 0 < value <= 1 else 1.0


def group_names_with_poses(package: MoveItPackage) -> tuple[str, ...]:
    """Groups of the package's SRDF that have at least two named poses, sorted."""
    srdf = package.srdf
    if srdf is None:
        return ()
    counts: dict[str, int] = {}
    for state in srdf.group_states:
        counts[state.group] = counts.get(state.group, 0) + 1
    return tuple(sorted(g for g, n in counts.items() if n >= 2 and any(x.name == g for x in srdf.groups)))


def planning_problem(
    package: MoveItPackage, robot: RobotModel, scene: CollisionScene, group: str
) -> PlanningProblem:
    """The problem for `group`; InputError (naming the SRDF) for an unknown group or missing limits."""
    srdf = package.srdf
    if srdf is None:
        raise InputError("no readable SRDF", path=package.shown)
    groups = groups_by_name(srdf.groups)
    if group not in groups:
        raise InputError(
            with_hint(f"unknown group '{group}'", did_you_mean(group, groups)),
            path=package.user_path(package.srdf_path),
            element="group",
        )
    joints = active_group_joints(groups[group], groups, robot, tuple(srdf.passive_joints))
    if not joints:
        raise InputError(
            f"group '{group}' has no active joints",
            path=package.user_path(package.srdf_path),
            element=f"group[{group}]",
        )
    entries, scale_v, scale_a = _limits_section(package)
    try:
        limits = limits_from_config(robot, joints, entries)
    except ValueError as exc:
        raise InputError(str(exc), path=_limits_file(package)) from None
    _check_timeable(limits, scale_v, scale_a, _limits_file(package))
    start = package_start_values(package, robot)
    poses = {
        s.name: onto_bounds(robot, wrap_continuous(robot, pose_configuration(s, robot, start)))
        for s in srdf.group_states
        if s.group == group
    }
    pairs = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    return PlanningProblem(
        group, joints, poses, limits, scale_v, scale_a, lambda q: scene.first_collisions(q, pairs)
    )


def _check_timeable(limits: JointLimits, scale_v: float, scale_a: float, file: str) -> None:
    """The group's limits, scaled by the package's factors, pass the timing rule init runs too
    (setup/limits.py); else an InputError naming the factor."""
    for kind, rates, scaling in (
        ("velocity", limits.max_velocity, scale_v),
        ("acceleration", limits.max_acceleration, scale_a),
    ):
        for name, rate in zip(limits.joint_names, rates, strict=True):
            if problem := timing_problem(name, f"max_{kind}", float(rate), scaling):
                raise InputError(problem, path=file, element=f"default_{kind}_scaling_factor")


def _limits_file(package: MoveItPackage) -> str:
    return package.user_path(package.joint_limits.where.file if package.joint_limits is not None else None)


def pose(problem: PlanningProblem, name: str, srdf_path: str | None) -> np.ndarray:
    """A named pose's full configuration; InputError naming the group's close (or few) poses."""
    if name not in problem.poses:
        raise InputError(
            with_hint(
                f"unknown pose '{name}' for group '{problem.group}'", did_you_mean(name, problem.poses)
            ),
            path=srdf_path,
            element="group_state",
        )
    return problem.poses[name]


def plan_between(
    problem: PlanningProblem,
    robot: RobotModel,
    q_start: np.ndarray,
    q_goal: np.ndarray,
    seed: int = 0,
    options: PlannerOptions = PlannerOptions(),
    execution: ExecutionOptions | None = None,
) -> Executed | PlanFailed:
    """Plan, time-parameterise within the scaled limits, and fake-execute against the hard limits."""
    rng = np.random.default_rng(seed)
    plan = plan_joint_path(robot, problem.check, q_start, q_goal, problem.joint_names, rng, options)
    if isinstance(plan, PlanFailed):
        return plan
    limits = problem.limits.scaled(problem.velocity_scaling, problem.acceleration_scaling)
    trajectory = time_parameterize(plan.q_path, limits)
    space = group_space(robot, problem.joint_names, q_start)
    execution = execution or ExecutionOptions(max_step=options.max_step / 4)
    report = fake_execute(trajectory, space, problem.limits, problem.check, q_goal[space.index], execution)
    return Executed(plan, trajectory, report)
