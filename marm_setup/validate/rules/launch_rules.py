"""Launch XML and package.xml: well-formed, paths into this package exist, args defined, typed params."""

from __future__ import annotations

import fnmatch
import os
import re
import shlex
from pathlib import Path

import yaml

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.findings import Finding, error, warning
from marm_setup.package import (
    LaunchXml,
    Scope,
    SubstitutionError,
    SubstitutionTooLarge,
    condition,
    substitute,
)
from marm_setup.ros import Target

FIND = re.compile(r"\$\((find|find-pkg-share)\s+([^\s)]+)\)|\$\((dirname)\)")
ARG_USE = re.compile(r"\$\((arg|var)\s+([^\s)]+)\)|\barg\(\s*['\"]([^'\"]+)['\"]\s*\)")
PATH_TAIL = re.compile(r"[^\s'\"]*")
FILE_ATTRS = ("file", "textfile", "command")


def check_launch_files(
    root: Path, package: str, launch: tuple[LaunchXml, ...], target: Target
) -> list[Finding]:
    """Every launch rule over the package's (parsed) launch files."""
    out: list[Finding] = [t.problem for t in launch if t.problem is not None]
    parsed = {t.file: t.root for t in launch if t.root is not None}
    shared_args = (
        set().union(*(_defined_args(t) for t in parsed.values())) if target == Target.ROS2 else set()
    )
    passed = passed_args(parsed, root, package)
    for rel, tree in parsed.items():
        out += check_paths(tree, rel, root, package, target == Target.ROS2)
        out += check_args(tree, rel, _defined_args(tree) | shared_args | passed.get(rel, set()))
        out += check_arg_growth(tree, rel, root / rel, target == Target.ROS2)
        if target == Target.ROS2:
            out += check_description_types(tree, rel)
        else:
            out += check_rosparam_mappings(tree, rel, root, package)
    return out


def passed_args(parsed: dict, root: Path, package: str) -> dict[str, set[str]]:
    """Args each file receives through `<include pass_all_args="true">` from files of this
    package (transitively): roslaunch's xmlloader.py `_include_tag` adds every arg of the
    including context to the child's, so the child may use them without declaring them."""
    edges: list[tuple[str, str]] = []
    for rel, tree in parsed.items():
        for inc in tree.iter("include"):
            if (inc.get("pass_all_args") or "").strip().lower() in ("true", "1"):
                pattern = _include_pattern(inc.get("file") or "", root, rel, package)
                edges += [(rel, child) for child in parsed if pattern and fnmatch.fnmatchcase(child, pattern)]
    out: dict[str, set[str]] = {}
    changed = True
    while changed:  # a fixpoint: a child passes on what it received
        changed = False
        for parent, child in edges:
            given = _defined_args(parsed[parent]) | out.get(parent, set())
            if not given <= out.get(child, set()):
                out[child] = out.get(child, set()) | given
                changed = True
    return out


def _include_pattern(text: str, root: Path, rel: str, package: str) -> str | None:
    """The package-relative path (a glob where it holds a substitution, as in
    `$(dirname)/$(arg moveit_controller_manager)_moveit_controller_manager.launch.xml`) that
    an include's `file` names, or None when it is outside this package."""
    m = FIND.match(text.strip())
    if m is None or (m.group(3) != "dirname" and m.group(2) != package):
        return None
    base = (root / rel).parent if m.group(3) == "dirname" else root
    tail = re.sub(r"\$\([^)]*\)", "*", text.strip()[m.end() :]).lstrip("/")
    path = os.path.normpath(os.path.relpath(base / tail, root))
    return None if path.startswith("..") else path.replace(os.sep, "/")


def _elements(tree):
    return (e for e in tree.iter() if isinstance(e.tag, str))


def _where(elem) -> str:
    name = elem.get("name")
    label = f"{elem.tag}[{name}]" if name else elem.tag
    return f"line {elem.sourceline}: {label}"


def check_paths(tree, rel: str, root: Path, package: str, ros2: bool = False) -> list[Finding]:
    """`$(find <this package>)/x`, `$(find-pkg-share ...)/x` and `$(dirname)/x` must exist.

    A file the launcher opens (`file`, `textfile`, `command`, a ROS 2 `<param from>`) is an error
    on the branch the file's own arg defaults take: roslaunch stops ("error loading <rosparam>
    tag: file does not exist", ros/ros_comm tools/roslaunch/src/roslaunch/loader.py l.390-391 at
    845f746; an `<include>` or `textfile` likewise), and launch_ros skips a parameter file that is
    not a file with only a log line, so the node starts without those parameters: move_group
    without its pipelines, kinematics or controllers (ros2/launch_ros
    launch_ros/actions/node.py l.459-463 at humble 25a207c and jazzy 62c56e5). On a branch only
    other args take (or that cannot be decided), and for any other attribute naming a path, a
    warning: with the defaults nothing fails. A path no launcher opens (an arg's value, a node's
    args) on a branch the defaults do not take: nothing, as roslaunch never opens it and the
    defaults never pass it on. MoveIt's own Setup Assistant template sets `launch_prefix` to `gdb
    -x $(dirname)/gdb_settings.gdb ...` only `if="$(arg debug)"` and never writes that file
    (moveit/moveit moveit_setup_assistant/templates/moveit_config_pkg_template/launch/
    move_group.launch l.6-7 at noetic-devel 5555c3d; configuration_files_widget.cpp l.411-745 lists no
    gdb_settings.gdb), and gdb only reports a missing `-x` file and runs on."""
    out = []
    launch_dir = (root / rel).parent
    scope = _default_scope(tree, launch_dir, ros2)
    for elem in _elements(tree):
        for attr, text in elem.attrib.items():
            opened = attr in FILE_ATTRS or "$(command" in text or (attr == "from" and elem.tag == "param")
            for target, shown in _referenced(attr, text, root, launch_dir, package):
                if target.exists():
                    continue
                if opened and _taken(elem, scope):
                    msg = f"{attr} '{shown}' does not exist: {_consequence(elem, attr)}"
                    out.append(error("launch.missing-file", rel, _where(elem), msg))
                elif opened:
                    msg = f"{attr} '{shown}' does not exist (on a branch only non-default launch args take: the launch fails then)"
                    out.append(warning("launch.missing-file", rel, _where(elem), msg))
                elif target.suffix and _taken(elem, scope):
                    msg = f"{attr} refers to '{shown}', which does not exist"
                    out.append(warning("launch.missing-file", rel, _where(elem), msg))
    return out


def _consequence(elem, attr: str) -> str:
    """What the launcher does without the file."""
    if attr == "from":
        return "launch_ros skips it ('Parameter file path is not a file'): the node starts without these parameters"
    if elem.tag == "rosparam":
        return "roslaunch stops ('error loading <rosparam> tag: file does not exist')"
    return "the launch fails"


def check_rosparam_mappings(tree, rel: str, root: Path, package: str) -> list[Finding]:
    """A `<rosparam command="load">` without `param` whose YAML is not a mapping (a top-level list
    or scalar): roslaunch stops ("'param' attribute must be set for non-dictionary values",
    ros/ros_comm tools/roslaunch/src/roslaunch/loader.py l.432-434 at 845f746). An error on the
    branch the file's arg defaults take, else a warning; YAML that does not parse is left to the
    rules of the file's kind."""
    from marm_setup.package import RosparamLoader
    from marm_setup.safe_yaml import load_yaml

    out = []
    launch_dir = (root / rel).parent
    scope = _default_scope(tree, launch_dir, ros2=False)
    for elem in tree.iter("rosparam"):
        if (elem.get("command") or "load") != "load" or elem.get("param"):
            continue
        targets = list(_referenced("file", elem.get("file") or "", root, launch_dir, package))
        try:
            texts = [bounded_read.read_text(t, bounded_read.YAML_BYTES) for t, _ in targets[:1]]
            data = load_yaml(texts[0] if texts else (elem.text or ""), RosparamLoader)
        except (OSError, UnicodeDecodeError, FileTooLarge, yaml.YAMLError):
            continue
        if data is None or isinstance(data, dict) or (not targets and elem.get("file")):
            continue
        what = f"'{targets[0][1]}'" if targets else "its text"
        kind = "a list" if isinstance(data, list) else f"the {type(data).__name__} {data!r:.40}"
        msg = (
            f"{what} holds {kind}, not a mapping, and no param attribute names where it goes: "
            "roslaunch stops ('param' attribute must be set for non-dictionary values)"
        )
        make = error if _taken(elem, scope) else warning
        hint = 'add param="NAME" or make the YAML a mapping'
        out.append(make("launch.rosparam-not-mapping", rel, _where(elem), msg, hint))
    return out


def check_arg_growth(tree, rel: str, path: Path, ros2: bool) -> list[Finding]:
    """The first arg whose default, built from the args before it (`$(arg a)$(arg a)` doubling
    each time), grows past the substitution bound: roslaunch and ros2 launch build it whole (a
    string of 2**n characters: out of memory); validate stops there (one finding, no value)."""
    args: dict[str, str] = {}
    for elem in _elements(tree):
        name, value = elem.get("name"), elem.get("default", elem.get("value"))
        if elem.tag not in ("arg", "let") or not name or value is None or "$(eval" in value:
            continue
        if getattr(elem.getparent(), "tag", None) == "include":
            continue
        try:
            args[name] = substitute(value, Scope(args, dirname=str(path.parent), ros2=ros2))
        except SubstitutionTooLarge as exc:
            return [error("launch.substitution-bound", rel, _where(elem), f"arg '{name}': {exc}")]
        except SubstitutionError:
            continue
    return []


def _default_scope(tree, launch_dir: Path, ros2: bool) -> Scope:
    """The substitutions a launch file sees run on its own: its args' defaults (or fixed values)."""
    args = {
        e.get("name"): e.get("default", e.get("value"))
        for e in _elements(tree)
        if e.tag == "arg" and e.get("name") and getattr(e.getparent(), "tag", None) != "include"
    }
    known = {name: value for name, value in args.items() if value is not None}
    return Scope(known, dirname=str(launch_dir), ros2=ros2)


def _taken(elem, scope: Scope) -> bool:
    """Whether the element and every element around it are on the branch `scope` takes (an
    `if` / `unless` that cannot be decided counts as not taken)."""
    return all(condition(e, scope) is True for e in (elem, *elem.iterancestors()))


WHOLE_PATH_ATTRS = ("file", "textfile", "binfile")


def _words(attr: str, text: str) -> list[tuple[str, bool]]:
    """Pieces of `text` as roslaunch reads them, each with whether a path runs to its end: a
    `file` / `textfile` / `binfile` value is one path (spaces and all); a `command` is split as
    a shell would (roslaunch loader.py param_value: `shlex.split(command)`); any other value is
    scanned whole, a path ending at white space or a quote."""
    if attr in WHOLE_PATH_ATTRS:
        return [(text.strip(), True)]
    if attr == "command":
        try:
            return [(word, True) for word in shlex.split(text)]
        except ValueError:  # an unbalanced quote: roslaunch fails on it too
            pass
    return [(text, False)]


def _referenced(attr: str, text: str, root: Path, launch_dir: Path, package: str):
    """(absolute path, path as written) for each resolvable path into this package in `text`."""
    for word, whole in _words(attr, text):
        for m in FIND.finditer(word):
            tail_match = None if whole else PATH_TAIL.match(word, m.end())
            tail = word[m.end() :] if whole else (tail_match.group(0) if tail_match else "")
            if "$(" in tail or not tail.strip("/"):
                continue
            if m.group(3) == "dirname":
                yield launch_dir / tail.lstrip("/"), f"$(dirname){tail}"
            elif m.group(2) == package:
                yield root / tail.lstrip("/"), f"$({m.group(1)} {package}){tail}"


def _defined_args(tree) -> set[str]:
    """Args a file declares (an `<arg>` inside `<include>` passes a value on; it declares nothing)."""
    return {
        e.get("name")
        for e in _elements(tree)
        if e.tag in ("arg", "let") and e.get("name") and getattr(e.getparent(), "tag", None) != "include"
    }


def check_args(tree, rel: str, defined: set[str]) -> list[Finding]:
    """Every `$(arg x)` / `$(var x)` / `arg('x')` names an `<arg>` this file can see."""
    out = []
    for elem in _elements(tree):
        for attr, text in elem.attrib.items():
            for m in ARG_USE.finditer(text):
                name = m.group(2) or m.group(3)
                if name and name not in defined and "$(" not in name:
                    msg = f"{attr} uses undefined arg '{name}'"
                    out.append(
                        error(
                            "launch.undefined-arg",
                            rel,
                            _where(elem),
                            msg,
                            f'declare <arg name="{name}" .../>',
                        )
                    )
    return out


def check_description_types(tree, rel: str) -> list[Finding]:
    """ROS 2: a `robot_description*` param must be typed `str` (or YAML parsing mangles the XML)."""
    out = []
    for elem in _elements(tree):
        if (
            elem.tag == "param"
            and (elem.get("name") or "").startswith("robot_description")
            and elem.get("type") != "str"
        ):
            msg = f"parameter '{elem.get('name')}' has no type=\"str\""
            out.append(error("launch.description-type", rel, _where(elem), msg, 'add type="str"'))
    return out


def check_package_xml(root: Path, rel: str | None) -> list[Finding]:
    """package.xml exists and parses with catkin_pkg (the strict ROS parser)."""
    if rel is None:
        return [error("package.missing", "package.xml", "", "no package.xml", "every ROS package needs one")]
    from catkin_pkg.package import InvalidPackage, parse_package_string

    from marm_setup.untrusted import inside

    if not inside(root / rel, (root,)):  # a symlink leaving the package: package.outside says so
        return []

    try:  # parse_package would read the file whole, however large
        text = bounded_read.read_text(root / rel, bounded_read.XML_BYTES, shown=rel)
        parse_package_string(text, filename=str(root / rel), warnings=[])
    except FileTooLarge as exc:
        return [error("package.invalid", rel, "", f"cannot read: {exc.message}")]
    except InvalidPackage as exc:
        text = " ".join(str(exc).split()).replace(str(root) + "/", "")
        return [error("package.invalid", rel, "", f"catkin_pkg rejects it: {text}")]
    except Exception as exc:  # catkin_pkg raises bare exceptions for malformed XML
        return [error("package.invalid", rel, "", f"cannot parse: {' '.join(str(exc).split())}")]
    return []
