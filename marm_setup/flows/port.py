"""`init --from-package`: read the package (its package model), port it, check the setup, render
and write it, then validate the new package and say which of its errors the source has too."""

from __future__ import annotations

import dataclasses
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError
from marm_setup.findings import Finding, Location
from marm_setup.flows.build import choose_distro, target_of
from marm_setup.flows.settings import RobotInput
from marm_setup.flows.write import with_collision_matrix, write_package
from marm_setup.robot import RobotModel
from marm_setup.setup import SetupModel
from marm_setup.untrusted import no_package_code

if TYPE_CHECKING:
    from marm_setup.collision import Progress
    from marm_setup.package import MoveItPackage
    from marm_setup.port import Ported, PortItem
    from marm_setup.validate import Validation


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
    robot: RobotInput = RobotInput()  # --urdf, --xacro-arg over the package's; --untrusted
    plan: bool = True  # validate's runtime checks on the new package
    jobs: int = 1


@dataclass(frozen=True)
class PortResult:
    ported: Ported  # its model is the one before the collision matrix
    model: SetupModel
    status_lines: tuple[str, ...]
    validation: Validation  # of the new package


def run_port(request: PortInitRequest, progress: Progress | None = None) -> PortResult:
    """Read the package, port it, check the setup, render and write it, then validate the result;
    with `untrusted`, none of the package's code runs (a xacro description is then an InputError
    saying so)."""
    with no_package_code() if request.robot.untrusted else nullcontext():
        return _run_port(request, progress)


def _run_port(request: PortInitRequest, progress: Progress | None) -> PortResult:
    from marm_setup.port import PortRequest, blamed_on_source, port_package
    from marm_setup.render import check_output_dir, format_change
    from marm_setup.setup import check_setup
    from marm_setup.validate import validate

    check_output_dir(request.out, force=request.force, shown=str(request.out))
    pkg, notes = _discover_for_port(request)
    robot = _package_robot(pkg, request.robot.xacro_mapping)
    target = target_of(request.target, None, "--target")
    distro = choose_distro(target, request.ros_distro, request.env_distro)
    ported = port_package(
        pkg,
        robot,
        PortRequest(request.out, target, distro, request.name, request.robot.package_paths, notes),
    )
    try:
        check_setup(ported.model, robot, pkg.user_path(pkg.srdf_path))
    except InputError as exc:  # named where the source package says the value
        raise blamed_on_source(exc, ported.items, pkg.user_path) from None
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
    from marm_setup.port import PortItem
    from marm_setup.validate import validate_read

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
    from marm_setup.package import read_package, setup_assistant_description
    from marm_setup.port import PortItem

    args = request.robot.xacro_mapping or None
    paths = request.robot.package_paths
    pkg = read_package(request.package, urdf=request.robot.urdf, package_paths=paths, xacro_args=args)
    urdf = pkg.description_file
    sa = pkg.setup_assistant
    convention = pkg.urdf_origin == "config/<robot>.urdf.xacro"
    named = sa is not None and bool(sa.urdf_package and sa.urdf_path)
    if not convention and not (_own_wrapper(pkg) and named):
        _check_own_description(pkg, request.name)
        return pkg, ()
    found = (
        setup_assistant_description(sa, pkg.package_paths, pkg.shown, ())
        if sa is not None and sa.urdf_package and sa.urdf_path
        else None
    )
    if found is None:
        raise InputError(
            f"the robot description is the package's own wrapper {urdf.name} (the new package writes its "
            "own) and .setup_assistant names no other: give the robot's URDF (init URDF --from-package PKG)",
            path=pkg.user_path(urdf.relative_to(pkg.root).as_posix()),
        )
    path, sa_args = found.urdf, sa.urdf_xacro_args if sa is not None else ()
    wrapper = urdf.relative_to(pkg.root).as_posix()
    pkg = read_package(request.package, urdf=path, package_paths=paths, xacro_args=args or dict(sa_args))
    note = PortItem(
        "changed",
        "robot.urdf",
        f"{wrapper}, .setup_assistant",
        f"{wrapper} wraps the description for the source's own launch files (the new package writes its "
        f"own wrapper): the description .setup_assistant names is used, {path}",
    )
    return pkg, (note,)


def _check_own_description(pkg: MoveItPackage, name: str | None) -> None:
    """A description inside the package itself, reached as package://<its name>/...: a new
    package of the same name, which writes its own files, would name itself (to ros2 its own
    wrapper including itself). InputError: give the URDF, or another --name."""
    if not _own_wrapper(pkg) or (name or pkg.name) != pkg.name:
        return
    rel = pkg.description_file.resolve().relative_to(pkg.root.resolve()).as_posix()
    raise InputError(
        f"the robot description {rel} is the package's own file and .setup_assistant names no other: "
        f"a new package named {pkg.name} would name itself; give the robot's URDF "
        "(init URDF --from-package PKG), or --name another package name to use this one's",
        path=pkg.user_path(rel),
        element="robot description",
    )


def _own_wrapper(pkg: MoveItPackage) -> bool:
    """The description is a `config/*.urdf.xacro` of the package itself that a launch file names
    (`MoveItConfigsBuilder.robot_description(file_path="config/fanuc.urdf.xacro")`): the Setup
    Assistant's ros2_control wrapper, which the new package, of the same name, writes anew."""
    if pkg.urdf is None or pkg.urdf_origin == "--urdf" or not pkg.urdf.name.endswith(".urdf.xacro"):
        return False
    return pkg.urdf.resolve().parent == (pkg.root / "config").resolve()


def _package_robot(pkg: MoveItPackage, xacro_args: dict[str, str] | None = None) -> RobotModel:
    """The package's robot; its load failure is the one error line, and so is a `--xacro-arg`
    (`xacro_args`) that neither its description nor its SRDF xacro takes."""
    from marm_setup.validate import check_given_xacro_args, load_package_robot

    robot, problems = load_package_robot(pkg)
    if robot is None and not problems:  # --untrusted: its xacro did not run
        message = "not run: its xacro is package code (--untrusted); give a plain .urdf as the URDF argument"
        urdf = pkg.description_file
        raise InputError(f"xacro of {urdf.name}: {message}", path=str(urdf), element="xacro")
    if robot is None:
        from marm_setup.setup import as_input_error

        found = problems[0]
        if found.rule == "urdf.missing":  # its hint is validate's --urdf: init says how it takes one
            raise InputError(found.message, path=found.file, element=found.element or None, needs="--urdf")
        raise as_input_error(found)
    if xacro_args:
        check_given_xacro_args(pkg, robot, xacro_args)
    return robot
