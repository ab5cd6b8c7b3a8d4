"""ROS 2 XML launch substitutions evaluated without ROS, as far as they can be: `$(var)` from the
file's own `<arg default>` and `<let>`, `$(find-pkg-share)` from the package paths, `$(dirname)`,
and `$(command '...' [on_stderr])` for the commands a MoveIt package runs: `xacro FILE ARGS`
(the real xacro, bounded, its stderr kept), `cat FILE`, and the generated
`python3 .../scripts/with_mock_hardware.py FILE ARGS`. Anything else leaves the value unknown
(None): the rules then say nothing rather than guess.

The frontend's grammar (launch/frontend/grammar.lark): `$(name arg ...)`, an argument quoted
with ' or " or bare up to white space, substitutions nested anywhere inside.
"""

from __future__ import annotations

import shlex
from dataclasses import dataclass, field
from pathlib import Path

from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_text
from marm_setup.errors import InputError
from marm_setup.robot import PackageMap
from marm_setup.untrusted import inside

ON_STDERR_DEFAULT = "fail"  # launch/substitutions/command.py: Command(..., on_stderr='fail')
MOCK_SCRIPT_NAME = "with_mock_hardware.py"


@dataclass(frozen=True, slots=True)
class Call:
    """One `$(name args...)`: each argument its raw text (quotes removed, nested calls kept)."""

    name: str
    args: tuple[str, ...]
    end: int  # index just past its `)`


@dataclass(frozen=True, slots=True)
class CommandRun:
    """A `$(command)` the file runs: the command as resolved, what it writes to stderr, the
    on_stderr choice, its output, and why it could not be evaluated (problem)."""

    command: str
    on_stderr: str
    stdout: str | None = None
    stderr: str = ""
    problem: str = ""


def parse_call(text: str, start: int) -> Call | None:
    """The substitution starting at `text[start:]` (which begins with `$(`), or None if unclosed."""
    i = start + 2
    name_end = i
    while name_end < len(text) and text[name_end] not in " \t\n)":
        name_end += 1
    name, i = text[start + 2 : name_end], name_end
    args: list[str] = []
    while i < len(text):
        if text[i] in " \t\n":
            i += 1
        elif text[i] == ")":
            return Call(name, tuple(args), i + 1)
        else:
            arg, i = _argument(text, i)
            if arg is None:
                return None
            args.append(arg)
    return None


def _argument(text: str, i: int) -> tuple[str | None, int]:
    """One argument from `text[i:]` (quoted or bare) and the index after it."""
    quote = text[i] if text[i] in "'\"" else None
    j = i + 1 if quote else i
    while j < len(text):
        if text.startswith("$(", j):
            inner = parse_call(text, j)
            if inner is None:
                return None, j
            j = inner.end
        elif (quote and text[j] == quote) or (not quote and text[j] in " \t\n)"):
            break
        else:
            j += 1
    if quote and j >= len(text):
        return None, j
    return (text[i + 1 : j], j + 1) if quote else (text[i:j], j)


@dataclass
class LaunchEvaluator:
    """Evaluates the substitutions of one launch file; remembers every command it ran."""

    launch_dir: Path
    packages: PackageMap
    scope: dict[str, str]  # arg defaults and lets, by name (raw text)
    commands: dict[tuple[str, str], CommandRun] = field(default_factory=dict)
    _busy: set[str] = field(default_factory=set)

    def value(self, text: str) -> str | None:
        """`text` with every substitution performed, or None when one cannot be."""
        out, i = [], 0
        while (j := text.find("$(", i)) >= 0:
            call = parse_call(text, j)
            if call is None:
                return None
            result = self.perform(call)
            if result is None:
                return None
            out += [text[i:j], result]
            i = call.end
        return "".join([*out, text[i:]])

    def perform(self, call: Call) -> str | None:
        args = [self.value(a) for a in call.args]
        if any(a is None for a in args):
            return None
        values = [a for a in args if a is not None]
        if call.name == "var" and len(values) == 1:
            return self._var(values[0])
        if call.name == "find-pkg-share" and len(values) == 1:
            return self._package(values[0])
        if call.name == "dirname" and not values:
            return str(self.launch_dir)
        if call.name == "command" and 1 <= len(values) <= 2:
            return self.command(values[0], values[1] if len(values) == 2 else ON_STDERR_DEFAULT).stdout
        return None

    def command(self, command: str, on_stderr: str) -> CommandRun:
        key = (command, on_stderr)
        if key not in self.commands:
            self.commands[key] = run_static_command(command, self.packages, on_stderr)
        return self.commands[key]

    def _var(self, name: str) -> str | None:
        if name not in self.scope or name in self._busy:
            return None
        self._busy.add(name)
        try:
            return self.value(self.scope[name])
        finally:
            self._busy.discard(name)

    def _package(self, name: str) -> str | None:
        found = self.packages.get(name)
        return None if found is None else str(found)


def run_static_command(command: str, packages: PackageMap, on_stderr: str = ON_STDERR_DEFAULT) -> CommandRun:
    """`xacro`, `cat` and the generated mock-hardware script, run as launch would run them."""
    from marm_setup.robot import on_mock_hardware

    try:
        words = shlex.split(command)
    except ValueError as exc:
        return CommandRun(command, on_stderr, problem=f"cannot split the command: {exc}")
    mock = False
    if len(words) >= 2 and words[0] in ("python3", "python") and Path(words[1]).name == MOCK_SCRIPT_NAME:
        words = words[2:]
        mock = _xacro_args(words).get("use_mock_hardware", "true").lower() in ("true", "1")
        words = ["xacro", *words]
    if len(words) == 2 and words[0] == "cat":
        if not inside(Path(words[1]), (packages[name] for name in packages)):
            return CommandRun(command, on_stderr, problem="cat: a file outside the packages is not read")
        try:
            return CommandRun(command, on_stderr, read_text(words[1], XML_BYTES))
        except OSError as exc:
            return CommandRun(command, on_stderr, problem=f"cat: {exc.strerror or exc}")
        except FileTooLarge as exc:
            return CommandRun(command, on_stderr, problem=f"cat: {exc.message}")
    if len(words) < 2 or words[0] != "xacro":
        return CommandRun(command, on_stderr, problem="not a command marm-setup can run without ROS")
    run = _xacro(words[1], _xacro_args(words[2:]), packages, command, on_stderr)
    if mock and run.stdout is not None:
        return CommandRun(command, on_stderr, on_mock_hardware(run.stdout), run.stderr)
    return run


def _xacro_args(words: list[str]) -> dict[str, str]:
    return dict(w.split(":=", 1) for w in words if ":=" in w and not w.startswith("-"))


def _xacro(file: str, args: dict[str, str], packages: PackageMap, command: str, on_stderr: str) -> CommandRun:
    from marm_setup.robot import run_xacro

    try:
        expansion = run_xacro(Path(file), args, packages, shown=Path(file).name)
    except InputError as exc:
        return CommandRun(command, on_stderr, problem=f"xacro fails: {exc.message}")
    return CommandRun(command, on_stderr, expansion.xml, expansion.stderr)
