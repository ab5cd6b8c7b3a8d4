"""What a SPEC replaces takes along what was inferred for it.

A SPEC group covering the joints of an inferred group replaces it (`arm` gives way to the SPEC's
`manipulator`); a SPEC group named like an inferred one but defined otherwise replaces its
definition. Either way, the controllers, kinematics, planner defaults, poses, end effectors,
start poses and servo entries inferred for the old group go too, in every list (also in a list
the SPEC gives: the SPEC's own items stay, each one the checks judge). An inferred controller
commanding a joint that a SPEC controller commands goes as well: a joint takes one trajectory
controller.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

from marm_setup.robot import RobotModel
from marm_setup.setup import ITEM_KEYS, Group, Partial, SetupModel, active_group_joints, groups_by_name

# the lists whose items belong to a group, and the fields naming it
GROUP_FIELDS = {
    "controllers": ("group",),
    "kinematics": ("group",),
    "planners": ("group",),
    "group_states": ("group",),
    "end_effectors": ("group", "parent_group"),
    "start_poses": ("group",),
    "servo": ("group",),
}

SpecItems = Mapping[str, frozenset[str]]


def spec_items(spec: Mapping) -> dict[str, frozenset[str]]:
    """{list: the keys (name, group, joint or link) of the SPEC's items} for each list a SPEC
    (parsed YAML) gives."""
    out = {}
    for key, value in spec.items():
        if isinstance(value, list):
            out[str(key)] = frozenset(k for k in map(_dict_key, value) if k is not None)
    return out


def patch_items(spec: Partial) -> dict[str, frozenset[str]]:
    """`spec_items` of a SPEC read as a typed patch (`yaml_io.patch_from_dict`)."""
    out = {}
    for key, value in spec.values:
        if isinstance(value, tuple):
            out[key] = frozenset(k for k in map(_item_key, value) if k is not None)
    return out


def without_replaced(
    inferred: SetupModel, merged: SetupModel, robot: RobotModel, given: SpecItems
) -> SetupModel:
    """`merged` (the SPEC over `inferred`) without the inferred groups the SPEC replaces and
    without every inferred item of a replaced or redefined group; `given` is `spec_items`."""
    gone = shadowed_groups(merged, robot, given.get("groups", frozenset()))
    stale = gone | redefined_groups(inferred, merged, given.get("groups", frozenset()))
    model = dataclasses.replace(merged, groups=tuple(g for g in merged.groups if g.name not in gone))
    changes: dict[str, Any] = {}
    for name, fields in GROUP_FIELDS.items():
        items = getattr(model, name)
        if items is None:
            continue
        mine = given.get(name, frozenset())
        kept = tuple(i for i in items if _item_key(i) in mine or not {getattr(i, f) for f in fields} & stale)
        if kept != items:
            changes[name] = kept
    model = dataclasses.replace(model, **changes)
    return _without_clashing_controllers(model, given.get("controllers", frozenset()))


def shadowed_groups(model: SetupModel, robot: RobotModel, given: frozenset[str]) -> set[str]:
    """The groups no SPEC group names (nor uses as a subgroup) whose joints a SPEC group
    covers, and the composites made of them."""
    if not given:
        return set()
    by_name = groups_by_name(model.groups)
    known = [g for g in model.groups if _resolvable(g, by_name, robot)]
    covered = {j for g in known if g.name in given for j in active_group_joints(g, by_name, robot)}
    used = {s for g in model.groups if g.name in given for s in g.subgroups}
    dropped = {
        g.name
        for g in known
        if g.name not in given | used
        and not g.subgroups
        and set(active_group_joints(g, by_name, robot)) & covered
    }
    while more := {
        g.name for g in model.groups if g.name not in dropped | given and set(g.subgroups) & dropped
    }:
        dropped |= more
    return dropped


def redefined_groups(inferred: SetupModel, merged: SetupModel, given: frozenset[str]) -> set[str]:
    """Inferred groups the SPEC defines again, otherwise, under the same name."""
    before = {g.name: g for g in inferred.groups}
    return {g.name for g in merged.groups if g.name in given and g.name in before and g != before[g.name]}


def _without_clashing_controllers(model: SetupModel, mine: frozenset[str]) -> SetupModel:
    """Without the inferred controllers that command a joint a SPEC controller commands."""
    taken = {j for c in model.controllers if c.name in mine for j in c.joints}
    kept = tuple(c for c in model.controllers if c.name in mine or not set(c.joints) & taken)
    return dataclasses.replace(model, controllers=kept) if kept != model.controllers else model


def _resolvable(group: Group, by_name: Mapping[str, Group], robot: RobotModel) -> bool:
    """Names only what the robot and the setup have (a SPEC's typo is for the checks to report)."""
    chain_ok = group.chain is None or {group.chain.base, group.chain.tip} <= set(robot.link_map)
    names_ok = all(j in robot.joint_map for j in group.joints) and all(
        x in robot.link_map for x in group.links
    )
    return chain_ok and names_ok and all(s in by_name for s in group.subgroups)


def _dict_key(item: object) -> str | None:
    if isinstance(item, dict):
        return next((str(item[k]) for k in ITEM_KEYS if isinstance(item.get(k), str)), None)
    return None


def _item_key(item: object) -> str | None:
    return next((str(getattr(item, k)) for k in ITEM_KEYS if isinstance(getattr(item, k, None), str)), None)
