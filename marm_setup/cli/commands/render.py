"""`marm-setup render`: re-render a package from its marm_setup.yaml, keeping hand edits safe."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

from marm_setup.cli.common import ROBOT
from marm_setup.cli.option_groups import takes
from marm_setup.flows import RobotInput

if TYPE_CHECKING:
    from marm_setup.render import FileChange
DirArg = Annotated[Path, typer.Argument(help="Config package folder holding marm_setup.yaml.", metavar="DIR")]


UrdfOption = Annotated[
    Path | None,
    typer.Option(
        "--urdf", help="The robot description, instead of the one marm_setup.yaml names.", metavar="URDF"
    ),
]


@takes("robot", ROBOT.of("urdf", "xacro_arg", "package_path", urdf=(UrdfOption, None)))
def render(
    dir: DirArg,
    force: Annotated[bool, typer.Option("--force", help="Overwrite hand-edited files.")] = False,
    dry_run: Annotated[
        bool, typer.Option("--dry-run", help="Print what would change; write nothing.")
    ] = False,
    robot: RobotInput = RobotInput(),
) -> None:
    """Re-render every generated file of DIR from DIR/marm_setup.yaml (create / update / unchanged / conflict).

    --xacro-arg and --package-path load the robot (over marm_setup.yaml's robot.xacro_args, after
    its robot.package_paths); the files rendered say what marm_setup.yaml says."""
    from marm_setup.flows import run_render
    from marm_setup.render import format_change

    result = run_render(dir, robot, force=force, dry_run=dry_run)
    for line in result.warnings:
        typer.echo(line)
    stale = [f"{'stale':<10}{path} (no longer generated; left in place)" for path in result.stale]
    # nothing written (a dry run, or refused): the plan; else what was written
    lines = [format_change(c, forced=force and result.written) for c in result.changes]
    if result.refused is not None:  # say of each file that it was not written, and why
        lines = [_refused_line(line, c.status) for line, c in zip(lines, result.changes, strict=True)]
    for line in [*lines, *stale]:
        typer.echo(line)
    if result.refused is not None:
        raise result.refused
    if dry_run:
        typer.echo(f"dry run: nothing written ({_summary(result.changes)})")
    else:
        typer.echo(_summary(result.changes))


def _refused_line(line: str, status: str) -> str:
    """A file's status line when a hand-edited file kept render from writing anything."""
    if status == "conflict":
        return f"{line} (edited by hand: not overwritten)"
    if status in ("new", "update"):
        return f"{line} (not written: a hand-edited file stopped the render)"
    return line


def _summary(changes: tuple[FileChange, ...]) -> str:
    from marm_setup.render import STATUS_WORDS

    counts = {word: 0 for word in STATUS_WORDS.values()}
    for change in changes:
        counts[STATUS_WORDS[change.status]] += 1
    return ", ".join(f"{n} {word}" for word, n in counts.items())
