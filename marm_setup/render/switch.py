"""Switch a package to its new version as a whole: lock, stage the complete new tree, swap.

The new package is built next to the old one (unchanged files hard-linked, changed ones written
fresh, never through a link) and exchanged with it in one `renameat2(RENAME_EXCHANGE)`: a run
killed at any point leaves the old package or the new one. Where the package folder cannot be
renamed (a mount point, a read-only parent, a file system without the exchange) the changed
files are staged inside the package and moved in one by one under a commit record; a run
killed then is completed by the next write (roll forward).
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import fcntl
import json
import os
import shutil
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

from marm_setup.errors import ConflictError, InputError

STATE_DIR = ".marm_setup"
COMMIT = f"{STATE_DIR}/commit.json"
EXECUTABLE_SUFFIXES = (".py", ".sh")
_NO_EXCHANGE = {errno.EBUSY, errno.EXDEV, errno.EINVAL, errno.ENOSYS, errno.EPERM, errno.EACCES, errno.EROFS}


@contextlib.contextmanager
def package_lock(real: Path, shown: str) -> Iterator[None]:
    """Hold an exclusive lock on the package folder (created if missing) for one write."""
    try:
        real.mkdir(parents=True, exist_ok=True)
        fd = os.open(real, os.O_RDONLY | os.O_DIRECTORY)
    except OSError as exc:
        raise InputError(f"cannot write: {exc.strerror or exc}", path=shown) from None
    try:
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            raise ConflictError(
                "another marm-setup run is writing this package; try again", path=shown
            ) from None
        if os.fstat(fd).st_ino != os.stat(real).st_ino:
            raise ConflictError(
                "another marm-setup run replaced this package meanwhile; try again", path=shown
            )
        finish_interrupted(real)
        yield
    finally:
        os.close(fd)


def switch_package(real: Path, files: dict[str, str | None], keep_orig: set[str], shown: str) -> None:
    """Make `real` hold `files` ({relative path: new text}) and everything else it held.

    `keep_orig` paths keep their current content as `<path>.orig` (hand edits under --force).
    """
    for rel in files:
        _refuse_links(real, rel, shown)
    try:
        stage = Path(tempfile.mkdtemp(prefix=f".{real.name}.marm-setup-", dir=real.parent))
    except OSError:
        _switch_in_place(real, files, keep_orig, shown)
        return
    try:
        _copy_tree(real, stage)
        _write_all(stage, files, keep_orig, shown)
        _exchange(stage, real)
    except BaseException as exc:
        shutil.rmtree(stage, ignore_errors=True)
        if isinstance(exc, OSError) and exc.errno in _NO_EXCHANGE:
            _switch_in_place(real, files, keep_orig, shown)
            return
        raise
    shutil.rmtree(stage, ignore_errors=True)  # the old package now


def _refuse_links(real: Path, rel: str, shown: str) -> None:
    """Refuse a path whose folders or file are symlinks: writing through one can leave the package."""
    current = real
    for part in Path(rel).parts:
        current = current / part
        if current.is_symlink():
            target = os.readlink(current)
            raise InputError(
                f"'{current.relative_to(real)}' is a symlink (to {target}): not written through; "
                "replace it with a real file or folder",
                path=shown,
                element=rel,
            )


def _copy_tree(real: Path, stage: Path) -> None:
    """The current package into `stage`: files hard-linked (copied across devices), links as links."""

    def link_or_copy(src: str, dst: str) -> None:
        try:
            os.link(src, dst, follow_symlinks=False)
        except OSError:
            shutil.copy2(src, dst, follow_symlinks=False)

    def ignore(folder: str, names: list[str]) -> set[str]:  # a killed in-place switch's leftovers
        if Path(folder) != real / STATE_DIR:
            return set()
        return {n for n in names if n.startswith(("stage-", "commit.json"))}

    shutil.copytree(real, stage, symlinks=True, copy_function=link_or_copy, dirs_exist_ok=True, ignore=ignore)


def _write_all(root: Path, files: dict[str, str | None], keep_orig: set[str], shown: str) -> None:
    delay = float(os.environ.get("MARM_SETUP_WRITE_DELAY", "0") or 0)  # a slow disk, for the kill tests
    for rel, text in sorted(files.items()):
        target = root / rel
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            if rel in keep_orig and target.exists():
                os.replace(target, target.with_name(target.name + ".orig"))
            write_new_file(target, text or "")
        except OSError as exc:
            raise InputError(f"cannot write: {exc.strerror or exc}", path=shown, element=rel) from None
        if delay:
            time.sleep(delay)


def write_new_file(path: Path, text: str) -> None:
    """A new inode at `path` (a hard link to the old package is never written into), with the
    mode a plain open() gives: 0666, or 0777 for scripts, less the umask."""
    with contextlib.suppress(FileNotFoundError):
        path.unlink()
    mode = 0o777 if path.suffix in EXECUTABLE_SUFFIXES else 0o666
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, mode)
    with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as handle:
        handle.write(text)


def _exchange(a: Path, b: Path) -> None:
    """Swap two paths atomically (Linux renameat2 RENAME_EXCHANGE)."""
    libc = ctypes.CDLL(None, use_errno=True)
    renameat2 = getattr(libc, "renameat2", None)
    if renameat2 is None:
        raise OSError(errno.ENOSYS, "renameat2 is not available")
    at_fdcwd, rename_exchange = -100, 2
    if renameat2(at_fdcwd, os.fsencode(a), at_fdcwd, os.fsencode(b), rename_exchange) != 0:
        code = ctypes.get_errno()
        raise OSError(code, os.strerror(code))


def _switch_in_place(real: Path, files: dict[str, str | None], keep_orig: set[str], shown: str) -> None:
    """Stage inside the package, record the commit, move each file in, drop the record."""
    (real / STATE_DIR).mkdir(exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix="stage-", dir=real / STATE_DIR))
    try:
        _write_all(stage, files, set(), shown)
        for rel in keep_orig:
            if (real / rel).exists():
                os.link(real / rel, stage / (rel + ".orig"))
        moves = sorted(str(p.relative_to(stage)) for p in stage.rglob("*") if p.is_file())
        record = {"stage": str(stage.relative_to(real)), "files": moves}
        tmp = real / (COMMIT + ".tmp")
        tmp.write_text(json.dumps(record), encoding="utf-8")
        os.replace(tmp, real / COMMIT)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    finish_interrupted(real)


def finish_interrupted(real: Path) -> None:
    """Complete an in-place switch a killed run left (its commit record exists), else drop
    stages and sibling builds it left unfinished."""
    commit = real / COMMIT
    if commit.is_file():
        record = json.loads(commit.read_text(encoding="utf-8"))
        stage = real / record["stage"]
        for rel in record["files"]:
            source = stage / rel
            if source.exists():
                (real / rel).parent.mkdir(parents=True, exist_ok=True)
                os.replace(source, real / rel)
        commit.unlink()
        shutil.rmtree(stage, ignore_errors=True)
    for leftover in (real / STATE_DIR).glob("stage-*"):
        shutil.rmtree(leftover, ignore_errors=True)
    for leftover in real.parent.glob(f".{real.name}.marm-setup-*"):
        shutil.rmtree(leftover, ignore_errors=True)
