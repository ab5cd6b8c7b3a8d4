"""Which controllers MoveIt picks to execute a motion of some joints: its real selection.

MoveIt 1 `moveit_ros/planning/trajectory_execution_manager/src/trajectory_execution_manager.cpp`
(MoveIt 2 keeps the same code in `moveit_ros/planning/trajectory_execution_manager/src/`):
- `reloadControllerInformation`: two controllers overlap when they share a joint;
- `selectControllers`: tries 1, 2, ... controllers and uses the first size that has an option;
- `generateControllerCombination` / `checkControllerCombination`: an option combines
  controllers that do not overlap and whose joints include every actuated joint of the motion;
- `findControllers`: a single option is used as it is; several are ranked by
  `OrderPotentialControllerCombination`: more `default` controllers first, then fewer joints
  in total. So `default` only breaks ties between controllers that could do the same job.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from itertools import combinations

from marm_setup.package import MoveItController


@dataclass(frozen=True, slots=True)
class Selection:
    """MoveIt's pick (controller names), and other options it ranks equally (an arbitrary choice)."""

    chosen: tuple[str, ...]
    tied: tuple[tuple[str, ...], ...] = ()


def select_controllers(joints: Iterable[str], ctrls: Sequence[MoveItController]) -> Selection | None:
    """The controllers MoveIt would use for a motion of `joints`; None when no option exists.

    `ctrls` have `name`, `joints` and `default` (MoveIt keys them by name: the last one wins).
    """
    wanted = set(joints)
    by_name = {c.name: c for c in ctrls}
    useful = [c for _, c in sorted(by_name.items()) if wanted & set(c.joints)]
    for size in range(1, len(useful) + 1):
        options = [combo for combo in combinations(useful, size) if _covers(combo, wanted)]
        if options:
            return _best(options)
    return None


def _covers(combo: tuple[MoveItController, ...], wanted: set[str]) -> bool:
    seen: set[str] = set()
    for c in combo:
        if seen & set(c.joints):
            return False  # overlapping controllers are never combined
        seen |= set(c.joints)
    return wanted <= seen


def _rank(combo: tuple[MoveItController, ...]) -> tuple[int, int]:
    return (-sum(1 for c in combo if c.default), sum(len(set(c.joints)) for c in combo))


def _best(options: list[tuple[MoveItController, ...]]) -> Selection:
    if len(options) == 1:
        return Selection(tuple(c.name for c in options[0]))
    ranked = sorted(options, key=_rank)
    top = [o for o in ranked if _rank(o) == _rank(ranked[0])]
    names = [tuple(c.name for c in o) for o in top]
    return Selection(names[0], tuple(names[1:]))
