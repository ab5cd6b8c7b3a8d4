"""Launch substitutions: the one place `$(...)` is evaluated, for ROS 1 roslaunch and ROS 2
launch XML.

roslaunch (`ros_comm/tools/roslaunch/src/roslaunch/substitution_args.py`): `$(arg x)` the arg's
value, `$(find pkg)` the package folder, `$(env X)` / `$(optenv X default)` the environment,
`$(dirname)` the launch file's folder, `$(anon name)` a unique name, `$(eval ...)` Python over
the args. ROS 2 launch XML (`launch/substitutions`, `launch_ros/substitutions`) spells an arg
`$(var x)` and a package `$(find-pkg-share pkg)`. A substitution that cannot be resolved (an
unknown arg, package or variable) raises SubstitutionError naming it.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

ROS1_COMMANDS = ("arg", "find", "env", "optenv", "dirname", "eval", "anon")
ROS2_COMMANDS = ("var", "find-pkg-share", "find-pkg-prefix", "env", "optenv", "dirname", "eval", "anon")
_PATTERN = r"\$\(({commands})(?=[\s)])\s*([^()]*(?:\([^()]*\)[^()]*)*)\)"
MAX_ROUNDS = 20  # an arg's value may hold substitutions itself; a cycle stops here


class SubstitutionError(ValueError):
    """A substitution that could not be resolved (unknown arg, package or variable)."""


@dataclass(frozen=True)
class Scope:
    """What substitutions see: the launch file's args, its folder, the package lookup."""

    args: Mapping[str, str] = field(default_factory=dict)
    find: Callable[[str], str | None] = lambda _name: None
    dirname: str = ""
    ros2: bool = False
    environ: Mapping[str, str] | None = None

    def with_args(self, args: Mapping[str, str]) -> Scope:
        return Scope(args, self.find, self.dirname, self.ros2, self.environ)


def substitute(text: str, scope: Scope) -> str:
    """`text` with every substitution resolved; SubstitutionError names the first that fails."""
    commands = ROS2_COMMANDS if scope.ros2 else ROS1_COMMANDS
    pattern = re.compile(_PATTERN.format(commands="|".join(re.escape(c) for c in commands)))
    environ = os.environ if scope.environ is None else scope.environ

    def one(match: re.Match) -> str:
        return _resolve(match.group(1), match.group(2).strip(), scope, environ)

    for _round in range(MAX_ROUNDS):
        if "$(" not in text:
            break
        previous, text = text, pattern.sub(one, text)
        if previous == text:
            break
    return text


def _resolve(command: str, rest: str, scope: Scope, environ: Mapping[str, str]) -> str:
    words = rest.split()
    if command in ("arg", "var"):
        if not words or words[0] not in scope.args:
            raise SubstitutionError(f"$({command} {rest}): no such arg in the launch file that loads it")
        return str(scope.args[words[0]])
    if command in ("find", "find-pkg-share", "find-pkg-prefix"):
        folder = scope.find(words[0]) if words else None
        if folder is None:
            raise SubstitutionError(f"$({command} {rest}): unknown package")
        return str(folder)
    if command == "env":
        if not words or words[0] not in environ:
            raise SubstitutionError(f"$(env {rest}): variable not set")
        return environ[words[0]]
    if command == "optenv":
        return environ.get(words[0], " ".join(words[1:])) if words else ""
    if command == "dirname":
        return scope.dirname
    if command == "anon":
        return f"{words[0] if words else ''}_anon"
    return evaluate(rest, scope.args)


def evaluate(expression: str, args: Mapping[str, str]) -> str:
    """roslaunch's `$(eval ...)` (substitution_args.py `_eval`): Python with `arg()` and the args."""
    if "__" in expression:
        raise SubstitutionError("$(eval ...) may not contain double underscores")
    names: dict[str, Any] = {name: auto_value(value) for name, value in args.items()}
    names.update(arg=lambda name: auto_value(args[name]), true=True, false=False)
    try:
        return str(eval(expression, {"__builtins__": {}}, names))  # noqa: S307 - roslaunch's own semantics
    except Exception as exc:  # noqa: BLE001 - any failure of the expression is the author's
        raise SubstitutionError(f"$(eval {expression}): {exc}") from None


def auto_value(value: str) -> Any:
    """roslaunch's `convert_value(value, 'auto')`: int, float, bool, else the string."""
    for cast in (int, float):
        try:
            return cast(value)
        except ValueError:
            pass
    lowered = value.strip().lower()
    return {"true": True, "false": False}.get(lowered, value)


def truth(text: str) -> bool | None:
    """An `if` / `unless` value as roslaunch reads it (true/1, false/0); None for anything else."""
    return {"true": True, "1": True, "false": False, "0": False}.get(text.strip().lower())
