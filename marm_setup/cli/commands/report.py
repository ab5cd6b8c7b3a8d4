"""`marm-setup report`: one offline HTML page showing a config package's robot at every pose."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated

import typer

from marm_setup.cli.common import MATRIX, ROBOT, PackageUrdf
from marm_setup.cli.option_groups import takes
from marm_setup.flows import MatrixSettings, RobotInput

TrialsOption = Annotated[
    str | None,
    typer.Option(
        "--trials",
        help="Random states for the matrix's hit counts [default: 10000; never the package's own setting].",
        metavar="N",
    ),
]


@takes("robot", ROBOT.of("urdf", "srdf", "xacro_arg", "package_path", "untrusted", urdf=(PackageUrdf, None)))
@takes("matrix", MATRIX.of("trials", "jobs", trials=(TrialsOption, None)))
def report(
    package: Annotated[Path, typer.Argument(help="The MoveIt config package folder.", metavar="PKG")],
    output: Annotated[
        Path, typer.Option("--output", "-o", help="The HTML file to write.", metavar="report.html")
    ] = Path("report.html"),
    robot: RobotInput = RobotInput(),
    no_plan: Annotated[
        bool, typer.Option("--no-plan", help="Skip planning between named poses (no trajectories).")
    ] = False,
    matrix: MatrixSettings = MatrixSettings(),
) -> None:
    """Write one self-contained HTML page (works offline): the robot in 3D at each named pose,
    groups lit, contacts in red, end effectors and the virtual joint's frame, every validate
    finding, the collision matrix with each pair's reason, hits and distance, and the planned
    trajectories animated. Exit 0 when the package has no errors, 1 when it has (the page is
    written either way), 2 when it cannot be read."""
    from marm_setup.cli.progress import StageProgress
    from marm_setup.findings import INTERNAL, count
    from marm_setup.flows import ReportRequest, run_report

    request = ReportRequest(package, output, robot, matrix, plan=not no_plan)
    with StageProgress() as progress:
        result = run_report(request, progress)
    findings = result.validated.validation.findings
    errors, warnings = count(findings)
    megabytes = len(result.html.encode()) / 1e6
    faces = sum(len(m.indices) for m in result.meshes)
    before = sum(m.faces_before for m in result.meshes)
    typer.echo(
        f"wrote {output} ({megabytes:.1f} MB): {errors} error{'' if errors == 1 else 's'}, "
        f"{warnings} warning{'' if warnings == 1 else 's'}; {len(result.meshes)} meshes, "
        f"{faces} triangles (of {before})"
    )
    for shape in result.not_drawn:  # the page says so too
        typer.echo(f"warning: {shape.line()} (not drawn: the page shows the robot without it)", err=True)
    if any(f.rule == INTERNAL for f in findings):
        raise typer.Exit(2)
    if errors:
        raise typer.Exit(1)
