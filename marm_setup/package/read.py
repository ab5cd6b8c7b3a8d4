"""read_package: a config package folder (ours, the Setup Assistant's, a vendor's) -> a
`MoveItPackage`, built once: its files found by following its launch files, each parsed once.

Reading never judges: files that cannot be read are findings in `problems`; only a folder that
is not a config package at all (or has no robot description) raises InputError (exit 2).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from marm_setup.bounded_read import XML_BYTES
from marm_setup.errors import InputError, PackageNotFound
from marm_setup.findings import Finding, Location, error, warning
from marm_setup.package.bringup import BringupRobot
from marm_setup.package.builder import BuilderFiles, Chosen, builder_files, builds_same_robot, chosen_file
from marm_setup.package.description import (
    MARM_MOVEIT_YAML,
    SRDF_GUESSED,
    Description,
    choose_srdf,
    detect_target,
    find_description,
    marm_package_paths,
)
from marm_setup.package.driver_file import Ros2ControlFile, read_ros2_control
from marm_setup.package.files import FileProblem, PackageFiles
from marm_setup.package.launch_python import XacroCommand, read_python_launch
from marm_setup.package.launch_ros1 import DescriptionLoad, LaunchParam, Ros1Launch, YamlLoad, evaluate_ros1
from marm_setup.package.launch_ros2 import evaluate_ros2_xml
from marm_setup.package.launch_xml import LaunchXml, launch_file_names, parse_launch, python_launch_names
from marm_setup.package.layout import Kinds, read_move_group_file, read_ros1_kinds, read_ros2_kinds
from marm_setup.package.model import MoveItPackage, Source
from marm_setup.package.setup_files import (
    MarmSetupFile,
    PackageXml,
    SetupAssistantFile,
    read_marm_setup,
    read_package_xml,
    read_setup_assistant,
)
from marm_setup.package.srdf_file import SrdfFile, read_srdf_file, srdf_robot_name
from marm_setup.package.substitution import Scope
from marm_setup.package.where import unwrap_parameters
from marm_setup.ros import Target
from marm_setup.untrusted import confine_reads, excerpt, readable


@dataclass(frozen=True)
class _Launched:
    """What the launch files load."""

    loads: tuple[YamlLoad, ...] = ()
    semantic: DescriptionLoad | None = None
    builder: BuilderFiles | None = None
    control_files: tuple[str, ...] = ()
    commands: tuple[XacroCommand, ...] = ()  # descriptions a Python launch file builds with xacro
    named_yaml: tuple[tuple[str, str], ...] = ()  # (package-relative YAML path, Python launch naming it)
    description: DescriptionLoad | None = None  # robot_description as a ROS 1 launch sets it
    params: tuple[LaunchParam, ...] = ()  # ROS 1 `<param name value>`s
    move_groups: tuple[str, ...] = ()  # ROS 1 move_group nodes' full names
    managers: tuple[str, ...] = ()  # ROS 1 moveit_controller_manager values
    taken_managers: tuple[LaunchParam, ...] = ()  # ROS 1: those set on branches the defaults take
    args: tuple[tuple[str, str], ...] = ()  # the launch arguments given (--launch-arg)

    def command(self, parameter: str) -> XacroCommand | None:
        return next((c for c in self.commands if c.parameter == parameter), None)

    def unread_args(self, parameter: str) -> tuple[str, ...]:
        """Xacro args the launch files pass `parameter`'s file with values only the run time gives."""
        command = self.command(parameter)
        own = self.builder.unread_args(parameter) if self.builder is not None else ()
        xml = self.semantic if parameter.endswith("_semantic") else self.description
        launched = (*(command.unread_args if command else ()), *(xml.unread_args if xml else ()))
        return tuple(sorted({*own, *launched}))


@dataclass(frozen=True)
class _Setup:
    """What says where the robot is and which ROS the package targets."""

    marm: MarmSetupFile | None
    sa: SetupAssistantFile | None
    package_xml: PackageXml | None
    paths: tuple[Path, ...]  # for $(find): this package, the user's, marm_setup.yaml's, its folder
    target: Target
    name: str


def read_package(
    path: str | Path,
    *,
    urdf: str | Path | None = None,
    srdf: str | Path | None = None,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    launch_args: Mapping[str, str] | None = None,
) -> MoveItPackage:
    """Read the config package at `path`; InputError when it is not one. Its `$(eval)`s run in
    one child process (package/eval_child.py), killed once it is read. `launch_args`: the
    launch files' arguments as `roslaunch` / `ros2 launch` would be given them."""
    from marm_setup.package.eval_child import eval_session

    with eval_session():
        return _read_package(
            path,
            urdf=urdf,
            srdf=srdf,
            xacro_args=xacro_args,
            package_paths=package_paths,
            launch_args=launch_args or {},
        )


def _read_package(
    path: str | Path,
    *,
    urdf: str | Path | None,
    srdf: str | Path | None,
    xacro_args: Mapping[str, str] | None,
    package_paths: Iterable[str | Path],
    launch_args: Mapping[str, str],
) -> MoveItPackage:
    shown, root = str(path), Path(path).resolve()
    if not root.is_dir():
        raise InputError("not a folder", path=shown)
    problems: list[Finding] = []
    package_paths = tuple(package_paths)
    files = PackageFiles(root, problems, _user_folders(package_paths, urdf, srdf))
    confine_reads((root, *files.allowed))  # --untrusted: nothing outside is read from now on
    found = _setup(files, shown, package_paths)
    trees = {rel: parse_launch(root / rel, rel) for rel in files.inside_only(launch_file_names(root))}
    wanted = _wanted_robots(srdf, urdf)
    launched = _launched(files, trees, found.paths, found.target, found.name, wanted, launch_args)
    problems += _other_robots(launched.builder, root, found.sa)
    srdf_rel, srdf_args, guessed = _srdf_choice(files, srdf, found, launched, wanted)
    if found.package_xml is None and srdf_rel is None:
        raise InputError("not a MoveIt config package (no package.xml and no config/*.srdf)", path=shown)
    chosen = _description(files, shown, urdf, xacro_args, found, srdf_rel, launched)
    description = _readable_description(files, chosen)
    bringup_srdf = _bringup_srdf(files, found.paths, chosen, launched) if srdf is None else None
    if bringup_srdf is not None:
        srdf_rel, srdf_args, guessed = bringup_srdf[0], bringup_srdf[1], False
    kinds = _kinds(files, found.target, launched, problems, chosen.bringup)
    unread = (*launched.unread_args("robot_description_semantic"), *(bringup_srdf[2] if bringup_srdf else ()))
    srdf_args, built = _built_srdf_args(files, srdf_rel, srdf_args, launched)
    srdf_file = _srdf(root, srdf_rel, (srdf_args, unread), xacro_args, found.paths, problems, built)
    return MoveItPackage(
        root=root,
        shown=shown,
        name=found.name,
        target=found.target,
        layout=kinds.values.pop("layout", "moveit2" if found.target == Target.ROS2 else "moveit1"),  # type: ignore[arg-type]
        urdf=description.urdf,
        urdf_origin=description.origin,
        description_unreadable=description.unreadable,
        xacro_args=description.xacro_args,
        launch_args=tuple(sorted(launch_args.items())),
        unread_xacro_args=_unread_args(launched, description, "robot_description", xacro_args)
        if urdf is None
        else (),
        package_paths=found.paths,
        package_xml=found.package_xml,
        setup_assistant=found.sa,
        marm_setup=found.marm,
        srdf_file=srdf_file,
        launch=tuple(trees.values()),
        launch_params=launched.params,
        python_launch_files=files.inside_only(python_launch_names(root)),
        ros2_control_files=_ros2_control_files(files) if found.target == Target.ROS2 else (),
        files=files.listing(),
        sources=(
            *kinds.sources,
            *_srdf_source(srdf_file, launched, guessed, chosen.bringup if bringup_srdf else None),
        ),
        problems=tuple(problems),
        **kinds.values,  # type: ignore[arg-type]
    )


def _user_folders(
    package_paths: tuple[str | Path, ...], urdf: str | Path | None, srdf: str | Path | None
) -> tuple[Path, ...]:
    """The folders the user named: each --package-path, and those of --urdf and --srdf; a file
    of the package may lead into them."""
    files = (Path(f).resolve().parent for f in (urdf, srdf) if f is not None)
    return (*(Path(p).resolve() for p in package_paths), *files)


def _setup(files: PackageFiles, shown: str, package_paths: Iterable[str | Path]) -> _Setup:
    root = files.root
    marm = None
    if files.is_file("marm_setup.yaml"):
        marm = read_marm_setup(files.yaml("marm_setup.yaml"), str(Path(shown) / "marm_setup.yaml"))
    sa = read_setup_assistant(files.yaml(".setup_assistant")) if files.is_file(".setup_assistant") else None
    pkg_xml = _package_xml(files)
    given = (Path(p).resolve() for p in package_paths)
    paths = (root, *given, *marm_package_paths(root, marm), root.parent, *_enclosing_workspace(root))
    return _Setup(marm, sa, pkg_xml, paths, detect_target(root, pkg_xml, marm), _name(root))


WORKSPACE_LEVELS = 4  # folders above the package looked at for its repository or workspace


def _enclosing_workspace(root: Path) -> tuple[Path, ...]:
    """The repository (a folder holding `.git`) or workspace `src/` folder enclosing the
    package, a few levels up: a vendor repository's description packages live there, as
    a sourced workspace's ROS_PACKAGE_PATH would find them."""
    for folder in list(root.parents)[1:WORKSPACE_LEVELS]:
        if (folder / ".git").exists() or folder.name == "src":
            return (folder,)
    return ()


def _name(root: Path) -> str:
    from marm_setup.robot import package_name

    return package_name(root) or root.name


def _own_names(files: PackageFiles) -> tuple[str, ...]:
    """The package's own name and the packages its package.xml depends on."""
    xml = _package_xml(files)
    names = xml.names if xml is not None else ()
    return names if xml is not None and xml.name else (files.root.name, *names)


def _package_xml(files: PackageFiles) -> PackageXml | None:
    try:
        text = files.text("package.xml", XML_BYTES)
    except FileProblem:
        text = ""
    return read_package_xml("package.xml", text) if text is not None else None


def _finder(paths: tuple[Path, ...]) -> Callable[[str], str | None]:
    from marm_setup.robot import PackageIndex, find_packages

    try:
        packages = find_packages(paths)
    except InputError:
        packages = PackageIndex()
    return lambda name: str(packages[name]) if name in packages else None


def _wanted_robots(srdf: str | Path | None, urdf: str | Path | None) -> tuple[str, ...]:
    """Robot names the user's --srdf (its `<robot name>`) and --urdf (its file name, as
    MoveItConfigsBuilder's `config/<robot_name>.urdf.xacro`, and its `<robot name>`, which
    srdfdom wants the SRDF's to be: srdfdom src/model.cpp initXml) point at."""
    out = []
    if srdf is not None and (name := srdf_robot_name(Path(srdf).resolve().parent, Path(srdf).name)):
        out.append(name)
    if urdf is not None:
        out.append(Path(urdf).name.split(".", 1)[0])
        named = srdf_robot_name(Path(urdf).resolve().parent, Path(urdf).name)
        if named and "$" not in named:
            out.append(named)
    return tuple(out)


def _other_robots(builder: BuilderFiles | None, root: Path, sa: SetupAssistantFile | None) -> list[Finding]:
    """A package whose launch files build several robots is validated for one of them; a robot
    name whose calls load the same description and SRDF is the same robot."""
    others = [o for o in builder.others if not builds_same_robot(builder, o, root, sa)] if builder else []
    if builder is None or not others:
        return []
    launch = builder.calls[0].launch if builder.calls else "its launch files"
    msg = (
        f"the launch files also build {', '.join(others)}: validated {builder.robot_name} "
        f"(what {launch} loads)"
    )
    return [
        warning(
            "launch.several-robots",
            launch,
            "MoveItConfigsBuilder",
            msg,
            "pass --srdf and --urdf of another robot to validate it",
        )
    ]


def _launched(
    files: PackageFiles,
    trees: Mapping[str, LaunchXml],
    paths: tuple[Path, ...],
    target: Target,
    name: str,
    wanted: tuple[str, ...] = (),
    args: Mapping[str, str] | None = None,
) -> _Launched:
    """What the launch files load, given the launch arguments `args`; subst_value files get
    their launch args before any is read."""
    find = _finder(paths)
    given = tuple(sorted((args or {}).items()))
    if target == Target.ROS1:
        ros1: Ros1Launch = evaluate_ros1(files.root, trees, find, args)
        _stopped_walks(files, ros1.stopped)
        for load in sorted(ros1.loads, key=lambda lo: lo.conditional):
            if load.scope is not None:
                files.scopes.setdefault(load.file, load.scope)
        return _Launched(
            ros1.loads,
            ros1.semantic,
            description=ros1.description,
            params=ros1.params,
            move_groups=ros1.move_groups,
            managers=ros1.managers,
            taken_managers=ros1.taken_managers,
            args=given,
        )
    xml = evaluate_ros2_xml(files.root, trees, find, args)
    _stopped_walks(files, xml.stopped)
    python = read_python_launch(files.root, files.inside_only(python_launch_names(files.root)), find, args)
    for launch_file, why in python.unread:
        files.problems.append(warning("launch.python-unread", launch_file, "", why))
    for path, defaults in python.substituted:  # ParameterFile(..., allow_substs=True)
        if (rel := _relative(path, files.root)) is not None:
            files.scopes.setdefault(rel, Scope(dict(defaults), find, ros2=True))
    for path, pairs in python.replaced:  # nav2_common's ReplaceString(source_file, replacements)
        if (rel := _relative(path, files.root)) is not None:
            files.replacements.setdefault(rel, pairs)
    builder = builder_files(python.builders, name, wanted, python.other_builders)
    control = tuple(
        rel for path, _ in python.control_files if (rel := _relative(path, files.root)) is not None
    )
    named = tuple((rel, launch) for path, launch in python.named_yaml if (rel := _relative(path, files.root)))
    return _Launched(
        xml.loads, xml.semantic, builder, control, python.commands, named, xml.description, args=given
    )


def _stopped_walks(files: PackageFiles, stopped: tuple[str, ...]) -> None:
    """A warning per launch file whose includes went past the walk bound (launch_ros1.MAX_VISITS)."""
    from marm_setup.package.launch_ros1 import MAX_VISITS

    for rel in stopped:
        msg = (
            f"its includes take more than {MAX_VISITS} file walks (a file including itself with new args): "
            "what lies past them was not read"
        )
        files.problems.append(warning("launch.include-bound", rel, "include", msg))


def _relative(path: str, root: Path) -> str | None:
    from marm_setup.package.launch_xml import package_relative

    return package_relative(path, root)


def _srdf_choice(
    files: PackageFiles,
    given: str | Path | None,
    found: _Setup,
    launched: _Launched,
    robots: tuple[str, ...] = (),
) -> tuple[str | None, tuple[tuple[str, str], ...], bool]:
    """(relative SRDF path or None, its xacro args): `--srdf` when given, else `choose_srdf`;
    a launch file's semantic description may lie in another package the package paths hold
    (a `.srdf.xacro` beside the URDF)."""
    root, marm, sa = files.root, found.marm, found.sa
    if given is not None:
        if not Path(given).is_file():
            raise InputError("file not found", path=str(given), element="--srdf")
        return Path(os.path.relpath(Path(given).resolve(), root)).as_posix(), (), False
    builder = launched.builder
    explicit = (
        chosen_file(builder, "robot_description_semantic", root)
        if builder and builder.explicit("robot_description_semantic")
        else None
    )
    named = (
        (explicit.file, builder.mappings("robot_description_semantic") or ())
        if explicit and builder
        else None
    )
    semantic = _launched_file(files, launched.semantic, "robot_description_semantic", found.paths)
    command = launched.command("robot_description_semantic")
    rel = _relative(command.file, root) if command is not None and command.file else None
    if semantic is None and command is not None and rel is not None:
        semantic = (rel, command.args)
    default = f"config/{builder.robot_name}.srdf" if builder is not None else None
    outside = semantic[0] if semantic is not None and semantic[0].startswith("../") else None

    def refused(rel: str, file: str, element: str) -> bool:
        return rel != outside and files.refused(rel, file, element)

    return choose_srdf(root, marm, sa, (named, semantic, default), files.problems, refused, robots)


def _launched_file(
    files: PackageFiles, load: DescriptionLoad | None, param: str, paths: tuple[Path, ...]
) -> tuple[str, tuple[tuple[str, str], ...]] | None:
    """(path relative to the package, xacro args) of the file a ROS 1 launch file loads as
    `param`, when it exists inside the package or a package the package paths hold; else None,
    with a finding saying why where MoveIt would not start or validate reads another file."""
    from marm_setup.untrusted import inside

    if load is None or (load.file is None and load.missing_package is None):
        return None
    if load.missing_package is not None:
        files.problems.append(
            missing_package(str(load.missing_package), load.launch, param, _own_names(files))
        )
        return None
    assert load.file is not None
    path = files.root / load.file
    if not inside(path, (files.root, *paths)):
        files.refused(load.file, load.launch, param)
        return None
    if not path.is_file() and load.file.startswith("../"):  # in this package: launch.missing-file
        files.problems.append(_missing_file(load, param))
    if not path.is_file():
        return None
    return load.file, load.xacro_args


def _missing_file(load: DescriptionLoad, param: str) -> Finding:
    """A description file of another package that does not exist: roslaunch stops before
    move_group starts; a warning when only a branch the arg defaults do not take loads it
    (e.g. `load_robot_description:=true`, where the robot publishes the description itself)."""
    if load.conditional:
        msg = (
            f"loads {load.file}, which does not exist, on a branch only other args take: roslaunch stops then"
        )
        return warning(f"{_kind(param)}.missing", load.launch, param, msg, "fix the path")
    msg = f"loads {load.file}, which does not exist: roslaunch stops before move_group starts"
    return error(f"{_kind(param)}.missing", load.launch, param, msg, "fix the path")


def _kind(param: str) -> str:
    return "srdf" if param.endswith("_semantic") else "urdf"


def missing_package(package: str, launch: str, param: str, own: tuple[str, ...] = ()) -> Finding:
    """A description in a package no package path holds: validate cannot read what MoveIt loads
    (the rules needing it are skipped); the user passes the folder holding it. An error when
    the name nearly spells one of `own` (the package's name and those its package.xml depends
    on): a typo, and roslaunch's $(find) stops before move_group starts (substitution_args.py
    _find)."""
    from marm_setup.robot import misspelt_package

    meant = misspelt_package(package, own)
    what = "SRDF" if param.endswith("_semantic") else "robot description"
    at = Location("package", package)
    if meant is not None:
        msg = f"loads its {what} from package '{package}', which does not exist: roslaunch stops before move_group starts"
        return error(f"{_kind(param)}.package-missing", launch, param, msg, f"did you mean '{meant}'?", at=at)
    msg = (
        f"loads its {'SRDF' if param.endswith('_semantic') else 'robot description'} from package "
        f"'{package}', which no package path holds: the rules needing it are skipped"
    )
    hint = f"pass --package-path DIR (the folder holding {package})"
    at = Location("package", package)
    return warning(f"{_kind(param)}.package-missing", launch, param, msg, hint, at=at)


def _description(
    files: PackageFiles,
    shown: str,
    urdf: str | Path | None,
    xacro_args: Mapping[str, str] | None,
    found: _Setup,
    srdf_rel: str | None,
    launched: _Launched,
) -> Description:
    root = files.root
    builder = launched.builder
    explicit = builder.explicit("robot_description") if builder is not None else None
    rel = _relative(explicit.file, root) if explicit is not None else None
    mappings = builder.mappings("robot_description") if builder is not None else None
    how = explicit.how if explicit is not None else ""
    robots = (builder.robot_name if builder and builder.calls else None, srdf_robot_name(root, srdf_rel))
    given = (Path(urdf) if urdf is not None else None, tuple(sorted((xacro_args or {}).items())))
    command = launched.command("robot_description")
    if urdf is None and not (found.marm and found.marm.urdf) and launched.description is not None:
        from_launch = _launch_description(files, launched.description, given[1], found.paths)
        if from_launch is not None:
            return from_launch
    if urdf is None and not (found.marm and found.marm.urdf) and explicit is not None and rel is None:
        from_builder = _external_builder_description(explicit, mappings, given[1], found.paths)
        if from_builder is not None:
            return from_builder
    if urdf is None and not (found.marm and found.marm.urdf) and not (rel and (root / rel).is_file()):
        from_command = _command_description(command, shown, given[1], found.paths)
        if from_command is not None:
            return from_command
    try:
        found_description = find_description(
            root,
            shown,
            found.name,
            given,
            found.marm,
            found.sa,
            found.paths,
            robots,
            (rel, mappings, how),
            files.refused,
            lambda: _bringup_description(files, found, given[1], dict(launched.args)),
        )
    except PackageNotFound as exc:  # .setup_assistant's or marm_setup.yaml's package: a finding
        return _missing_package(files, exc)
    if found_description.urdf is None and command is not None and command.unheld is not None:
        files.problems.append(
            missing_package(command.unheld, command.launch, "robot_description", _own_names(files))
        )
        why = f"xacro command in {command.launch}, from package '{command.unheld}' not found"
        return Description(None, why, (), unreadable=True)
    if found_description.urdf is None and command is not None:
        why = (
            f"{command.launch} builds it with xacro from {command.file}, outside the package and the folders named"
            if command.file
            else f"{command.launch} builds it with a xacro command whose file validate cannot read statically"
        )
        return Description(None, why, ())
    return found_description


def _bringup_srdf(
    files: PackageFiles, paths: tuple[Path, ...], chosen: Description, launched: _Launched
) -> tuple[str, tuple[tuple[str, str], ...], tuple[str, ...]] | None:
    """(path relative to the package, xacro args, args of unknown value) of the SRDF the bringup
    launch file that gave the robot sets beside it, when the package's own launch files set
    none: move_group gets both from that launch file (rdf_loader.cpp l.86-99)."""
    from marm_setup.untrusted import inside

    own = launched.semantic is not None or launched.command("robot_description_semantic") is not None
    builder = launched.builder
    own = own or bool(builder and builder.explicit("robot_description_semantic"))
    semantic = chosen.bringup.semantic if chosen.bringup is not None else None
    if own or semantic is None or not inside(semantic[0], (files.root, *paths)) or not readable(semantic[0]):
        return None
    rel = Path(os.path.relpath(semantic[0], files.root)).as_posix()
    return rel, semantic[1], semantic[2]


def _bringup_description(
    files: PackageFiles, found: _Setup, args: tuple[tuple[str, str], ...], launch_args: Mapping[str, str]
) -> Description | None:
    """The robot a bringup launch file of another package gives this one (package.bringup),
    given `launch_args`, with --xacro-arg on top; None when no launch file does."""
    from marm_setup.package.bringup import find_bringup_robot

    robot = find_bringup_robot(found.name, files.root, found.paths, found.target, launch_args)
    if robot is None:
        return None
    merged = tuple(sorted({**dict(robot.args), **dict(args)}.items()))
    return Description(robot.urdf, robot.origin, merged, bringup=robot)


def _unread_args(
    launched: _Launched, description: Description, parameter: str, given: Mapping[str, str] | None
) -> tuple[str, ...]:
    """Xacro args `parameter`'s file is passed with values only the run time gives: by the
    package's launch files, or by the bringup launch file the robot came from (less --xacro-arg)."""
    bringup = description.bringup.unread_args if description.bringup is not None else ()
    return tuple(sorted({*launched.unread_args(parameter), *(a for a in bringup if a not in (given or {}))}))


def _readable_description(files: PackageFiles, description: Description) -> Description:
    """`description`, or none under `--untrusted` when its file lies outside the package and the
    folders the user named (a `package.outside` warning: the robot rules are then skipped)."""
    if description.urdf is None or readable(description.urdf):
        return description
    msg = (
        f"the robot description {excerpt(str(description.urdf))} ({description.origin}) lies outside the "
        "package: not read (--untrusted reads nothing outside it)"
    )
    hint = "pass --urdf FILE (or --package-path DIR) to name it yourself"
    files.problems.append(
        warning("package.outside", description.origin.split(" ")[0], "robot description", msg, hint)
    )
    return Description(None, f"{description.origin}: outside the package, not read (--untrusted)", ())


def _missing_package(files: PackageFiles, exc: PackageNotFound) -> Description:
    """The package `.setup_assistant` (URDF.package) or marm_setup.yaml (robot.urdf's
    `package://`) names the description in, which no package path holds: the robot rules skip."""
    file = Path(exc.path or ".setup_assistant").name
    msg = (
        f"names the robot description in package '{exc.package}', which no package path holds: the "
        "rules needing the robot are skipped"
    )
    hint = f"pass --package-path DIR (the folder holding {exc.package}), or --urdf FILE"
    at = Location("package", exc.package)
    files.problems.append(warning("urdf.package-missing", file, exc.element or "", msg, hint, at=at))
    return Description(None, f"{file}, from package '{exc.package}' not found", (), unreadable=True)


def _launch_description(
    files: PackageFiles, load: DescriptionLoad, args: tuple[tuple[str, str], ...], paths: tuple[Path, ...]
) -> Description | None:
    """The robot description a ROS 1 launch file sets (what move_group reads), with its xacro
    args and --xacro-arg on top; None when it names no file validate can read statically (then
    the package's other sources are asked). A missing package or file is a finding, and the
    description is then unknown (None file), never another robot's."""
    origin = f"robot_description in {load.launch}"
    if load.missing_package is not None:
        files.problems.append(
            missing_package(str(load.missing_package), load.launch, "robot_description", _own_names(files))
        )
        return Description(
            None, f"{origin}, from package '{load.missing_package}' not found", (), unreadable=True
        )
    chosen = _launched_file(files, load, "robot_description", paths)
    if chosen is None:
        return (
            Description(None, f"{origin}: not found", (), unreadable=True) if load.file is not None else None
        )
    merged = tuple(sorted({**dict(load.xacro_args), **dict(args)}.items()))
    return Description((files.root / chosen[0]).resolve(), origin, merged)


def _external_builder_description(
    explicit: Chosen,
    mappings: tuple[tuple[str, str], ...] | None,
    args: tuple[tuple[str, str], ...],
    paths: tuple[Path, ...],
) -> Description | None:
    """The file a launch file's `MoveItConfigsBuilder.robot_description(file_path)` names in
    another package (`os.path.join(get_package_share_directory("pkg"), ...)`): the builder
    joins it to its package path, and an absolute path wins (moveit2 humble
    moveit_configs_utils/moveit_configs_builder.py robot_description l.213-227,
    `self._package_path / file_path`), so move_group gets that file, not the one `.setup_assistant` names. Taken only
    inside the packages the package paths hold, as a xacro command's file is; None otherwise."""
    from marm_setup.untrusted import inside

    file = Path(explicit.file)
    if not file.is_absolute() or not inside(file, paths) or not file.is_file():
        return None
    return Description(file, explicit.how, args or mappings or ())


def _command_description(
    command: XacroCommand | None, shown: str, args: tuple[tuple[str, str], ...], paths: tuple[Path, ...]
) -> Description | None:
    """The description a Python launch file builds itself with xacro: its file, its args with
    --xacro-arg on top. Its file is taken only inside the packages the package paths hold (where
    FindPackageShare looked), as `.setup_assistant`'s package is; one that does not exist there is
    bad input (InputError)."""
    from marm_setup.untrusted import inside

    if command is None or not command.file or not inside(Path(command.file), paths):
        return None
    if not Path(command.file).is_file():
        msg = f"the xacro command's file {command.file} does not exist"
        raise InputError(msg, path=str(Path(shown) / command.launch), element="robot_description")
    merged = tuple(sorted({**dict(command.args), **dict(args)}.items()))
    return Description(Path(command.file), f"xacro command in {command.launch}", merged)


def _kinds(
    files: PackageFiles,
    target: Target,
    launched: _Launched,
    problems: list[Finding],
    bringup: BringupRobot | None = None,
) -> Kinds:
    if target == Target.ROS1:
        return read_ros1_kinds(
            files, launched.loads, launched.move_groups, launched.managers, launched.taken_managers
        )
    assert launched.builder is not None
    named, by_hand = launched.named_yaml, None
    if bringup is not None and bringup.hand_loaded is not None and not launched.builder.calls:
        # the package's files as the bringup launch file that starts MoveIt loads them by hand
        by_hand = bringup.hand_loaded
        named += tuple((rel, str(bringup.launch_path)) for rel in by_hand)
    kinds = read_ros2_kinds(files, launched.loads, launched.builder, launched.control_files, named, by_hand)
    done = set()
    for load in sorted(launched.loads, key=lambda lo: lo.conditional):
        if load.file not in done and _holds_moveit_params(files, load.file):
            done.add(load.file)
            read_move_group_file(files, kinds, load.file, f"handed to {load.ns or 'a node'} by {load.launch}")
    if files.is_file(MARM_MOVEIT_YAML) and files.yaml(MARM_MOVEIT_YAML) is not None:
        raw = files.yaml(MARM_MOVEIT_YAML)
        problems.extend(ros2_parameter_file_problems(raw.data if raw else None, MARM_MOVEIT_YAML))
        kinds.values["move_group"] = read_move_group_file(
            files, kinds, MARM_MOVEIT_YAML, "move_group's parameter file"
        )
        kinds.values["layout"] = "marm_ros2"
    return kinds


MOVE_GROUP_KEYS = (
    "robot_description_kinematics",
    "robot_description_planning",
    "moveit_simple_controller_manager",
    "planning_pipelines",
)


def _holds_moveit_params(files: PackageFiles, rel: str) -> bool:
    doc = files.yaml(rel)
    params = unwrap_parameters(doc) if doc is not None else None
    return params is not None and params.is_mapping and any(k in params.data for k in MOVE_GROUP_KEYS)


def ros2_parameter_file_problems(raw: Any, file: str) -> list[Finding]:
    """A ROS 2 parameter file maps node names (or `/**`), optionally under a namespace, to
    `{ros__parameters: {...}}` (ros2/rcl rcl_yaml_param_parser/README.md); rcl rejects anything
    else and the node does not start."""
    if not isinstance(raw, dict) or not raw:
        return [error("yaml.ros2-params", file, "", "expected a mapping of node names to ros__parameters")]
    return [
        error("yaml.ros2-params", file, str(node), "expected {ros__parameters: {...}} under a node name")
        for node, value in raw.items()
        if not (
            _node_params(value)
            or (isinstance(value, dict) and value and all(map(_node_params, value.values())))
        )
    ]


def _node_params(value: Any) -> bool:
    return isinstance(value, dict) and isinstance(value.get("ros__parameters"), dict)


def _srdf(
    root: Path,
    rel: str | None,
    args: tuple[tuple[tuple[str, str], ...], tuple[str, ...]],
    user_args: Mapping[str, str] | None,
    paths: tuple[Path, ...],
    problems: list[Finding],
    built: tuple[tuple[str, str], ...] = (),
) -> SrdfFile | None:
    """The SRDF at `rel`, expanded with (the launch files' args, those whose value is unknown)
    and the user's --xacro-arg; `built` the build's REMAP args whose value only CMake knows."""
    if rel is None:
        return None
    known, unread = args
    merged = {**dict(known), **dict(user_args or {})}
    return read_srdf_file(root, rel, paths, problems, merged, unread, built)


def _built_srdf_args(
    files: PackageFiles,
    rel: str | None,
    args: tuple[tuple[str, str], ...],
    launched: _Launched,
) -> tuple[tuple[tuple[str, str], ...], tuple[tuple[str, str], ...]]:
    """(`args` with the literal REMAP args the package's CMakeLists.txt builds the `.srdf.xacro`
    `rel` with under them, the REMAP args whose value is a CMake variable) when no launch file
    names `rel` itself: the build expands it into the SRDF it installs (package.cmake_xacro), so
    that is what a launch loads. A launch file naming the xacro gives MoveIt what it passes."""
    from marm_setup.package.cmake_xacro import build_remaps

    if rel is None or not rel.endswith(".xacro") or (launched.semantic and launched.semantic.file == rel):
        return args, ()
    remaps = build_remaps(files, rel)
    literal = {k: v for k, v in remaps.items() if "${" not in v}
    built = tuple(sorted((k, v) for k, v in remaps.items() if "${" in v and k not in dict(args)))
    return tuple(sorted({**literal, **dict(args)}.items())), built


def _srdf_source(
    srdf: SrdfFile | None, launched: _Launched, guessed: bool, bringup: BringupRobot | None = None
) -> tuple[Source, ...]:
    if srdf is None:
        return ()
    how = (
        f"set as the semantic description by {bringup.launch}, beside the robot"
        if bringup is not None
        else f"set as the semantic description by {launched.semantic.launch}"
        if launched.semantic and launched.semantic.file == srdf.path
        else SRDF_GUESSED
        if guessed
        else "chosen by its name"
    )
    return (Source("srdf", srdf.path, how),)


def _ros2_control_files(files: PackageFiles) -> tuple[Ros2ControlFile, ...]:
    out = []
    for rel in files.glob("config/*.ros2_control.xacro"):
        try:
            out.append(read_ros2_control(rel, files.text(rel, XML_BYTES) or ""))
        except FileProblem:
            continue
    return tuple(out)
