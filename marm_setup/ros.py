"""The ROS versions a package is for: its target (ROS 1 / MoveIt 1 or ROS 2 / MoveIt 2) and the
ROS distro of that target it is written for.

Both are `str` enums: they are written and compared as their values (`ros2`, `humble`), so
YAML, JSON and templates see plain strings, and code names them by member (`Target.ROS2`)."""

from __future__ import annotations

import enum


class _Named(str, enum.Enum):
    """A str enum whose str() and format() are its value, on every Python version."""

    def __str__(self) -> str:
        return self.value

    def __format__(self, spec: str) -> str:
        return format(self.value, spec)


class Target(_Named):
    ROS2 = "ros2"  # ament packages, MoveIt 2
    ROS1 = "ros1"  # catkin packages, MoveIt 1


class Distro(_Named):
    NOETIC = "noetic"
    HUMBLE = "humble"
    JAZZY = "jazzy"


# The targets, the default first; the distros of each, the target's default first. Humble and
# Jazzy differ in MoveIt's planning pipeline parameters (DESIGN §4); Rolling writes what Jazzy
# writes, so it is not a distro of its own here.
TARGETS = (Target.ROS2, Target.ROS1)
ROS_DISTROS = {Target.ROS1: (Distro.NOETIC,), Target.ROS2: (Distro.HUMBLE, Distro.JAZZY)}
