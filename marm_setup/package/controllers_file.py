"""MoveIt's controller lists: the simple controller manager's (`controller_list` in MoveIt 1,
`controller_names` + one entry per name in MoveIt 2) and MoveIt 1's fake controllers.

MoveIt 1 moveit_simple_controller_manager.cpp (constructor, ~l.75) skips an entry unless it has
all of name, joints, action_ns and type; `name` may be empty. MoveIt 2's initialize() reads
`<name>.action_ns`, `<name>.type` and a non-empty `<name>.joints` under
`moveit_simple_controller_manager` (PARAM_BASE_NAME). moveit_fake_controller_manager.cpp (MoveIt
1, constructor) needs only name and joints, and reads `initial` (group, pose) entries. MoveIt
1's managers take an empty `joints` list (`joints: []`) as they take any array: the simple
manager checks only that it is one (moveit/moveit moveit_plugins/moveit_simple_controller_manager/
src/moveit_simple_controller_manager.cpp l.75-91 at fdb79ac), the fake one likewise
(moveit_fake_controller_manager.cpp l.86-105); the controller then drives no joint.
"""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.package.where import Located, Param, Where, freeze

REQUIRED_KEYS = ("name", "joints", "action_ns", "type")
FAKE_KEYS = ("name", "joints")
SIMPLE_MANAGER = "moveit_simple_controller_manager"
# the class a MoveIt 1 launch names as move_group's moveit_controller_manager for it
SIMPLE_MANAGER_CLASS = "MoveItSimpleControllerManager"
LIST_KEYS = ("controller_list", "controller_names", SIMPLE_MANAGER)


@dataclass(frozen=True, slots=True)
class MoveItController:
    name: str
    type: str
    action_ns: str | None
    default: bool
    joints: tuple[str, ...]
    where: Where

    @property
    def element(self) -> str:
        return self.where.element

    @property
    def action(self) -> str:
        """The action MoveIt connects to: `name/action_ns`, or `name` when action_ns is empty
        (`getActionName` in moveit_simple_controller_manager's action_based_controller_handle.h);
        an empty name gives `/action_ns`, the ROS-Industrial convention."""
        return f"{self.name}/{self.action_ns}" if self.action_ns else self.name


@dataclass(frozen=True, slots=True)
class SkippedController:
    """An entry the manager skips: the keys it misses (or has empty)."""

    where: Where
    missing: tuple[str, ...]


@dataclass(frozen=True, slots=True)
class InitialPose:
    """A fake controllers `initial` entry: start `group` at its named `pose`."""

    group: str
    pose: str
    where: Where


@dataclass(frozen=True, slots=True)
class ListLoad:
    """A MoveIt 1 launch file's load of a controller list file: where its `controller_list` lands
    (`ns`, '' for the root; the list is `/<ns>/controller_list`)."""

    launch: str
    line: int
    ns: str


@dataclass(frozen=True, slots=True)
class ControllersFile:
    """A controller list as its manager reads it. `where` is the list's mapping (in MoveIt 2
    the `moveit_simple_controller_manager` one when the file has it); `form` is
    `controller_list`, `controller_names` or None (neither: the manager finds none)."""

    where: Where
    form: str | None
    controllers: tuple[MoveItController, ...] = ()
    skipped: tuple[SkippedController, ...] = ()
    settings: tuple[Param, ...] = ()  # the file's other top-level keys (manager plugin, execution)
    initial: tuple[InitialPose, ...] | None = None  # fake controllers; None when absent
    initial_malformed: bool = False  # `initial` is not a list
    loaded_into: str = ""  # the key a launch file puts the whole file under ('' for none)
    # no launch file of the package loads the list (no MoveItConfigsBuilder, no load by hand):
    # the file is the builder's guess, and the key another package's launch puts it under unknown
    load_unknown: bool = False
    # MoveIt 1: the simple manager's loads of this list when none lands in move_group's private
    # namespace (`read_at`, the move_group nodes' full names) and MoveIt reads no list at all
    elsewhere: tuple[ListLoad, ...] = ()
    read_at: tuple[str, ...] = ()

    @property
    def namespaced(self) -> bool:
        """The list sits below a key of the file (MoveIt 2's `moveit_simple_controller_manager`)."""
        return bool(self.where.keys)

    @property
    def manager(self) -> str:
        found = next((p for p in self.settings if p.key == "moveit_controller_manager"), None)
        return str(found.value) if found is not None and found.value is not None else ""


def read_controllers(doc: Located, required: tuple[str, ...] = REQUIRED_KEYS) -> ControllersFile:
    """The list of `doc` (a whole file, or its `moveit_simple_controller_manager` mapping when it
    has one) with every entry the manager would skip."""
    section = doc.get(SIMPLE_MANAGER) if doc.get(SIMPLE_MANAGER).is_mapping else doc
    settings = tuple(p for k, v in doc.items() if k not in LIST_KEYS for p in _params(k, v))
    entries, form = _entries(section)
    found, skipped = [], []
    for where, entry in entries:
        missing = _missing_keys(entry, required, empty_joints=form == "controller_list")
        if missing or not isinstance(entry, dict):
            skipped.append(SkippedController(where, missing))
        else:
            found.append(_controller(entry, where))
    initial, malformed = _initial(doc)
    return ControllersFile(section.where, form, tuple(found), tuple(skipped), settings, initial, malformed)


def _params(key: str, value: Located) -> tuple[Param, ...]:
    if value.is_mapping and value.data:
        return tuple(Param(f"{key}.{p.key}", p.value, p.where) for p in value.params())
    return (Param(key, freeze(value.data), value.where),)


def _entries(section: Located) -> tuple[list[tuple[Where, object]], str | None]:
    """(where, entry) of each listed controller, and the list's form."""
    data = section.data if isinstance(section.data, dict) else {}
    if isinstance(data.get("controller_list"), list):
        return [
            (item.where, item.data) for item in section.get("controller_list").items_of_list()
        ], "controller_list"
    if isinstance(data.get("controller_names"), list):
        out: list[tuple[Where, object]] = []
        for name in map(str, data["controller_names"]):
            entry = section.get(name)
            body = entry.data if isinstance(entry.data, dict) else {}
            out.append((entry.where, {"name": name, **body}))
        return out, "controller_names"
    return [], None


def _missing_keys(entry: object, required: tuple[str, ...], empty_joints: bool = False) -> tuple[str, ...]:
    """The keys the manager misses in `entry`; `empty_joints`: an empty `joints` list is one it
    takes (MoveIt 1's `controller_list`; MoveIt 2 needs at least one joint)."""
    if not isinstance(entry, dict):
        return required
    missing = [k for k in required if k not in entry or entry[k] is None]
    joints = entry.get("joints")
    if "joints" not in missing and (not isinstance(joints, list) or not (joints or empty_joints)):
        missing.append("joints")
    return tuple(missing)


def _controller(entry: dict, where: Where) -> MoveItController:
    default = entry.get("default", False)
    return MoveItController(
        name=str(entry["name"]),
        type=str(entry.get("type", "")),
        action_ns=None if entry.get("action_ns") is None else str(entry["action_ns"]),
        default=default is True or str(default).lower() == "true",
        joints=tuple(str(j) for j in entry["joints"]),
        where=where,
    )


def _initial(doc: Located) -> tuple[tuple[InitialPose, ...] | None, bool]:
    initial = doc.get("initial")
    if initial.data is None:
        return None, False
    if not isinstance(initial.data, list):
        return None, True
    out = []
    for item in initial.items_of_list():
        data = item.data if isinstance(item.data, dict) else {}
        out.append(InitialPose(str(data.get("group")), str(data.get("pose")), item.where))
    return tuple(out), False
