"""Who owns a package's files: a write (as root on another user's package, say) gives the new
version of each folder and file the package had the owner, group and permission bits of the old
one, setgid included. New folders and files are made as the kernel makes them (the writing
user, the group of a setgid folder, the umask)."""

from __future__ import annotations

import contextlib
import errno
import os
import stat
from pathlib import Path

_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW


def same_owner_and_mode(info: os.stat_result, fd: int) -> None:
    """Give the open file or folder `fd` the owner, group and mode bits of `info` (the owner as
    far as we may: only root gives a file away). The owner first: chown may clear setgid."""
    try:
        os.fchown(fd, info.st_uid, info.st_gid)
    except OSError as exc:
        if exc.errno != errno.EPERM:
            raise
        with contextlib.suppress(OSError):  # a group of ours, at least
            os.fchown(fd, -1, info.st_gid)
    os.fchmod(fd, stat.S_IMODE(info.st_mode))


def copy_folder_owners(source: Path, copy: Path) -> None:
    """Each folder of the tree `copy` that `source` has at the same place gets the owner, group
    and mode of that folder (shutil.copytree copies the mode alone); symlinks are not followed."""
    for folder, _dirs, _files in os.walk(source):
        target = copy / Path(folder).relative_to(source)
        try:
            info = os.lstat(folder)
            fd = os.open(target, _DIR_FLAGS)
        except OSError:  # not copied (a leftover the copy skips) or not a folder there
            continue
        try:
            same_owner_and_mode(info, fd)
        finally:
            os.close(fd)


def regular_file_info(path: Path) -> os.stat_result | None:
    """`lstat(path)` when it is a regular file (whose owner a new version keeps), else None."""
    try:
        info = os.lstat(path)
    except OSError:
        return None
    return info if stat.S_ISREG(info.st_mode) else None
