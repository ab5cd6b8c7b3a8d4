"""Names: what a valid name is, per kind (the one definition setup checks, imports and validate
share), and the one "did you mean" of every message about an unknown name.

ROS constrains some kinds and we follow it there:
- package: REP 144 (`[a-z][a-z0-9_]*`), as catkin and ament require.
- group, controller, action namespace, topic, sensor: ROS graph / parameter names (a sensor
  names a move_group parameter namespace in MoveIt 2). MoveIt 1 reads a group's
  settings as parameters named after it (`robot_description_kinematics/<group>/...`,
  moveit_ros_planning kinematics_plugin_loader.cpp) and roscpp rejects a parameter name outside
  `[A-Za-z_/~][A-Za-z0-9_/]*` (ros_comm names.cpp `validate`); a ros2_control controller is a
  node named after the controller. Controllers and action namespaces may have `/` separators.
- robot: names our files (`config/<robot>.srdf`) and, behind an '_' where it starts with a
  digit, a xacro macro (`<xacro:<robot>_ros2_control>`, an XML name): letters, digits, '_', '.',
  '-' (urdfdom and srdfdom take `2dof_planar`).
- ros2_control: the hardware plugin is a pluginlib class name (`package/Class`), interfaces and
  hardware parameter names are ROS names; parameter values are free text (escaped for xacro).
ROS leaves the others free (URDF links and joints, SRDF poses and end effectors, TF frames); we
refuse only what no robot needs and what would turn into code in a generated file: control
characters, and for links, joints and frames also whitespace, quotes, '$' (a launch or xacro
substitution), '\\' and a leading '-' (an option on a command line); for joints also ',', '(',
')' (MoveIt's `projection_evaluator: joints(a,b)` splits at them: ompl_interface
model_based_planning_context.cpp getProjectionEvaluator) and '{', '}' (a xacro `${...}` ends at
the first '}', xacro's EXPR lexer token).
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable

FEW = 8  # at most this many valid names are listed when none is close to an unknown one
MAX_NAME = 200  # characters: a robot name becomes a file name, and file names stop at 255 bytes

_ROS_SEGMENT = r"[A-Za-z_][A-Za-z0-9_]*"
_PATTERNS = {
    "package": re.compile(r"[a-z][a-z0-9_]*"),
    "robot": re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.\-]*"),
    "plugin": re.compile(rf"{_ROS_SEGMENT}((/|::){_ROS_SEGMENT})+"),
    "interface": re.compile(rf"{_ROS_SEGMENT}(/{_ROS_SEGMENT})*"),
    "parameter": re.compile(rf"{_ROS_SEGMENT}([./]{_ROS_SEGMENT})*"),
    "group": re.compile(_ROS_SEGMENT),
    "controller": re.compile(rf"{_ROS_SEGMENT}(/{_ROS_SEGMENT})*"),
    "action_ns": re.compile(rf"{_ROS_SEGMENT}(/{_ROS_SEGMENT})*"),
    "topic": re.compile(rf"(~/|/)?{_ROS_SEGMENT}(/{_ROS_SEGMENT})*"),
    "sensor": re.compile(_ROS_SEGMENT),
}
_RULES = {
    "package": "lowercase letters, digits and '_', starting with a letter",
    "robot": "letters, digits, '_', '.' and '-', starting with a letter, a digit or '_'",
    "plugin": "a pluginlib class name: ROS names joined by '/' or '::' (package/Class)",
    "interface": "ROS names (letters, digits, '_', starting with a letter or '_') joined by '/'",
    "parameter": "ROS names (letters, digits, '_', starting with a letter or '_') joined by '.' or '/'",
    "group": "letters, digits and '_', starting with a letter or '_' (a ROS name)",
    "controller": "ROS names (letters, digits, '_', starting with a letter or '_') joined by '/'",
    "action_ns": "ROS names (letters, digits, '_', starting with a letter or '_') joined by '/'",
    "topic": "ROS names (letters, digits, '_', starting with a letter or '_') joined by '/', after an optional '/' or '~/'",
    "sensor": "letters, digits and '_', starting with a letter or '_' (MoveIt 2 reads `<sensor>.sensor_plugin`)",
}
REFERENCE_KINDS = ("link", "joint", "frame", "virtual joint")
LABEL_KINDS = ("pose", "end effector", "property")
_REFERENCE_FORBIDDEN = set("$'\"`\\")
_JOINT_FORBIDDEN = set(",(){}")  # a projection_evaluator list, a xacro ${...} (see the module doc)
KINDS = (*_PATTERNS, *REFERENCE_KINDS, *LABEL_KINDS)


def name_problem(kind: str, name: object) -> str | None:
    """Why `name` cannot be a `kind` name (one clause, quoting the name), or None when it can."""
    if not isinstance(name, str):
        return f"a {kind} name must be text, got {name!r}"
    if not name:
        return f"empty {kind} name"
    if len(name) > MAX_NAME:
        return f"{kind} name '{name[:20]}...' is longer than {MAX_NAME} characters"
    if kind == "package":
        return _package_problem(name)
    if kind in _PATTERNS:
        if _PATTERNS[kind].fullmatch(name):
            return None
        return f"{name!r} is not a valid {kind} name: {_RULES[kind]}"
    return _free_name_problem(kind, name)


def _package_problem(name: str) -> str | None:
    if _PATTERNS["package"].fullmatch(name):
        return None
    return f"{name!r} is not a valid ROS package name: {_RULES['package']} (e.g. '{ros_package_name(name)}')"


def ros_package_name(text: str) -> str:
    """`text` made into a valid package name: lowercase, other characters as '_'."""
    name = re.sub(r"[^a-z0-9_]+", "_", text.lower()).strip("_")
    return name if name[:1].isalpha() else f"pkg_{name}".rstrip("_")


def _free_name_problem(kind: str, name: str) -> str | None:
    if kind not in KINDS:
        raise ValueError(f"unknown name kind {kind!r}")
    if not name.isprintable():
        return f"{kind} name {name!r} holds a control or invisible character"
    if name != name.strip():
        return f"{kind} name {name!r} starts or ends with a space"
    if kind == "pose" and "$" in name:
        # ros1 fake_controllers.yaml names poses and is loaded with roslaunch's subst_value
        return f"pose name {name!r} holds '$' (a roslaunch substitution)"
    if kind in LABEL_KINDS:
        return None
    bad = sorted({c for c in name if c.isspace() or c in _REFERENCE_FORBIDDEN})
    if bad:
        shown = " ".join(repr(c) for c in bad)
        return f"{kind} name {name!r} holds {shown} (no spaces, quotes, '$', '`' or '\\' in {kind} names)"
    if name.startswith("-"):
        return f"{kind} name {name!r} starts with '-' (it would read as an option)"
    syntax = sorted({c for c in name if c in _JOINT_FORBIDDEN}) if kind == "joint" else []
    if syntax:
        shown = " ".join(repr(c) for c in syntax)
        return f"joint name {name!r} holds {shown} (MoveIt's joints(a,b) lists and xacro expressions cannot hold it)"
    return None


def is_valid_name(kind: str, name: object) -> bool:
    return name_problem(kind, name) is None


def did_you_mean(name: str, known: Iterable[str], *, few: float = FEW) -> str:
    """`did you mean 'a', 'b'?` for up to three close names, else `known: a, b` when there are
    at most `few` (0: never list them), else ''."""
    names = sorted(set(known))
    close = difflib.get_close_matches(str(name), names, n=3, cutoff=0.6)
    if close:
        quoted = ", ".join(f"'{c}'" for c in close)
        return f"did you mean {quoted}?"
    if len(names) <= few:
        return f"known: {', '.join(names) or 'none'}"
    return ""


def with_hint(message: str, hint: str) -> str:
    """A one-line message with its hint in parentheses (`unknown joint 'x' (did you mean 'y'?)`)."""
    return f"{message} ({hint})" if hint else message
