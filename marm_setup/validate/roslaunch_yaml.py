"""What ROS 1's roslaunch loads: YAML with rosparam's angle tags and `subst_value`
substitutions, the rosparam files and the SRDF (with its xacro args) that launch files name.

- rosparam (`ros_comm/tools/rosparam/src/rosparam/__init__.py`, `construct_angle_radians` /
  `construct_angle_degrees` and the resolvers at the end of the module) adds the tags
  `!radians EXPR` (an arithmetic expression, `pi` allowed) and `!degrees NUMBER`, and reads the
  plain scalars `rad(EXPR)` and `deg(NUMBER)` the same way: all become radians.
- roslaunch (`tools/roslaunch/src/roslaunch/xmlloader.py` `_rosparam_tag`, then
  `loader.py` `load_rosparam`) runs `resolve_args` over a file's whole text before parsing it
  when the `<rosparam>` has `subst_value="true"`: `$(arg x)` takes the including launch file's
  arg value (or default), `$(find pkg)` the package folder, `$(env X)` / `$(optenv X d)` the
  environment, `$(dirname)` the launch file's folder. `$(eval ...)` is evaluated too (Debian's
  roslaunch 1.15 refuses it inside a file's text; newer ones and authors use it), never flagged.
"""

from __future__ import annotations

import ast
import math
import operator
import os
import re
from collections.abc import Callable, Mapping
from typing import Any

import yaml

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.safe_yaml import BoundedSafeLoader, load_yaml

SUBST = re.compile(r"\$\((arg|find|env|optenv|dirname|eval|anon)\b\s*([^()]*(?:\([^()]*\)[^()]*)*)\)")


class SubstitutionError(ValueError):
    """A substitution roslaunch could not resolve (unknown arg, package or variable)."""


class RosparamLoader(BoundedSafeLoader):
    """PyYAML's safe loader plus rosparam's angle tags and `deg()` / `rad()` scalars."""


def _radians(loader: RosparamLoader, node: yaml.ScalarNode) -> float:
    text = str(loader.construct_scalar(node)).strip()
    if text.startswith("rad(") and text.endswith(")"):
        text = text[4:-1]
    return arithmetic(text)


def _degrees(loader: RosparamLoader, node: yaml.ScalarNode) -> float:
    text = str(loader.construct_scalar(node)).strip()
    if text.startswith("deg(") and text.endswith(")"):
        text = text[4:-1]
    try:
        return float(text) * math.pi / 180.0
    except ValueError:
        raise yaml.constructor.ConstructorError(
            None, None, f"invalid degree value: {text}", node.start_mark
        ) from None


RosparamLoader.add_constructor("!radians", _radians)
RosparamLoader.add_constructor("!degrees", _degrees)
RosparamLoader.add_implicit_resolver("!degrees", re.compile(r"^deg\([^\)]*\)$"), ["d"])
RosparamLoader.add_implicit_resolver("!radians", re.compile(r"^rad\([^\)]*\)$"), ["r"])

_OPS: dict[type, Callable] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.Pow: operator.pow,
    ast.USub: operator.neg,
    ast.UAdd: operator.pos,
}


def arithmetic(text: str) -> float:
    """The value of `2*pi/3`-style expressions (numbers, pi, + - * / **), as rosparam evaluates them."""
    try:
        return float(_arith(ast.parse(text.strip(), mode="eval").body))
    except (SyntaxError, ValueError, KeyError, TypeError, ZeroDivisionError):
        raise yaml.YAMLError(f"invalid radian expression: {text}") from None


def _arith(node: ast.AST) -> float:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        return node.value
    if isinstance(node, ast.Name) and node.id == "pi":
        return math.pi
    if isinstance(node, ast.BinOp):
        return _OPS[type(node.op)](_arith(node.left), _arith(node.right))
    if isinstance(node, ast.UnaryOp):
        return _OPS[type(node.op)](_arith(node.operand))
    raise ValueError("not arithmetic")


def load_ros_yaml(text: str) -> Any:
    """Parse YAML text the way rosparam does (angle tags and scalars become radians)."""
    return load_yaml(text, RosparamLoader)  # a bounded SafeLoader subclass


def substitute(
    text: str,
    args: Mapping[str, str],
    find: Callable[[str], str | None],
    dirname: str = "",
    environ: Mapping[str, str] | None = None,
) -> str:
    """`text` with roslaunch's substitutions resolved; SubstitutionError names the first that fails."""
    environ = os.environ if environ is None else environ

    def one(match: re.Match) -> str:
        command, rest = match.group(1), match.group(2).strip()
        return _resolve(command, rest, args, find, dirname, environ)

    previous = None
    while previous != text and "$(" in text:  # an arg's value may hold substitutions itself
        previous, text = text, SUBST.sub(one, text)
    return text


def _resolve(command, rest, args, find, dirname, environ) -> str:
    words = rest.split()
    if command == "arg":
        if not words or words[0] not in args:
            raise SubstitutionError(f"$(arg {rest}): no such arg in the launch file that loads it")
        return str(args[words[0]])
    if command == "find":
        folder = find(words[0]) if words else None
        if folder is None:
            raise SubstitutionError(f"$(find {rest}): unknown package")
        return str(folder)
    if command == "env":
        if not words or words[0] not in environ:
            raise SubstitutionError(f"$(env {rest}): variable not set")
        return environ[words[0]]
    if command == "optenv":
        return environ.get(words[0], " ".join(words[1:])) if words else ""
    if command == "dirname":
        return dirname
    if command == "anon":
        return f"{words[0] if words else ''}_anon"
    return _eval(rest, args)


def _eval(expression: str, args: Mapping[str, str]) -> str:
    """roslaunch's `$(eval ...)` (substitution_args.py `_eval`): Python with `arg()` and the args."""
    if "__" in expression:
        raise SubstitutionError("$(eval ...) may not contain double underscores")
    names: dict[str, Any] = {name: _auto(value) for name, value in args.items()}
    names.update(arg=lambda name: _auto(args[name]), true=True, false=False)
    try:
        return str(eval(expression, {"__builtins__": {}}, names))  # noqa: S307 - roslaunch's own semantics
    except Exception as exc:  # noqa: BLE001 - any failure of the expression is the author's
        raise SubstitutionError(f"$(eval {expression}): {exc}") from None


def _auto(value: str) -> Any:
    """roslaunch's `convert_value(value, 'auto')`: int, float, bool, else the string."""
    for cast in (int, float):
        try:
            return cast(value)
        except ValueError:
            pass
    lowered = value.strip().lower()
    return {"true": True, "false": False}.get(lowered, value)


# -- which launch file loads a YAML file with subst_value, and with which args ----------------


def subst_contexts(
    root, launch_files: tuple[str, ...], find: Callable[[str], str | None]
) -> dict[str, tuple[dict[str, str], str]]:
    """Package YAML files (relative paths) that a launch file loads with `subst_value="true"`,
    each with (that launch file's args, the launch file's folder); the first launch file (sorted)
    that loads a file wins."""
    trees = list(_launch_trees(root, launch_files, find))
    effective = _with_included_args(root, trees, find)
    out: dict[str, tuple[dict[str, str], str]] = {}
    for rel, tree, _own, dirname in trees:
        args = effective[rel]
        for elem in tree.iter("rosparam"):
            if (elem.get("subst_value") or "").strip().lower() not in ("true", "1"):
                continue
            target = _loaded_file(elem.get("file"), args, find, dirname, root)
            if target is not None:
                out.setdefault(target, (args, dirname))
    return out


def _with_included_args(root, trees, find) -> dict[str, dict[str, str]]:
    """Each launch file's args, plus what the package's other launch files pass to it through
    `<include>`: `<arg name value>` children, and every arg with `pass_all_args` (roslaunch
    xmlloader.py `_include_tag`); passed values win over the file's defaults. A few rounds carry
    them down include chains (demo -> move_group -> trajectory_execution -> ...)."""
    effective = {rel: dict(own) for rel, _tree, own, _dirname in trees}
    for _round in range(4):
        passed: dict[str, dict[str, str]] = {}
        for rel, tree, _own, dirname in trees:
            for inc in tree.iter("include"):
                target = _loaded_file(inc.get("file"), effective[rel], find, dirname, root)
                if target is not None and target in effective:  # the first includer (sorted) wins
                    given = _include_args(inc, effective[rel], find, dirname)
                    mine = passed.setdefault(target, {})
                    mine.update({k: v for k, v in given.items() if k not in mine})
        effective = {rel: {**own, **passed.get(rel, {})} for rel, _tree, own, _dirname in trees}
    return effective


def _include_args(inc, args: dict[str, str], find, dirname: str) -> dict[str, str]:
    given = dict(args) if (inc.get("pass_all_args") or "").strip().lower() in ("true", "1") else {}
    for elem in inc.iterchildren("arg"):
        name, value = elem.get("name"), elem.get("value")
        if name and value is not None:
            try:
                given[name] = substitute(value, args, find, dirname)
            except SubstitutionError:
                continue
    return given


def launch_args(tree, find: Callable[[str], str | None], dirname: str) -> dict[str, str]:
    """A launch file's own args (value, else default), substitutions inside them resolved where
    they can be; an arg without either is left out (whoever includes the file must pass it)."""
    raw: dict[str, str] = {}
    for elem in tree.iter("arg"):
        parent = elem.getparent()
        if elem.get("name") and getattr(parent, "tag", None) != "include":
            value = elem.get("value", elem.get("default"))
            if value is not None:
                raw.setdefault(elem.get("name"), value)
    out = {}
    for name, value in raw.items():
        try:
            out[name] = substitute(value, raw, find, dirname)
        except SubstitutionError:
            continue
    return out


def _loaded_file(attr, args, find, dirname, root) -> str | None:
    if not attr:
        return None
    try:
        path = os.path.normpath(substitute(attr, args, find, dirname))
    except SubstitutionError:
        return None
    rel = os.path.relpath(path, root)
    return None if rel.startswith("..") else rel.replace(os.sep, "/")


def _parse(path):
    from lxml import etree

    try:
        data = bounded_read.read_bytes(path, bounded_read.XML_BYTES)
        return etree.fromstring(data, etree.XMLParser(remove_comments=True), base_url=str(path))
    except (etree.XMLSyntaxError, OSError, FileTooLarge):
        return None


# -- what the launch files load: rosparam files and the SRDF (with its xacro args) -------------


def loaded_files(root, launch_files: tuple[str, ...], find: Callable[[str], str | None]) -> list[str]:
    """Package files (relative paths) that `<rosparam file=...>` elements load, in launch order."""
    out: list[str] = []
    for _rel, tree, args, dirname in _launch_trees(root, launch_files, find):
        for elem in tree.iter("rosparam"):
            target = _loaded_file(elem.get("file"), args, find, dirname, root)
            if target is not None and target not in out:
                out.append(target)
    return out


def launch_srdf(
    root, launch_files: tuple[str, ...], find: Callable[[str], str | None]
) -> tuple[str, tuple[tuple[str, str], ...]] | None:
    """The SRDF a launch file sets as `*_semantic` (MoveIt 1 planning_context.launch): from
    `textfile=`, or from `command="xacro FILE a:=b ..."` with those xacro args (launch args
    substituted); the first launch file (sorted) that sets one wins."""
    for _rel, tree, args, dirname in _launch_trees(root, launch_files, find):
        for elem in tree.iter("param"):
            name = elem.get("name") or ""
            if not name.endswith("_semantic"):
                continue
            if elem.get("textfile"):
                target = _loaded_file(elem.get("textfile"), args, find, dirname, root)
                if target is not None:
                    return target, ()
            found = _xacro_command(elem.get("command"), args, find, dirname, root)
            if found is not None:
                return found
    return None


def _xacro_command(command, args, find, dirname, root):
    if not command:
        return None
    try:
        # `$(find xacro)/xacro`: the tool's own package need not be on the package path
        text = substitute(command, args, lambda name: find(name) or f"/{name}", dirname)
        words = text.replace("'", " ").replace('"', " ").split()
    except SubstitutionError:
        return None
    files = [w for w in words if w.endswith(".xacro") or w.endswith(".srdf")]
    if not files:
        return None
    target = _loaded_file(files[-1], {}, find, dirname, root)
    mappings = tuple(tuple(w.split(":=", 1)) for w in words if ":=" in w and not w.startswith("__"))
    return (target, tuple(sorted(mappings))) if target is not None else None


def _launch_trees(root, launch_files, find):
    for rel in launch_files:
        tree = _parse(root / rel)
        if tree is not None:
            dirname = str((root / rel).parent)
            yield rel, tree, launch_args(tree, find, dirname), dirname
