"""Switch a package to its new version as a whole: lock, stage the complete new tree, swap.

The new package is built next to the old one (unchanged files hard-linked, changed ones written
fresh, never through a link) and exchanged with it in one `renameat2(RENAME_EXCHANGE)`: a run
killed at any point leaves the old package or the new one. Where the package folder cannot be
renamed (a mount point, a read-only parent, a file system without the exchange) or holds a mount
point, the changed files are staged inside the package and moved in one by one under a commit
record; a run killed then is completed by the next write (roll forward). Nothing on another file
system is ever deleted or moved, and nothing is written or removed through a symlink.
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import fcntl
import json
import os
import re
import shutil
import stat
import tempfile
import time
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path

from marm_setup.errors import ConflictError, InputError
from marm_setup.render.commit_record import (
    COMMIT,
    STAGE_PREFIX,
    STATE_DIR,
    TEMP_NAME,
    read_commit,
    refuse_linked_state,
)
from marm_setup.render.file_owners import copy_folder_owners, regular_file_info, same_owner_and_mode
from marm_setup.render.safe_fs import (
    mount_points_below,
    pinned_on_the_way,
    pinned_paths,
    remove_tree,
    unsafe_path,
)
from marm_setup.render.stage_folders import drop_recorded_stages, drop_stage, new_stage

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
        finish_interrupted(real, shown)
        yield
    finally:
        os.close(fd)


def switch_package(
    real: Path, files: dict[str, str | None], keep: dict[str, str], shown: str, remove: Sequence[str] = ()
) -> None:
    """Make `real` hold `files` ({relative path: new text}) and everything else it held but the
    files `remove` names (a folder they leave empty goes with them).

    `keep` maps a hand-edited path (--force) to the free name its current content is kept as.
    """
    mounts, pinned = mount_points_below(real), pinned_paths(real)
    for rel in [*files, *keep.values(), *remove]:
        reason = unsafe_path(real, rel, mounts) or _pinned_reason(rel, pinned)
        if reason:
            raise InputError(reason, path=shown, element=rel)
    if mounts or pinned or holds_a_working_folder(real):  # the old tree stays: a mount, a flag, a shell
        _switch_in_place(real, files, keep, shown, remove)
        return
    try:
        stage = new_stage(real)
    except OSError:
        _switch_in_place(real, files, keep, shown, remove)
        return
    try:
        _copy_tree(real, stage)
        _write_all(stage, files, keep, shown, real)
        remove_files(stage, remove)
        _exchange(stage, real)
    except BaseException as exc:
        drop_stage(stage)
        if isinstance(exc, OSError) and exc.errno in _NO_EXCHANGE:
            _switch_in_place(real, files, keep, shown, remove)
            return
        raise
    drop_stage(stage)  # the old package now


def remove_files(root: Path, remove: Iterable[str]) -> None:
    """Unlink each regular file `remove` names below `root` (a link or a folder there is left
    alone), then each folder on its way that this left empty (never `root`, nor a shell's folder)."""
    for rel in remove:
        path = root / rel
        with contextlib.suppress(OSError):
            if not stat.S_ISREG(os.lstat(path).st_mode):
                continue
            path.unlink()
        for folder in path.parents:
            if folder == root or root not in folder.parents or holds_a_working_folder(folder):
                break
            try:
                folder.rmdir()  # only an empty folder
            except OSError:
                break


def _pinned_reason(rel: str, pinned: set[str]) -> str | None:
    """Why `rel` cannot be written: an immutable or append-only file or folder on the way."""
    found = pinned_on_the_way(rel, pinned)
    if found is None:
        return None
    what = "the package folder" if found == "." else f"'{found}'"
    return f"{what} is immutable or append-only (chattr +i, +a): nothing written; clear the flag to write it"


def holds_a_working_folder(real: Path) -> bool:
    """Whether `real` is or holds the current folder of this process or of the one that ran it
    (the shell of `render .`): swapping a new folder in would leave that one in a deleted folder."""
    for link in ("/proc/self/cwd", f"/proc/{os.getppid()}/cwd"):
        try:
            folder = Path(os.readlink(link))
        except OSError:
            continue
        if folder == real or real in folder.parents:
            return True
    return False


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
        return {n for n in names if n.startswith((STAGE_PREFIX, "commit.json"))}

    shutil.copytree(real, stage, symlinks=True, copy_function=link_or_copy, dirs_exist_ok=True, ignore=ignore)
    copy_folder_owners(real, stage)


def _write_all(
    root: Path, files: dict[str, str | None], keep: dict[str, str], shown: str, package: Path
) -> None:
    """Write `files` below `root`; a file `package` has already keeps its owner, group and mode."""
    delay = float(os.environ.get("MARM_SETUP_WRITE_DELAY", "0") or 0)  # a slow disk, for the kill tests
    for rel, text in sorted(files.items()):
        target = root / rel
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            if rel in keep and target.exists():
                os.link(target, root / keep[rel], follow_symlinks=False)  # EEXIST: never over a file
            write_new_file(target, text or "", like=regular_file_info(package / rel))
        except OSError as exc:
            raise InputError(f"cannot write: {exc.strerror or exc}", path=shown, element=rel) from None
        if delay:
            time.sleep(delay)


def write_new_file(path: Path, text: str, like: os.stat_result | None = None) -> None:
    """A new inode at `path` (a hard link to the old package is never written into), with the
    owner, group and mode of the file it replaces (`like`), else the mode a plain open() gives:
    0666, or 0777 for scripts, less the umask."""
    with contextlib.suppress(FileNotFoundError):
        path.unlink()
    mode = 0o777 if path.suffix in EXECUTABLE_SUFFIXES else 0o666
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL, mode)
    if like is not None:
        same_owner_and_mode(like, fd)
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


def _switch_in_place(
    real: Path, files: dict[str, str | None], keep: dict[str, str], shown: str, remove: Sequence[str] = ()
) -> None:
    """Stage inside the package, record the commit (with the files to remove), move each file
    in, remove those, drop the record."""
    (real / STATE_DIR).mkdir(exist_ok=True)
    refuse_linked_state(real, shown)
    stage = Path(tempfile.mkdtemp(prefix=STAGE_PREFIX, dir=real / STATE_DIR))
    try:
        _write_all(stage, files, {}, shown, real)
        for rel, kept in keep.items():
            if (real / rel).exists():
                os.link(real / rel, stage / kept, follow_symlinks=False)
        moves = sorted(str(p.relative_to(stage)) for p in stage.rglob("*") if p.is_file())
        record = {"stage": str(stage.relative_to(real)), "files": moves, "remove": sorted(remove)}
        tmp = real / (COMMIT + ".tmp")
        write_new_file(tmp, json.dumps(record))  # a new file: never written through a link
        os.replace(tmp, real / COMMIT)
    except BaseException:
        remove_tree(stage)
        raise
    finish_interrupted(real, shown)


def finish_interrupted(real: Path, shown: str | None = None) -> None:
    """Complete an in-place switch a killed run left (its commit record exists), else drop the
    stages it left unfinished in the package's own state folder and the recorded builds beside
    it (render.stage_folders). A record this writer did not write (its stage not our staging
    folder, a file outside the package) is refused, and nothing touched."""
    shown = shown or str(real)
    record = read_commit(real, shown)
    if record is not None:
        stage, moves, removals = record
        for rel in moves:
            source = stage / rel
            if os.path.lexists(source):
                (real / rel).parent.mkdir(parents=True, exist_ok=True)
                os.replace(source, real / rel)
        remove_files(real, removals)
        (real / COMMIT).unlink()
        remove_tree(stage)
    _drop_leftovers(real / STATE_DIR, STAGE_PREFIX + TEMP_NAME)
    drop_recorded_stages(real)


def _drop_leftovers(folder: Path, pattern: str) -> None:
    """Remove the folders in `folder` whose whole name matches `pattern` (an unlistable folder: none)."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if re.fullmatch(pattern, name):
            remove_tree(folder / name)
