"""Names in a package that our own setup would refuse (`marm_setup.names`), for packages we did
not write: a control character, quote or `$(...)` in a name can break a generated file or turn
into a substitution in a launch file, and a group or controller name outside ROS naming is one
MoveIt 1 cannot read its parameters under."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, warning
from marm_setup.names import name_problem

if TYPE_CHECKING:
    from marm_setup.setup import Srdf


def check_srdf_names(srdf: Srdf, file: str) -> list[Finding]:
    """One `names.invalid` warning per SRDF name that is not valid for its kind."""
    return [_finding(file, where, problem) for where, problem in _srdf_problems(srdf)]


def check_controller_names(controllers: Iterable, file: str, *, global_names: bool = False) -> list[Finding]:
    """One `names.invalid` warning per MoveIt controller name or action_ns not valid as such.

    `global_names` (MoveIt 1's `controller_list`): a controller name may be a global ROS name
    (`/robot/limb/right`, Baxter's): the simple manager only prefixes the action it connects to
    with it (moveit/moveit moveit_simple_controller_manager action_based_controller_handle.h
    l.77 and l.140-145 at fdb79ac, `name + "/" + action_ns`), and roscpp takes a leading '/' and
    cleans the name it resolves (ros_comm names.cpp `resolve` l.177 -> `clean` l.99-116: '//'
    collapsed, a trailing '/' dropped)."""
    out = []
    for ctrl in controllers:
        name = _roscpp_clean(ctrl.name) if global_names else ctrl.name
        for kind, text in (("controller", name), ("action_ns", ctrl.action_ns)):
            if text and (problem := name_problem(kind, text)):
                out.append(_finding(file, ctrl.element, problem))
    return out


def _roscpp_clean(name: str) -> str:
    """`name` as roscpp resolves a global or relative name: without its leading '/', repeated
    '/' collapsed, a trailing '/' dropped ('' stays '')."""
    return "/".join(part for part in name.split("/") if part) if name.strip("/") else name


def _finding(file: str, where: str, problem: str) -> Finding:
    hint = "rename it: generated files and launch substitutions need plain names"
    return warning("names.invalid", file, where, problem, hint)


def _srdf_problems(srdf: Srdf) -> Iterator[tuple[str, str]]:
    checks = [("robot", srdf.robot_name, "robot")]
    checks += [("group", g.name, f"group[{g.name}]") for g in srdf.groups]
    checks += [("pose", s.name, f"group_state[{s.name}]") for s in srdf.group_states]
    checks += [("end effector", e.name, f"end_effector[{e.name}]") for e in srdf.end_effectors]
    checks += [("virtual joint", v.name, f"virtual_joint[{v.name}]") for v in srdf.virtual_joints]
    checks += [("frame", v.parent_frame, f"virtual_joint[{v.name}]") for v in srdf.virtual_joints]
    for kind, name, where in checks:
        problem = name_problem(kind, name)
        if problem:
            yield where, problem
