"""kinematics.yaml: groups exist, solver plugin known, KDL on chains only, positive timeout/resolution."""

from __future__ import annotations

from collections.abc import Mapping
from numbers import Real
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, error, warning
from marm_setup.robot.model import RobotModel
from marm_setup.setup.domain import CHAIN_ONLY_PLUGINS, IKFAST_PLUGIN_SUFFIX, KINEMATICS_PLUGINS
from marm_setup.setup.groups import groups_by_name, is_chain

if TYPE_CHECKING:
    from marm_setup.setup.model import Group
    from marm_setup.setup.srdf import Srdf
    from marm_setup.validate.discovery import ConfigSection

POSITIVE_KEYS = ("kinematics_solver_timeout", "kinematics_solver_search_resolution")


def check_kinematics(section: ConfigSection, srdf: Srdf, robot: RobotModel) -> list[Finding]:
    """Every rule on a kinematics section (`{group: {kinematics_solver: ..., ...}}`)."""
    data = section.data
    if not isinstance(data, dict):
        return [
            error("kinematics.malformed", section.file, section.element(), "expected a mapping of groups")
        ]
    by_name = groups_by_name(srdf.groups)
    out: list[Finding] = []
    for group, entry in data.items():
        where = section.element(group)
        if group not in by_name:
            known = ", ".join(sorted(by_name)) or "none"
            out.append(
                error(
                    "kinematics.unknown-group",
                    section.file,
                    where,
                    f"unknown group '{group}' (groups: {known})",
                )
            )
            continue
        if not isinstance(entry, dict):
            out.append(error("kinematics.malformed", section.file, where, "expected a mapping"))
            continue
        out += _check_entry(section, where, entry, by_name[group], by_name, srdf, robot)
    return out


def _check_entry(
    section: ConfigSection,
    where: str,
    entry: dict,
    group: Group,
    by_name: Mapping[str, Group],
    srdf: Srdf,
    robot: RobotModel,
) -> list[Finding]:
    out: list[Finding] = []
    solver = entry.get("kinematics_solver")
    if not isinstance(solver, str) or not solver:
        out.append(error("kinematics.missing-solver", section.file, where, "no kinematics_solver"))
    elif solver not in KINEMATICS_PLUGINS and not solver.endswith(IKFAST_PLUGIN_SUFFIX):
        msg = f"unknown solver plugin '{solver}'"
        out.append(
            warning(
                "kinematics.unknown-solver", section.file, f"{where}.kinematics_solver", msg, _solver_hint()
            )
        )
    elif solver in CHAIN_ONLY_PLUGINS and not is_chain(group, by_name, robot, tuple(srdf.passive_joints)):
        msg = f"{solver.split('/')[-1]} needs a serial chain, but group '{group.name}' is not one"
        hint = "use a chain group, or a solver for general groups (pick_ik, bio_ik, TRAC-IK)"
        out.append(error("kinematics.kdl-needs-chain", section.file, f"{where}.kinematics_solver", msg, hint))
    for key in POSITIVE_KEYS:
        if key in entry:
            value = entry[key]
            if isinstance(value, bool) or not isinstance(value, Real) or value <= 0:
                msg = f"{key} must be a positive number, got {value!r}"
                out.append(error("kinematics.non-positive", section.file, f"{where}.{key}", msg))
    return out


def _solver_hint() -> str:
    return "known: " + ", ".join(s.split("/")[0] for s in KINEMATICS_PLUGINS[:5]) + ", ikfast"
