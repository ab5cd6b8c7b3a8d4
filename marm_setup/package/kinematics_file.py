"""`kinematics.yaml` (`robot_description_kinematics`): one IK solver entry per planning group.

MoveIt hands every key of a group's entry to the solver plugin: besides the solver, timeout
and search resolution, plugin options such as `position_only_ik` (KDL, moveit_core
kinematics_base.h `lookupParam`), TRAC-IK's `solve_type` or bio_ik's `mode` live here too.
"""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.moveit_params import KINEMATICS_KEYS
from marm_setup.package.where import Located, Param, Where

SOLVER = "kinematics_solver"
STANDARD_KEYS = KINEMATICS_KEYS


@dataclass(frozen=True, slots=True)
class GroupKinematics:
    """One group's entry; `params` None when the entry is not a mapping."""

    group: str
    where: Where
    params: tuple[Param, ...] | None

    def param(self, key: str) -> Param | None:
        return next((p for p in self.params or () if p.key == key), None)

    @property
    def solver(self) -> str | None:
        """The solver plugin name, None when absent or not a non-empty string."""
        found = self.param(SOLVER)
        return found.value if found is not None and isinstance(found.value, str) and found.value else None

    @property
    def options(self) -> tuple[Param, ...]:
        """The plugin's own options: every key but solver, timeout, resolution and attempts."""
        return tuple(p for p in self.params or () if p.key not in STANDARD_KEYS)


@dataclass(frozen=True, slots=True)
class KinematicsFile:
    """The groups of a kinematics file; `groups` None when the file is not a mapping of groups.
    `top_level_by`: the launch file that hands the groups to move_group as its own top-level
    parameters (`<group>.kinematics_solver`), not under `robot_description_kinematics` ('' when
    they land under it, or where they land is not known)."""

    where: Where
    groups: tuple[GroupKinematics, ...] | None
    top_level_by: str = ""

    def group(self, name: str) -> GroupKinematics | None:
        return next((g for g in self.groups or () if g.group == name), None)


def read_kinematics(doc: Located) -> KinematicsFile:
    if not doc.is_mapping:
        return KinematicsFile(doc.where, None)
    groups = tuple(
        GroupKinematics(name, entry.where, entry.params(flat=False) if entry.is_mapping else None)
        for name, entry in doc.items()
    )
    return KinematicsFile(doc.where, groups)
