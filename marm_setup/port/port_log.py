"""What the port report is made of: every setting of the source package, and what became of it.

Each `PortItem` says what happened to one setting (`carried` as it was, `changed` on the way,
`dropped` because the new package has no place for it) or what the user must still do by
hand (`todo`), with the file and element it came from and why. Its `area` says what kind of
setting it is; the areas in MOTION change how the robot moves, and the report opens with them.
"""

from __future__ import annotations

from dataclasses import dataclass

STATUSES = ("carried", "changed", "dropped", "todo")
# Settings that change how the robot moves: joint limits, the default scaling factors, the
# controllers MoveIt executes with, the IK solvers and their options, the planners, how move_group
# executes and monitors trajectories.
MOTION = ("limits", "scaling", "controllers", "kinematics", "planners", "execution")
AREAS = (*MOTION, "robot", "srdf", "driver", "perception", "package", "files")


@dataclass(frozen=True, slots=True)
class PortItem:
    """One line of the report: `setting` from `source` (file, element), and why."""

    status: str  # carried | changed | dropped | todo
    setting: str
    source: str
    detail: str
    area: str = "package"

    @property
    def moves_robot(self) -> bool:
        return self.area in MOTION

    def as_dict(self) -> dict:
        return {
            "status": self.status,
            "setting": self.setting,
            "source": self.source,
            "detail": self.detail,
            "area": self.area,
        }


class PortLog:
    """Collects report items in the order the importer meets them."""

    def __init__(self) -> None:
        self.items: list[PortItem] = []

    def add(self, status: str, setting: str, source: object, detail: str, area: str = "package") -> None:
        self.items.append(PortItem(status, setting, str(source), detail, area))

    def carried(self, setting: str, source: object, detail: str = "", area: str = "package") -> None:
        self.add("carried", setting, source, detail, area)

    def changed(self, setting: str, source: object, detail: str, area: str = "package") -> None:
        self.add("changed", setting, source, detail, area)

    def dropped(self, setting: str, source: object, detail: str, area: str = "package") -> None:
        self.add("dropped", setting, source, detail, area)

    def todo(self, setting: str, source: object, detail: str, area: str = "package") -> None:
        self.add("todo", setting, source, detail, area)


def where(file: str | None, element: str = "") -> str:
    """`file: element` (or just the file) for a report item's source."""
    return f"{file}: {element}" if file and element else (file or element)


def counts(items: tuple[PortItem, ...], motion_only: bool = False) -> dict[str, int]:
    """Items per status, every status present (0 when none); with `motion_only`, only the
    settings that change how the robot moves."""
    chosen = [i for i in items if i.moves_robot or not motion_only]
    return {s: sum(1 for i in chosen if i.status == s) for s in STATUSES}


def summary(items: tuple[PortItem, ...]) -> str:
    """The closing line's port part: what was not carried as it was, never silent about it."""
    n, motion = counts(items), counts(items, motion_only=True)
    if not n["dropped"] and not motion["changed"] and not motion["dropped"]:
        return "every setting carried or rewritten for the target"
    return (
        f"{n['dropped']} setting{'s' if n['dropped'] != 1 else ''} dropped; of what changes how the robot "
        f"moves {motion['dropped']} dropped, {motion['changed']} changed (listed first above)"
    )
