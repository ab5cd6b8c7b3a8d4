"""The port report: every setting of the source package, and what became of it.

Each `PortItem` says what happened to one setting (`carried` as it was, `changed` on the way,
`dropped` because the new package has no place for it) or what the user must still do by
hand (`todo`), with the file and element it came from and why.
"""

from __future__ import annotations

from dataclasses import dataclass

STATUSES = ("carried", "changed", "dropped", "todo")


@dataclass(frozen=True, slots=True)
class PortItem:
    """One line of the report: `setting` from `source` (file, element), and why."""

    status: str  # carried | changed | dropped | todo
    setting: str
    source: str
    detail: str

    def as_dict(self) -> dict:
        return {"status": self.status, "setting": self.setting, "source": self.source, "detail": self.detail}


class PortLog:
    """Collects report items in the order the importer meets them."""

    def __init__(self) -> None:
        self.items: list[PortItem] = []

    def add(self, status: str, setting: str, source: str, detail: str) -> None:
        self.items.append(PortItem(status, setting, source, detail))

    def carried(self, setting: str, source: str, detail: str = "") -> None:
        self.add("carried", setting, source, detail)

    def changed(self, setting: str, source: str, detail: str) -> None:
        self.add("changed", setting, source, detail)

    def dropped(self, setting: str, source: str, detail: str) -> None:
        self.add("dropped", setting, source, detail)

    def todo(self, setting: str, source: str, detail: str) -> None:
        self.add("todo", setting, source, detail)


def where(file: str | None, element: str = "") -> str:
    """`file: element` (or just the file) for a report item's source."""
    return f"{file}: {element}" if file and element else (file or element)


def counts(items: tuple[PortItem, ...]) -> dict[str, int]:
    """Items per status, every status present (0 when none)."""
    return {s: sum(1 for i in items if i.status == s) for s in STATUSES}
