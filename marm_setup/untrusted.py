"""The trust boundary around a package marm-setup reads: what of it may run, which of its files
may be read, and how much of their content a message may show.

Packages come from downloads and pull requests. By default marm-setup runs the package's own
code the way ROS does when it loads the package (xacro of the robot description and SRDF,
`$(eval ...)` in launch files, `$(command ...)`), each in a child process bounded in time and
memory; `--untrusted` runs none of it (`no_package_code`), and whatever was skipped is recorded
for the summary. A file named by a package (a symlink, a path in `marm_setup.yaml` or
`.setup_assistant`) is read only when it lies inside the package or a folder the user named
(`confined`). Under `--untrusted` nothing else outside it is read either (`confine_reads`,
`readable`: a robot description or mesh elsewhere), nor the user's environment (`$(env)`,
`$(optenv)`: `environment_refused`). Findings quote package content only as `excerpt`: short and
printable.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path, PurePosixPath

from marm_setup.errors import InputError

EXCERPT_CHARS = 60

_code_allowed: ContextVar[bool] = ContextVar("package_code_allowed", default=True)
_skipped: ContextVar[list[str] | None] = ContextVar("package_code_skipped", default=None)
_read_folders: ContextVar[list[Path] | None] = ContextVar("package_read_folders", default=None)


class CodeNotRun(InputError):
    """Package code that `--untrusted` did not run (what it was and where)."""


class PathEscape(InputError):
    """A path a package names that leaves the package and the folders the user named."""


class SymlinkEscape(PathEscape):
    """A file of the package that is a symlink (or under one) leading outside it."""


@contextmanager
def no_package_code() -> Iterator[list[str]]:
    """Within: no package code runs (`refuse_code` raises); yields the list of what was skipped."""
    skipped: list[str] = []
    allowed, recorded = _code_allowed.set(False), _skipped.set(skipped)
    folders = _read_folders.set([])
    try:
        yield skipped
    finally:
        _code_allowed.reset(allowed)
        _skipped.reset(recorded)
        _read_folders.reset(folders)


def confine_reads(folders: Iterable[Path]) -> None:
    """Under `--untrusted` (inside `no_package_code`): from now on files are read only inside
    `folders` (the package and the folders the user named); otherwise nothing."""
    confined_to = _read_folders.get()
    if confined_to is not None:
        confined_to.extend(Path(os.path.realpath(f)) for f in folders)


def readable(path: Path) -> bool:
    """Whether `path` may be read: always, except under `--untrusted` once `confine_reads` named
    the package: then only inside the folders it named (symlinks followed)."""
    confined_to = _read_folders.get()
    return not confined_to or inside(path, confined_to)


def environment_refused(what: str) -> str | None:
    """Under `--untrusted`: why `what` (`$(env X)`) is not read (the user's environment may
    hold secrets a package would echo into findings); otherwise None."""
    if _code_allowed.get():
        return None
    return f"{what}: not read (--untrusted reads nothing from your environment)"


def package_code_allowed() -> bool:
    """False inside `no_package_code` (`--untrusted`)."""
    return _code_allowed.get()


def refuse_code(what: str, path: str, element: str | None = None) -> None:
    """Under `--untrusted`: record `what` (e.g. "xacro of urdf/robot.urdf.xacro") as skipped and
    raise CodeNotRun; otherwise nothing."""
    if _code_allowed.get():
        return
    skipped = _skipped.get()
    if skipped is not None and what not in skipped:
        skipped.append(what)
    raise CodeNotRun(f"not run: {what} is package code (--untrusted)", path=path, element=element)


def skips_code(what: str) -> bool:
    """Under `--untrusted`: record `what` as skipped and say True (the caller skips it)."""
    try:
        refuse_code(what, "")
    except CodeNotRun:
        return True
    return False


def skipped_code() -> tuple[str, ...]:
    """What `--untrusted` did not run so far (empty outside `no_package_code`)."""
    return tuple(_skipped.get() or ())


def confined(root: Path, rel: str, allowed: Iterable[Path] = (), *, shown: str, element: str) -> Path:
    """`root / rel` when `rel` is a relative path without `..` and, symlinks followed, stays
    inside `root` or one of the `allowed` folders; else PathEscape naming `shown` and `element`
    (never the content of what `rel` points at)."""
    relative_inside(rel, shown=shown, element=element)
    path = root / rel
    if not inside(path, (root, *allowed)):
        raise SymlinkEscape(
            f"'{excerpt(rel)}' is a symlink leading outside the package: refused", path=shown, element=element
        )
    return path


def relative_inside(rel: str, *, shown: str, element: str) -> None:
    """PathEscape unless `rel` is a relative path without `..` (what a package file may name)."""
    pure = PurePosixPath(rel.replace("\\", "/"))
    if pure.is_absolute() or os.path.isabs(rel):
        raise PathEscape(
            f"absolute path '{excerpt(rel)}' refused: a package's files are read inside it",
            path=shown,
            element=element,
        )
    if ".." in pure.parts:
        raise PathEscape(
            f"path '{excerpt(rel)}' leaves the package ('..'): refused", path=shown, element=element
        )


def inside(path: Path, folders: Iterable[Path]) -> bool:
    """Whether `path`, symlinks followed, is one of `folders` (resolved) or inside one."""
    real = Path(os.path.realpath(path))
    for folder in folders:
        top = Path(os.path.realpath(folder))
        if real == top or top in real.parents:
            return True
    return False


def excerpt(text: str, limit: int = EXCERPT_CHARS) -> str:
    """`text` as a message may quote it: printable characters only (white space as a space,
    others as `?`), at most `limit` of them (then `...`)."""
    shown = "".join(c if c.isprintable() else " " if c in "\t\n\r" else "?" for c in text[: limit + 1])
    return shown if len(shown) <= limit else shown[: limit - 3] + "..."
