"""Canonical link pairs and the reasons MoveIt gives for disabling their collision checks."""

from __future__ import annotations

import enum
from dataclasses import dataclass


class DisabledReason(str, enum.Enum):
    """MoveIt's `disable_collisions` reasons; values are the SRDF strings, in phase order."""

    ADJACENT = "Adjacent"
    DEFAULT = "Default"
    ALWAYS = "Always"
    NEVER = "Never"
    USER = "User"


def link_pair(a: str, b: str) -> tuple[str, str]:
    """The canonical (link1 < link2) order MoveIt writes pairs in."""
    return (a, b) if a < b else (b, a)


@dataclass(frozen=True, slots=True, order=True)
class DisabledPair:
    """One `<disable_collisions link1 link2 reason>`; build with `DisabledPair.of` to normalise."""

    link1: str
    link2: str
    reason: DisabledReason

    @classmethod
    def of(cls, a: str, b: str, reason: DisabledReason | str) -> DisabledPair:
        return cls(*link_pair(a, b), DisabledReason(reason))

    @property
    def pair(self) -> tuple[str, str]:
        return (self.link1, self.link2)
