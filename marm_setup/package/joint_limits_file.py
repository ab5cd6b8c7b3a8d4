"""`joint_limits.yaml` (`robot_description_planning`): per-joint limit overrides and the default
scaling factors. What MoveIt makes of the keys (per ROS version) is `package.limits`."""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.package.where import Located, Param, Where

VELOCITY_SCALING = "default_velocity_scaling_factor"
ACCELERATION_SCALING = "default_acceleration_scaling_factor"


@dataclass(frozen=True, slots=True)
class JointLimitEntry:
    """One joint's keys in file order; `params` None when the entry is not a mapping."""

    joint: str
    where: Where
    params: tuple[Param, ...] | None

    def param(self, key: str) -> Param | None:
        return next((p for p in self.params or () if p.key == key), None)


@dataclass(frozen=True, slots=True)
class JointLimitsFile:
    """`joints` None when the file has no `joint_limits` mapping; `settings` holds every other
    key (scaling factors, `cartesian_limits.*`), nested mappings flattened."""

    where: Where
    joints: tuple[JointLimitEntry, ...] | None
    settings: tuple[Param, ...] = ()

    def setting(self, key: str) -> Param | None:
        return next((p for p in self.settings if p.key == key), None)

    def joint(self, name: str) -> JointLimitEntry | None:
        return next((e for e in self.joints or () if e.joint == name), None)

    @property
    def velocity_scaling(self) -> Param | None:
        return self.setting(VELOCITY_SCALING)

    @property
    def acceleration_scaling(self) -> Param | None:
        return self.setting(ACCELERATION_SCALING)


def read_joint_limits(doc: Located) -> JointLimitsFile:
    limits = doc.get("joint_limits")
    joints = None
    if limits.is_mapping:
        joints = tuple(
            JointLimitEntry(name, entry.where, entry.params() if entry.is_mapping else None)
            for name, entry in limits.items()
        )
    settings = tuple(
        p for p in doc.params() if p.key != "joint_limits" and not p.key.startswith("joint_limits.")
    )
    return JointLimitsFile(doc.where, joints, settings)
