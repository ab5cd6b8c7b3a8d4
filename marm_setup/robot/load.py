"""load_robot: URDF/xacro file -> frozen RobotModel (xacro, package map, mesh resolution)."""

from __future__ import annotations

import contextlib
import dataclasses
import io
import logging
import os
import re
import sys
import types
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path

from lxml import etree

from marm_setup.errors import InputError
from marm_setup.robot.model import RobotModel
from marm_setup.robot.ros_packages import PackageMap, find_package, find_packages
from marm_setup.robot.urdf import parse_urdf

log = logging.getLogger(__name__)


def parse_xacro_args(items: Iterable[str]) -> dict[str, str]:
    """`NAME:=VALUE` strings -> mapping; a malformed item is an InputError."""
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            raise InputError(f"expected NAME:=VALUE, got '{item}'", element="--xacro-arg")
        out[name] = value
    return out


def load_robot(
    path: str | Path,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
) -> RobotModel:
    """Load a `.urdf` or xacro file into a RobotModel; every failure is an InputError."""
    shown = str(path)
    file = Path(path)
    if file.is_dir():
        raise InputError("is a folder; expected a .urdf or .xacro file", path=shown)
    if not file.is_file():
        raise InputError("file not found", path=shown)
    packages = find_packages(package_paths, near=file)
    if file.suffix == ".xacro":
        xml = expand_xacro(file, dict(xacro_args or {}), packages, shown=shown)
    else:
        xml = read_text(file, shown=shown)
    root = parse_xml(xml, shown=shown)
    robot = parse_urdf(root, xml, file.parent, packages, shown=shown)
    used = tuple((u.name, u.path, u.found_by) for u in sorted(packages.used.values(), key=lambda u: u.name))
    return dataclasses.replace(robot, packages=used)


def read_text(file: Path, *, shown: str) -> str:
    """The UTF-8 text of `file`; unreadable or non-UTF-8 content is an InputError."""
    try:
        return file.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=shown) from None
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=shown) from None


def parse_xml(text: str, *, shown: str) -> etree._Element:
    """Parse XML text; syntax errors become InputError with the line number."""
    try:
        parser = etree.XMLParser(remove_comments=True)
        return etree.fromstring(text.encode("utf-8"), parser)
    except etree.XMLSyntaxError as exc:
        raise InputError(
            f"malformed XML: {xml_syntax_message(exc)}", path=shown, element=f"line {exc.lineno}"
        ) from None


def xml_syntax_message(exc: etree.XMLSyntaxError) -> str:
    """libxml2's message on one line, without the position it repeats (the element names the line)."""
    text = " ".join(str(exc.msg).split())
    return re.sub(r"\s*,?\s*line \d+, column \d+$", "", text)


XACRO_SECONDS = 60.0  # [s] for one xacro expansion; MARM_SETUP_XACRO_TIMEOUT overrides
XACRO_MEMORY = 2 << 30  # [bytes]


def expand_xacro(file: Path, args: dict[str, str], packages: PackageMap, *, shown: str) -> str:
    """Run the real xacro on `file` with `args`, resolving `$(find pkg)` from `packages`, in a
    child process bounded in time and memory (xacro evaluates `${...}` as Python)."""
    from marm_setup.robot.sandbox import ChildDied, TimeLimitExceeded, run_limited

    text = read_text(file, shown=shown).replace("$(find-pkg-share ", "$(find ")
    seconds = float(os.environ.get("MARM_SETUP_XACRO_TIMEOUT", XACRO_SECONDS))
    try:
        return run_limited(
            lambda: _run_xacro(file, text, args, packages, shown), seconds=seconds, memory_bytes=XACRO_MEMORY
        )
    except TimeLimitExceeded:
        raise InputError(
            f"xacro did not finish within {seconds:g} s (an expression that never ends, like ${{10**10**8}}?)",
            path=shown,
            element="xacro",
        ) from None
    except ChildDied as exc:
        raise InputError(f"xacro stopped: {exc}", path=shown, element="xacro") from None


def _run_xacro(file: Path, text: str, args: dict[str, str], packages: PackageMap, shown: str) -> str:
    from xml.parsers.expat import ExpatError

    import xacro

    captured = io.StringIO()
    with _ament_index_stub(packages, shown), contextlib.redirect_stderr(captured):
        try:
            xacro.init_stacks(str(file))
            doc = xacro.parse(text, str(file))
            xacro.process_doc(doc, mappings=args)
        except InputError:
            raise
        except ExpatError as exc:
            raise InputError(f"malformed XML: {exc}", path=shown, element=f"line {exc.lineno}") from None
        except Exception as exc:  # xacro raises many types; all are bad input here
            inner = getattr(exc, "exc", None)
            if isinstance(inner, InputError):  # ours, wrapped by XacroException
                raise inner from None
            raise InputError(_xacro_message(exc), path=shown, element="xacro") from None
        finally:
            xacro.substitution_args_context["arg"] = {}
    if captured.getvalue().strip():
        log.debug("xacro: %s", captured.getvalue().strip())
    return doc.toxml()


def _xacro_message(exc: Exception) -> str:
    if isinstance(exc, MemoryError):
        return f"xacro needed more than {XACRO_MEMORY >> 30} GiB of memory"
    text = " ".join(str(exc).split())
    undefined = re.search(r"Undefined substitution argument (\S+)", text)
    if undefined:
        return f"undefined xacro arg '{undefined.group(1)}' (pass --xacro-arg NAME:=VALUE)"
    return text or type(exc).__name__


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
