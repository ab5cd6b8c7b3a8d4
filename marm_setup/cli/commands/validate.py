"""`marm-setup validate`: check a MoveIt config package (ours or the Setup Assistant's)."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import (
    OutputFormat,
    PackagePaths,
    PackageSrdf,
    PackageUrdf,
    UntrustedOption,
    XacroArgs,
    echo_err,
)
from marm_setup.ros import Target, distros_of

if TYPE_CHECKING:
    from marm_setup.validate import Validation


def validate(
    package: Annotated[Path, typer.Argument(help="The MoveIt config package folder.", metavar="DIR")],
    urdf: PackageUrdf = None,
    srdf: PackageSrdf = None,
    xacro_arg: XacroArgs = None,
    package_path: PackagePaths = None,
    no_plan: Annotated[
        bool, typer.Option("--no-plan", help="Skip the runtime checks (planning between named poses).")
    ] = False,
    strict: Annotated[bool, typer.Option("--strict", help="Warnings fail the check too (exit 1).")] = False,
    format: Annotated[OutputFormat, typer.Option("--format", help="text or json.")] = OutputFormat.text,
    untrusted: UntrustedOption = False,
    ros_distro: Annotated[
        str | None,
        typer.Option(
            "--ros-distro",
            help=f"Check for this distro: {', '.join(distros_of(Target.ROS1))} (ros1); "
            f"{', '.join(distros_of(Target.ROS2))} (ros2) [default: marm_setup.yaml's ros_distro, else inferred].",
            metavar="DISTRO",
        ),
    ] = None,
) -> None:
    """Validate a config package: SRDF vs URDF, poses, collision matrix, kinematics, limits,
    controllers, OMPL, launch files. Exit 0 clean, 1 with errors (or warnings with --strict),
    2 when the package cannot be read."""
    from marm_setup.findings import INTERNAL, count, format_json, format_text
    from marm_setup.robot import parse_xacro_args

    as_json = format is OutputFormat.json
    options = dict(
        urdf=urdf,
        srdf=srdf,
        xacro_args=parse_xacro_args(xacro_arg or []),
        package_paths=package_path or [],
        plan=not no_plan,
        untrusted=untrusted,
        ros_distro=ros_distro,
    )
    result = _run_for_json(package, options) if as_json else _run(package, options)
    if as_json:
        typer.echo(format_json(result.findings, checked=result.as_dict()), nl=False)
    else:
        text = format_text(result.findings, color=sys.stdout.isatty(), checked=result.describe())
        typer.echo(text, nl=False)
    errors, warnings = count(result.findings)
    if any(f.rule == INTERNAL for f in result.findings):
        raise typer.Exit(2)
    if errors or (strict and warnings):
        raise typer.Exit(1)


def _run(package: Path, options: dict, *, show_progress: bool = True) -> Validation:
    """The validation; planning's progress drawn on a terminal (stderr), never for json."""
    from marm_setup.cli.progress import StageProgress
    from marm_setup.validate import validate as run_validation

    with StageProgress(enabled=show_progress) as progress:
        return run_validation(package, progress=progress.stage("planning pose pairs"), **options)


def _run_for_json(package: Path, options: dict) -> Validation:
    """The validation, or (after printing a JSON document with the one finding) exit 2:
    `--format json` always prints JSON, whatever goes wrong."""
    from marm_setup.errors import MarmError, permission_error, remedy
    from marm_setup.findings import INTERNAL, error, format_json

    try:
        return _run(package, options, show_progress=False)
    except (MarmError, PermissionError) as caught:
        exc = permission_error(caught) if isinstance(caught, PermissionError) else caught
        finding = error(
            "input.unreadable", exc.path or str(package), exc.element or "", exc.message, remedy(exc.needs)
        )
        echo_err(f"error: {exc}" + (f" ({finding.hint})" if finding.hint else ""))
    except Exception as exc:  # noqa: BLE001 - a bug still gives a JSON document (and exit 2)
        import traceback

        message = f"validate crashed ({type(exc).__name__}: {exc})"
        finding = error(INTERNAL, str(package), "", message, "please report this with the package")
        echo_err(traceback.format_exc().rstrip())
    typer.echo(format_json([finding]), nl=False)
    raise typer.Exit(2)
