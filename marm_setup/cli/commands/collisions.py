"""`marm-setup collisions`: the self-collision matrix alone (a headless `collisions_updater`)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import MATRIX, ROBOT, OutputFormat, YesOption, echo_err, load_robot_from_cli
from marm_setup.cli.option_groups import takes
from marm_setup.errors import InputError
from marm_setup.flows import MatrixSettings, RobotInput

if TYPE_CHECKING:
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.collision import CollisionMatrix, DisabledPair

REPORT_SUFFIXES = (".svg", ".html")


@takes("robot", ROBOT.of("urdf", "xacro_arg", "package_path"))
@takes(
    "matrix",
    MATRIX.of(
        "trials", "min_collision_fraction", "seed", "jobs", "padding", "keep_disabled", "keep", "prove"
    ),
)
def collisions(
    robot: RobotInput,
    matrix: MatrixSettings,
    srdf: Annotated[
        Path | None,
        typer.Option("--srdf", help="Update this SRDF (in place unless --output).", metavar="IN.srdf"),
    ] = None,
    output: Annotated[
        Path | None, typer.Option("-o", "--output", help="Write the SRDF here (minimal SRDF without --srdf).")
    ] = None,
    default: Annotated[
        bool, typer.Option("--default/--no-default", help="Disable pairs colliding at the default state.")
    ] = True,
    always: Annotated[
        bool, typer.Option("--always/--no-always", help="Disable pairs (almost) always colliding.")
    ] = True,
    default_pose: Annotated[
        str | None,
        typer.Option(
            "--default-pose",
            help="With --srdf: a named pose of that SRDF as the default state (else 0 / mid-range).",
            metavar="NAME",
        ),
    ] = None,
    report: Annotated[
        Path | None, typer.Option("--report", help="Write a heat map of the matrix (.svg or .html).")
    ] = None,
    format: Annotated[OutputFormat, typer.Option("--format", help="text or json.")] = OutputFormat.text,
    force: Annotated[
        bool,
        typer.Option(
            "--force",
            help="With --srdf: update it even if it names another robot or links; with a package DIR: "
            "overwrite hand-edited files (kept as .orig).",
        ),
    ] = False,
    verbose: Annotated[
        bool, typer.Option("--verbose", help="With --srdf: list the pairs added and removed.")
    ] = False,
    yes: YesOption = False,
) -> None:
    """Compute which link pairs MoveIt need not check (Adjacent, Default, Always, Never).

    Seeded and deterministic (same seed, same bytes, whatever --jobs). Never is statistical: with N trials and no hit, a pair collides with probability below 3/N (95 %). With --prove (default on) each Never pair is also proved collision-free over its whole joint range, or found in contact (then enabled), or flagged unproved. Meshes are surfaces, as in MoveIt: a shape entirely inside a mesh, not touching it, does not collide.
    """
    assert robot.urdf is not None  # the URDF argument is required
    if robot.urdf.is_dir():  # a package made by init: its marm_setup.yaml and SRDF, together
        _refuse_unused(xacro_arg=robot.xacro_args, package_path=robot.package_paths)
        from marm_setup.cli.progress import SamplingProgress
        from marm_setup.flows import run_package_collisions

        with SamplingProgress(confirmed=yes) as progress:
            done = run_package_collisions(robot.urdf, matrix, force=force, progress=progress)
        for line in (*done.status_lines, done.summary):
            typer.echo(line)
        return
    _check_options(srdf, matrix.keep_disabled, report)
    if default_pose is not None and srdf is None:
        raise InputError("needs --srdf (the SRDF holding the pose)", element="--default-pose")
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.flows import CollisionsRequest, run_collisions

    request = CollisionsRequest(
        matrix,
        check_default=default,
        check_always=always,
        default_pose=default_pose,
        srdf=srdf,
        output=output,
        force=force,
        report=report,
        distances=format is OutputFormat.json or report is not None,
        verbose=verbose,
    )
    model = load_robot_from_cli(robot)
    with SamplingProgress(enabled=format is OutputFormat.text, confirmed=yes) as progress:
        result = run_collisions(request, model, progress)
    for line in result.messages:
        echo_err(line)
    _print_result(result.matrix, model.name, result.disabled, progress, format)


def _check_options(srdf: Path | None, keep: bool, report: Path | None) -> None:
    if keep and srdf is None:
        raise InputError("needs --srdf (the SRDF whose pairs to keep)", element="--keep-disabled")
    if report is not None and report.suffix.lower() not in REPORT_SUFFIXES:
        raise InputError(f"unknown report type '{report.suffix}'; expected .svg or .html", path=str(report))


def _refuse_unused(**given: object) -> None:
    """A package DIR's marm_setup.yaml names the robot: an option that would choose it is refused."""
    for name, value in given.items():
        if value:
            option = "--" + name.replace("_", "-")
            raise InputError(
                "not used with a package DIR (its marm_setup.yaml names the robot, its xacro args and "
                "package paths)",
                element=option,
            )


def _print_result(
    matrix: CollisionMatrix,
    robot_name: str,
    disabled: Sequence[DisabledPair],
    progress: SamplingProgress,
    format: OutputFormat,
) -> None:
    from marm_setup.collision import describe_matrix, format_summary

    if format is OutputFormat.json:
        typer.echo(json.dumps(describe_matrix(matrix, robot_name, disabled), indent=2))
    else:
        seconds = progress.finished - progress.started
        typer.echo(format_summary(matrix, robot_name, disabled, seconds, progress.denser_seconds()))
