"""`marm_setup.yaml` <-> SetupModel: typed conversion driven by the dataclasses' field types.

Dump: fields in declaration order, `None` and empty lists left out (an empty list is kept where
the field's default is None: there it says "none" rather than "the default"), `(name, value)` tuples as
mappings. Load: unknown keys and wrong types are InputErrors naming the key path
(`groups[arm].joints[3]`) and, for unknown keys, the closest valid key.
"""

from __future__ import annotations

import dataclasses
import enum
import math
import types
import typing
from functools import cache
from os import PathLike

import yaml

from marm_setup import bounded_read
from marm_setup.collision import PROVE_MODES, DisabledPair, UnprovedPair, link_pair
from marm_setup.errors import InputError
from marm_setup.moveit_params import (
    DRIVERS,
    MOVEIT_CONTROLLER_TYPES,
    OMPL_PLANNER_NAMES,
    SENSOR_TYPES,
    SERVO_COMMAND_IN_TYPES,
    SERVO_OUTPUTS,
    VIRTUAL_JOINT_TYPES,
)
from marm_setup.names import did_you_mean, with_hint
from marm_setup.safe_yaml import UniqueKeyLoader, load_yaml
from marm_setup.setup.model import (
    CollisionSettings,
    Controller,
    PlannerDefaults,
    Sensor,
    Servo,
    SetupModel,
    VirtualJoint,
)

HEADER = "# marm-setup: this robot's MoveIt setup. Edit it, then run `marm-setup render DIR`.\n"

# Fields whose strings must be one of a few values: (class, field) -> allowed values.
CHOICES: dict[tuple[type, str], tuple[str, ...]] = {
    (SetupModel, "driver"): DRIVERS,
    (VirtualJoint, "type"): VIRTUAL_JOINT_TYPES,
    (Controller, "type"): MOVEIT_CONTROLLER_TYPES,
    (PlannerDefaults, "default_planner"): OMPL_PLANNER_NAMES,
    (Servo, "command_out"): SERVO_OUTPUTS,
    (Servo, "command_in_type"): SERVO_COMMAND_IN_TYPES,
    (Sensor, "type"): tuple(SENSOR_TYPES),
    (CollisionSettings, "prove"): PROVE_MODES,
}
# Integer fields with a least value: (class, field) -> minimum. A seed seeds numpy's
# SeedSequence, which refuses a negative one ("expected non-negative integer").
MINIMUMS: dict[tuple[type, str], int] = {
    (CollisionSettings, "seed"): 0,
}
# Keys that name a list item in key paths (`groups[arm]`), tried in order.
ITEM_KEYS = ("name", "group", "joint", "link")


# -- dump ----------------------------------------------------------------------------------------


def dump_setup(model: SetupModel) -> str:
    """The YAML text of a setup: stable key order, no flow style, ends with a newline."""
    body = yaml.safe_dump(setup_to_dict(model), sort_keys=False, default_flow_style=False, width=100)
    return HEADER + body


def setup_to_dict(model: SetupModel) -> dict:
    return _dump_value(model, SetupModel)


def _dump_value(value, hint):
    if dataclasses.is_dataclass(value):
        return _dump_dataclass(value)
    if isinstance(value, enum.Enum):
        return value.value
    if isinstance(value, tuple):
        if _is_pairs(hint):
            _, value_hint = _pair_hints(hint)
            return {k: _dump_value(v, value_hint) for k, v in value}
        item_hint = _item_hint(hint)
        return [_dump_value(v, item_hint) for v in value]
    return value


def _dump_dataclass(obj: typing.Any) -> dict:
    cls: type = type(obj)
    hints = _hints(cls)
    out = {}
    for f in dataclasses.fields(obj):
        value = getattr(obj, f.name)
        required = f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
        empty_means_none = value == () and f.default is not None  # () defaults to (): left out
        if not required and (value is None or empty_means_none):
            continue
        dumped = _dump_value(value, hints[f.name])
        if dumped == {} and dataclasses.is_dataclass(value):
            continue
        out[f.name] = dumped
    return out


# -- load ----------------------------------------------------------------------------------------


def load_setup(path: str | PathLike) -> SetupModel:
    """Read `marm_setup.yaml` (or a complete SPEC); errors name the file as given."""
    return setup_from_dict(read_yaml_mapping(path), str(path))


def read_yaml_mapping(path: str | PathLike) -> dict:
    shown = str(path)
    try:
        text = bounded_read.read_text(path, bounded_read.YAML_BYTES, shown=shown)
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=shown) from None
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=shown) from None
    try:
        data = load_yaml(text, UniqueKeyLoader)
    except yaml.YAMLError as exc:
        where = getattr(exc, "problem_mark", None)
        at = f" (line {where.line + 1})" if where is not None else ""
        raise InputError(f"not valid YAML{at}: {getattr(exc, 'problem', exc)}", path=shown) from None
    if data is None:
        return {}
    if not isinstance(data, dict):
        raise InputError(f"expected a mapping at the top, got {_kind(data)}", path=shown)
    return data


def setup_from_dict(data: dict, path: str | None = None) -> SetupModel:
    """Build a SetupModel from parsed YAML, checking keys and types."""
    return _load_dataclass(SetupModel, data, _Ctx(path), "")


@dataclasses.dataclass(frozen=True)
class Partial:
    """Some fields of a setup (or of a mapping inside it: collision, author, ...), each read and
    type-checked as `setup_from_dict` reads it; the others keep the values they had."""

    cls: type
    values: tuple[tuple[str, object], ...]

    @property
    def keys(self) -> frozenset[str]:
        return frozenset(name for name, _ in self.values)

    def get(self, name: str) -> object:
        return next((value for key, value in self.values if key == name), None)


def patch_from_dict(data: dict, path: str | None = None, ignore: tuple[str, ...] = ()) -> Partial:
    """A SPEC (any subset of marm_setup.yaml) as a typed patch of a SetupModel: the same key and
    type errors as `setup_from_dict`; keys in `ignore` are left out (given elsewhere)."""
    return _load_partial(SetupModel, {k: v for k, v in data.items() if k not in ignore}, _Ctx(path), "")


def _load_partial(cls, data, ctx: _Ctx, where: str) -> Partial:
    if not isinstance(data, dict):
        raise ctx.fail(f"expected a mapping, got {_kind(data)}", where)
    hints = _hints(cls)
    for key in data:
        if key not in hints:
            raise ctx.fail(
                _unknown_key(key, [f.name for f in dataclasses.fields(cls)]), _join(where, str(key))
            )
    values = []
    for f in dataclasses.fields(cls):
        if f.name not in data:
            continue
        inner, key_where = _dataclass_of(hints[f.name]), _join(where, f.name)
        if inner is not None and isinstance(data[f.name], dict):
            values.append((f.name, _load_partial(inner, data[f.name], ctx, key_where)))
            continue
        value = _load_value(hints[f.name], data[f.name], ctx, key_where)
        _check_choice(cls, f.name, value, ctx, key_where)
        values.append((f.name, value))
    return Partial(cls, tuple(values))


def _dataclass_of(hint) -> type | None:
    """The dataclass a field holds (also when it may be None), else None."""
    if typing.get_origin(hint) in (typing.Union, types.UnionType):
        inner = [a for a in typing.get_args(hint) if a is not type(None)]
        hint = inner[0] if len(inner) == 1 else None
    return hint if dataclasses.is_dataclass(hint) and isinstance(hint, type) else None


@dataclasses.dataclass(frozen=True)
class _Ctx:
    path: str | None

    def fail(self, message: str, where: str) -> InputError:
        return InputError(message, path=self.path, element=where or None)


def _load_dataclass(cls, data, ctx: _Ctx, where: str):
    if not isinstance(data, dict):
        raise ctx.fail(f"expected a mapping, got {_kind(data)}", where)
    hints = _hints(cls)
    names = [f.name for f in dataclasses.fields(cls)]
    for key in data:
        if key not in hints:
            raise ctx.fail(_unknown_key(key, names), _join(where, str(key)))
    kwargs = {}
    for f in dataclasses.fields(cls):
        if f.name in data:
            kwargs[f.name] = _load_value(hints[f.name], data[f.name], ctx, _join(where, f.name))
            _check_choice(cls, f.name, kwargs[f.name], ctx, _join(where, f.name))
            _check_minimum(cls, f.name, kwargs[f.name], ctx, _join(where, f.name))
        elif f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING:
            raise ctx.fail(f"missing key '{f.name}'", where)
    if cls is DisabledPair:
        return DisabledPair.of(kwargs["link1"], kwargs["link2"], kwargs["reason"])
    if cls is UnprovedPair:
        return UnprovedPair(*link_pair(kwargs["link1"], kwargs["link2"]), kwargs["proved_fraction"])
    return cls(**kwargs)


def _load_value(hint, data, ctx: _Ctx, where: str):
    origin, args = typing.get_origin(hint), typing.get_args(hint)
    if origin in (typing.Union, types.UnionType):
        if data is None and type(None) in args:
            return None
        arms = [a for a in args if a is not type(None)]
        return (
            _load_value(arms[0], data, ctx, where) if len(arms) == 1 else _load_union(arms, data, ctx, where)
        )
    if dataclasses.is_dataclass(hint):
        return _load_dataclass(hint, data, ctx, where)
    if isinstance(hint, type) and issubclass(hint, enum.Enum):
        return _load_enum(hint, data, ctx, where)
    if origin is tuple:
        return _load_tuple(hint, data, ctx, where)
    return _load_scalar(hint, data, ctx, where)


def _load_tuple(hint, data, ctx: _Ctx, where: str):
    if _is_pairs(hint):
        if not isinstance(data, dict):
            raise ctx.fail(f"expected a mapping of names to values, got {_kind(data)}", where)
        key_hint, value_hint = _pair_hints(hint)
        if _is_multi_union(value_hint):  # parameters: a nested mapping is dotted names
            data = dict(_dotted(data))
        return tuple(
            (
                _load_scalar(key_hint, k, ctx, _join(where, str(k))),
                _load_value(value_hint, v, ctx, _join(where, str(k))),
            )
            for k, v in data.items()
        )
    if not isinstance(data, list):
        raise ctx.fail(f"expected a list, got {_kind(data)}", where)
    args = typing.get_args(hint)
    if len(args) == 2 and args[1] is Ellipsis:
        return tuple(_load_value(args[0], v, ctx, _item_where(where, i, v)) for i, v in enumerate(data))
    if len(data) != len(args):
        raise ctx.fail(f"expected a list of {len(args)} values, got {len(data)}", where)
    return tuple(
        _load_value(a, v, ctx, f"{where}[{i}]") for i, (a, v) in enumerate(zip(args, data, strict=True))
    )


def _load_scalar(hint, data, ctx: _Ctx, where: str):
    if hint is float and isinstance(data, int | float) and not isinstance(data, bool):
        try:
            value = float(data)
        except OverflowError:  # an integer beyond any float
            raise ctx.fail(
                f"expected a finite number, got an integer of {len(str(data))} digits", where
            ) from None
        if not math.isfinite(value):
            raise ctx.fail(f"expected a finite number, got {data}", where)
        return value
    if hint is int and isinstance(data, int) and not isinstance(data, bool):
        return data
    if hint in (str, bool) and isinstance(data, hint):
        return data
    names = {str: "a string", int: "an integer", float: "a number", bool: "true or false"}
    raise ctx.fail(f"expected {names.get(hint, hint)}, got {_kind(data)}", where)


def _load_union(arms: list, data, ctx: _Ctx, where: str):
    """A value of one of several types (a pipeline parameter): the one its YAML type is; an
    integer where only a number is taken becomes one."""
    kind = type(data)
    if kind in arms:
        return _load_scalar(kind, data, ctx, where)
    if kind is int and float in arms:
        return _load_scalar(float, data, ctx, where)
    lists = [a for a in arms if typing.get_origin(a) is tuple]
    if isinstance(data, list) and lists:
        return _load_tuple(lists[0], data, ctx, where)
    names = {str: "a string", int: "an integer", float: "a number", bool: "true or false"}
    wanted = [names[a] for a in arms if a in names] + (["a list of strings"] if lists else [])
    raise ctx.fail(f"expected {', '.join(wanted)}; got {_kind(data)}", where)


def _load_enum(hint, data, ctx: _Ctx, where: str):
    valid = [m.value for m in hint]
    if data not in valid:
        raise ctx.fail(f"'{data}' is not one of: {', '.join(valid)}", where)
    return hint(data)


def _check_choice(cls, name: str, value, ctx: _Ctx, where: str) -> None:
    allowed = CHOICES.get((cls, name))
    if allowed is not None and value is not None and value not in allowed:
        message = f"'{value}' is not one of: {', '.join(allowed)}"
        raise ctx.fail(with_hint(message, did_you_mean(str(value), allowed, few=0)), where)


def _check_minimum(cls, name: str, value, ctx: _Ctx, where: str) -> None:
    least = MINIMUMS.get((cls, name))
    if least is not None and isinstance(value, int) and value < least:
        raise ctx.fail(f"must be >= {least}, got {value}", where)


# -- helpers -------------------------------------------------------------------------------------


@cache
def _hints(cls) -> dict:
    return typing.get_type_hints(cls)


def _is_pairs(hint) -> bool:
    """tuple[tuple[str, X], ...]: written as a YAML mapping."""
    args = typing.get_args(hint)
    if len(args) != 2 or args[1] is not Ellipsis or typing.get_origin(args[0]) is not tuple:
        return False
    inner = typing.get_args(args[0])
    return len(inner) == 2 and inner[0] is str and inner[1] is not Ellipsis


def _is_multi_union(hint) -> bool:
    return typing.get_origin(hint) in (typing.Union, types.UnionType) and len(typing.get_args(hint)) > 2


def _dotted(data: dict, prefix: str = ""):
    """(dotted name, value) of every leaf of a nested mapping, as ROS 2 names parameters."""
    for key, value in data.items():
        if isinstance(value, dict) and value:
            yield from _dotted(value, f"{prefix}{key}.")
        else:
            yield f"{prefix}{key}", value


def _pair_hints(hint):
    return typing.get_args(typing.get_args(hint)[0])


def _item_hint(hint):
    args = typing.get_args(hint)
    return args[0] if len(args) == 2 and args[1] is Ellipsis else None


def _item_where(where: str, index: int, item) -> str:
    if isinstance(item, dict):
        for key in ITEM_KEYS:
            if isinstance(item.get(key), str):
                return f"{where}[{item[key]}]"
    return f"{where}[{index}]"


def _join(where: str, key: str) -> str:
    return f"{where}.{key}" if where else key


def _unknown_key(key, valid: list[str]) -> str:
    return with_hint(f"unknown key '{key}'", did_you_mean(str(key), valid, few=math.inf))


def _kind(value) -> str:
    if value is None:
        return "nothing (null)"
    names = {
        bool: "a boolean",
        int: "an integer",
        float: "a number",
        str: "a string",
        list: "a list",
        dict: "a mapping",
    }
    text = names.get(type(value), type(value).__name__)
    return f"{text} ({value!r})" if isinstance(value, bool | int | float | str) else text
