"""The `init` pipeline: infer -> import SRDF -> overlay SPEC -> check -> collision matrix ->
render -> write. Pure apart from reading SPEC/SRDF and the final atomic write."""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.findings import Finding, Location
from marm_setup.robot.load import parse_xacro_args
from marm_setup.robot.model import RobotModel
from marm_setup.ros import ROS_DISTROS, TARGETS, Distro, Target
from marm_setup.setup.model import CollisionSettings, RobotSource, SetupModel

if TYPE_CHECKING:
    from marm_setup.collision.matrix import Progress
    from marm_setup.collision.pairs import DisabledPair
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.package.model import MoveItPackage
    from marm_setup.port.importer import Ported
    from marm_setup.port.report import PortItem
    from marm_setup.render.writer import FileChange
    from marm_setup.templating import RenderedFile
    from marm_setup.validate.runner import Validation


@dataclass(frozen=True)
class InitRequest:
    urdf: Path
    out: Path
    name: str | None = None
    target: str | None = None
    ros_distro: str | None = None  # None: the SPEC's, else env_distro if it fits the target, else the default
    env_distro: str | None = None  # $ROS_DISTRO of the caller
    spec: Path | None = None
    from_srdf: Path | None = None
    trials: int | None = None  # None: the SPEC's collision.trials, else 10000
    seed: int | None = None  # None: the SPEC's collision.seed, else 0
    jobs: int = 1  # worker processes of the collision matrix (the result does not depend on it)
    force: bool = False
    keep_matrix: bool = False  # take a SPEC's collision.disabled as it is (else recompute, User pairs kept)
    xacro_args: tuple[str, ...] = ()
    package_paths: tuple[Path, ...] = ()


@dataclass(frozen=True)
class InitResult:
    model: SetupModel
    inferred: tuple[str, ...]  # what the setup holds, one line each
    status_lines: tuple[str, ...]  # one line per written file
    notes: tuple[str, ...] = ()  # what inference guessed, one line each


@dataclass(frozen=True)
class _Built:
    model: SetupModel
    notes: tuple[str, ...]
    poses_given: bool  # the SPEC or SRDF gives named poses: none are inferred


def run_init(request: InitRequest, robot: RobotModel, progress: Progress | None = None) -> InitResult:
    """`progress(done, total)` is called while the matrix samples (see compute_collision_matrix)."""
    from marm_setup.collision.scene import CollisionScene

    built = _build(request, robot)
    model, user = _matrix_to_compute(built.model, request)
    given = bool(model.collision.disabled)
    trials = model.collision.trials if request.trials is None else request.trials
    seed = model.collision.seed if request.seed is None else request.seed
    scene = CollisionScene(robot)
    model = with_collision_matrix(
        model, robot, trials=trials, seed=seed, jobs=request.jobs, progress=progress, scene=scene
    )
    model = _with_user_pairs(model, user)
    notes = built.notes
    if not built.poses_given:
        model, pose_notes = _with_poses(model, robot, scene, seed, request)
        notes += pose_notes
    model, start_notes = _with_start_poses(model, robot, scene)
    notes += start_notes
    lines = describe(model, matrix_given=given) + reused_ros2_control(model, robot)
    changes = write_package(model, robot, request.out, force=request.force)
    from marm_setup.render.writer import format_change

    return InitResult(
        model, tuple(lines), tuple(format_change(c, forced=request.force) for c in changes), notes
    )


def _with_poses(
    model: SetupModel, robot: RobotModel, scene: CollisionScene, seed: int, request: InitRequest
) -> tuple[SetupModel, tuple[str, ...]]:
    """The setup with inferred collision-free poses (home, ready), and notes on what was guessed."""
    from marm_setup.setup.checks import check_setup
    from marm_setup.setup.poses import infer_poses

    poses = infer_poses(model, robot, scene, seed=seed)
    model = dataclasses.replace(model, group_states=poses.states)
    check_setup(model, robot, str(request.spec or request.from_srdf or request.urdf))
    return model, poses.notes


def _with_start_poses(
    model: SetupModel, robot: RobotModel, scene: CollisionScene
) -> tuple[SetupModel, tuple[str, ...]]:
    """The setup with start poses the demo can start at out of collision (setup/poses.py)."""
    from marm_setup.setup.poses import choose_start_poses

    starts, notes = choose_start_poses(model, robot, scene)
    return dataclasses.replace(model, start_poses=starts), notes


@dataclass(frozen=True)
class PortInitRequest:
    """`init --from-package PKG --out DIR`: port PKG into a new package for `target`."""

    package: Path
    out: Path
    name: str | None = None
    target: str | None = None  # None: ros2
    ros_distro: str | None = None  # None: env_distro if it fits the target, else the default
    env_distro: str | None = None
    force: bool = False
    package_paths: tuple[Path, ...] = ()
    urdf: Path | None = None  # the robot description, instead of the one the package names
    xacro_args: tuple[str, ...] = ()  # NAME:=VALUE, instead of the ones the package passes
    plan: bool = True  # validate's runtime checks on the new package
    jobs: int = 1


@dataclass(frozen=True)
class PortResult:
    ported: Ported  # its model is the one before the collision matrix
    model: SetupModel
    status_lines: tuple[str, ...]
    validation: Validation  # of the new package


def run_port(request: PortInitRequest, progress: Progress | None = None) -> PortResult:
    """Read the package, port it, check the setup, render and write it, then validate the result."""
    from marm_setup.port.importer import PortRequest, port_package
    from marm_setup.render.writer import check_output_dir, format_change
    from marm_setup.setup.checks import check_setup
    from marm_setup.validate.runner import validate

    check_output_dir(request.out, force=request.force, shown=str(request.out))
    pkg, notes = _discover_for_port(request)
    robot = _package_robot(pkg, request.xacro_args)
    target = target_of(request.target, None, "--target")
    distro = _distro(
        InitRequest(Path(), request.out, ros_distro=request.ros_distro, env_distro=request.env_distro),
        {},
        target,
    )
    ported = port_package(
        pkg,
        robot,
        PortRequest(request.out, target, distro, request.name, tuple(request.package_paths), notes),
    )
    check_setup(ported.model, robot, pkg.user_path(pkg.srdf_path))
    model = with_collision_matrix(
        ported.model,
        robot,
        trials=ported.model.collision.trials,
        seed=ported.model.collision.seed,
        jobs=request.jobs,
        progress=progress,
    )
    changes = write_package(model, robot, request.out, force=request.force)
    validation = validate(request.out, plan=request.plan)
    ported = _with_validation_notes(ported, pkg, validation)
    return PortResult(
        ported, model, tuple(format_change(c, forced=request.force) for c in changes), validation
    )


def _with_validation_notes(ported: Ported, pkg: MoveItPackage, validation: Validation) -> Ported:
    """One report line per validation error of the new package, saying whether the source
    package has the same error (the port carried it as it was) or the port made it."""
    from marm_setup.port.report import PortItem
    from marm_setup.validate.runner import validate_read

    errors = [f for f in validation.findings if f.is_error]
    if not errors:
        return ported
    source = validate_read(pkg, plan=False).validation  # the package model the port read
    before = {_identity(f) for f in source.findings if f.is_error}
    items = []
    for f in errors:
        why = (
            "the source package has the same error: the port carried the setting as it was; fix it in marm_setup.yaml"
            if _identity(f) in before
            else "new in the port: please report it"
        )
        items.append(PortItem("todo", f"validate {f.rule}", f"{f.file}: {f.element}", f"{f.message}; {why}"))
    return dataclasses.replace(ported, items=(*ported.items, *items))


def _identity(finding: Finding) -> tuple:
    """What makes a finding the same in two packages of different layouts (their files and
    elements differ): its rule and structured location, else its rule and message."""
    if finding.location != Location():
        return finding.rule, finding.location
    return finding.rule, finding.message


def _discover_for_port(request: PortInitRequest) -> tuple[MoveItPackage, tuple[PortItem, ...]]:
    """The package as validate reads it; a MoveIt 2 `config/<robot>.urdf.xacro` wrapper (the
    new package writes its own) gives way to the description `.setup_assistant` names."""
    from marm_setup.package.description import setup_assistant_description
    from marm_setup.package.read import read_package
    from marm_setup.port.report import PortItem

    args = parse_xacro_args(list(request.xacro_args)) or None
    pkg = read_package(
        request.package, urdf=request.urdf, package_paths=request.package_paths, xacro_args=args
    )
    if pkg.urdf_origin != "config/<robot>.urdf.xacro":
        return pkg, ()
    sa = pkg.setup_assistant
    found = (
        setup_assistant_description(sa, pkg.package_paths, pkg.shown, ())
        if sa is not None and sa.urdf_package and sa.urdf_path
        else None
    )
    if found is None:
        raise InputError(
            f"the robot description is the package's own wrapper {pkg.urdf.name} (the new package writes its "
            "own) and .setup_assistant names no other: give the robot's URDF (init URDF --from-package PKG)",
            path=pkg.user_path(pkg.urdf.relative_to(pkg.root).as_posix()),
        )
    path, sa_args = found.urdf, sa.urdf_xacro_args if sa is not None else ()
    wrapper = pkg.urdf.relative_to(pkg.root).as_posix()
    pkg = read_package(
        request.package, urdf=path, package_paths=request.package_paths, xacro_args=args or dict(sa_args)
    )
    note = PortItem(
        "changed",
        "robot.urdf",
        f"{wrapper}, .setup_assistant",
        f"{wrapper} wraps the description for the source's own launch files (the new package writes its "
        f"own wrapper): the description .setup_assistant names is used, {path}",
    )
    return pkg, (note,)


def _package_robot(pkg: MoveItPackage, xacro_args: tuple[str, ...] = ()) -> RobotModel:
    """The package's robot; its load failure is the one error line, and so is a `--xacro-arg`
    (`xacro_args`) that neither its description nor its SRDF xacro takes."""
    from marm_setup.validate.runner import check_given_xacro_args, load_package_robot

    robot, problems = load_package_robot(pkg)
    if robot is None:
        from marm_setup.setup.checks import as_input_error

        found = problems[0]
        if found.rule == "urdf.missing":  # its hint is validate's --urdf: init says how it takes one
            raise InputError(found.message, path=found.file, element=found.element or None, needs="--urdf")
        raise as_input_error(found)
    if xacro_args:
        check_given_xacro_args(pkg, robot, parse_xacro_args(list(xacro_args)))
    return robot


def build_setup(request: InitRequest, robot: RobotModel) -> SetupModel:
    """Inference, then the SRDF import, then the SPEC; checked against the robot."""
    return _build(request, robot).model


def _build(request: InitRequest, robot: RobotModel) -> _Built:
    from marm_setup.names import ros_package_name
    from marm_setup.setup.checks import check_setup, package_name_problem, setup_warnings
    from marm_setup.setup.infer import REFERENCE, infer

    if request.name and (problem := package_name_problem(request.name)):
        raise InputError(problem, element="--name")
    spec = _read_spec(request.spec)
    target = _target(request, spec)
    name = request.name or spec.get("package_name") or ros_package_name(f"{robot.name}_moveit_config")
    given = bool(spec) or request.from_srdf is not None  # may give the groups inference cannot find
    driver = spec.get("driver") if isinstance(spec.get("driver"), str) else None
    inference = infer(
        robot,
        package_name=str(name),
        source=_source(request),
        target=target,
        arm_required=not given,
        driver=driver,
    )
    model, notes = inference.model, inference.notes
    inferred_groups = bool(model.groups)
    srdf_args: frozenset[str] | None = None
    if request.from_srdf is not None:
        model, notes, srdf_args = _import_srdf(request, model, notes, robot)
    _check_xacro_args(request, robot, srdf_args)
    if spec:
        model = _with_spec(model, spec, request, robot, inferred_groups)
    model = dataclasses.replace(model, ros_distro=_distro(request, spec, model.target))
    if not model.groups:
        raise InputError(
            f"no planning groups: no limb to infer, and the SPEC / SRDF gives none (see {REFERENCE})",
            path=str(request.spec or request.from_srdf),
            element="groups",
        )
    check_setup(model, robot, str(request.spec or request.from_srdf or request.urdf))
    poses_given = "group_states" in spec or (request.from_srdf is not None and bool(model.group_states))
    if not (request.name or spec.get("package_name")):
        notes = (*notes, *_taken_name_warnings(str(name), request))
    return _Built(model, (*notes, *_empty_group_warnings(model), *setup_warnings(model)), poses_given)


def _with_spec(
    model: SetupModel, spec: dict, request: InitRequest, robot: RobotModel, inferred_groups: bool
) -> SetupModel:
    """`model` with the SPEC's sections in place of its own, fitted to the robot; group settings
    filled when the groups are all the SPEC's, home poses when neither SPEC nor SRDF gives poses."""
    from marm_setup.setup.infer import fill_group_settings, fit_to_spec, home_poses
    from marm_setup.setup.spec_overlay import spec_items, without_replaced

    model = _make_room_for_spec(model, spec)
    merged = without_replaced(model, _apply_spec(model, spec, request), robot, spec_items(spec))
    model = fit_to_spec(merged, robot, spec)
    if not inferred_groups:
        model = fill_group_settings(model, robot)
    if "group_states" not in spec and request.from_srdf is None:
        model = dataclasses.replace(model, group_states=home_poses(model, robot))
    return model


def _import_srdf(
    request: InitRequest, model: SetupModel, notes: tuple[str, ...], robot: RobotModel
) -> tuple[SetupModel, tuple[str, ...], frozenset[str] | None]:
    """`model` with the SRDF's elements, as srdfdom and MoveIt load them: what they skip is
    dropped with a warning line each (setup/srdf_load.py); the rest must pass the rules. A
    `.srdf.xacro` is expanded first with the `--xacro-arg`s (also returned: the arguments it
    takes). An SRDF without groups keeps the inferred ones (and their notes); one whose groups
    all fail to load is refused: MoveIt would have nothing to plan for."""
    from marm_setup.setup.checks import check_setup
    from marm_setup.setup.infer import derive_group_settings
    from marm_setup.setup.rules import srdf_element
    from marm_setup.setup.srdf import load_srdf, srdf_to_setup
    from marm_setup.setup.srdf_load import as_moveit_loads

    path = request.from_srdf
    assert path is not None
    skipped: list[InputError] = []
    args = parse_xacro_args(list(request.xacro_args))
    raw, declared = load_srdf(path, skipped, xacro_args=args, package_paths=request.package_paths)
    srdf, dropped = as_moveit_loads(raw, robot)
    lines = [f"{e.element}: {e.message}" if e.element else e.message for e in skipped] + list(dropped)
    named = len(raw.groups) + sum(1 for e in skipped if (e.element or "").startswith("group["))
    if named and not any(g.chain or g.joints or g.links for g in srdf.groups):  # subgroups hold nothing else
        why = f" (first: {lines[0]})" if lines else ""
        raise InputError(
            f"none of its {named} groups holds a joint or link of robot '{robot.name}' as MoveIt loads it{why}",
            path=str(path),
            element="groups",
        )
    warnings = tuple(f"warning: {path}: {line} (as MoveIt loads it: left out or changed)" for line in lines)
    if srdf.groups:
        model, notes = derive_group_settings(srdf_to_setup(srdf, model), robot), ()
    else:
        model = srdf_to_setup(srdf, model)
        notes = (*notes, f"{path} defines no groups: the inferred ones are kept, with its collision pairs")
    check_setup(model, robot, str(path), srdf_element)
    return model, (*notes, *warnings), declared


def _check_xacro_args(request: InitRequest, robot: RobotModel, srdf_args: frozenset[str] | None) -> None:
    """Every `--xacro-arg` must be an argument of the robot's xacro or of the SRDF xacro."""
    from marm_setup.robot.xacro_expand import check_xacro_args

    given = parse_xacro_args(list(request.xacro_args))
    if srdf_args is None:
        check_xacro_args(given, robot.xacro_args, path=str(request.urdf))
        return
    declared = {*(robot.xacro_args or ()), *srdf_args}
    check_xacro_args(given, declared, path=str(request.urdf), others=(str(request.from_srdf),))


# Config packages people have installed or cloned under their default name (<robot>_moveit_config)
WELL_KNOWN_PACKAGES = {
    "panda_moveit_config": "MoveIt's own panda_moveit_config",  # the moveit/panda_moveit_config repository
}


def _taken_name_warnings(name: str, request: InitRequest) -> tuple[str, ...]:
    """A warning when the default package name is another package's: one whose package.xml the
    package paths (and the environment, the folders around the URDF) hold, or a well-known one."""
    from marm_setup.robot.ros_packages import find_packages

    found = find_packages(request.package_paths, near=Path(request.urdf)).manifests.get(name)
    if found is not None and found.resolve() != request.out.resolve():
        other = f"is also the package at {found}: two packages of one name break a workspace"
    elif name in WELL_KNOWN_PACKAGES:
        other = f"is the name of {WELL_KNOWN_PACKAGES[name]}"
    else:
        return ()
    return (f"warning: package name '{name}' (the default) {other}; pass --name",)


def _empty_group_warnings(model: SetupModel) -> tuple[str, ...]:
    """srdfdom keeps a group that names nothing and MoveIt warns about it: so do we."""
    return tuple(
        f"warning: group '{g.name}' holds no chain, joints, links or subgroups (kept; MoveIt warns about it)"
        for g in model.groups
        if g.chain is None and not (g.joints or g.links or g.subgroups)
    )


def _make_room_for_spec(model: SetupModel, spec: dict) -> SetupModel:
    """Drop what the SPEC gives in its own way: its poses replace the inferred ones (pose names
    repeat across groups), and its end effectors those on the same groups."""
    if "group_states" in spec:
        model = dataclasses.replace(model, group_states=())
    items = spec.get("end_effectors")
    if isinstance(items, list):
        taken = {e.get("group") for e in items if isinstance(e, dict)}
        kept = tuple(e for e in model.end_effectors if e.group not in taken)
        model = dataclasses.replace(model, end_effectors=kept)
    return model


def _read_spec(path: Path | None) -> dict:
    if path is None:
        return {}
    from marm_setup.setup.yaml_io import read_yaml_mapping

    return read_yaml_mapping(path)


def _target(request: InitRequest, spec: dict) -> Target:
    return target_of(request.target or spec.get("target"), str(request.spec), "target")


def target_of(given: object, path: str | None, element: str) -> Target:
    """`given` as a Target (None: ros2, the default); InputError naming the valid ones."""
    if given is None:
        return Target.ROS2
    if given not in TARGETS:
        raise InputError(f"'{given}' is not one of: {', '.join(TARGETS)}", path=path, element=element)
    return Target(given)


def _distro(request: InitRequest, spec: dict, target: Target) -> Distro:
    """--ros-distro, else the SPEC's ros_distro, else $ROS_DISTRO when it is one of the target's,
    else the target's default (noetic for ros1, humble for ros2)."""
    from marm_setup.setup.checks import distro_problem

    distros = ROS_DISTROS[target]
    for given, where in ((request.ros_distro, "--ros-distro"), (spec.get("ros_distro"), "ros_distro")):
        if given is None:
            continue
        problem = distro_problem(target, given)
        if problem:
            raise InputError(
                problem, path=None if where == "--ros-distro" else str(request.spec), element=where
            )
        return Distro(given)
    return Distro(request.env_distro) if request.env_distro in distros else distros[0]


def _apply_spec(model: SetupModel, spec: dict, request: InitRequest) -> SetupModel:
    from marm_setup.setup.infer import merge_spec
    from marm_setup.setup.yaml_io import setup_from_dict, setup_to_dict

    merged = merge_spec(setup_to_dict(model), spec)
    if request.name:
        merged["package_name"] = request.name
    if request.target:
        merged["target"] = request.target
    merged["robot"] = setup_to_dict(model)["robot"]  # where the robot is comes from the command line
    return setup_from_dict(merged, str(request.spec))


def _source(request: InitRequest) -> RobotSource:
    """Where the robot is, so the package can move (see `render.package.robot_reference`)."""
    from marm_setup.render.package import robot_reference

    out = request.out.resolve()
    paths = [_relative(p, out) for p in request.package_paths]
    urdf, paths = robot_reference(Path(request.urdf), out, paths)
    return RobotSource(
        urdf=urdf,
        xacro_args=tuple(sorted(parse_xacro_args(list(request.xacro_args)).items())),
        package_paths=tuple(paths),
    )


def _relative(path: Path, base: Path) -> str:
    return Path(os.path.relpath(Path(path).resolve(), base)).as_posix()


def _matrix_to_compute(
    model: SetupModel, request: InitRequest
) -> tuple[SetupModel, tuple[DisabledPair, ...]]:
    """A SPEC's matrix (an old marm_setup.yaml's, maybe stale) is computed again unless
    `keep_matrix`, its User pairs kept; an imported SRDF's matrix is the import: kept."""
    from marm_setup.collision.pairs import DisabledReason

    if request.from_srdf is not None or request.keep_matrix or not model.collision.disabled:
        return model, ()
    user = tuple(p for p in model.collision.disabled if p.reason is DisabledReason.USER)
    return dataclasses.replace(model, collision=dataclasses.replace(model.collision, disabled=())), user


def _with_user_pairs(model: SetupModel, user: tuple[DisabledPair, ...]) -> SetupModel:
    """The computed matrix with the given User pairs (they stay User: never recomputed)."""
    if not user:
        return model
    mine = {p.pair for p in user}
    disabled = tuple(sorted((*(p for p in model.collision.disabled if p.pair not in mine), *user)))
    return dataclasses.replace(model, collision=dataclasses.replace(model.collision, disabled=disabled))


def with_collision_matrix(
    model: SetupModel,
    robot: RobotModel,
    *,
    trials: int,
    seed: int,
    jobs: int = 1,
    progress: Progress | None = None,
    scene: CollisionScene | None = None,
) -> SetupModel:
    """Compute the matrix unless the setup already has pairs (from an SRDF or the SPEC)."""
    if model.collision.disabled:
        return model
    fraction = model.collision.min_collision_fraction
    disabled = _disabled_pairs(
        robot, trials=trials, seed=seed, fraction=fraction, jobs=jobs, progress=progress, scene=scene
    )
    settings = CollisionSettings(seed=seed, trials=trials, min_collision_fraction=fraction, disabled=disabled)
    return dataclasses.replace(model, collision=settings)


def _disabled_pairs(
    robot: RobotModel,
    *,
    trials: int,
    seed: int,
    fraction: float,
    jobs: int,
    progress: Progress | None,
    scene: CollisionScene | None = None,
) -> tuple[DisabledPair, ...]:
    from marm_setup.collision.matrix import compute_collision_matrix

    matrix = compute_collision_matrix(
        robot,
        scene,
        trials=trials,
        seed=seed,
        min_collision_fraction=fraction,
        jobs=jobs,
        progress=progress,
        distances=False,  # a setup keeps the pairs only
    )
    return matrix.disabled


def describe(model: SetupModel, *, matrix_given: bool) -> list[str]:
    """What the setup holds; the matrix line says whether it was computed or taken as given."""
    from marm_setup.collision.pairs import DisabledReason
    from marm_setup.setup.infer import describe_setup

    counts = {r: sum(1 for d in model.collision.disabled if d.reason is r) for r in DisabledReason}
    summary = ", ".join(f"{n} {r.value}" for r, n in counts.items() if n)
    source = (
        "as given (SRDF / SPEC), not recomputed"
        if matrix_given
        else f"{model.collision.trials} trials, seed {model.collision.seed}"
    )
    lines = describe_setup(model)
    lines.append(
        f"collision matrix: {len(model.collision.disabled)} disabled pairs ({summary or 'none'}); {source}"
    )
    return lines


def reused_ros2_control(model: SetupModel, robot: RobotModel) -> list[str]:
    """What the package's ros2_control systems are and what use_mock_hardware does to each
    (ros2): the generated system, each `<ros2_control>` system the description already has
    (reused), and how the demo puts those on mock hardware (render/hardware.py)."""
    if model.target != Target.ROS2:
        return []
    from marm_setup.render.context import ros2_control_joints
    from marm_setup.render.hardware import description_hardware, hardware_lines
    from marm_setup.setup.model import Ros2ControlHardware

    own = model.ros2_control or Ros2ControlHardware()
    joints = len(ros2_control_joints(model, robot))
    return hardware_lines(description_hardware(robot, model.distro), own, joints)


def write_package(model: SetupModel, robot: RobotModel, out: Path, *, force: bool) -> list[FileChange]:
    """Render every file and write them atomically; returns the file changes."""
    from marm_setup.render.writer import apply_writes, check_output_dir, plan_writes

    check_output_dir(out, force=force)
    rendered = _render(model, robot)
    changes = plan_writes(rendered, out)
    apply_writes(changes, out, force=force, require_fresh=not force)
    return changes


def _render(model: SetupModel, robot: RobotModel) -> list[RenderedFile]:
    from marm_setup.render.package import render_package

    return render_package(model, robot)
