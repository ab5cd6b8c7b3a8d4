"""Write rendered files safely: compare with disk and a hash manifest, then stage and swap in.

`plan_writes` is pure apart from reading the package dir; `apply_writes` is the only writer.
A file we wrote and the user did not touch since (its disk hash equals the manifest's) may be
updated; a file that differs from what we last wrote is a `conflict` and needs `force`.
"""

from __future__ import annotations

import hashlib
import json
import os
import stat
import tempfile
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Literal

from marm_setup.errors import ConflictError, InputError
from marm_setup.render.switch import package_lock, switch_package
from marm_setup.templating import RenderedFile

MANIFEST = ".marm_setup/manifest.json"
Status = Literal["new", "identical", "update", "conflict"]


@dataclass(frozen=True, slots=True)
class FileChange:
    """What writing one rendered file would do: status is new | identical | update | conflict."""

    path: str
    status: Status
    content: str

    @property
    def writes(self) -> bool:
        return self.status != "identical"


def sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def _encode(content: str) -> bytes:
    return content.encode("utf-8")


def load_manifest(out_dir: Path) -> dict[str, str]:
    """{relative path: sha256} of what we last wrote into out_dir ({} when none or unreadable)."""
    path = out_dir / MANIFEST
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError):
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
    old = path.read_bytes()
    if old == new:
        return "identical"
    return "update" if recorded is not None and sha256(old) == recorded else "conflict"


def _check_path(rel: str) -> None:
    parts = Path(rel).parts
    if not parts or Path(rel).is_absolute() or ".." in parts:
        raise InputError("rendered path escapes the package", element=rel)


def plan_writes(rendered: Iterable[RenderedFile], out_dir: Path) -> list[FileChange]:
    """Compare each rendered file with disk and the manifest; sorted by path."""
    manifest = load_manifest(out_dir)
    changes = []
    for item in sorted(rendered, key=lambda r: r.path):
        _check_path(item.path)
        status = _status(out_dir / item.path, _encode(item.content), manifest.get(item.path))
        changes.append(FileChange(item.path, status, item.content))
    return changes


def stale_files(changes: Iterable[FileChange], out_dir: Path, keep: Iterable[str] = ()) -> list[str]:
    """Files we wrote before (manifest) that this render no longer produces and still exist."""
    current = {c.path for c in changes} | set(keep)
    return sorted(p for p in load_manifest(out_dir) if p not in current and (out_dir / p).is_file())


def conflicts(changes: Iterable[FileChange]) -> list[str]:
    return [c.path for c in changes if c.status == "conflict"]


def _is_fresh(out_dir: Path) -> bool:
    return not out_dir.exists() or (out_dir.is_dir() and not any(out_dir.iterdir()))


def apply_writes(changes: list[FileChange], out_dir: Path, *, force: bool = False) -> list[FileChange]:
    """Switch the package to its new version as a whole; returns the changes that wrote something.

    Raises ConflictError (nothing written) when a hand-edited file would be overwritten and
    `force` is false; with `force` the edited file is kept as `<path>.orig`. Under the package's
    lock the disk is compared again with what `changes` was planned from (another run may have
    written meanwhile), then the complete new package is swapped in (`render.switch`).
    """
    clashing = conflicts(changes)
    if clashing and not force:
        raise ConflictError(
            f"{len(clashing)} hand-edited file(s) would be overwritten: {', '.join(clashing)} "
            "(use --force to overwrite)",
            path=str(out_dir),
        )
    out_dir = Path(out_dir)
    if _nothing_to_do(changes, out_dir):
        return []
    shown, real = str(out_dir), Path(os.path.realpath(out_dir))
    try:
        with package_lock(real, shown):
            _recheck(changes, real, shown)
            manifest = {} if _is_fresh(real) else load_manifest(real)
            files: dict[str, str | None] = {}
            for change in changes:
                manifest[change.path] = sha256(_encode(change.content))
                if change.writes:
                    files[change.path] = change.content
            files[MANIFEST] = _manifest_text(manifest)
            switch_package(real, files, set(conflicts(changes)), shown)
    except OSError as exc:
        raise _write_error(exc, out_dir) from None
    return [c for c in changes if c.writes]


def _recheck(changes: list[FileChange], real: Path, shown: str) -> None:
    """The disk still is what the changes were planned from (no other run wrote meanwhile)."""
    manifest = load_manifest(real)
    for change in changes:
        if _status(real / change.path, _encode(change.content), manifest.get(change.path)) != change.status:
            raise ConflictError(
                f"{change.path} changed while this run was rendering (another marm-setup run?): "
                "nothing written; run again",
                path=shown,
            )


def _write_error(exc: OSError, out_dir: Path, rel: str | None = None) -> InputError:
    return InputError(f"cannot write: {exc.strerror or exc}", path=str(out_dir), element=rel)


def _nothing_to_do(changes: list[FileChange], out_dir: Path) -> bool:
    """Every file identical and the manifest already records them: leave the disk untouched."""
    if any(c.writes for c in changes) or not (out_dir / MANIFEST).is_file():
        return False
    manifest = load_manifest(out_dir)
    return all(manifest.get(c.path) == sha256(_encode(c.content)) for c in changes)


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


def format_change(change: FileChange) -> str:
    """`create    config/marm.srdf`: one status line for the CLI."""
    return f"{STATUS_WORDS[change.status]:<10}{change.path}"


def write_text_atomic(path: Path, text: str, *, shown: str) -> None:
    """Write `text` (UTF-8, newlines as given) to `path` through a temporary file.

    A symlink is followed (its target is replaced, the link stays); the file keeps its mode, and
    a new file gets the mode a plain open() would give (0666 less the umask).
    """
    path, tmp = Path(os.path.realpath(path)), None
    try:
        if path.is_dir():
            raise IsADirectoryError(21, "is a folder")
        path.parent.mkdir(parents=True, exist_ok=True)
        mode = file_mode(path)
        fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.")
        with os.fdopen(fd, "wb") as out:
            os.fchmod(out.fileno(), mode)
            out.write(text.encode("utf-8"))
        os.replace(tmp, path)
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
