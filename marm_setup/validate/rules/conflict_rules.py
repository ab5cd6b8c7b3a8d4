"""Git merge-conflict markers left in a package's files: `<<<<<<< ours`, `=======`, `>>>>>>> theirs`
at the start of a line, as `git merge` writes them and `git diff --check` looks for them.

Rule `file.merge-conflict`, one finding per file at its first marker line:
- error in a file ROS or MoveIt parses (launch files, SRDF, URDF, xacro, YAML, package.xml,
  CMakeLists.txt, Python launch files, .setup_assistant, RViz configs): a marker line is
  malformed there, and the whole file fails: roslaunch raises "Invalid roslaunch XML syntax"
  (ros/ros_comm tools/roslaunch/src/roslaunch/xmlloader.py l.743 at 845f746); srdfdom's
  initString logs "Could not parse the SRDF XML File" and returns false, so MoveIt has no
  robot model (moveit/srdfdom src/model.cpp l.729-733 at 148991a); a YAML or Python file does
  not parse, and catkin / colcon stop on package.xml or CMakeLists.txt.
- warning in any other text file (README, notes): nothing ROS reads, but a merge left unfinished.

Binary files (meshes, images: by suffix, or a NUL byte in what was read) are skipped, as are
hidden folders (`.git`, `.marm_setup`) and files over READ_BYTES; at most MAX_FILES files are read.
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

from marm_setup.bounded_read import FileTooLarge, read_bytes
from marm_setup.findings import Finding, error, warning

READ_BYTES = 4 << 20  # far above any config file (the largest shared URDF is 0.1 MB)
MAX_FILES = 5000
BINARY_SUFFIXES = frozenset(
    {".stl", ".dae", ".obj", ".ply", ".3ds", ".glb", ".gltf", ".png", ".jpg", ".jpeg", ".gif", ".bmp"}
    | {".tif", ".tiff", ".pdf", ".zip", ".gz", ".tgz", ".xz", ".bz2", ".tar", ".so", ".a", ".o"}
    | {".pyc", ".bag", ".db3", ".mcap", ".bt", ".ot", ".pgm", ".ico", ".svg"}
)
PARSED_SUFFIXES = frozenset(
    {".launch", ".xml", ".srdf", ".urdf", ".xacro", ".yaml", ".yml", ".py", ".rviz", ".cmake"}
    | {".cfg", ".json", ".sdf", ".world"}
)
PARSED_NAMES = frozenset({"CMakeLists.txt", "package.xml", ".setup_assistant", "setup.cfg"})
START, END = b"<<<<<<<", b">>>>>>>"


def check_merge_conflicts(root: Path) -> list[Finding]:
    """`file.merge-conflict` for every file of the package at `root` with a conflict marker."""
    out = []
    for rel in _text_files(root):
        try:
            data = read_bytes(root / rel, READ_BYTES, shown=rel)
        except (OSError, FileTooLarge):
            continue
        line = None if b"\0" in data else first_marker(data)
        if line is not None:
            out.append(_finding(rel, line, marker_count(data)))
    return out


def first_marker(data: bytes) -> int | None:
    """The 1-based line of the first conflict marker, else None: `<<<<<<<` or `>>>>>>>` opening
    a line, then a space or the line's end. A `=======` line alone is none (reStructuredText
    underlines a title with it), and one always sits between the other two."""
    return next((n for n, line in enumerate(data.splitlines(), 1) if _marker(line)), None)


def marker_count(data: bytes) -> int:
    """How many `<<<<<<<` blocks the file has."""
    return sum(1 for line in data.splitlines() if _marker(line) == START)


def _marker(line: bytes) -> bytes | None:
    for marker in (START, END):
        if line.startswith(marker) and line[7:8] in (b"", b" ", b"\t", b"\r"):
            return marker
    return None


def _finding(rel: str, line: int, blocks: int) -> Finding:
    count = (
        f"{blocks} unresolved merge conflict{'s' if blocks != 1 else ''}"
        if blocks
        else "a merge conflict marker"
    )
    hint = "resolve the merge (keep one side, delete the <<<<<<< / ======= / >>>>>>> lines)"
    name = Path(rel).name
    if name in PARSED_NAMES or Path(rel).suffix.lower() in PARSED_SUFFIXES:
        msg = f"{count} (git merge markers): the file no longer parses, and what loads it fails"
        return error("file.merge-conflict", rel, f"line {line}", msg, hint)
    msg = f"{count} (git merge markers) in a file no ROS tool reads: the merge was left unfinished"
    return warning("file.merge-conflict", rel, f"line {line}", msg, hint)


def _text_files(root: Path) -> list[str]:
    """Regular files of the package (relative, sorted; symlinks and hidden folders left out, at
    most MAX_FILES), binary ones by suffix left out."""
    out: list[str] = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d != "__pycache__")
        for name in sorted(files):
            path = Path(folder) / name
            if Path(name).suffix.lower() in BINARY_SUFFIXES or not _regular(path):
                continue
            out.append(path.relative_to(root).as_posix())
            if len(out) >= MAX_FILES:
                return out
    return out


def _regular(path: Path) -> bool:
    """A regular file, not a symlink (it may lead outside) or a FIFO (opening one blocks)."""
    try:
        return stat.S_ISREG(os.lstat(path).st_mode)
    except OSError:
        return False
