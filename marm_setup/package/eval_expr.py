"""A restricted evaluator for launch files' `$(eval ...)`: the expressions MoveIt packages write,
and nothing that runs code.

roslaunch (ros/ros_comm noetic, tools/roslaunch/src/roslaunch/substitution_args.py, 1.15.15:
`_eval_dict` :302-311, `_DictWrapper` :313-322, `_eval` :324-347) calls Python's `eval` with
`true`/`false`/`True`/`False`, the builtins `list dict map str float int`, `env`, `optenv`,
`find`, every name of `math`, and per file `arg`, `anon`, `dirname`; a bare name is a launch arg
(converted like `convert_value(v, 'auto')`). Its only guard is refusing `__` in the text, which
NFKC look-alikes (`_＿globals_＿`) pass: Python normalises identifiers. ROS 2 launch's
`PythonExpression` (launch/substitutions/python_expression.py) evaluates with `math`'s names.

Here the expression is parsed with `ast` and walked over an allow-list: literals (numbers,
strings, lists, tuples, dicts), names (launch args, the constants above), the calls named above
and `math`'s number functions, arithmetic, comparisons, `in`, `and`/`or`/`not`, conditional
expressions and subscripts. Anything else (attributes, lambdas, comprehensions, `**` past a
bound, strings or numbers past a bound) is `EvalRefused` naming the construct. Every step is
bounded, so no expression runs long or grows large; callers still run it in the bounded child.
"""

from __future__ import annotations

import ast
import math
import operator
from collections.abc import Callable, Mapping
from typing import Any

MAX_EXPRESSION = 4096  # characters of one expression
MAX_INT_BITS = 4096  # an integer result (2**4096 has 1234 digits)
MAX_SEQUENCE = 100_000  # a string, list or tuple result
MAX_NODES = 2000  # syntax nodes of one expression

CONSTANTS: dict[str, Any] = {"true": True, "false": False, "True": True, "False": False, "None": None}
CONSTANTS.update({name: getattr(math, name) for name in ("pi", "e", "tau", "inf", "nan")})
MATH_FUNCTIONS = (
    *("acos", "asin", "atan", "atan2", "ceil", "copysign", "cos", "cosh", "degrees", "exp", "fabs"),
    *("floor", "fmod", "hypot", "isclose", "isfinite", "isinf", "isnan", "log", "log10", "log2"),
    *("radians", "sin", "sinh", "sqrt", "tan", "tanh", "trunc"),
)
BUILTINS: dict[str, Callable[..., Any]] = {"str": str, "float": float, "int": int, "list": list, "dict": dict}

_BINARY: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: operator.mul,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: operator.mod,
    ast.Pow: operator.pow,
}
_UNARY: dict[type, Callable[[Any], Any]] = {
    ast.USub: operator.neg,
    ast.UAdd: operator.pos,
    ast.Not: operator.not_,
}
_COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
    ast.Is: operator.is_,
    ast.IsNot: operator.is_not,
}


class EvalRefused(ValueError):
    """An expression the restricted evaluator does not run (or that fails), with why."""


def evaluate_expression(
    expression: str, names: Mapping[str, Any], functions: Mapping[str, Callable[..., Any]]
) -> Any:
    """The value of `expression`; `names` are the launch args (already converted), `functions`
    the launch's own (`arg`, `env`, `optenv`, `find`, `anon`, `dirname`). EvalRefused otherwise."""
    if len(expression) > MAX_EXPRESSION:
        raise EvalRefused(f"longer than {MAX_EXPRESSION} characters")
    try:
        tree = ast.parse(expression.strip(), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:
        raise EvalRefused(
            f"not a Python expression ({getattr(exc, 'msg', None) or type(exc).__name__})"
        ) from None
    if sum(1 for _ in ast.walk(tree)) > MAX_NODES:
        raise EvalRefused(f"more than {MAX_NODES} syntax nodes")
    calls = {**BUILTINS, **{n: getattr(math, n) for n in MATH_FUNCTIONS}, **functions}
    return _Walker(names, calls).value(tree.body)


class _Walker:
    def __init__(self, names: Mapping[str, Any], calls: Mapping[str, Callable[..., Any]]):
        self.names = names
        self.calls = calls

    def value(self, node: ast.AST) -> Any:
        method = getattr(self, f"_{type(node).__name__}", None)
        if method is None:
            allowed = "args, literals, arithmetic, comparisons, and/or/not, if-else and the launch functions"
            raise EvalRefused(f"{_describe(node)} is not evaluated (only {allowed} are)")
        try:
            return _bounded(method(node))
        except EvalRefused:
            raise
        except (ArithmeticError, TypeError, ValueError, KeyError, IndexError, RecursionError) as exc:
            raise EvalRefused(f"{type(exc).__name__}: {exc}") from None

    def _Constant(self, node: ast.Constant) -> Any:
        if not isinstance(node.value, (int, float, str, bool, type(None))):
            raise EvalRefused(f"a {type(node.value).__name__} literal is not evaluated")
        return node.value

    def _Name(self, node: ast.Name) -> Any:
        if node.id in CONSTANTS:  # roslaunch's _DictWrapper: its own names first, then the args
            return CONSTANTS[node.id]
        if node.id in self.calls:
            return self.calls[node.id]
        if node.id in self.names:
            return self.names[node.id]
        raise EvalRefused(f"unknown name '{node.id}' (not a launch arg)")

    def _List(self, node: ast.List) -> list:
        return [self.value(e) for e in node.elts]

    def _Tuple(self, node: ast.Tuple) -> tuple:
        return tuple(self.value(e) for e in node.elts)

    def _Dict(self, node: ast.Dict) -> dict:
        if any(k is None for k in node.keys):
            raise EvalRefused("'**' in a dict is not evaluated")
        return {self.value(k): self.value(v) for k, v in zip(node.keys, node.values, strict=True)}  # type: ignore[arg-type]

    def _BinOp(self, node: ast.BinOp) -> Any:
        op = _BINARY.get(type(node.op))
        if op is None:
            raise EvalRefused(f"the operator {type(node.op).__name__} is not evaluated")
        left, right = self.value(node.left), self.value(node.right)
        _check_size(node.op, left, right)
        return op(left, right)

    def _UnaryOp(self, node: ast.UnaryOp) -> Any:
        op = _UNARY.get(type(node.op))
        if op is None:
            raise EvalRefused(f"the operator {type(node.op).__name__} is not evaluated")
        return op(self.value(node.operand))

    def _BoolOp(self, node: ast.BoolOp) -> Any:
        result: Any = None
        for operand in node.values:  # short-circuit as Python does
            result = self.value(operand)
            if bool(result) is isinstance(node.op, ast.Or):
                return result
        return result

    def _Compare(self, node: ast.Compare) -> bool:
        left = self.value(node.left)
        for op, right_node in zip(node.ops, node.comparators, strict=True):
            right = self.value(right_node)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _IfExp(self, node: ast.IfExp) -> Any:
        return self.value(node.body) if self.value(node.test) else self.value(node.orelse)

    def _Subscript(self, node: ast.Subscript) -> Any:
        container = self.value(node.value)
        if isinstance(node.slice, ast.Slice):
            parts = (node.slice.lower, node.slice.upper, node.slice.step)
            return container[slice(*(None if p is None else self.value(p) for p in parts))]
        return container[self.value(node.slice)]

    def _Call(self, node: ast.Call) -> Any:
        if not isinstance(node.func, ast.Name) or node.func.id not in self.calls or node.keywords:
            name = node.func.id if isinstance(node.func, ast.Name) else _describe(node.func)
            raise EvalRefused(f"the call {name}(...) is not evaluated")
        return self.calls[node.func.id](*(self.value(a) for a in node.args))


def _check_size(op: ast.operator, left: Any, right: Any) -> None:
    """Refuse an operation whose result would pass the bounds before computing it."""
    big = _is_int(left) and _is_int(right) and right > 0 and abs(left) > 1
    if isinstance(op, ast.Pow) and big and abs(left).bit_length() * right > MAX_INT_BITS:
        raise EvalRefused(f"{_short(left)} ** {_short(right)} is larger than {MAX_INT_BITS} bits")
    if isinstance(op, ast.Mult):
        seq, count = (left, right) if isinstance(left, (str, list, tuple)) else (right, left)
        if isinstance(seq, (str, list, tuple)) and _is_int(count) and len(seq) * count > MAX_SEQUENCE:
            raise EvalRefused(f"a sequence repeated {_short(count)} times is longer than {MAX_SEQUENCE}")
        if isinstance(seq, (list, tuple)) and any(isinstance(e, (str, list, tuple, dict)) for e in seq):
            raise EvalRefused("repeating a list of strings or lists is not evaluated")
    if isinstance(op, ast.Mod) and isinstance(left, str):
        raise EvalRefused("string formatting with % is not evaluated")


def _bounded(result: Any) -> Any:
    if _is_int(result) and result.bit_length() > MAX_INT_BITS:
        raise EvalRefused(f"an integer larger than {MAX_INT_BITS} bits")
    if isinstance(result, (str, list, tuple, dict)) and len(result) > MAX_SEQUENCE:
        raise EvalRefused(f"a value longer than {MAX_SEQUENCE}")
    return result


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _short(value: Any) -> str:
    text = str(value)
    return text if len(text) <= 20 else text[:17] + "..."


def _describe(node: ast.AST) -> str:
    if isinstance(node, ast.Attribute):
        return f"the attribute '.{node.attr}'"
    if isinstance(node, ast.Name):
        return f"'{node.id}'"
    return f"a {type(node).__name__}"
