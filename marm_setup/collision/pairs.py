"""Canonical link pairs, the reasons MoveIt gives for disabling their collision checks, and
the note an SRDF carries on a Never pair whose proof was not finished."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass

PROVE_MODES = ("off", "on", "exhaustive")
UNPROVED_MARK = "unproved Never:"  # how an SRDF comment written by us on such a pair starts


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


@dataclass(frozen=True, slots=True, order=True)
class UnprovedPair:
    """A Never pair whose proof ran out of budget: `proved_fraction` of its joint box (by the
    sampling measure) is proved collision-free, the rest only sampled."""

    link1: str
    link2: str
    proved_fraction: float

    @property
    def pair(self) -> tuple[str, str]:
        return (self.link1, self.link2)

    def note(self, trials: int) -> str:
        """The SRDF comment's text (deterministic: the share rounded down to 0.1 %)."""
        share = math.floor(1000 * self.proved_fraction) / 10
        return (
            f"{UNPROVED_MARK} proved collision-free over {share:.1f} % of its joint range; "
            f"the rest only sampled ({trials} states, no contact)"
        )
