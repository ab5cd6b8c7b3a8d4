"""`marm-setup render`: re-render a package from its marm_setup.yaml, keeping hand edits safe."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

if TYPE_CHECKING:
    from marm_setup.render import FileChange
DirArg = Annotated[Path, typer.Argument(help="Config package folder holding marm_setup.yaml.", metavar="DIR")]


def render(
    dir: DirArg,
    force: Annotated[bool, typer.Option("--force", help="Overwrite hand-edited files.")] = False,
    dry_run: Annotated[
        bool, typer.Option("--dry-run", help="Print what would change; write nothing.")
    ] = False,
    urdf: Annotated[
        Path | None,
        typer.Option(
            "--urdf", help="The robot description, instead of the one marm_setup.yaml names.", metavar="URDF"
        ),
    ] = None,
) -> None:
    """Re-render every generated file of DIR from DIR/marm_setup.yaml (create / update / unchanged / conflict)."""
    from marm_setup.pipeline import run_render
    from marm_setup.render import format_change

    result = run_render(dir, urdf, force=force, dry_run=dry_run)
    for line in result.warnings:
        typer.echo(line)
    stale = [f"{'stale':<10}{path} (no longer generated; left in place)" for path in result.stale]
    # nothing written (a dry run, or refused): the plan; else what was written
    for line in [*(format_change(c, forced=force and result.written) for c in result.changes), *stale]:
        typer.echo(line)
    if result.refused is not None:
        raise result.refused
    if dry_run:
        typer.echo(f"dry run: nothing written ({_summary(result.changes)})")
    else:
        typer.echo(_summary(result.changes))


def _summary(changes: tuple[FileChange, ...]) -> str:
    from marm_setup.render import STATUS_WORDS

    counts = {word: 0 for word in STATUS_WORDS.values()}
    for change in changes:
        counts[STATUS_WORDS[change.status]] += 1
    return ", ".join(f"{n} {word}" for word, n in counts.items())
