"""Porting the IK solvers (kinematics): each group's solver, search resolution and timeout, and
the solver plugin's own options (KDL's `position_only_ik`, TRAC-IK's `solve_type`, ...), from
the package model's kinematics file."""

from __future__ import annotations

from collections.abc import Iterable

from marm_setup.moveit_params import MOVEIT_KINEMATICS_PLUGINS
from marm_setup.package import GroupKinematics, KinematicsFile
from marm_setup.port.port_log import PortLog
from marm_setup.setup import Kinematics

# MoveIt's kinematics.yaml keys per group -> Kinematics field
KINEMATICS_KEYS = {
    "kinematics_solver": "solver",
    "kinematics_solver_search_resolution": "search_resolution",
    "kinematics_solver_timeout": "timeout",
    "kinematics_solver_attempts": "attempts",
}


def short(value: object) -> str:
    """`repr(value)`, cut to a report line's length."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def yaml_text(value: object) -> str:
    """A value for a report line: true/false, a quoted string, a number as written."""
    if isinstance(value, bool):
        return str(value).lower()
    return repr(value) if isinstance(value, str) else f"{value}"


# -- kinematics --------------------------------------------------------------------------------


def port_kinematics(
    kinematics: KinematicsFile | None, groups: Iterable[str], log: PortLog
) -> tuple[Kinematics, ...]:
    """One Kinematics per group entry that names a solver, its plugin options included."""
    if kinematics is None:
        log.changed(
            "kinematics", "", "no kinematics file: no group has an IK solver (as in the source)", "kinematics"
        )
        return ()
    known = set(groups)
    out = []
    for entry in kinematics.groups or ():
        setting = f"kinematics[{entry.group}]"
        if entry.group not in known:
            log.dropped(setting, entry.where, "no planning group of that name in the SRDF", "kinematics")
        elif entry.solver is None:
            log.dropped(setting, entry.where, "names no kinematics_solver: MoveIt loads none", "kinematics")
        else:
            out.append(_kinematics(entry, log))
    return tuple(sorted(out, key=lambda k: k.group))


def _kinematics(entry: GroupKinematics, log: PortLog) -> Kinematics:
    values: dict = {"group": entry.group, "solver": entry.solver}
    log.carried(f"kinematics[{entry.group}].kinematics_solver", entry.where, str(entry.solver), "kinematics")
    for param in entry.params or ():
        field = KINEMATICS_KEYS.get(param.key)
        setting = f"kinematics[{entry.group}].{param.key}"
        if field == "solver":
            continue
        if field is None:
            continue  # options, below
        number = param.number
        if field == "attempts" and number is not None and number == int(number) and number > 0:
            values[field] = int(number)
            detail = f"{int(number)} (kept in marm_setup.yaml; MoveIt >= 1.0 reads no attempts)"
            log.carried(setting, entry.where, detail, "kinematics")
        elif field != "attempts" and number is not None and number > 0:
            values[field] = number
            log.carried(setting, entry.where, f"{number:g}", "kinematics")
        else:
            log.dropped(
                setting,
                entry.where,
                f"{short(param.value)} is not a positive number; the default applies",
                "kinematics",
            )
    values["options"] = _options(entry, log)
    if values["solver"] not in MOVEIT_KINEMATICS_PLUGINS:
        log.todo(
            f"kinematics[{entry.group}].kinematics_solver",
            entry.where,
            f"{values['solver']}: the new package.xml depends on moveit_kinematics (KDL, LMA, cached IK) only; "
            "install and depend on this plugin's package for the target distro",
            "kinematics",
        )
    return Kinematics(**values)


def _options(entry: GroupKinematics, log: PortLog) -> tuple[tuple[str, str | int | float | bool], ...]:
    """The solver plugin's own keys, carried as they are (typed: MoveIt hands each to the plugin)."""
    out = []
    for param in entry.options:
        setting = f"kinematics[{entry.group}].{param.key}"
        value = param.value
        if isinstance(value, str | int | float | bool) and param.key:
            out.append((param.key, value))
            log.carried(setting, entry.where, f"{yaml_text(value)} (a {_plugin(entry)} option)", "kinematics")
        else:
            log.dropped(
                setting,
                entry.where,
                f"{short(value)}: only single values are carried; add it by hand",
                "kinematics",
            )
    return tuple(out)


def _plugin(entry: GroupKinematics) -> str:
    return str(entry.solver).split("/")[0]
