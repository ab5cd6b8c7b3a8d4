"""`marm-setup plan`: plan, time-parameterise and fake-execute a motion between two named poses."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import ROBOT
from marm_setup.cli.option_groups import takes
from marm_setup.flows import RobotInput

if TYPE_CHECKING:
    from marm_setup.plan import Executed, PlanningProblem

PackageDir = Annotated[
    Path, typer.Argument(help="MoveIt config package folder (ours or the Setup Assistant's).", metavar="DIR")
]


UrdfOption = Annotated[
    Path | None, typer.Option("--urdf", help="Robot description, if not the package's.", metavar="URDF")
]


@takes("robot", ROBOT.of("urdf", "package_path", urdf=(UrdfOption, None)))
def plan(
    package_dir: PackageDir,
    group: Annotated[str, typer.Option("--group", help="Planning group (SRDF).", metavar="G")],
    from_pose: Annotated[str, typer.Option("--from", help="Named pose to start from.", metavar="POSE")],
    to_pose: Annotated[str, typer.Option("--to", help="Named pose to reach.", metavar="POSE")],
    output: Annotated[
        Path | None,
        typer.Option(
            "-o", "--output", help="Write the trajectory (JointTrajectory YAML) here.", metavar="TRAJ.yaml"
        ),
    ] = None,
    seed: Annotated[int, typer.Option("--seed", help="Planner random seed.", metavar="S")] = 0,
    robot: RobotInput = RobotInput(),
) -> None:
    """Plan a collision-free, time-parameterised joint trajectory between named poses."""
    from marm_setup.flows import PlanRequest, run_plan

    request = PlanRequest(package_dir, group, from_pose, to_pose, output, seed, robot)
    result = run_plan(request)
    typer.echo(f"planned {group}: {from_pose} -> {to_pose} ({', '.join(result.problem.joint_names)})")
    typer.echo(_summary(result.problem, result.outcome))
    if output is not None:
        typer.echo(f"wrote {output}")


def _summary(problem: PlanningProblem, outcome: Executed) -> str:
    """The indented summary lines of a successful, fake-executed plan."""
    from marm_setup.plan import path_length

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
