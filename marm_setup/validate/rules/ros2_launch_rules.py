"""What the launcher fails on or does wrong though every file parses, checked without ROS.

- `launch.command-stderr`: `$(command '...')` fails the launch when the command writes anything
  to stderr (launch/substitutions/command.py, Command.perform: on_stderr 'fail' by default
  raises SubstitutionFailure "executed command showed stderr output"; 'warn' logs it, 'ignore'
  drops it, both in Humble's launch 1.0 and Jazzy's 3.4). xacro writes its warnings there
  (`redefining global symbol: pi`), so the robot description is expanded here as the launch
  file would run it, and its stderr decides.
- `launch.leaves-package`: `$(find-pkg-share pkg)/..` (or xacro's `$(find pkg)/..`) climbs out of
  the package's share folder. ament_index_python's get_package_share_directory answers
  `<prefix>/share/<pkg>`, and an ament_cmake package installs only what its install() rules put
  under share/${PROJECT_NAME}: nothing outside that folder is there once installed (an error on
  ROS 2; on ROS 1 catkin's devel space resolves $(find) to the source folder, so it works until
  the package is installed: a warning).
- `demo.real-hardware`: a demo launch file (`demo.launch.xml`), run with its default args, gives
  robot_state_publisher or ros2_control_node a robot description whose `<ros2_control>`
  hardware is not a mock of the package's distro (mock_components/GenericSystem; Humble also
  fake_components/GenericSystem): the controller manager would load that driver and move the
  real robot.
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from marm_setup.bounded_read import XML_BYTES, FileTooLarge, read_bytes
from marm_setup.findings import Finding, error, warning
from marm_setup.robot import find_packages
from marm_setup.ros import Target
from marm_setup.untrusted import excerpt, inside
from marm_setup.validate.launch_eval import ON_STDERR_DEFAULT, Call, LaunchEvaluator, parse_call

if TYPE_CHECKING:
    from marm_setup.package import MoveItPackage

DESCRIPTION_NODES = ("robot_state_publisher", "ros2_control_node")
SHARE_PATH = re.compile(
    r"\$\((find|find-pkg-share)\s+([^\s)]+)\)((?:/[^\s'\"<>)$]*)?)|\$\(dirname\)(/[^\s'\"<>)$]*)"
)


def check_ros2_launch(pkg: MoveItPackage, distro: str | None) -> list[Finding]:
    """The command and demo-hardware rules over a ROS 2 package's XML launch files."""
    out: list[Finding] = []
    packages = find_packages(pkg.package_paths)
    for launch in pkg.launch:
        rel, tree = launch.file, launch.root  # a malformed file has its finding already
        if tree is None or tree.tag != "launch":
            continue
        ev = LaunchEvaluator(pkg.path(rel).parent, packages, launch_scope(tree))
        out += check_command_stderr(tree, rel, ev)
        if Path(rel).name.startswith("demo"):
            out += check_demo_hardware(tree, rel, ev, distro)
    return out


def launch_scope(tree: etree._Element) -> dict[str, str]:
    """Arg defaults and lets of one file, by name (a let after an arg of the same name wins)."""
    scope: dict[str, str] = {}
    for elem in tree.iter("arg", "let"):
        parent = elem.getparent()
        if parent is not None and parent.tag == "include":
            continue
        name = elem.get("name")
        value = elem.get("default") if elem.tag == "arg" else elem.get("value")
        if name and value is not None:
            scope[name] = value
    return scope


def _where(elem: etree._Element) -> str:
    name = elem.get("name") or elem.get("exec")
    where = f"line {elem.sourceline}: {elem.tag!s}"
    return f"{where}[{name}]" if name else where


def command_calls(text: str) -> Iterator[Call]:
    """Every `$(command ...)` written in `text` (nested ones too)."""
    i = 0
    while (j := text.find("$(", i)) >= 0:
        call = parse_call(text, j)
        if call is None:
            return
        if call.name == "command":
            yield call
        for arg in call.args:
            yield from command_calls(arg)
        i = call.end


def check_command_stderr(tree: etree._Element, rel: str, ev: LaunchEvaluator) -> list[Finding]:
    """A `$(command)` that fails on stderr around a command that writes to it fails the launch."""
    out = []
    for elem in tree.iter():
        if not isinstance(elem.tag, str):
            continue
        for attr, text in elem.attrib.items():
            for call in command_calls(text):
                on_stderr = ev.value(call.args[1]) if len(call.args) > 1 else ON_STDERR_DEFAULT
                command = ev.value(call.args[0]) if call.args else None
                if command is None or on_stderr != ON_STDERR_DEFAULT:
                    continue
                run = ev.command(command, on_stderr)
                if run.stderr.strip():
                    first = excerpt(run.stderr.strip().splitlines()[0], 120)
                    msg = (
                        f"{attr}: the command writes to stderr ('{first}') and $(command) fails the "
                        "launch on any stderr output by default: nothing after it starts"
                    )
                    hint = "$(command '...' warn) shows the warning without failing"
                    out.append(error("launch.command-stderr", rel, _where(elem), msg, hint))
    return out


def check_demo_hardware(
    tree: etree._Element, rel: str, ev: LaunchEvaluator, distro: str | None
) -> list[Finding]:
    """The demo's robot description, with the default args, has only mock ros2_control hardware."""
    from marm_setup.robot import systems_in_urdf

    out, seen = [], set()
    for node in tree.iter("node"):
        if node.get("exec") not in DESCRIPTION_NODES or _disabled(node, ev):
            continue
        for param in node.iter("param"):
            value = ev.value(param.get("value", "")) if param.get("name") == "robot_description" else None
            for system in systems_in_urdf(value or ""):
                if system.is_mock(distro) or system.name in seen:
                    continue
                seen.add(system.name)
                msg = (
                    f"with its default args the demo starts ros2_control system '{system.name}' on "
                    f"'{system.plugin}', not mock hardware: it would drive the real robot"
                )
                hint = (
                    "put every system on mock_components/GenericSystem on the demo's path (use_mock_hardware)"
                )
                out.append(error("demo.real-hardware", rel, _where(param), msg, hint))
    return out


def _disabled(elem: etree._Element, ev: LaunchEvaluator) -> bool:
    """An `if` that evaluates false or an `unless` that evaluates true (unknown: enabled)."""
    for attr, off in (("if", ("false", "0")), ("unless", ("true", "1"))):
        text = elem.get(attr)
        if text is not None:
            value = ev.value(text)
            if value is not None and value.strip().lower() in off:
                return True
    return False


def check_install_paths(pkg: MoveItPackage) -> list[Finding]:
    """Launch and xacro files of the package that reach out of a package's share folder."""
    files = sorted(
        {*pkg.launch_files, *(p.relative_to(pkg.root).as_posix() for p in pkg.root.rglob("*.xacro"))}
    )
    out = []
    for rel in files:
        if not inside(pkg.path(rel), (pkg.root,)):  # a symlink leaving the package: package.outside
            continue
        try:
            text = read_bytes(pkg.path(rel), XML_BYTES).decode("utf-8", errors="replace")
        except (OSError, FileTooLarge):  # too large: not searched (its own rules say why)
            continue
        for m in SHARE_PATH.finditer(text):
            tail = m.group(3) if m.group(4) is None else m.group(4)
            depth = len(Path(rel).parent.parts) if m.group(4) is not None else 0
            if tail and _climbs_out(tail, depth):
                out.append(_leaves_package(pkg, rel, text, m))
    return out


def _climbs_out(tail: str, depth: int) -> bool:
    """A `/a/../..` tail, read from `depth` folders below the share folder, goes above it."""
    for part in tail.split("/"):
        if part == "..":
            depth -= 1
            if depth < 0:
                return True
        elif part not in ("", "."):
            depth += 1
    return False


def _leaves_package(pkg: MoveItPackage, rel: str, text: str, m: re.Match) -> Finding:
    line = text.count("\n", 0, m.start()) + 1
    msg = f"'{m.group(0)}' climbs out of the package's share folder: once installed nothing is there"
    hint = "install the file into the package (or use a file of a ROS package by its name)"
    if pkg.target == Target.ROS2:
        return error("launch.leaves-package", rel, f"line {line}", msg, hint)
    return warning(
        "launch.leaves-package", rel, f"line {line}", f"{msg} (works from a catkin devel space)", hint
    )
