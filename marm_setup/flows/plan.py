"""`plan`: one planning query on a package's files: plan between two named poses of a group,
time-parameterise, fake-execute, and write the trajectory when asked."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError, PlanningFailed
from marm_setup.flows.settings import RobotInput

if TYPE_CHECKING:
    from marm_setup.plan import Executed, PlanningProblem


@dataclass(frozen=True)
class PlanRequest:
    package: Path
    group: str
    from_pose: str
    to_pose: str
    output: Path | None = None  # the JointTrajectory YAML to write
    seed: int = 0  # the planner's
    robot: RobotInput = RobotInput()  # --urdf, --package-path over the package's


@dataclass(frozen=True, eq=False)
class PlanResult:
    problem: PlanningProblem
    outcome: Executed


def run_plan(request: PlanRequest) -> PlanResult:
    """The executed plan; PlanningFailed (exit 1) when there is none or its execution fails."""
    from marm_setup.collision import CollisionScene
    from marm_setup.package import read_package
    from marm_setup.plan import PlanFailed, plan_between, planning_problem, pose, write_trajectory
    from marm_setup.robot import load_robot

    if request.seed < 0:
        raise InputError(f"must be >= 0, got {request.seed}", element="--seed")
    given = request.robot
    package = read_package(request.package, urdf=given.urdf, package_paths=given.package_paths)
    robot = load_robot(package.description_file, dict(package.xacro_args), list(package.package_paths))
    problem = planning_problem(package, robot, CollisionScene(robot), request.group)
    srdf_shown = package.user_path(package.srdf_path)
    q_start, q_goal = (pose(problem, name, srdf_shown) for name in (request.from_pose, request.to_pose))
    outcome = plan_between(problem, robot, q_start, q_goal, request.seed)
    where = f"group[{request.group}]/{request.from_pose} -> {request.to_pose}"
    if isinstance(outcome, PlanFailed):
        raise PlanningFailed(f"no plan: {outcome.reason}", path=srdf_shown, element=where)
    if not outcome.execution.ok:
        message = "fake execution failed: " + "; ".join(outcome.execution.violations)
        raise PlanningFailed(message, path=srdf_shown, element=where)
    if request.output is not None:
        write_trajectory(outcome.trajectory, request.output)
    return PlanResult(problem, outcome)
