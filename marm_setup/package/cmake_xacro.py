"""`xacro_add_files(...)` calls of a package's CMakeLists.txt: the build runs
`xacro -o <output> <input> ${_XACRO_REMAP}` on each listed file and installs the output (ros/xacro
ros2 cmake/xacro-extras.cmake, `xacro_add_files` parses `REMAP` and `DEPENDS` as lists, `OUTPUT`,
`TARGET`, `DESTINATION` as one value and `INSTALL` as an option, then calls
`xacro_add_xacro_file`). Read as text: comments dropped, arguments split on whitespace, quotes
removed; nothing of CMake is evaluated, so a `${variable}` stays as written."""

from __future__ import annotations

import re
import shlex

from marm_setup.package.files import FileProblem, PackageFiles

CMAKE_LISTS = "CMakeLists.txt"
_CALL = re.compile(r"\bxacro_add_files\s*\(([^()]*)\)", re.IGNORECASE)
_KEYWORDS = {"REMAP", "DEPENDS", "OUTPUT", "TARGET", "DESTINATION", "INSTALL"}


def build_remaps(files: PackageFiles, rel: str) -> dict[str, str]:
    """The `REMAP name:=value` args the package's CMakeLists.txt gives the xacro file `rel` (a
    path relative to the package), as written; {} when no call lists it or the file is unreadable."""
    try:
        text = files.text(CMAKE_LISTS)
    except FileProblem:
        return {}
    if text is None:
        return {}
    text = re.sub(r"#[^\n]*", "", text)
    out: dict[str, str] = {}
    for call in _CALL.finditer(text):
        try:
            words = shlex.split(call.group(1))
        except ValueError:
            continue
        section, inputs, remaps = "", [], []
        for word in words:
            if word in _KEYWORDS:
                section = word
            elif section == "REMAP":
                remaps.append(word)
            elif section in ("", "INSTALL"):
                inputs.append(word)
            elif section in ("OUTPUT", "TARGET", "DESTINATION"):
                section = ""  # one value, then back to the files
        if rel in (i.removeprefix("./") for i in inputs):
            for remap in remaps:
                name, sep, value = remap.partition(":=")
                if sep:
                    out[name] = value
    return out
