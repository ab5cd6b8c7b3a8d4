"""Whether a parameter value fits its declared row, as ROS 2 reads it: rclcpp keeps a YAML
integer an integer, and refuses it for a double (a declared parameter: node_parameters.cpp
declare_parameter throws InvalidParameterTypeException; one read through get_parameter<double>:
ParameterValue::get throws ParameterTypeException "expected [double] got [integer]"); and the
generate_parameter_library validators a row carries (gt, gt_eq, lt, lt_eq, bounds, one_of,
not_empty, subset_of, element_bounds, lower/upper_element_bounds; others, e.g. moveit_servo's own, are not checked)."""

from __future__ import annotations

from collections.abc import Callable

from marm_setup.moveit_params.tables import ParamRow

_ARRAY_ITEM = {"string_array": "string", "double_array": "double", "int_array": "int", "bool_array": "bool"}


def is_number(value: object) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def fits(type_: str, value: object) -> bool:
    """Whether `value` (as YAML gave it) has the declared type."""
    if type_ in _ARRAY_ITEM:
        return isinstance(value, list | tuple) and all(fits(_ARRAY_ITEM[type_], v) for v in value)
    checks: dict[str, Callable[[object], bool]] = {
        "bool": lambda v: isinstance(v, bool),
        "int": lambda v: isinstance(v, int) and not isinstance(v, bool),
        "double": lambda v: isinstance(v, float),
        "number": is_number,
        "string": lambda v: isinstance(v, str),
        "list": lambda v: isinstance(v, list | tuple),
    }
    return checks.get(type_, lambda v: True)(value)


def type_problem(row: ParamRow, value: object) -> str | None:
    """Why `value` is not of the row's type (None: it is)."""
    if fits(row.type, value):
        return None
    if row.type == "double" and is_number(value):
        return f"the integer {value!r} where MoveIt declares a double (write {float(value)!r})"  # type: ignore[arg-type]
    if row.type == "double_array" and isinstance(value, list | tuple) and all(map(is_number, value)):
        return "integers in a list MoveIt declares as doubles (write each with a decimal point)"
    return f"expected {row.type.replace('_', ' ')}, got {value!r}"


def validator_problem(row: ParamRow, value: object) -> str | None:
    """The first of the row's validators that `value` (already of its type) fails, else None."""
    for name, args in row.validation:
        check = _VALIDATORS.get(name)
        if check is not None and not check(value, args):
            return f"{value!r} fails {name}{list(args)} ({row.source})"
    return None


def _compare(op: Callable[[float, float], bool]) -> Callable[[object, tuple], bool]:
    return lambda v, a: not is_number(v) or op(v, a[0])  # type: ignore[arg-type]


_VALIDATORS: dict[str, Callable[[object, tuple], bool]] = {
    "gt": _compare(lambda v, b: v > b),
    "gt_eq": _compare(lambda v, b: v >= b),
    "lt": _compare(lambda v, b: v < b),
    "lt_eq": _compare(lambda v, b: v <= b),
    "bounds": lambda v, a: not is_number(v) or a[0] <= v <= a[1],
    "one_of": lambda v, a: v in a[0],
    "not_empty": lambda v, a: bool(v),
    "subset_of": lambda v, a: not isinstance(v, list | tuple) or set(v) <= set(a[0]),
    "element_bounds": lambda v, a: (
        not isinstance(v, list | tuple) or all(a[0] <= x <= a[1] for x in v if is_number(x))
    ),
    "lower_element_bounds": lambda v, a: (
        not isinstance(v, list | tuple) or all(x >= a[0] for x in v if is_number(x))
    ),
    "upper_element_bounds": lambda v, a: (
        not isinstance(v, list | tuple) or all(x <= a[0] for x in v if is_number(x))
    ),
}
# NaN fails every comparison above (each asks that the value lie inside its bound), as it fails
# generate_parameter_library's gt / gt_eq / lt / lt_eq (parameter_traits: OK only when the
# comparison holds).
