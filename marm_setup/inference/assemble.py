"""A setup assembled from its parts and checked once: the inferred (or SRDF-imported) setup with
a SPEC laid over it as a typed patch (`yaml_io.patch_from_dict`), what the SPEC replaces taken
out with what was inferred for it (`spec_overlay`), fitted to the robot.

A patch merges as the SPEC reads: a mapping key by key (`collision: {trials: 2000}` keeps the
other collision settings), a list of named items (name / group / joint / link) item by item (a
SPEC item replaces the one of the same name, new ones are appended), any other value replaced.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from marm_setup.inference.infer import fill_group_settings, fit_to_spec, home_poses
from marm_setup.inference.spec_overlay import patch_items, without_replaced
from marm_setup.robot import RobotModel
from marm_setup.setup import ITEM_KEYS, Partial, SetupModel, Style, check_setup, setup_element

# What the SPEC takes from other sources: the robot's place is the command line's.
COMMAND_LINE_KEYS = ("robot",)


def apply_patch(value: Any, patch: Partial) -> Any:
    """`value` (a setup, or a mapping inside it) with `patch` laid over it."""
    changes = {}
    for name, new in patch.values:
        old = getattr(value, name)
        if isinstance(new, Partial):
            changes[name] = apply_patch(old, new) if old is not None else _build(new)
        elif isinstance(old, tuple) and isinstance(new, tuple) and _keyed(old) and _keyed(new):
            changes[name] = _merge_items(old, new)
        else:
            changes[name] = new
    return dataclasses.replace(value, **changes)


def _build(patch: Partial) -> Any:
    """A mapping the setup had none of (ros2_control): its defaults with the patch over them."""
    return patch.cls(**{name: _build(v) if isinstance(v, Partial) else v for name, v in patch.values})


def _key(item: object) -> str | None:
    for name in ITEM_KEYS:
        value = getattr(item, name, None)
        if isinstance(value, str):
            return f"{name}={value}"
    return None


def _keyed(items: tuple) -> bool:
    return all(_key(i) is not None for i in items)


def _merge_items(old: tuple, new: tuple) -> tuple:
    """The setup's items in place, replaced by the SPEC's of the same key; the SPEC's others
    appended (duplicates in the SPEC are kept, so the checks report them)."""
    first_new: dict[str | None, int] = {}
    for index, item in enumerate(new):
        first_new.setdefault(_key(item), index)
    used = {first_new[_key(o)] for o in old if _key(o) in first_new}
    out = [new[first_new[_key(o)]] if _key(o) in first_new else o for o in old]
    return (*out, *(item for index, item in enumerate(new) if index not in used))


def with_spec(
    model: SetupModel, spec: Partial, robot: RobotModel, *, inferred_groups: bool, poses_from_srdf: bool
) -> SetupModel:
    """`model` with the SPEC's sections in place of its own, fitted to the robot; group settings
    filled when the groups are all the SPEC's, home poses when neither SPEC nor SRDF gives poses."""
    inferred = _make_room(model, spec)
    merged = without_replaced(inferred, apply_patch(inferred, spec), robot, patch_items(spec))
    model = fit_to_spec(merged, robot, spec.keys)
    if not inferred_groups:
        model = fill_group_settings(model, robot)
    if "group_states" not in spec.keys and not poses_from_srdf:
        model = dataclasses.replace(model, group_states=home_poses(model, robot))
    return model


def _make_room(model: SetupModel, spec: Partial) -> SetupModel:
    """Drop what the SPEC gives in its own way: its poses replace the inferred ones (pose names
    repeat across groups), and its end effectors those on the same groups."""
    if "group_states" in spec.keys:
        model = dataclasses.replace(model, group_states=())
    items = spec.get("end_effectors")
    if isinstance(items, tuple):
        taken = {e.group for e in items}
        model = dataclasses.replace(
            model, end_effectors=tuple(e for e in model.end_effectors if e.group not in taken)
        )
    return model


def checked(
    model: SetupModel, robot: RobotModel, path: str | None, style: Style = setup_element
) -> SetupModel:
    """The assembled setup, after the one check of it against the robot (`check_setup`)."""
    check_setup(model, robot, path, style)
    return model
