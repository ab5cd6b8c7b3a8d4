"""`marm-setup validate`: check MoveIt config packages (ours or the Setup Assistant's)."""

from __future__ import annotations

import enum
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import ROBOT, PackageUrdf, echo_err
from marm_setup.cli.option_groups import takes
from marm_setup.flows import RobotInput
from marm_setup.ros import Target, distros_of

if TYPE_CHECKING:
    from marm_setup.errors import MarmError
    from marm_setup.findings import Finding
    from marm_setup.validate import Validation


class ValidateFormat(str, enum.Enum):
    text = "text"
    json = "json"
    sarif = "sarif"
    junit = "junit"


@dataclass(frozen=True)
class Outcome:
    """One package's validation: its findings, what was checked (None when it could not be
    read) and its exit code."""

    package: Path
    findings: tuple[Finding, ...]
    validation: Validation | None
    code: int


@takes("robot", ROBOT.of("urdf", "srdf", "xacro_arg", "package_path", "untrusted", urdf=(PackageUrdf, None)))
def validate(
    packages: Annotated[
        list[Path],
        typer.Argument(
            help="The MoveIt config package folder(s); with --changed-files, any files or folders inside them.",
            metavar="DIR...",
            show_default=False,
        ),
    ],
    robot: RobotInput = RobotInput(),
    no_plan: Annotated[
        bool, typer.Option("--no-plan", help="Skip the runtime checks (planning between named poses).")
    ] = False,
    strict: Annotated[bool, typer.Option("--strict", help="Warnings fail the check too (exit 1).")] = False,
    format: Annotated[
        ValidateFormat,
        typer.Option(
            "--format",
            help="text, json, sarif (SARIF 2.1.0 for code scanning, paths relative to the git "
            "repository) or junit (a test case per package and rule family).",
        ),
    ] = ValidateFormat.text,
    changed_files: Annotated[
        bool,
        typer.Option(
            "--changed-files",
            help="The arguments are changed files (as pre-commit passes them): validate the config "
            "packages holding them, nothing when none does.",
        ),
    ] = False,
    launch_arg: Annotated[
        list[str] | None,
        typer.Option(
            "--launch-arg",
            help="Launch argument NAME:=VALUE, as roslaunch / ros2 launch take it (repeatable): for "
            "the launch files' arguments without a default (ur_type:=ur5e), or another variant.",
            metavar="NAME:=VALUE",
            show_default=False,
        ),
    ] = None,
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
    """Validate config packages: SRDF vs URDF, poses, collision matrix, kinematics, limits,
    controllers, OMPL, launch files. Exit 0 clean, 1 with errors (or warnings with --strict),
    2 when a package cannot be read."""
    from marm_setup.cli.changed_packages import changed_packages
    from marm_setup.robot import parse_xacro_args

    launch_args = parse_xacro_args(launch_arg or (), option="--launch-arg")
    folders = changed_packages(packages) if changed_files else packages
    if not folders:
        echo_err(f"no MoveIt config package holds the {len(packages)} changed file(s): nothing to validate")
        return
    options = dict(
        urdf=robot.urdf,
        srdf=robot.srdf,
        xacro_args=robot.xacro_mapping,
        package_paths=list(robot.package_paths),
        plan=not no_plan,
        untrusted=robot.untrusted,
        ros_distro=ros_distro,
        launch_args=launch_args,
    )
    machine = format is not ValidateFormat.text
    outcomes = [
        _validated(folder, options, strict, machine=machine, alone=len(folders) == 1) for folder in folders
    ]
    typer.echo(_formatted(outcomes, format, strict), nl=False)
    code = max(o.code for o in outcomes)
    if code:
        raise typer.Exit(code)


def _formatted(outcomes: list[Outcome], format: ValidateFormat, strict: bool) -> str:
    from marm_setup.findings import format_text

    if format is ValidateFormat.sarif:
        from marm_setup.validate import finding_uri, format_sarif, location_base

        return format_sarif(
            (f, finding_uri(f, o.package, location_base(o.package))) for o in outcomes for f in o.findings
        )
    if format is ValidateFormat.junit:
        from marm_setup.validate import format_junit

        return format_junit([(str(o.package), o.findings) for o in outcomes], strict=strict)
    if format is ValidateFormat.json:
        docs = [_json_doc(o) for o in outcomes]
        if len(docs) == 1:
            return docs[0]
        return _json_of_several(outcomes, docs)
    return "".join(
        format_text(o.findings, color=sys.stdout.isatty(), checked=o.validation.describe())
        for o in outcomes
        if o.validation is not None
    )


def _json_doc(o: Outcome) -> str:
    from marm_setup.findings import format_json

    checked = o.validation.as_dict() if o.validation is not None else None
    return format_json(o.findings, checked=checked)


def _json_of_several(outcomes: list[Outcome], docs: list[str]) -> str:
    """`{"packages": [{"path": ..., <one package's document>}, ...], "errors": n, "warnings": n}`."""
    import json

    parsed = [{"path": str(o.package), **json.loads(doc)} for o, doc in zip(outcomes, docs, strict=True)]
    totals = {key: sum(doc[key] for doc in parsed) for key in ("errors", "warnings")}
    return json.dumps({"packages": parsed, **totals}, indent=2) + "\n"


def _validated(package: Path, options: dict, strict: bool, *, machine: bool, alone: bool) -> Outcome:
    """One package's outcome. An unreadable package is one `input.unreadable` finding for the
    machine formats (which always print their document) and one error line for text (raised as
    every command's when it is the only package); a crash inside validate is an `internal.error`."""
    from marm_setup.errors import MarmError, permission_error
    from marm_setup.findings import INTERNAL, count, error

    try:
        result = _run(package, options, show_progress=not machine)
    except (MarmError, PermissionError) as caught:
        if alone and not machine:
            raise
        exc = permission_error(caught) if isinstance(caught, PermissionError) else caught
        return Outcome(package, (_unreadable(package, exc),), None, 2)
    except Exception as exc:  # noqa: BLE001 - a bug still gives the document (and exit 2)
        if not machine:
            raise
        import traceback

        message = f"validate crashed ({type(exc).__name__}: {exc})"
        echo_err(traceback.format_exc().rstrip())
        crash = error(INTERNAL, str(package), "", message, "please report this with the package")
        return Outcome(package, (crash,), None, 2)
    errors, warnings = count(result.findings)
    internal = any(f.rule == INTERNAL for f in result.findings)
    code = 2 if internal else 1 if errors or (strict and warnings) else 0
    return Outcome(package, tuple(result.findings), result, code)


def _unreadable(package: Path, exc: MarmError) -> Finding:
    """The finding of a package that could not be read, its line said on stderr too."""
    from marm_setup.errors import remedy
    from marm_setup.findings import error

    finding = error(
        "input.unreadable", exc.path or str(package), exc.element or "", exc.message, remedy(exc.needs)
    )
    echo_err(f"error: {exc}" + (f" ({finding.hint})" if finding.hint else ""))
    return finding


def _run(package: Path, options: dict, *, show_progress: bool = True) -> Validation:
    """The validation; planning's progress drawn on a terminal (stderr), never for machine formats."""
    from marm_setup.cli.progress import StageProgress
    from marm_setup.validate import validate as run_validation

    with StageProgress(enabled=show_progress) as progress:
        return run_validation(package, progress=progress.stage("planning pose pairs"), **options)
