"""Run the real xacro on a file, in a bounded child process, and say which arguments it takes.

Real xacro silently ignores an argument nothing reads: `process_doc` makes the mappings its arg
table (ros/xacro, ros2 branch, xacro/__init__.py:1035), `<xacro:arg>` only fills in a default
when the name is missing (:939-942), and only `$(arg)` (substitution_args.py:161), names in
`$(eval)` (:288) and `xacro.arg()` (__init__.py:205) read the table; no code looks at the
remaining keys, so `hnad:=true` changes nothing and says nothing. The expansion therefore
records every name the xacro asks its table about (declared or read) and, statically, every
`<xacro:arg name=...>`, `$(arg NAME)` and `arg('NAME')` in the files it read (a declaration in
a branch not taken is an argument all the same); `check_xacro_args` refuses any other.
"""

from __future__ import annotations

import contextlib
import io
import logging
import os
import re
import sys
import types
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass
from pathlib import Path

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.errors import InputError
from marm_setup.names import did_you_mean, with_hint
from marm_setup.robot.ros_packages import PackageMap, find_package

log = logging.getLogger(__name__)

XACRO_SECONDS = 60.0  # [s] for one xacro expansion; MARM_SETUP_XACRO_TIMEOUT overrides
XACRO_MEMORY = 2 << 30  # [bytes]
_DECLARED_IN_TEXT = re.compile(
    r"""<xacro:arg\b[^>]*?\bname\s*=\s*["']([^"']+)["']"""  # <xacro:arg name="x" .../>
    r"""|\$\(arg\s+([^\s)]+)\s*\)"""  # $(arg x)
    r"""|\barg\(\s*["']([^"']+)["']\s*\)"""  # arg('x') in $(eval), xacro.arg('x') in ${}
)
_OPTENV_IN_TEXT = re.compile(
    r"""\$\(optenv\s+([^\s)]+)"""  # $(optenv NAME default)
    r"""|\boptenv\(\s*["']([^"']+)["']"""  # optenv('NAME', default) in $(eval) and ${}
)


@dataclass(frozen=True)
class XacroOutput:
    """The expanded XML, the names of the arguments the xacro declares or reads, every argument
    its table held at the end with its value (given, or a declared default), and what xacro
    wrote to stderr (its warnings: launch's $(command) fails on them by default)."""

    xml: str
    declared: frozenset[str]
    values: tuple[tuple[str, str], ...] = ()
    stderr: str = ""
    env_defaults: tuple[
        str, ...
    ] = ()  # unset environment variables it reads with optenv: their defaults used


class _ArgTable(dict):
    """xacro's table of arguments (its `mappings`), recording the names xacro asks about: a
    `<xacro:arg>` tests membership, `$(arg)`, `arg()`, `xacro.arg()` and `$(eval)` names look up."""

    def __init__(self, given: Mapping[str, str]):
        super().__init__(given)
        self.asked: set[str] = set()

    def __contains__(self, key: object) -> bool:
        self.asked.add(str(key))
        return super().__contains__(key)

    def __getitem__(self, key: str) -> str:
        if super().__contains__(key):  # `$(eval)` looks up every name, builtins too: keep ours
            self.asked.add(key)
        return super().__getitem__(key)


def expand_xacro(file: Path, args: dict[str, str], packages: PackageMap, *, shown: str) -> str:
    """The XML real xacro makes of `file` with `args` (see `run_xacro`)."""
    return run_xacro(file, args, packages, shown=shown).xml


def run_xacro(file: Path, args: Mapping[str, str], packages: PackageMap, *, shown: str) -> XacroOutput:
    """Run the real xacro on `file` with `args`, resolving `$(find pkg)` from `packages`, in a
    child process bounded in time and memory (xacro evaluates `${...}` as Python)."""
    from marm_setup.robot.sandbox import ChildDied, TimeLimitExceeded, run_limited
    from marm_setup.robot.text_input import read_text
    from marm_setup.untrusted import refuse_code

    refuse_code(f"xacro of {shown}", shown, "xacro")
    text = read_text(file, shown=shown).replace("$(find-pkg-share ", "$(find ")
    seconds = float(os.environ.get("MARM_SETUP_XACRO_TIMEOUT", XACRO_SECONDS))
    try:
        return run_limited(
            lambda: _run_xacro(file, text, dict(args), packages, shown),
            seconds=seconds,
            memory_bytes=XACRO_MEMORY,
        )
    except TimeLimitExceeded:
        raise InputError(
            f"xacro did not finish within {seconds:g} s (an expression that never ends, like ${{10**10**8}}?)",
            path=shown,
            element="xacro",
        ) from None
    except ChildDied as exc:
        raise InputError(f"xacro stopped: {exc}", path=shown, element="xacro") from None
    except MemoryError:  # the child ran out while sending its answer
        raise _xacro_error(MemoryError(), shown) from None


def check_xacro_args(
    given: Iterable[str],
    declared: Iterable[str] | None,
    *,
    path: str,
    others: Iterable[str] = (),
    key: str = "--xacro-arg",
) -> None:
    """Refuse an argument that no xacro it is given to takes: the robot description's
    (`declared` None: a plain URDF) and the `others` (an SRDF xacro), whose names `declared`
    holds too; `path` and `key` (`--xacro-arg`, or a setup file's `robot.xacro_args`) name
    where the argument was given."""
    others = tuple(others)
    unknown = sorted(set(given) - set(declared or ()))
    if not unknown:
        return
    element = f"{key} {', '.join(unknown)}" if key.startswith("-") else f"{key}.{unknown[0]}"
    if declared is None:
        raise InputError(
            "a plain URDF takes no xacro argument (it is not a xacro file)", path=path, element=element
        )
    known = sorted(declared)
    files = " or ".join(("this xacro" if key.startswith("-") else "the robot's xacro", *others))
    hint = did_you_mean(unknown[0], known, few=0) if len(unknown) == 1 else ""
    message = with_hint(f"not an argument of {files}", hint)
    takes = "they take" if others else "it takes"
    raise InputError(f"{message}; {takes}: {', '.join(known) or 'none'}", path=path, element=element)


def _run_xacro(file: Path, text: str, args: dict[str, str], packages: PackageMap, shown: str) -> XacroOutput:
    from xml.parsers.expat import ExpatError

    import xacro

    captured = io.StringIO()
    table = _ArgTable(args)
    first_include = len(xacro.all_includes)
    with _ament_index_stub(packages, shown), _size_checked_opens(xacro), contextlib.redirect_stderr(captured):
        try:
            xacro.init_stacks(str(file))
            doc = xacro.parse(text, str(file))
            xacro.process_doc(doc, mappings=table)
            xml = doc.toxml()
        except InputError:
            raise
        except ExpatError as exc:
            raise InputError(f"malformed XML: {exc}", path=shown, element=f"line {exc.lineno}") from None
        except Exception as exc:  # xacro raises many types; all are bad input here
            inner = getattr(exc, "exc", None)
            if isinstance(inner, InputError):  # ours, wrapped by XacroException
                raise inner from None
            raise _xacro_error(exc, shown) from None
        finally:
            xacro.substitution_args_context["arg"] = {}
    if captured.getvalue().strip():
        log.debug("xacro: %s", captured.getvalue().strip())
    bounded_read.check_text_size(xml, bounded_read.XML_BYTES, shown=shown, element="xacro output")
    read = [text, *(_file_text(f) for f in xacro.all_includes[first_include:])]
    values = tuple(sorted((str(k), str(v)) for k, v in dict.items(table)))
    unset = _unset_optenv(read)
    return XacroOutput(xml, frozenset(table.asked) | _declared_in(read), values, captured.getvalue(), unset)


def _unset_optenv(texts: Iterable[str]) -> tuple[str, ...]:
    """The environment variables `$(optenv NAME ...)` or `optenv('NAME', ...)` name anywhere in
    `texts` that are not set here (xacro substitution_args.py _eval_optenv: their defaults)."""
    names = {next(g for g in m.groups() if g) for text in texts for m in _OPTENV_IN_TEXT.finditer(text)}
    return tuple(sorted(name for name in names if name not in os.environ))


@contextlib.contextmanager
def _size_checked_opens(xacro_module: types.ModuleType) -> Iterator[None]:
    """xacro's own file reads (`<xacro:include>`, `load_yaml`) refuse a file over XML_BYTES
    before reading it, as every other read does (bounded_read): xacro calls `open` by name, so a
    module global of that name stands in for the builtin while it runs."""

    def open_checked(name, mode="r", *args, **kwargs):
        stream = open(name, mode, *args, **kwargs)  # noqa: SIM115 - returned to xacro, which closes it
        size = os.fstat(stream.fileno()).st_size
        if size > bounded_read.XML_BYTES and "r" in mode:
            stream.close()
            raise bounded_read.too_large(size, bounded_read.XML_BYTES, shown=str(name), element="xacro")
        return stream

    xacro_module.__dict__["open"] = open_checked
    try:
        yield
    finally:
        xacro_module.__dict__.pop("open", None)


def _declared_in(texts: Iterable[str]) -> frozenset[str]:
    """Argument names that `<xacro:arg>`, `$(arg)` and `arg('...')` name anywhere in `texts`."""
    return frozenset(
        next(g for g in m.groups() if g) for text in texts for m in _DECLARED_IN_TEXT.finditer(text)
    )


def _file_text(name: str) -> str:
    try:
        return bounded_read.read_bytes(name, bounded_read.XML_BYTES).decode("utf-8", errors="replace")
    except (OSError, FileTooLarge):
        return ""


def _is_out_of_memory(exc: BaseException | None) -> bool:
    """MemoryError itself, or wrapped by xacro (`XacroException.exc`, xacro/__init__.py eval_text)."""
    seen = 0
    while exc is not None and seen < 10:
        if isinstance(exc, MemoryError):
            return True
        exc, seen = getattr(exc, "exc", None) or exc.__cause__ or exc.__context__, seen + 1
    return False


def _xacro_error(exc: Exception, shown: str) -> InputError:
    if _is_out_of_memory(exc):
        message = f"xacro needed more than {bounded_read.format_size(XACRO_MEMORY)} of memory"
        return InputError(message, path=shown, element="xacro")
    text = " ".join(str(exc).split())
    undefined = re.search(r"Undefined substitution argument (\S+)", text)
    if undefined:
        return InputError(
            f"undefined xacro arg '{undefined.group(1)}'", path=shown, element="xacro", needs="--xacro-arg"
        )
    return InputError(text or type(exc).__name__, path=shown, element="xacro")


@contextlib.contextmanager
def _ament_index_stub(packages: PackageMap, shown: str) -> Iterator[None]:
    """Install an `ament_index_python.packages` stand-in that answers from `packages`."""

    def get_package_share_directory(name: str) -> str:
        return str(find_package(name, packages, path=shown, element=f"$(find {name})"))

    module = types.ModuleType("ament_index_python.packages")
    module.__dict__["get_package_share_directory"] = get_package_share_directory
    parent = types.ModuleType("ament_index_python")
    parent.__dict__["packages"] = module
    saved = {k: sys.modules.get(k) for k in ("ament_index_python", "ament_index_python.packages")}
    sys.modules.update({"ament_index_python": parent, "ament_index_python.packages": module})
    try:
        yield
    finally:
        for key, value in saved.items():
            if value is None:
                sys.modules.pop(key, None)
            else:
                sys.modules[key] = value
