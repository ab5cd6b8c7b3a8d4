"""`marm-setup init`: infer (or take) a setup, compute the collision matrix, write the package."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Annotated

import typer

from marm_setup.cli.common import (
    MATRIX,
    ROBOT,
    OutputFormat,
    ProveMode,
    YesOption,
    either,
    load_robot_from_cli,
)
from marm_setup.cli.option_groups import takes
from marm_setup.flows import MatrixSettings, RobotInput
from marm_setup.ros import Target, distros_of

OutputOption = Annotated[
    Path | None,
    typer.Option("-o", "--output", help="Package folder to create.", metavar="DIR", show_default=False),
]
OldOutOption = Annotated[Path | None, typer.Option("--out", hidden=True)]  # -o/--output's old name
NameOption = Annotated[
    str | None, typer.Option("--name", help="Package name (default: <robot>_moveit_config).", metavar="PKG")
]
TargetOption = Annotated[Target | None, typer.Option("--target", help="ros2 (default) or ros1.")]
DistroOption = Annotated[
    str | None,
    typer.Option(
        "--ros-distro",
        help=f"{', '.join(distros_of(Target.ROS1))} (ros1); {', '.join(distros_of(Target.ROS2))} (ros2) "
        "[default: SPEC's, else $ROS_DISTRO, else the target's first].",
        metavar="DISTRO",
    ),
]
SetupOption = Annotated[
    Path | None,
    typer.Option(
        "--setup",
        help="SPEC yaml (marm_setup.yaml schema, any subset) over the inference; see docs/setup-file.md.",
        metavar="SPEC",
    ),
]
FromSrdfOption = Annotated[
    Path | None,
    typer.Option("--from-srdf", help="Import groups, poses, ... from an existing SRDF.", metavar="SRDF"),
]


FromPackageOption = Annotated[
    Path | None,
    typer.Option(
        "--from-package",
        help="Port an existing MoveIt config package (MoveIt 1 or 2, any layout) instead of a URDF.",
        metavar="PKG",
    ),
]
OptionalUrdfArg = Annotated[
    Path | None,
    typer.Argument(
        help=(
            "Robot description: .urdf, .xacro or .urdf.xacro (with --from-package: the robot, where the "
            "package's launch files take it from another package)."
        ),
        metavar="URDF",
    ),
]


TrialsOption = Annotated[
    str | None,
    typer.Option(
        "--trials",
        help="Random states for the Never pairs (10000, 100k, 1M) [default: SPEC's, else 10000].",
        metavar="N",
    ),
]
SeedOption = Annotated[
    int | None,
    typer.Option("--seed", help="Seed of the collision sampling [default: SPEC's, else 0].", metavar="S"),
]
KeepDisabledOption = Annotated[
    bool,
    typer.Option(
        "--keep-disabled",
        help="Take the SPEC's collision.disabled as it is (default: compute it again, User pairs kept).",
    ),
]
ProveOption = Annotated[
    ProveMode | None,
    typer.Option(
        "--prove",
        help="Prove Never pairs collision-free over their whole joint range (off: MoveIt's sampling "
        "alone; exhaustive: a far larger budget) [default: SPEC's, else on].",
    ),
]


@takes("robot", ROBOT.of("urdf", "xacro_arg", "package_path", "untrusted", urdf=(OptionalUrdfArg, None)))
@takes(
    "matrix",
    MATRIX.of(
        "trials",
        "seed",
        "jobs",
        "keep_disabled",
        "keep_matrix",
        "prove",
        trials=(TrialsOption, None),
        seed=(SeedOption, None),
        keep_disabled=(KeepDisabledOption, False),
        keep_matrix=(Annotated[bool, typer.Option("--keep-matrix", hidden=True)], False),  # the old name
        prove=(ProveOption, None),
    ),
)
def init(
    output: OutputOption = None,
    out: OldOutOption = None,
    name: NameOption = None,
    target: TargetOption = None,
    ros_distro: DistroOption = None,
    setup: SetupOption = None,
    from_srdf: FromSrdfOption = None,
    robot: RobotInput = RobotInput(),
    matrix: MatrixSettings = MatrixSettings(),
    force: Annotated[bool, typer.Option("--force", help="Write into an existing non-empty DIR.")] = False,
    from_package: FromPackageOption = None,
    no_plan: Annotated[
        bool, typer.Option("--no-plan", help="With --from-package: validate without the planning checks.")
    ] = False,
    format: Annotated[
        OutputFormat, typer.Option("--format", help="With --from-package: the port report as text or json.")
    ] = OutputFormat.text,
    yes: YesOption = False,
) -> None:
    """Infer a MoveIt setup for a robot (or take SPEC / an SRDF) and write the config package;
    or, with --from-package, port an existing config package and report every setting.

    The setup file (marm_setup.yaml, and the SPEC of --setup) is described key by key, with
    examples, in docs/setup-file.md."""
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.errors import InputError
    from marm_setup.flows import InitRequest, run_init
    from marm_setup.render import check_output_dir

    if robot.urdf is None and from_package is None:
        raise InputError(
            "missing: the robot's URDF (marm-setup init URDF -o DIR), or --from-package PKG", element="URDF"
        )
    out = either(output, out, name="-o/--output", old_name="--out")
    if out is None:
        raise InputError("missing: the package folder to write (-o DIR)", element="-o/--output")
    if from_package is not None:
        given = [o for o, v in (("--setup", setup), ("--from-srdf", from_srdf)) if v]
        if given:
            raise InputError(
                f"--from-package takes the robot from the package: drop {', '.join(given)}",
                element="--from-package",
            )
        _port(
            from_package,
            out,
            name,
            target,
            ros_distro,
            format,
            force=force,
            robot=robot,
            jobs=matrix.jobs,
            plan=not no_plan,
            yes=yes,
        )
        return
    if robot.untrusted:
        raise InputError(
            "--untrusted goes with --from-package (init URDF runs the xacro you give)", element="--untrusted"
        )
    request = InitRequest(
        robot=robot,
        out=out,
        name=name,
        target=target.value if target else None,
        ros_distro=ros_distro,
        env_distro=os.environ.get("ROS_DISTRO") or None,
        spec=setup,
        from_srdf=from_srdf,
        matrix=matrix,
        force=force,
    )
    check_output_dir(out, force=force, shown=str(out))
    model = load_robot_from_cli(robot, check_args=False)  # run_init checks them
    with SamplingProgress(confirmed=yes) as progress:
        result = run_init(request, model, progress)
    sources = ["inferred", *(f"{o} {p}" for o, p in (("SRDF", from_srdf), ("SPEC", setup)) if p)]
    typer.echo(
        f"setup for robot {model.name} ({' + '.join(sources)}), target {result.model.target} ({result.model.distro}):"
    )
    for line in result.inferred:
        typer.echo(f"  {line}")
    for line in result.notes:
        typer.echo(f"  {line}")
    for line in result.status_lines:
        typer.echo(line)


def _port(
    package: Path,
    out: Path,
    name: str | None,
    target: Target | None,
    ros_distro: str | None,
    format: OutputFormat,
    *,
    force: bool,
    robot: RobotInput,
    jobs: int,
    plan: bool,
    yes: bool = False,
) -> None:
    """`init --from-package`: port, render, validate; print the report; exit 1 on validation errors."""
    from marm_setup.cli.port_format import closing_line, format_port_json, format_port_text
    from marm_setup.cli.progress import SamplingProgress
    from marm_setup.findings import count, format_text
    from marm_setup.flows import PortInitRequest, run_port

    request = PortInitRequest(
        package=package,
        out=out,
        name=name,
        target=target.value if target else None,
        ros_distro=ros_distro,
        env_distro=os.environ.get("ROS_DISTRO") or None,
        force=force,
        robot=robot,
        plan=plan,
        jobs=jobs,
    )
    with SamplingProgress(enabled=format is OutputFormat.text, confirmed=yes) as progress:
        result = run_port(request, progress)
    validation = result.validation
    if format is OutputFormat.json:
        typer.echo(format_port_json(result), nl=False)
    else:
        typer.echo(format_port_text(result), nl=False)
        for line in result.status_lines:
            typer.echo(line)
        typer.echo(format_text(validation.findings, color=False, checked=validation.describe()), nl=False)
        typer.echo(closing_line(result))
    if count(validation.findings)[0]:
        raise typer.Exit(1)
