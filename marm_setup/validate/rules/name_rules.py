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


def check_controller_names(controllers: Iterable, file: str) -> list[Finding]:
    """One `names.invalid` warning per MoveIt controller name or action_ns not valid as such."""
    out = []
    for ctrl in controllers:
        for kind, name in (("controller", ctrl.name), ("action_ns", ctrl.action_ns)):
            if name and (problem := name_problem(kind, name)):
                out.append(_finding(file, ctrl.element, problem))
    return out


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
