"""`marm-setup collisions`: the self-collision matrix alone (a headless `collisions_updater`)."""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import (
    JobsOption,
    OutputFormat,
    PackagePaths,
    ProveMode,
    ProveOption,
    TrialsText,
    UrdfArg,
    XacroArgs,
    YesOption,
    default_jobs,
    echo_err,
    load_robot_from_cli,
    parse_count,
)
from marm_setup.errors import InputError

if TYPE_CHECKING:
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.collision import CollisionMatrix, DisabledPair

REPORT_SUFFIXES = (".svg", ".html")


def collisions(
    urdf: UrdfArg,
    xacro_arg: XacroArgs = None,
    package_path: PackagePaths = None,
    trials: TrialsText = "10000",
    min_collision_fraction: Annotated[
        float,
        typer.Option(
            "--min-collision-fraction", help="Always: in collision in at least this share of samples."
        ),
    ] = 0.95,
    seed: Annotated[int, typer.Option("--seed", help="Random seed (same seed, same output).")] = 0,
    jobs: JobsOption = None,
    padding: Annotated[
        float, typer.Option("--padding", help="Treat pairs closer than this [m] as colliding.")
    ] = 0.0,
    srdf: Annotated[
        Path | None,
        typer.Option("--srdf", help="Update this SRDF (in place unless --output).", metavar="IN.srdf"),
    ] = None,
    output: Annotated[
        Path | None, typer.Option("-o", "--output", help="Write the SRDF here (minimal SRDF without --srdf).")
    ] = None,
    keep_disabled: Annotated[
        bool,
        typer.Option(
            "--keep-disabled", help="With --srdf: keep every pair it already disables (User always kept)."
        ),
    ] = False,
    keep: Annotated[bool, typer.Option("--keep", hidden=True)] = False,  # --keep-disabled's old name
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
    prove: ProveOption = ProveMode.on,
) -> None:
    """Compute which link pairs MoveIt need not check (Adjacent, Default, Always, Never).

    Seeded and deterministic (same seed, same bytes, whatever --jobs). Never is statistical: with N trials and no hit, a pair collides with probability below 3/N (95 %). With --prove (default on) each Never pair is also proved collision-free over its whole joint range, or found in contact (then enabled), or flagged unproved. Meshes are surfaces, as in MoveIt: a shape entirely inside a mesh, not touching it, does not collide.
    """
    count = parse_count(trials, element="--trials")
    jobs = default_jobs(jobs)
    keep = keep or keep_disabled
    if urdf.is_dir():  # a package made by init: its marm_setup.yaml and SRDF, together
        _check_options(min_collision_fraction, seed, padding, None, False, None)
        _refuse_unused(xacro_arg=xacro_arg, package_path=package_path)
        from marm_setup.cli.progress import SamplingProgress
        from marm_setup.flows import run_package_collisions

        with SamplingProgress(confirmed=yes) as progress:
            done = run_package_collisions(
                urdf,
                count,
                seed,
                min_collision_fraction,
                jobs,
                prove=prove.value,
                force=force,
                progress=progress,
            )
        for line in (*done.status_lines, done.summary):
            typer.echo(line)
        return
    _check_options(min_collision_fraction, seed, padding, srdf, keep, report)
    if default_pose is not None and srdf is None:
        raise InputError("needs --srdf (the SRDF holding the pose)", element="--default-pose")
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.flows import CollisionsRequest, run_collisions

    request = CollisionsRequest(
        trials=count,
        seed=seed,
        min_collision_fraction=min_collision_fraction,
        jobs=jobs,
        padding=padding,
        check_default=default,
        check_always=always,
        default_pose=default_pose,
        srdf=srdf,
        output=output,
        keep=keep,
        force=force,
        report=report,
        distances=format is OutputFormat.json or report is not None,
        verbose=verbose,
        prove=prove.value,
    )
    robot = load_robot_from_cli(urdf, xacro_arg, package_path)
    with SamplingProgress(enabled=format is OutputFormat.text, confirmed=yes) as progress:
        result = run_collisions(request, robot, progress)
    for line in result.messages:
        echo_err(line)
    _print_result(result.matrix, robot.name, result.disabled, progress, format)


def _check_options(
    fraction: float, seed: int, padding: float, srdf: Path | None, keep: bool, report: Path | None
) -> None:
    if seed < 0:
        raise InputError(f"must be >= 0, got {seed}", element="--seed")
    if not 0.0 < fraction <= 1.0:
        raise InputError(f"must be in (0, 1], got {fraction}", element="--min-collision-fraction")
    if not 0.0 <= padding < float("inf"):  # also refuses nan, which would disable every pair
        raise InputError(f"must be >= 0 and finite, got {padding}", element="--padding")
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
