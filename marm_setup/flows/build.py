"""init's setup: inference, then an imported SRDF, then the SPEC laid over it as a typed patch
(inference.assemble), the distro chosen; checked once against the robot. Reads only the SPEC and the
SRDF."""

from __future__ import annotations

import dataclasses
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.flows.settings import MatrixSettings, RobotInput
from marm_setup.robot import RobotModel
from marm_setup.ros import TARGETS, Distro, Target, default_distro, distros_of
from marm_setup.setup import RobotSource, SetupModel

if TYPE_CHECKING:
    from marm_setup.setup import Partial


@dataclass(frozen=True)
class InitRequest:
    robot: RobotInput  # its urdf: the description to load
    out: Path
    name: str | None = None
    target: str | None = None
    ros_distro: str | None = None  # None: the SPEC's, else env_distro if it fits the target, else the default
    env_distro: str | None = None  # $ROS_DISTRO of the caller
    spec: Path | None = None
    from_srdf: Path | None = None
    matrix: MatrixSettings = MatrixSettings()  # trials, seed, prove not given: the SPEC's
    force: bool = False

    @property
    def urdf(self) -> Path:
        assert self.robot.urdf is not None  # init loads the URDF argument
        return self.robot.urdf

    @property
    def package_paths(self) -> tuple[Path, ...]:
        return self.robot.package_paths


@dataclass(frozen=True)
class Built:
    model: SetupModel
    notes: tuple[str, ...]
    poses_given: bool  # the SPEC or SRDF gives named poses: none are inferred


def build_setup(request: InitRequest, robot: RobotModel) -> SetupModel:
    """Inference, then the SRDF import, then the SPEC; checked against the robot."""
    return build(request, robot).model


def build(request: InitRequest, robot: RobotModel) -> Built:
    """The setup init writes: inferred, the SRDF imported, the SPEC laid over it as a typed
    patch, the distro chosen, then checked once against the robot."""
    from marm_setup.inference import REFERENCE, infer_setup
    from marm_setup.names import ros_package_name
    from marm_setup.setup import package_name_problem, setup_warnings

    if request.name and (problem := package_name_problem(request.name)):
        raise InputError(problem, element="--name")
    spec = _read_spec(request.spec)
    target = target_of(request.target, None, "--target") if request.target else spec_target(spec)
    given_name = request.name or spec.get("package_name")
    name = str(given_name or ros_package_name(f"{robot.name}_moveit_config"))
    driver = spec.get("driver")
    inference = infer_setup(
        robot,
        package_name=name,
        source=_source(request),
        target=target,
        arm_required=not (spec.keys or request.from_srdf is not None),  # they may give the groups
        driver=driver if isinstance(driver, str) else None,
    )
    model, notes = inference.model, inference.notes
    inferred_groups = bool(model.groups)
    srdf_args: frozenset[str] | None = None
    if request.from_srdf is not None:
        model, notes, srdf_args = _import_srdf(request, model, notes, robot)
    _check_xacro_args(request, robot, srdf_args)
    model = _with_spec(model, spec, request, robot, inferred_groups)
    distro = choose_distro(model.target, request.ros_distro, request.env_distro, spec, request.spec)
    model = dataclasses.replace(model, ros_distro=distro)
    if not model.groups:
        raise InputError(
            f"no planning groups: no limb to infer, and the SPEC / SRDF gives none (see {REFERENCE})",
            path=str(request.spec or request.from_srdf),
            element="groups",
        )
    model = _checked(model, robot, request, spec)
    poses_given = "group_states" in spec.keys or (request.from_srdf is not None and bool(model.group_states))
    if not given_name:
        notes = (*notes, *_taken_name_warnings(name, request))
    return Built(model, (*notes, *_empty_group_warnings(model), *setup_warnings(model)), poses_given)


def _with_spec(
    model: SetupModel, spec: Partial, request: InitRequest, robot: RobotModel, inferred_groups: bool
) -> SetupModel:
    """`model` with the SPEC laid over it (inference.assemble), the command line's name and target
    in place of the SPEC's."""
    from marm_setup.inference import with_spec
    from marm_setup.setup import Partial

    if not spec.keys:
        return model
    given = {"package_name": request.name, "target": Target(request.target) if request.target else None}
    overrides = tuple((k, v) for k, v in given.items() if v is not None)
    patch = Partial(spec.cls, (*(kv for kv in spec.values if kv[0] not in dict(overrides)), *overrides))
    from_srdf = request.from_srdf is not None
    return with_spec(model, patch, robot, inferred_groups=inferred_groups, poses_from_srdf=from_srdf)


def _checked(model: SetupModel, robot: RobotModel, request: InitRequest, spec: Partial) -> SetupModel:
    """The one check of the assembled setup, its errors naming the input they come from: the
    SPEC's keys, else the SRDF's elements, else the setup's keys for the URDF."""
    from marm_setup.inference import checked
    from marm_setup.setup import setup_element, srdf_element

    if request.from_srdf is not None and not spec.keys:
        return checked(model, robot, str(request.from_srdf), srdf_element)
    return checked(model, robot, str(request.spec or request.from_srdf or request.urdf), setup_element)


def _import_srdf(
    request: InitRequest, model: SetupModel, notes: tuple[str, ...], robot: RobotModel
) -> tuple[SetupModel, tuple[str, ...], frozenset[str] | None]:
    """`model` with the SRDF's elements, as srdfdom and MoveIt load them: what they skip is
    dropped with a warning line each (setup/srdf_load.py); the rest must pass the rules. A
    `.srdf.xacro` is expanded first with the `--xacro-arg`s (also returned: the arguments it
    takes). An SRDF without groups keeps the inferred ones (and their notes); one whose groups
    all fail to load is refused: MoveIt would have nothing to plan for."""
    from marm_setup.inference import derive_group_settings
    from marm_setup.setup import as_moveit_loads, load_srdf, srdf_to_setup

    path = request.from_srdf
    assert path is not None
    skipped: list[InputError] = []
    args = request.robot.xacro_mapping
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
    return model, (*notes, *warnings), declared


def _check_xacro_args(request: InitRequest, robot: RobotModel, srdf_args: frozenset[str] | None) -> None:
    """Every `--xacro-arg` must be an argument of the robot's xacro or of the SRDF xacro."""
    from marm_setup.robot import check_xacro_args

    given = request.robot.xacro_mapping
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
    from marm_setup.robot import find_packages

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


def _read_spec(path: Path | None) -> Partial:
    """The SPEC as a typed patch (none given: an empty one); its robot is the command line's."""
    from marm_setup.inference import COMMAND_LINE_KEYS
    from marm_setup.setup import Partial, patch_from_dict, read_yaml_mapping

    if path is None:
        return Partial(SetupModel, ())
    return patch_from_dict(read_yaml_mapping(path), str(path), ignore=COMMAND_LINE_KEYS)


def spec_target(spec: Partial) -> Target:
    given = spec.get("target")
    return given if isinstance(given, Target) else Target.ROS2


def target_of(given: object, path: str | None, element: str) -> Target:
    """`given` as a Target (None: ros2, the default); InputError naming the valid ones."""
    if given is None:
        return Target.ROS2
    if given not in TARGETS:
        raise InputError(f"'{given}' is not one of: {', '.join(TARGETS)}", path=path, element=element)
    return Target(given)


def choose_distro(
    target: Target,
    ros_distro: str | None,
    env_distro: str | None,
    spec: Partial | None = None,
    spec_path: Path | None = None,
) -> Distro:
    """--ros-distro, else the SPEC's ros_distro, else $ROS_DISTRO when it is one of the target's,
    else the target's default (noetic for ros1, humble for ros2)."""
    from marm_setup.setup import distro_problem

    distros = distros_of(target)
    from_spec = spec.get("ros_distro") if spec is not None else None
    for given, where in (
        (ros_distro, "--ros-distro"),
        (str(from_spec) if from_spec else None, "ros_distro"),
    ):
        if given is None:
            continue
        problem = distro_problem(target, given)
        if problem:
            raise InputError(problem, path=None if where == "--ros-distro" else str(spec_path), element=where)
        return given
    return env_distro if env_distro in distros else default_distro(target)


def _source(request: InitRequest) -> RobotSource:
    """Where the robot is, so the package can move (see `render.package.robot_reference`)."""
    from marm_setup.render import robot_reference

    out = request.out.resolve()
    paths = [_relative(p, out) for p in request.package_paths]
    urdf, paths = robot_reference(Path(request.urdf), out, paths)
    return RobotSource(
        urdf=urdf,
        xacro_args=tuple(sorted(request.robot.xacro_args)),
        package_paths=tuple(paths),
    )


def _relative(path: Path, base: Path) -> str:
    return Path(os.path.relpath(Path(path).resolve(), base)).as_posix()
