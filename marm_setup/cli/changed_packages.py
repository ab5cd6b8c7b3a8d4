"""The MoveIt config packages that changed files belong to (`validate --changed-files`, the
pre-commit hook): each file's nearest folder holding a package.xml, when that package has an
SRDF (`config/*.srdf*`, `srdf/*.srdf*`) or a `.setup_assistant`."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

SRDF_FOLDERS = ("config", "srdf")


def is_config_package(folder: Path) -> bool:
    """Whether `folder` is a ROS package with a MoveIt semantic description."""
    if not (folder / "package.xml").is_file():
        return False
    if (folder / ".setup_assistant").is_file():
        return True
    return any(
        path.is_file()
        for name in SRDF_FOLDERS
        if (folder / name).is_dir()
        for path in (folder / name).glob("*.srdf*")
    )


def enclosing_package(file: Path) -> Path | None:
    """The config package holding `file` (a file or folder, as the user wrote it: the answer
    keeps its form, relative or absolute), or None when its nearest package is none."""
    start = file if file.is_dir() else file.parent
    for folder in (start, *start.parents):
        if (folder / "package.xml").is_file():
            return folder if is_config_package(folder) else None
    return None


def changed_packages(files: Iterable[Path]) -> list[Path]:
    """The config packages of `files`, each once, in the order first named."""
    out: list[Path] = []
    for file in files:
        found = enclosing_package(file)
        if found is not None and found not in out:
            out.append(found)
    return out
