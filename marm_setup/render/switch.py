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
from collections.abc import Iterator
from pathlib import Path, PurePosixPath

from marm_setup.errors import ConflictError, InputError

STATE_DIR = ".marm_setup"
COMMIT = f"{STATE_DIR}/commit.json"
STAGE_PREFIX = "stage-"
EXECUTABLE_SUFFIXES = (".py", ".sh")
_NO_EXCHANGE = {errno.EBUSY, errno.EXDEV, errno.EINVAL, errno.ENOSYS, errno.EPERM, errno.EACCES, errno.EROFS}
_TEMP_NAME = "[a-z0-9_]+"  # what tempfile.mkdtemp appends to a prefix
_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW


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


def switch_package(real: Path, files: dict[str, str | None], keep: dict[str, str], shown: str) -> None:
    """Make `real` hold `files` ({relative path: new text}) and everything else it held.

    `keep` maps a hand-edited path (--force) to the free name its current content is kept as.
    """
    mounts = mount_points_below(real)
    for rel in [*files, *keep.values()]:
        reason = unsafe_path(real, rel, mounts)
        if reason:
            raise InputError(reason, path=shown, element=rel)
    if mounts:  # the old tree could not be dropped without reaching into them
        _switch_in_place(real, files, keep, shown)
        return
    try:
        stage = Path(tempfile.mkdtemp(prefix=f".{real.name}.marm-setup-", dir=real.parent))
    except OSError:
        _switch_in_place(real, files, keep, shown)
        return
    try:
        _copy_tree(real, stage)
        _write_all(stage, files, keep, shown)
        _exchange(stage, real)
    except BaseException as exc:
        remove_tree(stage)
        if isinstance(exc, OSError) and exc.errno in _NO_EXCHANGE:
            _switch_in_place(real, files, keep, shown)
            return
        raise
    remove_tree(stage)  # the old package now


def unsafe_path(root: Path, rel: str, mounts: set[Path]) -> str | None:
    """Why writing `root/rel` could leave `root` (a symlink or a mount point on the way), else None."""
    current, dev = root, os.lstat(root).st_dev
    for part in PurePosixPath(rel).parts:
        current = current / part
        try:
            info = os.lstat(current)
        except OSError:  # missing (created by the write) or below a file (the write says so)
            return None
        where = current.relative_to(root)
        if stat.S_ISLNK(info.st_mode):
            return (
                f"'{where}' is a symlink (to {os.readlink(current)}): not written through; "
                "replace it with a real file or folder"
            )
        if info.st_dev != dev or current in mounts:
            return f"'{where}' is a mount point (another file system): not written into"
    return None


def mount_points_below(root: Path) -> set[Path]:
    """Mount points strictly inside the folder `root` (a real path): /proc/self/mountinfo's,
    and folders whose device differs from `root`'s (where /proc is missing)."""
    found = {m for m in _mount_table() if root in m.parents}
    dev = os.lstat(root).st_dev
    for folder, dirs, _files in os.walk(root):
        for name in list(dirs):
            path = Path(folder) / name
            with contextlib.suppress(OSError):
                if path in found or os.lstat(path).st_dev != dev:
                    found.add(path)
                    dirs.remove(name)
    return found


def _mount_table() -> set[Path]:
    """Every mount point of this mount namespace (empty when /proc is not mounted)."""
    try:
        lines = Path("/proc/self/mountinfo").read_bytes().splitlines()
    except OSError:
        return set()
    unescape = re.compile(rb"\\([0-7]{3})")  # mountinfo writes space, tab, newline, \ as \ooo
    points = set()
    for line in lines:
        fields = line.split()
        if len(fields) > 4:
            points.add(Path(os.fsdecode(unescape.sub(lambda m: bytes([int(m[1], 8)]), fields[4]))))
    return points


def remove_tree(path: Path) -> None:
    """Delete the folder `path` and what it holds, on its own file system only: never through a
    symlink and never into a mount point (those, and what cannot be deleted, stay)."""
    try:
        fd = os.open(path, _DIR_FLAGS)
    except OSError:  # gone, a symlink or not a folder: not ours to delete
        return
    try:
        dev, table = os.fstat(fd).st_dev, _mount_table()
        if os.lstat(path.parent).st_dev != dev or path in table:
            return
        _empty_folder(fd, path, dev, {m for m in table if path in m.parents})
    finally:
        os.close(fd)
    with contextlib.suppress(OSError):
        os.rmdir(path)


def _empty_folder(fd: int, path: Path, dev: int, mounts: set[Path]) -> None:
    """Delete what the open folder `fd` (at `path`) holds on device `dev`, outside `mounts`."""
    with os.scandir(fd) as entries:
        names = [(e.name, e.is_dir(follow_symlinks=False)) for e in entries]
    for name, is_dir in names:
        with contextlib.suppress(OSError):
            if not is_dir:
                os.unlink(name, dir_fd=fd)
                continue
            if path / name in mounts:
                continue
            child = os.open(name, _DIR_FLAGS, dir_fd=fd)
            try:
                if os.fstat(child).st_dev != dev:
                    continue
                _empty_folder(child, path / name, dev, mounts)
            finally:
                os.close(child)
            os.rmdir(name, dir_fd=fd)


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


def _write_all(root: Path, files: dict[str, str | None], keep: dict[str, str], shown: str) -> None:
    delay = float(os.environ.get("MARM_SETUP_WRITE_DELAY", "0") or 0)  # a slow disk, for the kill tests
    for rel, text in sorted(files.items()):
        target = root / rel
        try:
            target.parent.mkdir(parents=True, exist_ok=True)
            if rel in keep and target.exists():
                os.link(target, root / keep[rel], follow_symlinks=False)  # EEXIST: never over a file
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


def _switch_in_place(real: Path, files: dict[str, str | None], keep: dict[str, str], shown: str) -> None:
    """Stage inside the package, record the commit, move each file in, drop the record."""
    (real / STATE_DIR).mkdir(exist_ok=True)
    _refuse_linked_state(real, shown)
    stage = Path(tempfile.mkdtemp(prefix=STAGE_PREFIX, dir=real / STATE_DIR))
    try:
        _write_all(stage, files, {}, shown)
        for rel, kept in keep.items():
            if (real / rel).exists():
                os.link(real / rel, stage / kept, follow_symlinks=False)
        moves = sorted(str(p.relative_to(stage)) for p in stage.rglob("*") if p.is_file())
        record = {"stage": str(stage.relative_to(real)), "files": moves}
        tmp = real / (COMMIT + ".tmp")
        write_new_file(tmp, json.dumps(record))  # a new file: never written through a link
        os.replace(tmp, real / COMMIT)
    except BaseException:
        remove_tree(stage)
        raise
    finish_interrupted(real, shown)


def finish_interrupted(real: Path, shown: str | None = None) -> None:
    """Complete an in-place switch a killed run left (its commit record exists), else drop
    stages and sibling builds it left unfinished. A record this writer did not write (its stage
    not our staging folder, a file outside the package) is refused, and nothing touched."""
    shown = shown or str(real)
    record = read_commit(real, shown)
    if record is not None:
        stage, moves = record
        for rel in moves:
            source = stage / rel
            if os.path.lexists(source):
                (real / rel).parent.mkdir(parents=True, exist_ok=True)
                os.replace(source, real / rel)
        (real / COMMIT).unlink()
        remove_tree(stage)
    _drop_leftovers(real / STATE_DIR, STAGE_PREFIX + _TEMP_NAME)
    _drop_leftovers(real.parent, re.escape(f".{real.name}.marm-setup-") + _TEMP_NAME)


def _drop_leftovers(folder: Path, pattern: str) -> None:
    """Remove the folders in `folder` whose whole name matches `pattern` (an unlistable folder: none)."""
    try:
        names = os.listdir(folder)
    except OSError:
        return
    for name in names:
        if re.fullmatch(pattern, name):
            remove_tree(folder / name)


def _refuse_linked_state(real: Path, shown: str) -> None:
    """`.marm_setup` must be a real folder: stages and records are never kept through a link."""
    state = real / STATE_DIR
    if state.is_symlink():
        raise InputError(
            f"'{STATE_DIR}' is a symlink (to {os.readlink(state)}): not written through; "
            "replace it with a real folder",
            path=shown,
            element=STATE_DIR,
        )


def read_commit(real: Path, shown: str) -> tuple[Path, list[str]] | None:
    """(stage, files) of the package's commit record, None when there is none; a record whose
    stage is not one of our staging folders or whose files leave the package is an InputError."""
    _refuse_linked_state(real, shown)
    commit = real / COMMIT
    if not os.path.lexists(commit):
        return None
    record, problem = _parse_record(commit)
    problem = problem or _record_problem(real, record)
    if problem:
        element, what = problem
        raise InputError(
            f"{what}; not a commit record marm-setup wrote, nothing done "
            "(delete this file to write the package)",
            path=f"{shown}/{COMMIT}",
            element=element,
        )
    return real / record["stage"], record["files"]


def pending_files(real: Path) -> dict[str, Path]:
    """{relative path: staged file} an interrupted in-place switch has yet to move in (the next
    write does so first); {} without a record, or with one the next write refuses."""
    try:
        record = read_commit(real, str(real))
    except (InputError, OSError):
        return {}
    if record is None:
        return {}
    stage, moves = record
    return {rel: stage / rel for rel in moves if os.path.lexists(stage / rel)}


Problem = tuple[str | None, str]  # (the record's element or None for the whole file, what is wrong)


def _parse_record(commit: Path) -> tuple[dict, Problem | None]:
    """The record as JSON with a string `stage` and a list of string `files`, or what it lacks."""
    if not stat.S_ISREG(os.lstat(commit).st_mode):
        return {}, (None, "not a regular file")
    try:
        record = json.loads(commit.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        return {}, (None, f"unreadable ({exc})")
    if not isinstance(record, dict) or not isinstance(record.get("stage"), str):
        return {}, ("stage", "missing or not a string")
    moves = record.get("files")
    if not isinstance(moves, list) or not all(isinstance(m, str) for m in moves):
        return {}, ("files", "missing or not a list of paths")
    return record, None


def _record_problem(real: Path, record: dict) -> Problem | None:
    """What makes a parsed record unsafe to replay: its stage, or a file that leaves the package."""
    why = _bad_stage(real, record["stage"])
    if why:
        return "stage", f"'{record['stage']}' {why}"
    stage, mounts = real / record["stage"], mount_points_below(real)
    for rel in record["files"]:
        why = _bad_move(rel) or unsafe_path(real, rel, mounts) or _bad_source(stage, rel, mounts)
        if why:
            return "files", f"'{rel}': {why}"
    return None


def _bad_stage(real: Path, name: str) -> str | None:
    """Why `name` is not a staging folder _switch_in_place makes (a real folder
    `.marm_setup/stage-*` on the package's file system), else None."""
    if not re.fullmatch(re.escape(f"{STATE_DIR}/{STAGE_PREFIX}") + _TEMP_NAME, name):
        return f"is not a staging folder ({STATE_DIR}/{STAGE_PREFIX}...)"
    try:
        info = os.lstat(real / name)
    except FileNotFoundError:
        return None  # already dropped: nothing left to move
    if not stat.S_ISDIR(info.st_mode):
        return "is not a folder (a symlink?)"
    if info.st_dev != os.lstat(real).st_dev or (real / name) in _mount_table():
        return "is a mount point (another file system)"
    return None


def _bad_move(rel: str) -> str | None:
    """Why `rel` is not a plain relative path to a generated file, else None."""
    path = PurePosixPath(rel)
    if not rel or "\0" in rel or path.is_absolute() or str(path) != rel or ".." in path.parts:
        return "not a plain relative path inside the package"
    if path.parts[0] == STATE_DIR and rel != f"{STATE_DIR}/manifest.json":
        return "the writer's own state"
    return None


def _bad_source(stage: Path, rel: str, mounts: set[Path]) -> str | None:
    """Why `stage/rel` is not a staged file to move in (missing is fine: moved already), else None."""
    if not os.path.lexists(stage):
        return None
    why = unsafe_path(stage, rel, mounts)
    if why or not os.path.lexists(stage / rel):
        return why
    return None if stat.S_ISREG(os.lstat(stage / rel).st_mode) else "not a file in the stage"
