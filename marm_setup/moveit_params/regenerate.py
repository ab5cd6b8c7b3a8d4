"""Rebuild the declared-parameter tables (data/<family>.yaml) from MoveIt's git repositories,
and the drivers' (data/drivers_<family>.yaml, driver_params.py) from ros2_control's:
`python -m marm_setup.moveit_params.regenerate --moveit2 DIR --moveit DIR
[--ros2-control DIR --ros2-controllers DIR] [--check]`.

DIR is a git repository (a bare mirror or a checkout) holding the branches named below; each
table pins the commit it was read at. Sources: the generate_parameter_library files (gpl.py),
the pluginlib description files (plugin_xml.py), Humble's servo declarations (servo_humble.py),
and curated.yaml's rows, whose citations are looked up at the pinned commit (git_source.py).
`--check` compares instead of writing (exit 1 on a difference).
"""

from __future__ import annotations

import argparse
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import yaml

from marm_setup.moveit_params.git_source import GitRef, SourceError
from marm_setup.moveit_params.gpl import gpl_rows
from marm_setup.moveit_params.plugin_xml import plugin_rows
from marm_setup.moveit_params.servo_humble import CPP, HEADER, servo_rows
from marm_setup.moveit_params.tables import DATA, FAMILIES

CURATED = Path(__file__).with_name("curated.yaml")
PIPELINE, GROUP = "<pipeline>.", "robot_description_kinematics.<group>."
# Jazzy's gpl files: (path, name prefix, node); byte-identical on kilted and main (checked)
GPL_FILES = (
    ("moveit_ros/planning/planning_pipeline/res/planning_pipeline_parameters.yaml", PIPELINE, "move_group"),
    ("moveit_ros/planning/planning_request_adapter_plugins/res/default_request_adapter_params.yaml", PIPELINE, "move_group"),
    ("moveit_ros/planning/planning_response_adapter_plugins/res/default_response_adapter_params.yaml", PIPELINE, "move_group"),
    ("moveit_planners/stomp/res/stomp_moveit.yaml", PIPELINE, "move_group"),
    ("moveit_ros/planning/kinematics_plugin_loader/src/kinematics_parameters.yaml", GROUP, "move_group"),
    ("moveit_planners/pilz_industrial_motion_planner/src/cartesian_limits_parameters.yaml",
     "robot_description_planning.cartesian_limits.", "move_group"),
    ("moveit_ros/moveit_servo/config/servo_parameters.yaml", "", "servo"),
)  # fmt: skip


@dataclass(frozen=True, slots=True)
class Refs:
    """The branches each family is read from (`also`: must hold identical gpl files)."""

    repo: str  # moveit2 | moveit
    ref: str
    also: tuple[str, ...] = ()


REFS = {
    "jazzy": Refs("moveit2", "jazzy", ("kilted", "main")),
    "humble": Refs("moveit2", "humble"),
    "noetic": Refs("moveit", "noetic-devel"),
}
GITHUB = {"moveit2": "moveit/moveit2", "moveit": "moveit/moveit"}


def build_table(family: str, git: GitRef, also: list[GitRef], curated: dict) -> dict:
    """The table of one family as a plain mapping (what data/<family>.yaml holds)."""
    rows: dict[tuple[str, str], dict] = {}
    if family == "jazzy":
        for path, prefix, node in GPL_FILES:
            _same_everywhere(git, also, path)
            for row in gpl_rows(git.text(path), path, prefix, node):
                rows[(row["node"], row["name"])] = row
    if family == "humble":
        for row in servo_rows(git.text(CPP), git.text(HEADER)):
            rows[(row["node"], row["name"])] = row
    shared = curated.get("ros2", []) if family != "noetic" else []
    for spec in (*shared, *curated.get(family, [])):
        row = _curated_row(spec, git, curated["files"])
        rows[(row["node"], row["name"])] = row
    owned = curated["owned"].get(family, [])
    owned = [*curated["owned"]["ros2"], *owned] if family != "noetic" else owned
    return {
        "family": family,
        "distros": list(FAMILIES[family]),
        "pinned": _pins(family, git, also),
        "parameters": [rows[k] for k in sorted(rows)],
        "owned": [{"prefix": o["prefix"], "source": _cite(git, curated["files"], o)} for o in owned],
        "plugins": _plugins(git),
        "third_party": curated["third_party"],
        "ompl_planners": _ompl_planners(git),
    }


def _pins(family: str, git: GitRef, also: list[GitRef]) -> dict:
    repo = GITHUB[REFS[family].repo]
    return {repo: {r.ref: r.commit() for r in (git, *also)}}


def _same_everywhere(git: GitRef, also: list[GitRef], path: str) -> None:
    for other in also:
        if other.blob(path) != git.blob(path):
            raise SourceError(f"{path} differs between {git.ref} and {other.ref}: split the family")


def _curated_row(spec: dict, git: GitRef, files: dict) -> dict:
    row = {"node": spec.get("node", "move_group"), "name": spec["name"], "type": spec["type"]}
    for key in ("default", "validation"):
        if key in spec:
            row[key] = spec[key]
    row["on_wrong"] = spec["on_wrong"]
    row["source"] = spec["source"] if "source" in spec else _cite(git, files, spec)
    if "note" in spec:
        row["note"] = spec["note"]
    return row


def _cite(git: GitRef, files: dict, spec: dict) -> str:
    """`path:line` of the first candidate literal found in the spec's file."""
    path = files[spec["file"]]
    last = spec.get("name", spec.get("prefix", "")).replace("/", ".").rstrip(".").rsplit(".", 1)[-1]
    full = spec.get("name", "")
    match = spec.get("match")
    literals = [match] if isinstance(match, str) else match or [f'"{full}"', f'"{last}"', f'.{last}"']
    for literal in literals:
        try:
            return f"{path}:{git.line_of(path, literal)}"
        except SourceError:
            continue
    raise SourceError(f"{git.ref}:{path}: none of {literals} found (row {full or spec.get('prefix')})")


OMPL_CONTEXTS = "moveit_planners/ompl/ompl_interface/src/planning_context_manager.cpp"
OMPL_REGISTERED = re.compile(r'registerPlannerAllocatorHelper<[^>]*>\("([^"]+)"\)')


def _ompl_planners(git: GitRef) -> list[dict]:
    """The planner types OMPL's PlanningContextManager registers (registerDefaultPlanners); any
    other `type` is "Unknown planner" (plannerSelector)."""
    lines = git.text(OMPL_CONTEXTS).splitlines()
    found = [(m.group(1), n) for n, line in enumerate(lines, 1) for m in OMPL_REGISTERED.finditer(line)]
    return [{"type": name, "source": f"{OMPL_CONTEXTS}:{n}"} for name, n in sorted(found)]


def _plugins(git: GitRef) -> dict[str, list[dict]]:
    out: dict[str, list[dict]] = {}
    for path in git.files(".xml"):
        if "test" in path or "setup_assistant" in path or path.endswith("package.xml"):
            continue
        text = git.text(path)
        if "<class" not in text:
            continue
        for kind, row in plugin_rows(text, path):
            out.setdefault(kind, []).append(row)
    return {k: sorted(v, key=lambda r: r["class"]) for k, v in sorted(out.items())}


def dump_table(table: dict) -> str:
    """The table as the committed file's text: a header, then the YAML body."""
    pins = ", ".join(
        f"{repo} {ref} {sha}" for repo, refs in table["pinned"].items() for ref, sha in refs.items()
    )
    header = (
        f"# MoveIt's declared parameters, {table['family']} family ({', '.join(table['distros'])}).\n"
        f"# Generated by `python -m marm_setup.moveit_params.regenerate`; do not edit by hand.\n"
        f"# Pinned: {pins}\n"
    )
    return header + yaml.safe_dump(table, sort_keys=False, width=110, allow_unicode=True)


def render_all(moveit2: Path | None, moveit: Path | None) -> dict[str, str]:
    """{family: text} for every family whose repository is given."""
    curated = yaml.safe_load(CURATED.read_text(encoding="utf-8"))
    repos = {"moveit2": moveit2, "moveit": moveit}
    out = {}
    for family, refs in REFS.items():
        repo = repos[refs.repo]
        if repo is None:
            continue
        git = GitRef(repo, refs.ref)
        also = [GitRef(repo, r) for r in refs.also]
        out[family] = dump_table(build_table(family, git, also, curated))
    return out


def render_drivers(control: Path | None, controllers: Path | None) -> dict[Path, str]:
    """{table path: text} of the drivers' tables, when both repositories are given."""
    from marm_setup.moveit_params.driver_params import (
        REFS as DRIVER_REFS,
    )
    from marm_setup.moveit_params.driver_params import (
        build_driver_table,
        driver_table_path,
        dump_driver_table,
    )

    if control is None or controllers is None:
        return {}
    return {
        driver_table_path(family): dump_driver_table(
            build_driver_table(family, GitRef(controllers, ref), GitRef(control, ref))
        )
        for family, ref in DRIVER_REFS.items()
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moveit2", type=Path, help="git repository of moveit/moveit2")
    parser.add_argument("--moveit", type=Path, help="git repository of moveit/moveit (noetic-devel)")
    parser.add_argument("--ros2-control", type=Path, help="git repository of ros-controls/ros2_control")
    parser.add_argument(
        "--ros2-controllers", type=Path, help="git repository of ros-controls/ros2_controllers"
    )
    parser.add_argument("--check", action="store_true", help="compare with the committed tables")
    args = parser.parse_args(argv)
    changed = []
    tables = {DATA / f"{family}.yaml": text for family, text in render_all(args.moveit2, args.moveit).items()}
    tables.update(render_drivers(args.ros2_control, args.ros2_controllers))
    for path, text in tables.items():
        if path.exists() and path.read_text(encoding="utf-8") == text:
            continue
        changed.append(path.name)
        if not args.check:
            path.write_text(text, encoding="utf-8", newline="\n")
    verb = "differ" if args.check else "written"
    print(f"{verb}: {', '.join(changed)}" if changed else "tables up to date")
    return 1 if changed and args.check else 0


if __name__ == "__main__":
    sys.exit(main())
