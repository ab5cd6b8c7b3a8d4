"""kinematics.yaml: groups exist, solver plugin known, KDL on chains only, positive timeout/resolution.

A group the SRDF lacks is only a warning: the kinematics plugin loader looks up
`<group>/kinematics_solver` for each group of the SRDF and never reads other keys (moveit/moveit
`moveit_ros/planning/kinematics_plugin_loader/src/kinematics_plugin_loader.cpp` l.286-309,
moveit/moveit2 the same file l.254-265); such a key is a leftover or a typo.

A solver none of whose names we know is a warning unless the package declares a dependency on
the package its name starts with (`moveit_opw_kinematics_plugin/MoveItOPWKinematicsPlugin` and
`<exec_depend>moveit_opw_kinematics_plugin</exec_depend>`): the loader asks pluginlib for the
name among every installed package's plugin descriptions (moveit/moveit
kinematics_plugin_loader.cpp l.168 at fdb79ac, `createUniqueInstance`; l.199 the error when
none has it), and the package pluginlib names are conventionally prefixed with is installed
with this one.

Groups a launch file hands to move_group as its own top-level parameters (`<group>.
kinematics_solver`: a ROS 2 parameter file of groups, or `load_yaml(...)` listed bare among
move_group's parameters) are found by Humble's loader, which looks there first
(moveit/moveit2 humble kinematics_plugin_loader.cpp l.306-319), and by no later one: Jazzy,
Kilted and Rolling look only at `robot_description_kinematics.<group>` (jazzy l.258-272, kilted
and main l.260) and skip a group with no solver there (l.268-272): it has no IK solver.
MoveItConfigsBuilder puts the file under robot_description_kinematics itself
(moveit_configs_builder.py `robot_description_kinematics`), so this is only about launch files
that hand the file over themselves (`KinematicsFile.top_level_by`).
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from typing import TYPE_CHECKING

from marm_setup.findings import Finding, Location, error, warning
from marm_setup.moveit_params import CHAIN_ONLY_PLUGINS, IKFAST_PLUGIN_SUFFIX, load_table
from marm_setup.package import GroupKinematics, KinematicsFile
from marm_setup.robot import RobotModel
from marm_setup.setup import groups_by_name, is_chain

if TYPE_CHECKING:
    from marm_setup.ros import DistroRow
    from marm_setup.setup import Group, Srdf

POSITIVE_KEYS = ("kinematics_solver_timeout", "kinematics_solver_search_resolution")


def check_kinematics(
    kinematics: KinematicsFile,
    srdf: Srdf,
    robot: RobotModel | None,
    *,
    moveit1: bool = True,
    depends: tuple[str, ...] = (),
    exported: frozenset[str] = frozenset(),
) -> list[Finding]:
    """Every rule on a kinematics file (`{group: {kinematics_solver: ..., ...}}`); without the
    robot (a description only the run time gives) whether a group is a chain is not checked.
    `moveit1`: a MoveIt 1 package, whose solver class names (and ignored attempts) are this
    rule's to check (a ROS 2 package's classes are declared_param_rules', against MoveIt 2's
    plugin description files); `depends`: the packages package.xml depends on; `exported`: the
    plugin classes packages on the package paths export (pluginlib loads those, whatever the
    prefix of their name)."""
    file = kinematics.where.file
    if kinematics.groups is None:
        return [error("kinematics.malformed", file, kinematics.where.element, "expected a mapping of groups")]
    by_name = groups_by_name(srdf.groups)
    out: list[Finding] = []
    for entry in kinematics.groups:
        where = entry.where.element
        if entry.group not in by_name:
            known = ", ".join(sorted(by_name)) or "none"
            msg = f"unknown group '{entry.group}' (groups: {known}): MoveIt never reads it"
            at = Location("kinematics", entry.group, ("group", entry.group))
            hint = "a leftover or a typo: rename it to a group of the SRDF, or remove it"
            out.append(warning("kinematics.unknown-group", file, where, msg, hint, at=at))
        elif entry.params is None:
            out.append(error("kinematics.malformed", file, where, "expected a mapping"))
        else:
            names = moveit1 and not _declared(entry.solver, depends) and entry.solver not in exported
            out += _check_entry(file, entry, by_name[entry.group], by_name, srdf, robot, names)
            out += _attempts(file, entry) if moveit1 else []
    return out


def _attempts(file: str, entry: GroupKinematics) -> list[Finding]:
    """MoveIt 1 >= 1.0 ignores kinematics_solver_attempts and warns at start-up that it is no
    longer supported (kinematics_plugin_loader.cpp noetic l.350-357)."""
    if entry.param("kinematics_solver_attempts") is None:
        return []
    msg = "kinematics_solver_attempts is ignored since MoveIt 1.0: move_group warns at start-up"
    hint = "remove it; raise kinematics_solver_timeout instead"
    return [
        warning(
            "kinematics.attempts-ignored",
            file,
            f"{entry.where.element}.kinematics_solver_attempts",
            msg,
            hint,
        )
    ]


def _check_entry(
    file: str,
    entry: GroupKinematics,
    group: Group,
    by_name: Mapping[str, Group],
    srdf: Srdf,
    robot: RobotModel | None,
    solver_names: bool = True,
) -> list[Finding]:
    out: list[Finding] = []
    where = entry.where.element
    solver = entry.solver
    if solver is None:
        out.append(error("kinematics.missing-solver", file, where, "no kinematics_solver"))
    elif solver_names and solver not in _known_solvers() and not solver.endswith(IKFAST_PLUGIN_SUFFIX):
        out.append(_unknown_solver(file, f"{where}.kinematics_solver", solver))
    elif (
        robot is not None
        and solver in CHAIN_ONLY_PLUGINS
        and not is_chain(group, by_name, robot, tuple(srdf.passive_joints))
    ):
        msg = f"{solver.split('/')[-1]} needs a serial chain, but group '{group.name}' is not one"
        hint = "use a chain group, or a solver for general groups (pick_ik, bio_ik, TRAC-IK)"
        out.append(error("kinematics.kdl-needs-chain", file, f"{where}.kinematics_solver", msg, hint))
    for key in POSITIVE_KEYS:
        param = entry.param(key)
        if param is not None:
            value = param.value
            if isinstance(value, bool) or not isinstance(value, int | float) or value <= 0:
                msg = f"{key} must be a positive number, got {value!r}"
                out.append(error("kinematics.non-positive", file, f"{where}.{key}", msg))
    return out


def _unknown_solver(file: str, element: str, solver: str) -> Finding:
    """A solver class no known plugin package exports: an error when its package is one of the
    known ones (that package exports no such class: pluginlib cannot load it, a typo), else a
    warning (another package may export it once built)."""
    owner = solver.split("/", 1)[0]
    if owner not in _known_owners():
        return warning(
            "kinematics.unknown-solver", file, element, f"unknown solver plugin '{solver}'", _solver_hint()
        )
    close = difflib.get_close_matches(solver, _known_solvers(), n=1, cutoff=0.6)
    msg = f"package '{owner}' exports no solver '{solver}': pluginlib cannot load it, the group has no IK"
    return error(
        "kinematics.unknown-solver",
        file,
        element,
        msg,
        f"did you mean {close[0]}?" if close else _solver_hint(),
    )


def _declared(solver: str | None, depends: tuple[str, ...]) -> bool:
    """`solver`'s name starts with a package the package depends on (and whose classes are not
    known: a known package's other class is a typo whatever package.xml says)."""
    owner = str(solver).split("/", 1)[0] if solver and "/" in str(solver) else None
    return owner is not None and owner in depends and owner not in _known_owners()


def _known_owners() -> set[str]:
    return {known.split("/", 1)[0] for known in _known_solvers()}


def _solver_hint() -> str:
    return "known: " + ", ".join(s.split("/")[0] for s in _known_solvers()[:5]) + ", ikfast"


def _known_solvers() -> tuple[str, ...]:
    """MoveIt 1's solver classes (the noetic table: its pluginlib files) and the known
    third-party ones (a ROS 2 package's are declared_param_rules')."""
    return load_table("noetic").classes("kinematics")


def check_top_level_kinematics(
    kinematics: KinematicsFile, srdf: Srdf, row: DistroRow | None
) -> list[Finding]:
    """Each group of the SRDF with a solver in a kinematics file a launch file hands to
    move_group at the top level of its parameters (see the module docstring): an error for a
    distro whose MoveIt does not look there (`row.kinematics_top_level` false), a warning when
    the distro is not known; nothing for Humble."""
    launch = kinematics.top_level_by
    if not launch or (row is not None and row.kinematics_top_level):
        return []
    known = {g.name for g in srdf.groups}
    out = []
    for entry in kinematics.groups or ():
        if entry.group not in known or entry.solver is None:
            continue
        name = entry.group
        where = f"robot_description_kinematics.{name}.kinematics_solver"
        said = f"{launch} hands the groups of this file to move_group at the top level ({name}.kinematics_solver)"
        hint = (
            "put the groups under robot_description_kinematics: (in a launch file: "
            '{"robot_description_kinematics": kinematics_yaml})'
        )
        if row is None:
            msg = (
                f"{said}: Humble's MoveIt finds the solver there; Jazzy's and later look only at "
                f"{where}, so there group '{name}' has no IK solver"
            )
            out.append(warning("kinematics.top-level", kinematics.where.file, entry.where.element, msg, hint))
        else:
            msg = f"{said}: {row.name}'s MoveIt looks only at {where}: group '{name}' has no IK solver"
            out.append(error("kinematics.top-level", kinematics.where.file, entry.where.element, msg, hint))
    return out
