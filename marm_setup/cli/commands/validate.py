"""`marm-setup validate`: check a MoveIt config package (ours or the Setup Assistant's)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated

import typer

from marm_setup.cli.common import OutputFormat, PackagePaths, XacroArgs


def validate(
    package: Annotated[Path, typer.Argument(help="The MoveIt config package folder.", metavar="DIR")],
    urdf: Annotated[
        Path | None,
        typer.Option("--urdf", help="Robot description to use instead of the one the package names."),
    ] = None,
    xacro_arg: XacroArgs = None,
    package_path: PackagePaths = None,
    no_plan: Annotated[
        bool, typer.Option("--no-plan", help="Skip the runtime checks (planning between named poses).")
    ] = False,
    strict: Annotated[bool, typer.Option("--strict", help="Warnings fail the check too (exit 1).")] = False,
    format: Annotated[OutputFormat, typer.Option("--format", help="text or json.")] = OutputFormat.text,
) -> None:
    """Validate a config package: SRDF vs URDF, poses, collision matrix, kinematics, limits,
    controllers, OMPL, launch files. Exit 0 clean, 1 with errors (or warnings with --strict),
    2 when the package cannot be read."""
    from marm_setup.findings import count, format_json, format_text
    from marm_setup.robot.load import parse_xacro_args
    from marm_setup.validate.runner import validate as run_validation

    result = run_validation(
        package,
        urdf=urdf,
        xacro_args=parse_xacro_args(xacro_arg or []),
        package_paths=package_path or [],
        plan=not no_plan,
    )
    if format is OutputFormat.json:
        typer.echo(format_json(result.findings, checked=result.as_dict()), nl=False)
    else:
        text = format_text(result.findings, color=sys.stdout.isatty(), checked=result.describe())
        typer.echo(text, nl=False)
    errors, warnings = count(result.findings)
    if errors or (strict and warnings):
        raise typer.Exit(1)
