"""File system moves that never leave a package: paths without symlinks or mount points on the
way, the mount points below a folder, and a tree removal that stays on its own file system."""

from __future__ import annotations

import contextlib
import fcntl
import os
import re
import stat
import struct
from pathlib import Path, PurePosixPath

_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW


def relative_path_problem(rel: str) -> str | None:
    """Why `rel` is not a plain relative path inside a folder (empty, '.', a NUL, absolute, not
    normalised, or a '..' part), else None."""
    path = PurePosixPath(rel)
    if (
        not rel
        or "\0" in rel
        or path.is_absolute()
        or str(path) != rel
        or not path.parts
        or ".." in path.parts
    ):
        return "not a plain relative path inside the package"
    return None


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
    found = {m for m in mount_table() if root in m.parents}
    dev = os.lstat(root).st_dev
    for folder, dirs, _files in os.walk(root):
        for name in list(dirs):
            path = Path(folder) / name
            with contextlib.suppress(OSError):
                if path in found or os.lstat(path).st_dev != dev:
                    found.add(path)
                    dirs.remove(name)
    return found


def mount_table() -> set[Path]:
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
        dev, table = os.fstat(fd).st_dev, mount_table()
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


_FS_IOC_GETFLAGS = 0x80086601  # linux/fs.h _IOR('f', 1, long)
_PINNED_FLAGS = 0x10 | 0x20  # FS_IMMUTABLE_FL, FS_APPEND_FL (chattr +i, +a)


def pinned_paths(root: Path) -> set[str]:
    """Relative paths ('.' for `root`) of the folders and files below `root` (on its file system,
    not through symlinks) that are immutable or append-only: nobody, root included, may replace,
    rename or delete them, nor add to or remove from such a folder."""
    found = set()
    dev = os.lstat(root).st_dev
    for folder, dirs, files in os.walk(root):
        dirs[:] = [d for d in dirs if os.lstat(Path(folder) / d).st_dev == dev]
        for path in (Path(folder), *(Path(folder) / f for f in files)):
            if _pinned(path):
                found.add(path.relative_to(root).as_posix())
    return found


def _pinned(path: Path) -> bool:
    """Whether the folder or regular file `path` has the immutable or append-only flag (False
    where the file system has no such flags, or for anything else)."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK)
    except OSError:
        return False
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode) and not stat.S_ISDIR(os.fstat(fd).st_mode):
            return False
        flags = struct.unpack("l", fcntl.ioctl(fd, _FS_IOC_GETFLAGS, bytes(8)))[0]
    except OSError:
        return False
    finally:
        os.close(fd)
    return bool(flags & _PINNED_FLAGS)


def pinned_on_the_way(rel: str, pinned: set[str]) -> str | None:
    """The pinned path (see `pinned_paths`) that writing `rel` would have to change: the file
    itself or a folder holding it; None when there is none."""
    path = PurePosixPath(rel)
    for candidate in (path, *path.parents):
        if candidate.as_posix() in pinned:
            return candidate.as_posix()
    return None
