"""Write rendered files safely: compare with disk and a hash manifest, then stage and swap in.

`plan_writes` is pure apart from reading the package dir; `apply_writes` is the only writer.
A file we wrote and the user did not touch since (its disk hash equals the manifest's) may be
updated; a file that differs from what we last wrote is a `conflict` and needs `force`, which
keeps the user's version under a free name (`<path>.orig`, else `.orig.1`, `.orig.2`, ...).
A file we wrote that this render no longer produces (init --force switching ros1 <-> ros2) is
removed when it is still as we wrote it (`remove`), else left in place and listed (`stale`).
"""

from __future__ import annotations

import hashlib
import json
import os
import stat
import tempfile
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path, PurePosixPath
from typing import Literal

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.errors import ConflictError, InputError
from marm_setup.render.commit_record import COMMIT, STATE_DIR, pending_files
from marm_setup.render.safe_fs import relative_path_problem
from marm_setup.render.switch import package_lock, switch_package
from marm_setup.templating import RenderedFile
from marm_setup.untrusted import excerpt

MANIFEST = ".marm_setup/manifest.json"
Status = Literal["new", "identical", "update", "conflict", "remove", "stale"]


@dataclass(frozen=True, slots=True)
class FileChange:
    """What writing one rendered file would do: status is new | identical | update | conflict,
    or for a file we wrote that is no longer rendered: remove (unchanged since) | stale (edited).

    `kept_as`: for a conflict, where --force keeps the file on disk (a name no file has).
    """

    path: str
    status: Status
    content: str
    kept_as: str | None = None

    @property
    def writes(self) -> bool:
        return self.status not in ("identical", "stale")


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _encode(content: str) -> bytes:
    return content.encode("utf-8")


@dataclass(frozen=True, slots=True)
class _Disk:
    """The package as its next write sees it: the files an interrupted in-place switch has yet
    to move in (that write moves them first) in place of those they replace."""

    root: Path
    pending: dict[str, Path]

    @classmethod
    def of(cls, root: Path) -> _Disk:
        return cls(root, pending_files(Path(os.path.realpath(root))) if root.is_dir() else {})

    def path(self, rel: str) -> Path:
        return self.pending.get(rel, self.root / rel)

    def taken(self, rel: str) -> bool:
        return rel in self.pending or os.path.lexists(self.root / rel)


def load_manifest(out_dir: Path) -> dict[str, str]:
    """{relative path: sha256} of what we last wrote into out_dir ({} when none or unreadable)."""
    return _read_manifest(_Disk.of(out_dir).path(MANIFEST))


def _read_manifest(path: Path) -> dict[str, str]:
    """The manifest file at `path` as {relative path: sha256} ({} when none or unreadable)."""
    try:
        data = json.loads(bounded_read.read_text(path, bounded_read.JSON_BYTES))
    except (OSError, ValueError, FileTooLarge):
        return {}
    files = data.get("files") if isinstance(data, dict) else None
    if not isinstance(files, dict):
        return {}
    return {str(k): str(v) for k, v in files.items()}


def _manifest_text(files: dict[str, str]) -> str:
    body = {"version": 1, "files": dict(sorted(files.items()))}
    return json.dumps(body, indent=2, sort_keys=False) + "\n"


def _status(path: Path, new: bytes, recorded: str | None) -> Status:
    if not path.is_file():
        return "new"
    try:
        old = bounded_read.read_bytes(path, bounded_read.XML_BYTES)
    except FileTooLarge:  # larger than anything we render: not ours as we wrote it
        return "conflict"
    if old == new:
        return "identical"
    return "update" if recorded is not None and sha256(old) == recorded else "conflict"


def _check_path(rel: str) -> None:
    if relative_path_problem(rel):
        raise InputError("rendered path escapes the package", element=rel)


def plan_writes(
    rendered: Iterable[RenderedFile], out_dir: Path, *, remove_stale: bool = False
) -> list[FileChange]:
    """Compare each rendered file with disk and the manifest; sorted by path. A package an
    interrupted in-place switch left is compared as that switch leaves it. With `remove_stale`
    (init --force), each file the manifest records that is no longer rendered follows, as
    `remove` or `stale` (_leftover_status); a file the manifest does not record is never one."""
    disk = _Disk.of(out_dir)
    manifest = _read_manifest(disk.path(MANIFEST))
    changes = []
    for item in sorted(rendered, key=lambda r: r.path):
        _check_path(item.path)
        status = _status(disk.path(item.path), _encode(item.content), manifest.get(item.path))
        kept = _free_orig_name(disk, item.path) if status == "conflict" else None
        changes.append(FileChange(item.path, status, item.content, kept))
    if remove_stale:
        done = {c.path for c in changes}
        for rel in sorted(p for p in manifest if p not in done and _may_remove(p)):
            leftover = _leftover_status(disk.path(rel), manifest[rel])
            if leftover is not None:
                changes.append(FileChange(rel, leftover, ""))
    return changes


def _may_remove(rel: str) -> bool:
    """A manifest path a removal may name: plain, inside the package, not the writer's state."""
    return relative_path_problem(rel) is None and PurePosixPath(rel).parts[0] != STATE_DIR


def _leftover_status(path: Path, recorded: str | None) -> Status | None:
    """`remove` for a regular file (not a link) whose bytes are what the manifest records we
    wrote, `stale` for any other file there, None when nothing is there."""
    try:
        info = os.lstat(path)
    except OSError:
        return None
    if not stat.S_ISREG(info.st_mode) or info.st_size > bounded_read.XML_BYTES:
        return "stale"
    try:
        data = bounded_read.read_bytes(path, bounded_read.XML_BYTES)
    except (OSError, FileTooLarge):
        return "stale"
    return "remove" if recorded is not None and sha256(data) == recorded else "stale"


def _free_orig_name(disk: _Disk, rel: str) -> str:
    """`<rel>.orig`, or the first of `<rel>.orig.1`, `.orig.2`, ... no file (or link) has yet."""
    name, n = f"{rel}.orig", 0
    while disk.taken(name):
        n += 1
        name = f"{rel}.orig.{n}"
    return name


def stale_files(changes: Iterable[FileChange], out_dir: Path, keep: Iterable[str] = ()) -> list[str]:
    """Files we wrote before (manifest) that this render no longer produces and still exist."""
    current = {c.path for c in changes} | set(keep)
    disk = _Disk.of(out_dir)
    manifest = _read_manifest(disk.path(MANIFEST))
    return sorted(p for p in manifest if p not in current and disk.path(p).is_file())


def conflicts(changes: Iterable[FileChange]) -> list[str]:
    return [c.path for c in changes if c.status == "conflict"]


def _is_fresh(out_dir: Path) -> bool:
    return not out_dir.exists() or (out_dir.is_dir() and not any(out_dir.iterdir()))


def apply_writes(
    changes: list[FileChange], out_dir: Path, *, force: bool = False, require_fresh: bool = False
) -> list[FileChange]:
    """Switch the package to its new version as a whole; returns the changes that wrote something.

    Raises ConflictError (nothing written) when a hand-edited file would be overwritten and
    `force` is false; with `force` the edited file is kept as its `kept_as` name. Under the
    package's lock the disk is compared again with what `changes` was planned from (another run
    may have written meanwhile), and with `require_fresh` (init without --force) the folder must
    still be missing or empty; then the complete new package is swapped in (`render.switch`).
    """
    clashing = conflicts(changes)
    if clashing and not force:
        raise ConflictError(
            f"{len(clashing)} hand-edited file(s) would be overwritten: {', '.join(clashing)} "
            "(use --force to overwrite)",
            path=str(out_dir),
        )
    out_dir = Path(out_dir)
    if not require_fresh and _nothing_to_do(changes, out_dir):
        return []
    shown, real = str(out_dir), Path(os.path.realpath(out_dir))
    try:
        with package_lock(real, shown):
            if require_fresh:
                check_output_dir(real, force=False, shown=shown)
            # the lock completed any interrupted switch: the folder is the disk as it is
            manifest = _read_manifest(real / MANIFEST)
            _recheck(changes, real, manifest, shown)
            disk = _Disk(real, {})
            keep = {
                c.path: c.kept_as or _free_orig_name(disk, c.path) for c in changes if c.status == "conflict"
            }
            remove = [c.path for c in changes if c.status == "remove"]
            switch_package(real, _files_to_write(changes, manifest), keep, shown, remove)
    except OSError as exc:
        raise _write_error(exc, out_dir) from None
    return [c for c in changes if c.writes]


def _files_to_write(changes: list[FileChange], manifest: dict[str, str]) -> dict[str, str | None]:
    """{relative path: text} of the changed files and of the manifest (`manifest`, the one on
    disk, updated) recording every one (a removed file no longer, a stale one still)."""
    manifest = dict(manifest)
    files: dict[str, str | None] = {}
    for change in changes:
        if change.status in ("remove", "stale"):
            if change.status == "remove":
                manifest.pop(change.path, None)
            continue
        manifest[change.path] = sha256(_encode(change.content))
        if change.writes:
            files[change.path] = change.content
    files[MANIFEST] = _manifest_text(manifest)
    return files


def _recheck(changes: list[FileChange], real: Path, manifest: dict[str, str], shown: str) -> None:
    """The disk still is what the changes were planned from (no other run wrote meanwhile)."""
    for change in changes:
        recorded = manifest.get(change.path)
        if change.status in ("remove", "stale"):
            now = _leftover_status(real / change.path, recorded)
        else:
            now = _status(real / change.path, _encode(change.content), recorded)
        taken = change.kept_as is not None and os.path.lexists(real / change.kept_as)
        if now != change.status or taken:
            raise ConflictError(
                f"{change.kept_as if taken else change.path} changed while this run was rendering "
                "(another marm-setup run?): nothing written; run again",
                path=shown,
            )


def _write_error(exc: OSError, out_dir: Path, rel: str | None = None) -> InputError:
    return InputError(f"cannot write: {exc.strerror or exc}", path=str(out_dir), element=rel)


def _nothing_to_do(changes: list[FileChange], out_dir: Path) -> bool:
    """Every file identical and the manifest already records them: leave the disk untouched
    (unless an interrupted switch is to be completed)."""
    if (
        any(c.writes for c in changes)
        or os.path.lexists(out_dir / COMMIT)
        or not (out_dir / MANIFEST).is_file()
    ):
        return False
    manifest = load_manifest(out_dir)
    return all(manifest.get(c.path) == sha256(_encode(c.content)) for c in changes if c.status != "stale")


def check_output_dir(out_dir: Path, *, force: bool, shown: str | None = None) -> None:
    """Refuse an existing non-empty DIR (or a non-directory) unless `force` (for `init`)."""
    shown = shown or str(out_dir)
    if out_dir.exists() and not out_dir.is_dir():
        raise InputError("exists and is not a directory", path=shown)
    above = next((p for p in out_dir.parents if p.exists()), None)
    if above is not None and not above.is_dir():
        raise InputError(f"cannot create it: '{above}' is not a directory", path=shown)
    if not force and not _is_fresh(out_dir):
        raise InputError("directory exists and is not empty (use --force to write into it)", path=shown)


# The word each status prints as in `render` / `init` output (one line per file).
STATUS_WORDS = {"new": "create", "identical": "unchanged", "update": "update", "conflict": "conflict"}
# What a file we wrote that is no longer generated prints after its path (init --force)
LEFTOVER_LINES = {
    "remove": "no longer generated; unchanged since written: removed",
    "stale": "no longer generated; edited by hand since written: left in place",
}


def format_change(change: FileChange, *, forced: bool = False) -> str:
    """`create    config/marm.srdf`: one status line for the CLI; `forced` (a --force write) adds
    where a conflict's hand edit is kept."""
    if change.status in LEFTOVER_LINES:
        return f"{change.status:<10}{change.path} ({LEFTOVER_LINES[change.status]})"
    line = f"{STATUS_WORDS[change.status]:<10}{change.path}"
    if forced and change.status == "conflict" and change.kept_as:
        line += f" (overwritten: --force; yours kept as {change.kept_as})"
    return line


def write_text_atomic(path: Path, text: str, *, shown: str, follow_symlink: bool = False) -> None:
    """Write `text` (UTF-8, newlines as given) to `path` through a temporary file.

    A symlink at `path` is refused (InputError): marm-setup writes through no link it did not
    create (a package may ship one leading anywhere); `follow_symlink` (an SRDF the user named to
    update in place) replaces its target and keeps the link. The file keeps its mode, and a new
    file gets the mode a plain open() would give (0666 less the umask).
    """
    if not follow_symlink and os.path.islink(path):
        raise InputError(
            f"is a symlink (to {excerpt(os.readlink(path))}): not written through (marm-setup writes through no "
            "link it did not create); remove it or choose another file",
            path=shown,
        )
    path, tmp = Path(os.path.realpath(path) if follow_symlink else os.path.abspath(path)), None
    try:
        if path.is_dir():
            raise IsADirectoryError(21, "is a folder")
        path.parent.mkdir(parents=True, exist_ok=True)
        mode = file_mode(path)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
        with os.fdopen(fd, "wb") as out:
            os.fchmod(out.fileno(), mode)
            out.write(text.encode("utf-8"))
        os.replace(tmp, path)  # replaces a link put there meanwhile, never its target
    except OSError as exc:
        if tmp is not None:
            Path(tmp).unlink(missing_ok=True)
        raise InputError(f"cannot write: {exc.strerror or exc}", path=shown) from None


def file_mode(path: Path, *, executable: bool = False) -> int:
    """The mode `path` has (when it exists), else the one a plain open() gives a new file."""
    try:
        return stat.S_IMODE(path.stat().st_mode)
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return (0o777 if executable else 0o666) & ~umask
