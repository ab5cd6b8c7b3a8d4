"""`marm-setup render`: re-render a package from its marm_setup.yaml, keeping hand edits safe."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer

if TYPE_CHECKING:
    from marm_setup.render.writer import FileChange
    from marm_setup.robot.model import RobotModel
    from marm_setup.setup.model import SetupModel

# What a robot loaded from marm_setup.yaml needs is given there, not by an option
SETUP_KEYS = {"--package-path": "robot.package_paths", "--xacro-arg": "robot.xacro_args"}
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
    from marm_setup.errors import ConflictError
    from marm_setup.render.package import SETUP_FILE, render_package
    from marm_setup.render.writer import apply_writes, conflicts, format_change, plan_writes, stale_files
    from marm_setup.setup.checks import setup_warnings

    if urdf is not None and not urdf.is_file():
        from marm_setup.errors import InputError

        raise InputError("file not found", path=str(urdf), element="--urdf")
    model, robot = load_package_setup(dir, urdf)
    for line in setup_warnings(model):
        typer.echo(line)
    # marm_setup.yaml is the input here: render never rewrites it.
    rendered = [f for f in render_package(model, robot) if f.path != SETUP_FILE]
    changes = plan_writes(rendered, dir)
    clashing = conflicts(changes)
    stale = [
        f"{'stale':<10}{path} (no longer generated; left in place)"
        for path in stale_files(changes, dir, keep=[SETUP_FILE])
    ]
    if dry_run or (clashing and not force):  # the plan: nothing is written
        for line in [*(format_change(c) for c in changes), *stale]:
            typer.echo(line)
    if dry_run:
        typer.echo(f"dry run: nothing written ({_summary(changes)})")
        return
    if clashing and not force:
        raise ConflictError(
            f"{len(clashing)} hand-edited file(s) not overwritten: {', '.join(clashing)} (use --force)",
            path=str(dir),
        )
    apply_writes(changes, dir, force=force)
    for line in [*(format_change(c, forced=force) for c in changes), *stale]:  # what was written
        typer.echo(line)
    typer.echo(_summary(changes))


def _summary(changes: list[FileChange]) -> str:
    from marm_setup.render.writer import STATUS_WORDS

    counts = {word: 0 for word in STATUS_WORDS.values()}
    for change in changes:
        counts[STATUS_WORDS[change.status]] += 1
    return ", ".join(f"{n} {word}" for word, n in counts.items())


def load_package_setup(pkg_dir: Path, urdf: Path | None = None) -> tuple[SetupModel, RobotModel]:
    """(SetupModel, RobotModel) of a package: DIR/marm_setup.yaml and the robot it names (or
    `urdf`, when given: the package moved away from the description it names)."""
    from marm_setup.errors import InputError
    from marm_setup.robot.load import load_robot
    from marm_setup.robot.ros_packages import description_file
    from marm_setup.robot.xacro_expand import check_xacro_args
    from marm_setup.setup.checks import check_setup
    from marm_setup.setup.yaml_io import load_setup

    setup_path = pkg_dir / "marm_setup.yaml"
    if not pkg_dir.is_dir():
        raise InputError("not a directory", path=str(pkg_dir))
    if not setup_path.is_file():
        raise InputError(
            "no marm_setup.yaml here (create the package with `marm-setup init`)", path=str(pkg_dir)
        )
    model = load_setup(setup_path)
    source = model.robot
    package_paths = [p for p in (_relative_to(pkg_dir, p) for p in source.package_paths) if p.is_dir()]
    try:
        urdf = description_file(source.urdf, pkg_dir, package_paths) if urdf is None else urdf
        robot = load_robot(urdf, dict(source.xacro_args), package_paths)
    except InputError as exc:  # the robot's package paths and xacro args are the setup file's
        exc.needs = SETUP_KEYS.get(exc.needs or "", exc.needs)
        raise
    check_xacro_args(dict(source.xacro_args), robot.xacro_args, path=str(setup_path), key="robot.xacro_args")
    check_setup(model, robot, str(setup_path))  # an edit may name unknown joints or leave limits
    return model, robot


def _relative_to(base: Path, path: str) -> Path:
    candidate = Path(path)
    return candidate if candidate.is_absolute() else base / candidate
