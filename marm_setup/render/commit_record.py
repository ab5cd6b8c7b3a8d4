"""The commit record of an in-place switch (`.marm_setup/commit.json`): written before staged
files move in, so a killed write is completed by the next one. A record is replayed only when it
is one the writer could have written: its stage a real `.marm_setup/stage-*` folder on the
package's file system, its files (and those it removes) plain relative paths with no symlink or
mount point on the way."""

from __future__ import annotations

import json
import os
import re
import stat
from pathlib import Path, PurePosixPath

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.errors import InputError
from marm_setup.render.safe_fs import mount_points_below, mount_table, relative_path_problem, unsafe_path

STATE_DIR = ".marm_setup"
COMMIT = f"{STATE_DIR}/commit.json"
STAGE_PREFIX = "stage-"
TEMP_NAME = "[a-z0-9_]+"  # what tempfile.mkdtemp appends to a prefix


def refuse_linked_state(real: Path, shown: str) -> None:
    """`.marm_setup` must be a real folder: stages and records are never kept through a link."""
    state = real / STATE_DIR
    if state.is_symlink():
        raise InputError(
            f"'{STATE_DIR}' is a symlink (to {os.readlink(state)}): not written through; "
            "replace it with a real folder",
            path=shown,
            element=STATE_DIR,
        )


def read_commit(real: Path, shown: str) -> tuple[Path, list[str], list[str]] | None:
    """(stage, files, files to remove) of the package's commit record, None when there is none;
    a record whose stage is not one of our staging folders or whose files leave the package is an
    InputError."""
    refuse_linked_state(real, shown)
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
    return real / record["stage"], record["files"], record.get("remove", [])


def pending_files(real: Path) -> dict[str, Path]:
    """{relative path: staged file} an interrupted in-place switch has yet to move in (the next
    write does so first); {} without a record, or with one the next write refuses."""
    try:
        record = read_commit(real, str(real))
    except (InputError, OSError):
        return {}
    if record is None:
        return {}
    stage, moves, _removals = record
    return {rel: stage / rel for rel in moves if os.path.lexists(stage / rel)}


Problem = tuple[str | None, str]  # (the record's element or None for the whole file, what is wrong)


def _parse_record(commit: Path) -> tuple[dict, Problem | None]:
    """The record as JSON with a string `stage` and a list of string `files`, or what it lacks."""
    if not stat.S_ISREG(os.lstat(commit).st_mode):
        return {}, (None, "not a regular file")
    try:
        record = json.loads(bounded_read.read_text(commit, bounded_read.JSON_BYTES))
    except (OSError, ValueError, FileTooLarge) as exc:
        return {}, (None, f"unreadable ({exc})")
    if not isinstance(record, dict) or not isinstance(record.get("stage"), str):
        return {}, ("stage", "missing or not a string")
    moves = record.get("files")
    if not isinstance(moves, list) or not all(isinstance(m, str) for m in moves):
        return {}, ("files", "missing or not a list of paths")
    removals = record.get("remove", [])
    if not isinstance(removals, list) or not all(isinstance(m, str) for m in removals):
        return {}, ("remove", "not a list of paths")
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
    for rel in record.get("remove", []):
        why = _bad_move(rel) or unsafe_path(real, rel, mounts)
        if why:
            return "remove", f"'{rel}': {why}"
    return None


def _bad_stage(real: Path, name: str) -> str | None:
    """Why `name` is not a staging folder _switch_in_place makes (a real folder
    `.marm_setup/stage-*` on the package's file system), else None."""
    if not re.fullmatch(re.escape(f"{STATE_DIR}/{STAGE_PREFIX}") + TEMP_NAME, name):
        return f"is not a staging folder ({STATE_DIR}/{STAGE_PREFIX}...)"
    try:
        info = os.lstat(real / name)
    except FileNotFoundError:
        return None  # already dropped: nothing left to move
    if not stat.S_ISDIR(info.st_mode):
        return "is not a folder (a symlink?)"
    if info.st_dev != os.lstat(real).st_dev or (real / name) in mount_table():
        return "is a mount point (another file system)"
    return None


def _bad_move(rel: str) -> str | None:
    """Why `rel` is not a plain relative path to a generated file, else None."""
    problem = relative_path_problem(rel)
    if problem:
        return problem
    if PurePosixPath(rel).parts[0] == STATE_DIR and rel != f"{STATE_DIR}/manifest.json":
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
