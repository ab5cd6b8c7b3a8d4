"""rosparam's YAML: the angle tags and scalars roslaunch's `<rosparam>` understands.

rosparam (`ros_comm/tools/rosparam/src/rosparam/__init__.py`, `construct_angle_radians` /
`construct_angle_degrees` and the resolvers at the end of the module) adds the tags
`!radians EXPR` (an arithmetic expression, `pi` allowed) and `!degrees NUMBER`, and reads the
plain scalars `rad(EXPR)` and `deg(NUMBER)` the same way: all become radians.
"""

from __future__ import annotations

import ast
import math
import operator
import re
from collections.abc import Callable

import yaml

from marm_setup.safe_yaml import BoundedSafeLoader


class RosparamLoader(BoundedSafeLoader):
    """PyYAML's bounded safe loader plus rosparam's angle tags and `deg()` / `rad()` scalars."""


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
