"""A `xacro` command line read as xacro reads it: which file it expands, with which args.

xacro (ros/xacro `xacro/cli.py`, `process_args` l.94-140 and `load_mappings` l.68-91) first
takes every word holding `:=` as a mapping, wherever it stands (`_name:=` ROS parameter
assignments are ignored), then parses the rest with optparse: `-o FILE`, `--root-dir DIR` and
`--verbosity N` take a value, `--inorder` / `-i`, `--deps`, `-q`, `-v` do not, and exactly one
positional word is the input file. A launch file's command names the tool first: `xacro`,
`$(find xacro)/xacro`, `xacro.py`, `rosrun xacro xacro`, `python3 .../xacro`.
"""

from __future__ import annotations

import shlex
from collections.abc import Sequence
from dataclasses import dataclass

REMAP = ":="
VALUE_OPTIONS = frozenset({"-o", "--root-dir", "--verbosity"})
TOOL_WORDS = frozenset({"rosrun", "python", "python3", "env", "xacro", "xacro.py"})
XACRO_NAMES = frozenset({"xacro", "xacro.py"})


@dataclass(frozen=True, slots=True)
class XacroCall:
    """What one xacro command expands: its input file (None when it names none) and mappings."""

    file: str | None
    args: tuple[tuple[str, str], ...] = ()


def parse_xacro_argv(argv: Sequence[str]) -> XacroCall:
    """xacro's own arguments (after the tool's name): mappings anywhere, options skipped, the
    first positional word the file."""
    args: dict[str, str] = {}
    rest: list[str] = []
    for word in argv:
        if REMAP in word:
            src, _, dst = (part.strip() for part in word.partition(REMAP))
            if src and dst and not (len(src) > 1 and src[0] == "_" and src[1] != "_"):
                args[src] = dst
        else:
            rest.append(word)
    positional: list[str] = []
    skip = False
    for word in rest:
        if skip:
            skip = False
        elif word in VALUE_OPTIONS:
            skip = True
        elif not word.startswith("-") or word == "-":
            positional.append(word)
    return XacroCall(positional[0] if positional else None, tuple(sorted(args.items())))


def parse_xacro_command(command: str | Sequence[str]) -> XacroCall | None:
    """A whole command line (a string split as roslaunch splits it, shlex, or its words): None
    when it does not run xacro."""
    words = split_command(command) if isinstance(command, str) else list(command)
    start = 0
    while start < len(words) and _tool_word(words[start]):
        start += 1
    if not any(_basename(w) in XACRO_NAMES for w in words[:start]):
        return None
    return parse_xacro_argv(words[start:])


def split_command(command: str) -> list[str]:
    """A command line's words, as roslaunch and launch's `$(command)` split it (shlex)."""
    try:
        return shlex.split(command)
    except ValueError:  # unbalanced quotes: roslaunch fails too; read what is there
        return command.replace("'", " ").replace('"', " ").split()


def _basename(word: str) -> str:
    return word.rstrip("/").rsplit("/", 1)[-1]


def _tool_word(word: str) -> bool:
    """A word naming the tool rather than its input: xacro itself (any path to it), rosrun,
    the Python interpreter, and the package name in `rosrun xacro xacro`."""
    return _basename(word) in TOOL_WORDS or _basename(word).startswith("python3.")
