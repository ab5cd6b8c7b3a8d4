"""`render DIR`: a generated package's marm_setup.yaml and robot, rendered again and written,
hand-edited files left alone unless forced; `collisions DIR` loads a package the same way."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import ConflictError, InputError
from marm_setup.flows.settings import RobotInput

if TYPE_CHECKING:
    from marm_setup.render import FileChange
    from marm_setup.robot import RobotModel
    from marm_setup.setup import SetupModel

# What a robot loaded from marm_setup.yaml needs is given there, not by an option
SETUP_KEYS = {"--package-path": "robot.package_paths", "--xacro-arg": "robot.xacro_args"}


@dataclass(frozen=True)
class RenderResult:
    """Each file's change, files no longer generated, whether the changes were written, and why
    not when hand-edited files kept them from it (for the caller to raise after saying what
    would have changed)."""

    changes: tuple[FileChange, ...]
    stale: tuple[str, ...]
    written: bool
    refused: ConflictError | None = None
    warnings: tuple[str, ...] = ()  # what the setup asks for that its distro's MoveIt may not do


def run_render(
    pkg_dir: Path, robot_input: RobotInput = RobotInput(), *, force: bool = False, dry_run: bool = False
) -> RenderResult:
    """Render DIR from DIR/marm_setup.yaml (which render never rewrites) and, unless `dry_run`,
    write it; nothing is written when a hand-edited file would be overwritten without `force`
    (`refused` says which). `robot_input`'s urdf, xacro args and package paths load the robot
    (load_package_setup)."""
    from marm_setup.render import (
        SETUP_FILE,
        apply_writes,
        conflicts,
        plan_writes,
        render_package,
        stale_files,
    )
    from marm_setup.setup import setup_warnings

    urdf = robot_input.urdf
    if urdf is not None and not urdf.is_file():
        raise InputError("file not found", path=str(urdf), element="--urdf")
    model, robot = load_package_setup(pkg_dir, urdf, robot_input.xacro_mapping, robot_input.package_paths)
    warnings = tuple(setup_warnings(model))
    rendered = [f for f in render_package(model, robot) if f.path != SETUP_FILE]
    changes = plan_writes(rendered, pkg_dir)
    stale = tuple(stale_files(changes, pkg_dir, keep=[SETUP_FILE]))
    if dry_run:
        return RenderResult(tuple(changes), stale, False, warnings=warnings)
    clashing = conflicts(changes)
    if clashing and not force:
        refused = ConflictError(
            f"nothing written: {len(clashing)} file(s) edited by hand since the last render would be "
            f"overwritten: {', '.join(clashing)} (use --force to overwrite them, each edit kept beside "
            "it as <file>.orig; or undo the edits)",
            path=str(pkg_dir),
        )
        return RenderResult(tuple(changes), stale, False, refused, warnings)
    apply_writes(changes, pkg_dir, force=force)
    return RenderResult(tuple(changes), stale, True, warnings=warnings)


def load_package_setup(
    pkg_dir: Path,
    urdf: Path | None = None,
    xacro_args: dict[str, str] | None = None,
    package_paths: tuple[Path, ...] = (),
) -> tuple[SetupModel, RobotModel]:
    """(SetupModel, RobotModel) of a package: DIR/marm_setup.yaml and the robot it names (or
    `urdf`, when given: the package moved away from the description it names), expanded with
    `xacro_args` over the setup's robot.xacro_args and found through `package_paths` after its
    robot.package_paths."""
    from marm_setup.robot import check_xacro_args, description_file, load_robot
    from marm_setup.setup import check_setup, load_setup

    setup_path = pkg_dir / "marm_setup.yaml"
    if not pkg_dir.is_dir():
        raise InputError("not a directory", path=str(pkg_dir))
    if not setup_path.is_file():
        raise InputError(
            "no marm_setup.yaml here (create the package with `marm-setup init`)", path=str(pkg_dir)
        )
    model = load_setup(setup_path)
    source = model.robot
    found = [p for p in (_relative_to(pkg_dir, p) for p in source.package_paths) if p.is_dir()]
    searched = [*found, *package_paths]
    try:
        urdf = description_file(source.urdf, pkg_dir, searched) if urdf is None else urdf
        robot = load_robot(urdf, {**dict(source.xacro_args), **(xacro_args or {})}, searched)
    except InputError as exc:  # the robot's package paths and xacro args are the setup file's
        exc.needs = SETUP_KEYS.get(exc.needs or "", exc.needs)
        raise
    check_xacro_args(dict(source.xacro_args), robot.xacro_args, path=str(setup_path), key="robot.xacro_args")
    check_xacro_args(dict(xacro_args or {}), robot.xacro_args, path=str(urdf))
    check_setup(model, robot, str(setup_path))  # an edit may name unknown joints or leave limits
    return model, robot


def _relative_to(base: Path, path: str) -> Path:
    candidate = Path(path)
    return candidate if candidate.is_absolute() else base / candidate
