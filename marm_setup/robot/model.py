"""Frozen robot model (links, joints, collision shapes) and pure tree queries."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

from marm_setup.robot.ros2_control import Ros2ControlSystem, systems_in_urdf

if TYPE_CHECKING:
    from marm_setup.robot.ros2_control import HardwareArg, MockSwitch

Vec3 = tuple[float, float, float]

FIXED_TYPES = ("fixed",)
ACTUATED_TYPES = ("revolute", "continuous", "prismatic")
# [rad] or [m]: the slack of every comparison with a joint limit (a value written at full
# precision sits on its limit).
LIMIT_TOLERANCE = 1e-9
MIN_RATE = 1e-6  # [rad/s, m/s, /s^2] slower than any joint moves (1 rad in 11.6 days): a speed,
# acceleration or scaling below it makes the durations of a trajectory overflow
# Limits in YAML files are written rounded (2.0944 for the URDF's 2.0943951): a value within this
# fraction of a limit is that limit.
LIMIT_ROUNDING = 1e-4
# [rad] or [m]: MoveIt's default goal_joint_tolerance (moveit move_group_interface.h
# DEFAULT_GOAL_JOINT_TOLERANCE l.78, read per group from robot_description_kinematics): a joint
# goal is met by any state that close to it, so a named pose that far past a bound is met by the
# state on the bound (a pose written rounded, 0.1745 for a limit of 0.174533).
GOAL_JOINT_TOLERANCE = 1e-4


def limit_slack(limit: float) -> float:
    """How far a value written in a file may pass `limit` and still be on it [rad, m, or per s]."""
    return max(LIMIT_TOLERANCE, LIMIT_ROUNDING * abs(limit))


@dataclass(frozen=True, slots=True)
class Origin:
    """A URDF `<origin>`: translation in [m], roll-pitch-yaw in [rad]."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True, slots=True)
class Box:
    size: Vec3


@dataclass(frozen=True, slots=True)
class Cylinder:
    radius: float
    length: float


@dataclass(frozen=True, slots=True)
class Sphere:
    radius: float


@dataclass(frozen=True, slots=True)
class Mesh:
    """A mesh: `uri` as written in the URDF, `path` the resolved absolute file."""

    uri: str
    path: str
    scale: Vec3 = (1.0, 1.0, 1.0)


Geometry = Box | Cylinder | Sphere | Mesh


@dataclass(frozen=True, slots=True)
class CollisionShape:
    geometry: Geometry
    origin: Origin = Origin()


@dataclass(frozen=True, slots=True)
class Link:
    name: str
    collisions: tuple[CollisionShape, ...] = ()
    has_visual: bool = False  # a <visual> element (MoveIt's Gazebo `world` root test reads it)

    @property
    def has_geometry(self) -> bool:
        return bool(self.collisions)


@dataclass(frozen=True, slots=True)
class Mimic:
    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True, slots=True)
class Joint:
    """A URDF joint; limits in [rad] or [m], velocity in [rad/s] or [m/s]."""

    name: str
    type: str
    parent: str
    child: str
    origin: Origin = Origin()
    axis: Vec3 = (1.0, 0.0, 0.0)
    lower: float | None = None
    upper: float | None = None
    velocity: float | None = None
    effort: float | None = None
    mimic: Mimic | None = None
    soft_lower: float | None = None
    soft_upper: float | None = None

    @property
    def is_actuated(self) -> bool:
        """Moves at all (revolute, continuous, prismatic); mimic joints included."""
        return self.type in ACTUATED_TYPES

    @property
    def is_active(self) -> bool:
        """A variable of its own: actuated and not a mimic."""
        return self.is_actuated and self.mimic is None

    @property
    def bounds(self) -> tuple[float, float]:
        """Sampling/planning bounds: URDF limits narrowed by safety_controller soft limits."""
        if self.type == "continuous" or self.lower is None or self.upper is None:
            if self.type in FIXED_TYPES:
                return (0.0, 0.0)
            return (-math.pi, math.pi)
        lo, hi = self.lower, self.upper
        if self.soft_lower is not None:
            lo = max(lo, self.soft_lower)
        if self.soft_upper is not None:
            hi = min(hi, self.soft_upper)
        return (lo, hi)

    def within_limits(self, value: float) -> bool:
        """`value` lies within the bounds (continuous and non-moving joints take any value)."""
        if self.type == "continuous" or not self.is_actuated:
            return True
        lo, hi = self.bounds
        return lo - LIMIT_TOLERANCE <= value <= hi + LIMIT_TOLERANCE

    def reaches(self, value: float) -> bool:
        """MoveIt meets `value` as a joint goal: within the bounds, or past one by no more than
        GOAL_JOINT_TOLERANCE, as the goal constraint's tolerance then holds the state on the
        bound (moveit kinematic_constraint.cpp JointConstraint::configure l.217-237 moves only a
        goal farther out onto the bound, with a warning; move_group_interface.cpp
        setJointValueTarget checks satisfiesBounds(goal_joint_tolerance))."""
        if self.type == "continuous" or not self.is_actuated:
            return True
        lo, hi = self.bounds
        return lo - GOAL_JOINT_TOLERANCE <= value <= hi + GOAL_JOINT_TOLERANCE

    @property
    def default_position(self) -> float:
        """MoveIt's default: 0, or mid-range where 0 is outside the bounds."""
        lo, hi = self.bounds
        return 0.0 if lo <= 0.0 <= hi else (lo + hi) / 2.0


@dataclass(frozen=True)
class RobotModel:
    """A robot: links and joints in URDF document order; `source` is the path the user gave."""

    name: str
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    root: str
    source: str = ""
    urdf_xml: str = field(default="", repr=False, compare=False)
    # ROS packages the description used: (name, folder, found by "package.xml" | "folder name")
    packages: tuple[tuple[str, str, str], ...] = field(default=(), compare=False)
    # the arguments its xacro declares or reads, sorted (robot/xacro_expand.py); None: no xacro
    xacro_args: tuple[str, ...] | None = field(default=None, compare=False)
    # the xacro arg that provably puts the description's own <ros2_control> systems on mock
    # hardware (robot/mock_switch.py); None: none found, or no such systems
    mock_switch: MockSwitch | None = field(default=None, compare=False)
    # the xacro args that configure its real ros2_control hardware, with their defaults
    # (robot/hardware_args.py): the launch files offer them
    hardware_args: tuple[HardwareArg, ...] = field(default=(), compare=False)
    # environment variables its xacro reads with optenv that were unset: their defaults made it
    env_defaults: tuple[str, ...] = field(default=(), compare=False)

    # -- lookups -------------------------------------------------------------------------------
    @cached_property
    def link_map(self) -> dict[str, Link]:
        return {link.name: link for link in self.links}

    @cached_property
    def joint_map(self) -> dict[str, Joint]:
        return {joint.name: joint for joint in self.joints}

    @cached_property
    def parent_joint_of(self) -> dict[str, Joint]:
        return {joint.child: joint for joint in self.joints}

    @cached_property
    def child_joints_of(self) -> dict[str, tuple[Joint, ...]]:
        out: dict[str, list[Joint]] = {link.name: [] for link in self.links}
        for joint in self.joints:
            out[joint.parent].append(joint)
        return {name: tuple(js) for name, js in out.items()}

    def link(self, name: str) -> Link:
        return self.link_map[name]

    def joint(self, name: str) -> Joint:
        return self.joint_map[name]

    # -- tree order ----------------------------------------------------------------------------
    @cached_property
    def joints_in_tree_order(self) -> tuple[Joint, ...]:
        """Depth-first pre-order from the root, children in document order."""
        return self.subtree_joints(self.root)

    @cached_property
    def links_in_tree_order(self) -> tuple[str, ...]:
        return (self.root, *(j.child for j in self.joints_in_tree_order))

    @cached_property
    def active_joints(self) -> tuple[Joint, ...]:
        """The robot's variables: actuated, non-mimic joints in tree order."""
        return tuple(j for j in self.joints_in_tree_order if j.is_active)

    @cached_property
    def active_joint_names(self) -> tuple[str, ...]:
        return tuple(j.name for j in self.active_joints)

    @cached_property
    def rigid_body_of(self) -> dict[str, frozenset[str]]:
        """Link -> its rigid body: the links joined to it through fixed joints only."""
        body_root = {self.root: self.root}
        for joint in self.joints_in_tree_order:
            body_root[joint.child] = body_root[joint.parent] if joint.type in FIXED_TYPES else joint.child
        bodies: dict[str, set[str]] = {}
        for link, top in body_root.items():
            bodies.setdefault(top, set()).add(link)
        return {link: frozenset(bodies[top]) for link, top in body_root.items()}

    @cached_property
    def geometry_links(self) -> tuple[str, ...]:
        """Names of links that have collision geometry, sorted."""
        return tuple(sorted(link.name for link in self.links if link.has_geometry))

    # -- tree queries --------------------------------------------------------------------------
    def path_to_root(self, link: str) -> list[Joint]:
        """Joints from `link` up to the root (nearest first)."""
        joints = []
        while link in self.parent_joint_of:
            joint = self.parent_joint_of[link]
            joints.append(joint)
            link = joint.parent
        return joints

    def chain(self, base: str, tip: str) -> tuple[Joint, ...] | None:
        """Joints from `base` down to `tip`, or None when `tip` is not below `base`."""
        joints: list[Joint] = []
        link = tip
        while link != base:
            joint = self.parent_joint_of.get(link)
            if joint is None:
                return None
            joints.append(joint)
            link = joint.parent
        return tuple(reversed(joints))

    def subtree_links(self, link: str) -> tuple[str, ...]:
        """`link` and every link below it, in tree order (iterative: any depth)."""
        return (link, *(j.child for j in self.subtree_joints(link)))

    def subtree_joints(self, link: str) -> tuple[Joint, ...]:
        """Every joint below `link`, in tree order (depth first, children in document order)."""
        out: list[Joint] = []
        stack = list(reversed(self.child_joints_of[link]))
        while stack:
            joint = stack.pop()
            out.append(joint)
            stack.extend(reversed(self.child_joints_of[joint.child]))
        return tuple(out)

    def adjacent_geometry_pairs(self) -> frozenset[tuple[str, str]]:
        """Pairs of geometry links joined by a joint, geometry-less links made transparent."""
        pairs: set[tuple[str, str]] = set()
        for link in self.geometry_links:
            for other in self._geometry_neighbours(link):
                pairs.add((min(link, other), max(link, other)))
        return frozenset(pairs)

    def _geometry_neighbours(self, start: str) -> set[str]:
        """Geometry links reachable from `start` through geometry-less links only."""
        seen, found, frontier = {start}, set(), [start]
        while frontier:
            link = frontier.pop()
            for nbr in self._tree_neighbours(link):
                if nbr in seen:
                    continue
                seen.add(nbr)
                if self.link_map[nbr].has_geometry:
                    found.add(nbr)
                else:
                    frontier.append(nbr)
        return found

    def _tree_neighbours(self, link: str) -> list[str]:
        nbrs = [j.child for j in self.child_joints_of[link]]
        if link in self.parent_joint_of:
            nbrs.append(self.parent_joint_of[link].parent)
        return nbrs


def described_systems(robot: RobotModel) -> tuple[Ros2ControlSystem, ...]:
    """The `<ros2_control>` elements directly under the (expanded) URDF's `<robot>`."""
    return systems_in_urdf(robot.urdf_xml)


def described_joints(robot: RobotModel) -> frozenset[str]:
    """Joints some `<ros2_control>` of the description drives or reports, with the setup's xacro
    args or with its mock switch on (a switch may add systems or joints, e.g. mimic joints)."""
    systems = described_systems(robot) + (robot.mock_switch.mock if robot.mock_switch else ())
    return frozenset(j for system in systems for j in system.joints)
