"""Launch substitutions: the one place `$(...)` is evaluated, for ROS 1 roslaunch and ROS 2
launch XML.

roslaunch (`ros_comm/tools/roslaunch/src/roslaunch/substitution_args.py`): `$(arg x)` the arg's
value, `$(find pkg)` the package folder, `$(env X)` / `$(optenv X default)` the environment,
`$(dirname)` the launch file's folder, `$(anon name)` a unique name, `$(eval ...)` Python over
the args (here a restricted evaluator, package/eval_expr.py). ROS 2 launch XML
(`launch/substitutions`, `launch_ros/substitutions`) spells an arg `$(var x)` and a package
`$(find-pkg-share pkg)`. A substitution that cannot be resolved (an
unknown arg, package or variable) raises SubstitutionError naming it.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from marm_setup.package.eval_expr import EvalRefused, evaluate_expression
from marm_setup.untrusted import CodeNotRun, environment_refused, excerpt, refuse_code

ROS1_COMMANDS = ("arg", "find", "env", "optenv", "dirname", "anon")
ROS2_COMMANDS = ("var", "find-pkg-share", "find-pkg-prefix", "env", "optenv", "dirname", "eval", "anon")
EVAL_SECONDS = 5.0  # one `$(eval)` in its child process; the evaluator bounds each step besides
EVAL_MEMORY = 2 << 30  # [bytes] as xacro's child
SUBSTITUTED_CHARS = 1 << 20  # one substituted text: args doubling themselves reach it in 20 steps


class SubstitutionError(ValueError):
    """A substitution that could not be resolved (unknown arg, package or variable)."""


class SubstitutionTooLarge(SubstitutionError):
    """A substituted text past SUBSTITUTED_CHARS."""


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
    """`text` with every substitution resolved, in one pass over the text as written: what a
    substitution gives is never read for substitutions again (roslaunch resolve_args,
    substitution_args.py:349-393, resolves the text it was given; a `$(dirname)` whose folder
    holds `$(eval ...)` is a folder name). roslaunch evaluates `$(eval ...)` only as the whole
    text (:377-378); ROS 2 anywhere, after the substitutions inside it. SubstitutionError names
    the first that fails."""
    environ = os.environ if scope.environ is None else scope.environ
    stripped = text.strip()
    whole = stripped.startswith("$(eval ") and _closing(stripped, 0) == len(stripped) - 1
    if whole and not scope.ros2:
        return evaluate(stripped[7:-1], scope, environ)
    return _substitute(text, scope, environ)


def _substitute(text: str, scope: Scope, environ: Mapping[str, str]) -> str:
    commands = ROS2_COMMANDS if scope.ros2 else ROS1_COMMANDS
    out: list[str] = []
    i = size = 0
    while (start := text.find("$(", i)) >= 0:
        end = _closing(text, start)
        if end < 0:
            break
        body = text[start + 2 : end]
        command = body.split(None, 1)[0] if body.strip() else ""
        rest = body[len(command) :] if body[: len(command)] == command else ""
        if command not in commands:
            if command == "eval":
                raise SubstitutionError("$(eval ...): roslaunch evaluates it only as a whole attribute")
            out.append(text[i : start + 2])
            i = start + 2
            continue
        out.append(text[i:start])
        if command == "eval":
            out.append(evaluate(_substitute(rest, scope, environ), scope, environ))
        else:
            out.append(_resolve(command, _substitute(rest, scope, environ).strip(), scope, environ))
        size = _bounded(size + len(out[-2]) + len(out[-1]))
        i = end + 1
    out.append(text[i:])
    _bounded(size + len(out[-1]))
    return "".join(out)


def _bounded(size: int) -> int:
    """`size`, or SubstitutionError past SUBSTITUTED_CHARS (checked before the text is joined)."""
    if size > SUBSTITUTED_CHARS:
        raise SubstitutionTooLarge(
            f"the substituted text grows past {SUBSTITUTED_CHARS:,} characters (an arg built from "
            "itself over and over?): not expanded"
        )
    return size


def _closing(text: str, start: int) -> int:
    """The index of the `)` closing the `$(` at `start` (parentheses in quotes not counted), or -1."""
    depth, quote = 0, ""
    for i in range(start + 1, len(text)):
        c = text[i]
        if quote:
            quote = "" if c == quote else quote
        elif c in "'\"" and depth > 0:
            quote = c
        elif c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
            if depth == 0:
                return i
    return -1


def _resolve(command: str, rest: str, scope: Scope, environ: Mapping[str, str]) -> str:
    words = rest.split()
    if command in ("arg", "var"):
        if not words or words[0] not in scope.args:
            raise SubstitutionError(
                f"$({command} {excerpt(rest)}): no such arg in the launch file that loads it"
            )
        return str(scope.args[words[0]])
    if command in ("find", "find-pkg-share", "find-pkg-prefix"):
        folder = scope.find(words[0]) if words else None
        if folder is None:
            raise SubstitutionError(f"$({command} {excerpt(rest)}): unknown package")
        return str(folder)
    if command in ("env", "optenv") and (refused := environment_refused(f"$({command} {excerpt(rest)})")):
        raise SubstitutionError(refused)
    if command == "env":
        if not words or words[0] not in environ:
            raise SubstitutionError(f"$(env {excerpt(rest)}): variable not set")
        return environ[words[0]]
    if command == "optenv":
        return environ.get(words[0], " ".join(words[1:])) if words else ""
    if command == "dirname":
        return scope.dirname
    return f"{words[0] if words else ''}_anon"


def evaluate(expression: str, scope: Scope, environ: Mapping[str, str] | None = None) -> str:
    """`$(eval ...)` (roslaunch substitution_args.py `_eval` :324-347; ROS 2 launch's
    PythonExpression) by the restricted evaluator (package/eval_expr.py), in the package read's
    one child process (package/eval_child.py), bounded in time and memory as xacro is; under
    `--untrusted` not at all. SubstitutionError names the expression (an excerpt) and why; a
    value over SUBSTITUTED_CHARS is SubstitutionTooLarge."""
    from marm_setup.package.eval_child import evaluate_in_child
    from marm_setup.robot import ChildDied, TimeLimitExceeded

    shown = excerpt(expression.strip())
    try:
        refuse_code(f"$(eval {shown})", scope.dirname or "launch file")
    except CodeNotRun:
        raise SubstitutionError(
            f"$(eval {shown}): not evaluated (--untrusted runs no package code)"
        ) from None
    env = dict(os.environ if environ is None else environ) if "env" in expression else {}
    base = (expression, scope.dirname, scope.ros2, scope.find, tuple(sorted(env.items())))
    found = _remembered(base, scope.args)
    if found is None:  # the same expression over the same args: evaluated once (an include read twice)
        if len(_MEMO) >= MEMO_SIZE:
            _MEMO.clear()
            _READ.clear()
        used: dict[str, str | None] = {}
        try:
            found = evaluate_in_child(
                _evaluate_request,
                (expression, scope.dirname, scope.ros2, env),
                lambda what, name: _answer(scope, used, what, name),
                seconds=EVAL_SECONDS,
                memory_bytes=EVAL_MEMORY,
            )
        except (TimeLimitExceeded, ChildDied, OSError) as exc:
            found = SubstitutionError(f"$(eval {shown}): stopped ({exc})")
        except SubstitutionError as exc:
            found = exc
        except Exception as exc:  # the child's own failure (MemoryError under its limit, ...)
            found = SubstitutionError(f"$(eval {shown}): stopped ({type(exc).__name__}: {exc})")
        names = tuple(sorted(used))
        _READ.setdefault(base, set()).add(names)
        _MEMO[(base, tuple((n, used[n]) for n in names))] = found
    if isinstance(found, SubstitutionError):
        raise type(found)(str(found))  # SubstitutionTooLarge stays one
    return found


MEMO_SIZE = 4096
# (expression and what it depends on besides args, (arg, value or None) it read) -> its value
_MEMO: dict[tuple, str | SubstitutionError] = {}
_READ: dict[tuple, set[tuple[str, ...]]] = {}  # the arg names each evaluation of it read


def _remembered(base: tuple, args: Mapping[str, str]) -> str | SubstitutionError | None:
    """The value of an evaluation of `base` that read the args `args` holds as they are now."""
    for names in _READ.get(base, ()):
        found = _MEMO.get((base, tuple((n, args.get(n)) for n in names)))
        if found is not None:
            return found
    return None


def _answer(scope: Scope, used: dict[str, str | None], what: str, name: str) -> Any:
    """The child's question answered from `scope`: an arg's value (None: no such arg, recorded
    in `used`) or a package's folder."""
    if what == "arg":
        used[name] = scope.args.get(name)
        return used[name]
    return scope.find(name)


def _evaluate_request(request: tuple, ask: Callable[[str, str], Any]) -> str:
    """One request of `evaluate` in the child: (expression, dirname, ros2, environment); each
    arg and package it reads asked of the parent (`ask`), so a request is as large as its
    expression, not as the launch file's args; a value past SUBSTITUTED_CHARS refused here."""
    expression, dirname, ros2, environ = request
    scope = Scope(_AskedArgs(ask), lambda name: ask("find", name), dirname, ros2)
    value = _evaluate_here(expression, scope, environ)
    _bounded(len(value))  # before it is sent back
    return value


class _AskedArgs(Mapping[str, str]):
    """The launch file's args as the child sees them: each asked of the parent once."""

    def __init__(self, ask: Callable[[str, str], Any]):
        self._ask, self._known = ask, dict[str, Any]()

    def _get(self, name: str) -> str | None:
        if name not in self._known:
            self._known[name] = self._ask("arg", name)
        return self._known[name]

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and self._get(name) is not None

    def __getitem__(self, name: str) -> str:
        value = self._get(name)
        if value is None:
            raise KeyError(name)
        return value

    def __iter__(self) -> Iterator[str]:  # the evaluator only looks names up
        return iter(())

    def __len__(self) -> int:
        return 0


class _Converted(Mapping[str, Any]):
    """`args` as `$(eval)` names them: each converted (auto_value) when it is read."""

    def __init__(self, args: Mapping[str, str]):
        self._args = args

    def __contains__(self, name: object) -> bool:
        return name in self._args

    def __getitem__(self, name: str) -> Any:
        return auto_value(self._args[name])

    def __iter__(self) -> Iterator[str]:
        return iter(self._args)

    def __len__(self) -> int:
        return len(self._args)


def _evaluate_here(expression: str, scope: Scope, environ: Mapping[str, str]) -> str:
    """The evaluation itself (in the child): the launch's functions over `scope`."""
    args = scope.args

    def arg(name: str) -> Any:
        if name not in args:
            raise SubstitutionError(f"$(eval ...): no arg '{excerpt(str(name))}'")
        return auto_value(args[name])

    def optenv(name: str, default: str = "") -> str:
        return environ.get(name, default)

    functions: dict[str, Callable[..., Any]] = {
        "arg": arg,
        "env": lambda name: _resolve("env", str(name), scope, environ),
        "optenv": optenv,
        "find": lambda name: _resolve("find", str(name), scope, environ),
        "anon": lambda name: _resolve("anon", str(name), scope, environ),
        "dirname": lambda: scope.dirname,
    }
    names = _Converted(args)
    try:
        return str(evaluate_expression(expression, names, functions))
    except EvalRefused as exc:
        raise SubstitutionError(f"$(eval {excerpt(expression.strip())}): {exc}") from None


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
