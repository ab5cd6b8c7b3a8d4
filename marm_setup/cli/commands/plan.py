"""`marm-setup plan`: plan, time-parameterise and fake-execute a motion between two named poses."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import PackagePaths

if TYPE_CHECKING:
    from marm_setup.plan.problem import Executed, PlanningProblem

PackageDir = Annotated[
    Path, typer.Argument(help="MoveIt config package folder (ours or the Setup Assistant's).", metavar="DIR")
]


def plan(
    package_dir: PackageDir,
    group: Annotated[str, typer.Option("--group", help="Planning group (SRDF).", metavar="G")],
    from_pose: Annotated[str, typer.Option("--from", help="Named pose to start from.", metavar="POSE")],
    to_pose: Annotated[str, typer.Option("--to", help="Named pose to reach.", metavar="POSE")],
    output: Annotated[
        Path | None,
        typer.Option(
            "--output", help="Write the trajectory (JointTrajectory YAML) here.", metavar="TRAJ.yaml"
        ),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Planner random seed.", metavar="S")] = 0,
    urdf: Annotated[
        Path | None, typer.Option("--urdf", help="Robot description, if not the package's.", metavar="URDF")
    ] = None,
    package_path: PackagePaths = None,
) -> None:
    """Plan a collision-free, time-parameterised joint trajectory between named poses."""
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.errors import InputError, PlanningFailed
    from marm_setup.package import read_package
    from marm_setup.plan.planner import PlanFailed
    from marm_setup.plan.problem import plan_between, planning_problem, pose
    from marm_setup.plan.trajectory_io import write_trajectory
    from marm_setup.robot.load import load_robot

    if seed < 0:
        raise InputError(f"must be >= 0, got {seed}", element="--seed")
    package = read_package(package_dir, urdf=urdf, package_paths=package_path or ())
    robot = load_robot(package.urdf, dict(package.xacro_args), list(package.package_paths))
    problem = planning_problem(package, robot, CollisionScene(robot), group)
    srdf_shown = package.user_path(package.srdf_path)
    q_start, q_goal = pose(problem, from_pose, srdf_shown), pose(problem, to_pose, srdf_shown)
    outcome = plan_between(problem, robot, q_start, q_goal, seed)
    where = f"group[{group}]/{from_pose} -> {to_pose}"
    if isinstance(outcome, PlanFailed):
        raise PlanningFailed(f"no plan: {outcome.reason}", path=srdf_shown, element=where)
    if not outcome.execution.ok:
        message = "fake execution failed: " + "; ".join(outcome.execution.violations)
        raise PlanningFailed(message, path=srdf_shown, element=where)
    typer.echo(f"planned {group}: {from_pose} -> {to_pose} ({', '.join(problem.joint_names)})")
    typer.echo(_summary(problem, outcome))
    if output is not None:
        write_trajectory(outcome.trajectory, output)
        typer.echo(f"wrote {output}")


def _summary(problem: PlanningProblem, outcome: Executed) -> str:
    """The indented summary lines of a successful, fake-executed plan."""
    from marm_setup.plan.planner import path_length

    traj, result = outcome.trajectory, outcome.plan
    return "\n".join(
        [
            f"  waypoints:     {len(result.q_path)} ({len(traj.times)} trajectory points)",
            f"  path length:   {path_length(result.q_path):.4f} (joint space, rad/m)",
            f"  duration:      {traj.duration:.3f} s (velocity scaling {problem.velocity_scaling:g}, "
            f"acceleration scaling {problem.acceleration_scaling:g})",
            f"  planning time: {result.planning_time_s * 1000:.1f} ms ({result.iterations} iterations)",
            f"  fake execution: ok ({outcome.execution.samples} states checked)",
            *(
                [
                    f"  note: no velocity limit for {', '.join(problem.limits.unbounded)}: timed at MoveIt's default 1 rad/s"
                ]
                if problem.limits.unbounded
                else []
            ),
        ]
    )
