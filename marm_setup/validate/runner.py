"""validate: every static check of a MoveIt config package, plus the runtime seam.

Rule families live in `validate/rules/`; this module reads the package (via
`package.read_package`), loads the robot and the collision scene once, and runs them all. The
runtime checks (plan between named poses, execute as a fake controller) come from
`marm_setup.validate.runtime.check_runtime(package, robot, scene)` when `plan` is true.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from contextlib import nullcontext
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from marm_setup.errors import InputError, MarmError, MeshNotFound, PackageNotFound, remedy
from marm_setup.findings import INTERNAL, Finding, Location, error, sort_findings, warning
from marm_setup.package import (
    ControllersFile,
    DriverFile,
    MoveItPackage,
    launch_nodes,
    package_start_values,
    read_package,
    undefined_unread_arg,
)
from marm_setup.ros import DISTROS, DistroRow, Target
from marm_setup.untrusted import CodeNotRun, no_package_code, skipped_code, skips_code
from marm_setup.validate.registry import rule_family
from marm_setup.validate.rules.conflict_rules import check_merge_conflicts
from marm_setup.validate.rules.controller_rules import (
    check_coverage,
    check_fake_controllers,
    check_listed,
    check_moveit_controllers,
    check_ros1_list_loaded,
    check_ros1_manager_plugins,
    check_ros1_namespace,
    check_ros2_namespace,
    check_ros_control_coverage,
    uses_ros_control_interface,
)
from marm_setup.validate.rules.declared_param_rules import check_declared_parameters, exported_classes
from marm_setup.validate.rules.distro_rules import check_package_runtime
from marm_setup.validate.rules.driver_param_rules import check_driver_parameters
from marm_setup.validate.rules.driver_rules import check_arbotix, check_driver_controllers
from marm_setup.validate.rules.kinematics_rules import check_kinematics, check_top_level_kinematics
from marm_setup.validate.rules.launch_rules import check_launch_files, check_package_xml
from marm_setup.validate.rules.limits_rules import check_cartesian_limits, check_joint_limits, uses_pilz
from marm_setup.validate.rules.name_rules import check_controller_names, check_srdf_names
from marm_setup.validate.rules.ompl_rules import check_ompl
from marm_setup.validate.rules.perception_rules import check_sensors, check_servos
from marm_setup.validate.rules.pose_rules import check_initial_positions
from marm_setup.validate.rules.srdf_rules import check_srdf, check_srdf_without_robot, publishes_static_tfs
from marm_setup.validate.rules.write_state_rules import check_pending_write
from marm_setup.validate.srdf_fit import fitting_srdf

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene
    from marm_setup.robot import RobotModel
    from marm_setup.validate.runtime import PlannedPair, Progress

MATRIX_TRIALS = 1000


@dataclass(frozen=True)
class Validation:
    """What one validation checked, and what it found."""

    findings: tuple[Finding, ...]
    package: str  # package.xml <name>
    target: Target
    layout: str  # moveit1 | moveit2 | marm_ros2
    urdf: str  # the robot description, as the user would type it
    urdf_origin: str  # --urdf, marm_setup.yaml, .setup_assistant, config/<robot>.urdf.xacro
    robot: str | None  # the URDF's robot name; None when it did not load
    planned_pairs: int | None  # pose pairs planned by the runtime checks; None when they did not run
    skipped: tuple[str, ...] = ()  # rule families that did not run, each with why
    launched_by: str = ""  # what ran the launch files: the user's ROS, or the static rules only
    srdf: str | None = None  # the SRDF read, relative to the package
    srdf_origin: str = ""  # which launch file sets it, or how it was chosen
    xacro_args: tuple[tuple[str, str], ...] = ()  # those the description was expanded with
    env_defaults: tuple[str, ...] = ()  # unset environment variables its xacro read with optenv
    launch_args: tuple[tuple[str, str], ...] = ()  # given to the launch files (--launch-arg)

    def describe(self) -> str:
        """One line: what was validated, against which robot, and whether planning ran."""
        robot = f"robot '{self.robot}'" if self.robot else "robot (not loaded: URDF checks skipped)"
        n = self.planned_pairs
        runtime = "runtime planning skipped" if n is None else f"planned {n} pose pair{'' if n == 1 else 's'}"
        runtime += " (no group has two usable named poses)" if n == 0 else ""
        skipped = "".join(f"; skipped {s}" for s in self.skipped)
        launched = f"; launch files: {self.launched_by}" if self.launched_by else ""
        if self.launch_args:
            launched += f"; launch args {' '.join(f'{k}:={v}' for k, v in self.launch_args)}"
        args = " ".join(f"{k}:={v}" for k, v in self.xacro_args)
        urdf = f"{self.urdf}{f' {args}' if args else ''} ({self.urdf_origin})"
        if self.env_defaults:
            names = ", ".join(self.env_defaults)
            urdf += f" with the defaults of the unset environment variables it reads with $(optenv): {names}"
            urdf += self._variant_hint()
        srdf = f", SRDF {self.srdf} ({self.srdf_origin})" if self.srdf else ", no SRDF"
        return (
            f"validated {self.package} ({self.target}, {self.layout} layout) with {robot} "
            f"from {urdf}{srdf}; {runtime}{launched}{skipped}"
        )

    def _variant_hint(self) -> str:
        """What to do when findings name joints or links the robot lacks while its xacro took
        environment variables' defaults: the package may be for the variant they select."""
        lacking = sum(f.rule.endswith(("unknown-joint", "unknown-link")) for f in self.findings)
        if not lacking:
            return ""
        example = f"{self.env_defaults[0]}=... marm-setup validate ..."
        return (
            f" ({lacking} finding{'' if lacking == 1 else 's'} name joints or links it lacks: if the"
            f" package is for a variant those variables select, set them as the robot's setup does: {example})"
        )

    def as_dict(self) -> dict:
        """The json `validated` object (everything but the findings)."""
        keys = ("package", "target", "layout", "urdf", "urdf_origin", "robot", "planned_pairs", "launched_by")
        loaded = {
            "srdf": self.srdf,
            "srdf_origin": self.srdf_origin,
            "xacro_args": dict(self.xacro_args),
            "env_defaults": list(self.env_defaults),
            "launch_args": dict(self.launch_args),
        }
        return {**{key: getattr(self, key) for key in keys}, **loaded, "skipped": list(self.skipped)}


def guarded(family: str, fn: Callable[..., Iterable[Finding]], *args: Any, **kwargs: Any) -> list[Finding]:
    """`fn(*args)`'s findings; a crash in one rule family becomes one finding of its own (exit 2)
    instead of stopping the others. `family` is one of the registry's (KeyError otherwise)."""
    rule_family(family)
    try:
        return list(fn(*args, **kwargs))
    except MarmError as exc:  # a file the family needed could not be read
        return [error(f"{family}.unreadable", exc.path or "", exc.element or "", exc.message)]
    except Exception as exc:  # noqa: BLE001 - a bug in one family must not hide the rest
        msg = f"the {family} rules crashed ({type(exc).__name__}: {exc}); the other rules ran"
        return [error(INTERNAL, "", family, msg, "please report this with the package")]


@dataclass(frozen=True)
class ValidatedPackage:
    """A validation and what it read and computed on the way (what the report draws): the package
    as discovered, its robot (None when it did not load) and every pose pair the runtime checks
    planned, with its trajectory."""

    validation: Validation
    package: MoveItPackage
    robot: RobotModel | None
    plans: tuple[PlannedPair, ...] = ()


def validate(
    path: str | Path,
    *,
    urdf: str | Path | None = None,
    srdf: str | Path | None = None,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    plan: bool = True,
    matrix_trials: int = MATRIX_TRIALS,
    progress: Progress | None = None,
    untrusted: bool = False,
    ros_distro: str | None = None,
    launch_args: Mapping[str, str] | None = None,
) -> Validation:
    """Validate the package at `path`: its findings and what was checked (`validate_package`).

    Raises InputError (exit 2) only when `path` is not a readable config package at all.
    """
    return validate_package(
        path,
        urdf=urdf,
        srdf=srdf,
        xacro_args=xacro_args,
        package_paths=package_paths,
        plan=plan,
        matrix_trials=matrix_trials,
        progress=progress,
        untrusted=untrusted,
        ros_distro=ros_distro,
        launch_args=launch_args,
    ).validation


def validate_package(
    path: str | Path,
    *,
    urdf: str | Path | None = None,
    srdf: str | Path | None = None,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    plan: bool = True,
    matrix_trials: int = MATRIX_TRIALS,
    progress: Progress | None = None,
    untrusted: bool = False,
    ros_distro: str | None = None,
    launch_args: Mapping[str, str] | None = None,
) -> ValidatedPackage:
    """Validate the package at `path`, keeping what was read and planned; `progress(done, total)`
    hears of each pose pair the runtime checks plan. `untrusted`: no package code runs (no
    xacro, `$(eval)`, `$(command)` or launch file); the summary names what was skipped.
    `launch_args`: the launch files' arguments, as `roslaunch` / `ros2 launch` would get them.

    Raises InputError (exit 2) only when `path` is not a readable config package at all.
    """
    with no_package_code() if untrusted else nullcontext():
        pkg = read_package(
            path,
            urdf=urdf,
            srdf=srdf,
            xacro_args=xacro_args,
            package_paths=package_paths,
            launch_args=launch_args,
        )
        pkg = pkg.for_distro(ros_distro)  # --ros-distro over marm_setup.yaml's
        return validate_read(
            pkg, xacro_args=xacro_args, plan=plan, matrix_trials=matrix_trials, progress=progress
        )


def validate_read(
    pkg: MoveItPackage,
    *,
    xacro_args: Mapping[str, str] | None = None,
    plan: bool = True,
    matrix_trials: int = MATRIX_TRIALS,
    progress: Progress | None = None,
) -> ValidatedPackage:
    """Validate a package already read (its model), keeping what was planned; the
    `--xacro-arg`s given for it, if any, are checked against what its xacros take."""
    robot, problems = load_package_robot(pkg)
    if robot is not None:
        pkg = fitting_srdf(pkg, robot)  # an SRDF chosen by name: the one made for this robot
    findings = list(pkg.problems)
    xml = pkg.package_xml.file if pkg.package_xml is not None else None
    findings += guarded("package", check_package_xml, pkg.root, xml)
    findings += guarded("package", check_pending_write, pkg.root)
    findings += guarded("package", check_merge_conflicts, pkg.root)
    findings += guarded("launch", check_launch_files, pkg.root, pkg.name, pkg.launch, pkg.target)
    findings += problems
    if robot is not None and xacro_args:
        check_given_xacro_args(pkg, robot, xacro_args)
    launched, launched_by = check_as_launched(pkg, robot)
    findings += launched
    if pkg.srdf_path is None:
        findings.append(error("srdf.missing", "config", "", "no SRDF found (config/<robot>.srdf)"))
    planned = None
    if robot is not None and pkg.srdf is not None:
        findings += without_skipped_group_cascade(check_static(pkg, robot), pkg)
        scene_findings, planned = check_with_scene(
            pkg, robot, plan=plan, matrix_trials=matrix_trials, progress=progress
        )
        findings += scene_findings
    elif robot is None and any(f.rule in RUNTIME_RULES for f in problems):
        findings += without_skipped_group_cascade(check_without_robot(pkg), pkg)
    validation = _validation(pkg, robot, findings, planned, launched_by)
    return ValidatedPackage(validation, pkg, robot, tuple(planned or ()))


def _untrusted_skips() -> tuple[str, ...]:
    """The summary's line for what `--untrusted` did not run (none when all ran)."""
    skipped = skipped_code()
    return (f"package code (--untrusted): {'; '.join(skipped)}",) if skipped else ()


def _validation(
    pkg: MoveItPackage,
    robot: RobotModel | None,
    findings: list[Finding],
    planned: list[PlannedPair] | None,
    launched_by: str,
) -> Validation:
    from marm_setup.validate.runtime import unplanned_pairs

    return Validation(
        findings=tuple(sort_findings(findings)),
        package=pkg.name,
        target=pkg.target,
        layout=pkg.layout,
        urdf=user_urdf(pkg),
        urdf_origin=pkg.urdf_origin,
        robot=robot.name if robot is not None else None,
        planned_pairs=None if planned is None else len(planned),
        skipped=(*skipped_families(pkg, robot), *unplanned_pairs(planned or ()), *_untrusted_skips()),
        launched_by=launched_by,
        srdf=pkg.srdf_path,
        srdf_origin=source.how if (source := pkg.source("srdf")) is not None else "",
        xacro_args=pkg.xacro_args,
        env_defaults=robot.env_defaults if robot is not None else (),
        launch_args=pkg.launch_args,
    )


def check_given_xacro_args(pkg: MoveItPackage, robot: RobotModel, given: Mapping[str, str]) -> None:
    """The `--xacro-arg`s the user gave for a package must each be an argument of its robot
    description's xacro or of its SRDF xacro (the arguments the package model's SRDF reader saw
    it take); else an InputError (robot/xacro_expand.check_xacro_args)."""
    from marm_setup.robot import check_xacro_args

    left = set(given) - set(robot.xacro_args or ())
    srdf = pkg.srdf_file
    if not left or srdf is None or srdf.xacro_declared is None:
        check_xacro_args(given, robot.xacro_args, path=user_urdf(pkg))
        return
    declared = {*(robot.xacro_args or ()), *srdf.xacro_declared}
    check_xacro_args(given, declared, path=user_urdf(pkg), others=(pkg.user_path(pkg.srdf_path),))


def check_as_launched(pkg: MoveItPackage, robot: RobotModel | None) -> tuple[list[Finding], str]:
    """The launch files and parameter files as ROS runs them: the static rules (validate/rules/
    ros2_launch_rules.py, ros2_params_rules.py), then the user's own ROS when it is there
    (validate/consumers.py); with the summary's words for what ran."""
    from marm_setup.validate.consumers import run_consumer
    from marm_setup.validate.rules.ros2_launch_rules import check_install_paths, check_ros2_launch
    from marm_setup.validate.rules.ros2_params_rules import check_params_files

    distro = pkg.ros_distro
    out = guarded("launch", check_install_paths, pkg)
    if pkg.target == Target.ROS2:
        if not skips_code("the $(command ...) of the XML launch files (the launch command rules)"):
            out += guarded("launch", check_ros2_launch, pkg, distro)
        out += guarded("params", check_params_files, pkg.root)
        out += guarded("params", check_declared_parameters, pkg, distro)
        out += guarded("controller", check_driver_parameters, pkg, distro)
    if skips_code("the launch files in the user's ROS (roslaunch / ros2 launch)"):
        return out, "static rules only (--untrusted: no launch file was run)"
    run = run_consumer(pkg, robot, distro)
    return out + list(run.findings), run.ran


def without_skipped_group_cascade(findings: list[Finding], pkg: MoveItPackage) -> list[Finding]:
    """Drop 'unknown group' findings about a group the SRDF has but that could not be read (its
    own finding says why): subgroups, kinematics, OMPL and controllers name it rightly."""
    gone = pkg.srdf_file.skipped_groups if pkg.srdf_file is not None else frozenset()
    return [f for f in findings if f.location.refers not in {("group", g) for g in gone}]


def skipped_families(pkg: MoveItPackage, robot: RobotModel | None) -> tuple[str, ...]:
    """What did not run or ran on less than the whole file, each with why (for the summary)."""
    out = [f"the rules on {f.file} ({f.message})" for f in pkg.problems if f.rule == "yaml.parse"]
    out += [
        f"{f.element} of {f.file} ({f.message})"
        for f in pkg.problems
        if f.rule in ("srdf.parse", "srdf.unsupported", "srdf.runtime-arg")
    ]
    if robot is None and description_unreadable(pkg):
        out.append(f"every rule needing the robot (its description, {pkg.urdf_origin})")
    elif robot is None and pkg.urdf is None:
        out.append(
            f"every rule needing the robot ({RUNTIME_ONLY_SKIPPED}: its description comes only at run time)"
        )
    elif robot is None:
        untrusted = any(s.startswith("xacro of") for s in skipped_code())
        why = "its xacro did not run: --untrusted" if untrusted else "its URDF did not load"
        out.append(f"every rule needing the robot ({why})")
    elif pkg.srdf is None:
        why = "no SRDF found" if pkg.srdf_path is None else f"{pkg.srdf_path} could not be read"
        out.append(f"the {', '.join(SRDF_FAMILIES)} rules ({why})")
    out += pkg.opaque
    return tuple(out)


SRDF_FAMILIES = tuple(
    rule_family(f).name for f in ("srdf", "pose", "kinematics", "limits", "ompl", "controller", "matrix")
)


def shown_path(pkg: MoveItPackage, file: Path) -> str:
    """A file's path for findings: relative to the package (`../x` outside it), never absolute."""
    return Path(os.path.relpath(Path(file).resolve(), pkg.root)).as_posix()


def user_urdf(pkg: MoveItPackage) -> str:
    """The robot description as the user would type it: as given to --urdf, else `DIR/...`."""
    if pkg.urdf is None:
        return "no file" if description_unreadable(pkg) else "the run time's /robot_description"
    if pkg.urdf_origin == "--urdf":
        return str(pkg.urdf)
    return os.path.normpath(pkg.user_path(shown_path(pkg, pkg.urdf)))


def load_package_robot(pkg: MoveItPackage) -> tuple[RobotModel | None, list[Finding]]:
    """(RobotModel or None, findings): the URDF loads and its meshes resolve."""
    from marm_setup.robot import load_robot

    if pkg.urdf is None:
        if description_unreadable(pkg):  # its own finding (package.read) says why
            return None, []
        return None, [runtime_only_description(pkg)]
    shown = shown_path(pkg, pkg.urdf) if pkg.urdf_origin != "--urdf" else str(pkg.urdf)
    if not pkg.urdf.is_file():  # named by marm_setup.yaml or .setup_assistant (--urdf is checked earlier)
        marm = pkg.urdf_origin == "marm_setup.yaml"
        file, element = (
            ("marm_setup.yaml", "robot.urdf") if marm else (".setup_assistant", "URDF.relative_path")
        )
        message = f"robot description '{shown}' not found"
        return None, [error("urdf.missing", file, element, message, "fix the path, or pass --urdf URDF")]
    try:
        return load_robot(pkg.urdf, dict(pkg.xacro_args), pkg.package_paths), []
    except CodeNotRun:  # --untrusted: a xacro description is not expanded (the summary says so)
        return None, []
    except PackageNotFound as exc:  # a mesh's or $(find)'s package no path holds: the user's environment
        return None, [_robot_package_missing(pkg, shown, exc)]
    except InputError as exc:
        if (arg := undefined_unread_arg(exc.message, pkg.unread_xacro_args)) is not None:
            return None, [runtime_arg_description(pkg, shown, arg)]
        rule = "urdf.mesh-missing" if isinstance(exc, MeshNotFound) else "urdf.load"
        message = f"{exc.message} (robot description from {pkg.urdf_origin})"
        return None, [error(rule, shown, exc.element or "", message, _package_hint(exc))]


def _robot_package_missing(pkg: MoveItPackage, shown: str, exc: PackageNotFound) -> Finding:
    """The description loads a package (a `package://` mesh, a xacro `$(find)`) that no package
    path holds: a warning, as for the description's own package (package/read.py
    missing_package): MoveIt resolves it where ROS has it installed (geometric_shapes'
    createMeshFromResource through resource_retriever, package:// via ROS_PACKAGE_PATH), so
    validate cannot tell it is missing; only a file missing from a package at hand is an error."""
    message = (
        f"loads package '{exc.package}', which no package path holds ({exc.element or 'the description'}; "
        f"robot description from {pkg.urdf_origin}): the rules needing the robot are skipped"
    )
    hint = f"pass --package-path DIR (the folder holding {exc.package})"
    at = Location("package", exc.package)
    return warning("urdf.package-missing", shown, exc.element or "", message, hint, at=at)


RUNTIME_RULES = ("urdf.runtime-only", "urdf.runtime-arg")


def description_unreadable(pkg: MoveItPackage) -> bool:
    """The description the launch files (or .setup_assistant, marm_setup.yaml) name is in a
    package no package path holds, or does not exist: reading the package said so."""
    return pkg.urdf is None and pkg.description_unreadable


RUNTIME_ONLY_SKIPPED = (
    "SRDF links and joints against the URDF, named pose values, KDL chains, joint limits against the "
    "URDF, controller joints and coverage, ros2_control systems, collisions, the matrix and planning"
)


def runtime_only_description(pkg: MoveItPackage) -> Finding:
    """A package whose robot description only the run time gives (package.description
    `RUNTIME_ONLY`): MoveIt loads it then, so nothing is wrong; validate says what it could not
    read and which checks it skipped (a warning, never an error: DESIGN §5)."""
    launch = ", ".join(pkg.python_launch_files) or ("launch/*.launch" if pkg.launch else "launch/*.py")
    msg = f"robot description not read ({pkg.urdf_origin}); skipped: {RUNTIME_ONLY_SKIPPED}"
    hint = "pass --urdf FILE (and --xacro-arg NAME:=VALUE) to run them"
    return warning("urdf.runtime-only", launch, "robot_description", msg, hint)


def runtime_arg_description(pkg: MoveItPackage, shown: str, arg: str) -> Finding:
    """A description whose xacro needs an arg the launch files pass a value only the run time
    gives (a launch argument without default): MoveIt has it then, validate does not."""
    msg = (
        f"not expanded: its xacro needs {arg}:=, which {pkg.urdf_origin} sets from a value only the "
        f"run time gives; skipped: {RUNTIME_ONLY_SKIPPED}"
    )
    return warning("urdf.runtime-arg", shown, "xacro", msg, f"pass --xacro-arg {arg}:=VALUE to run them")


def check_without_robot(pkg: MoveItPackage) -> list[Finding]:
    """The static rules that read no robot: the SRDF's own structure and names, kinematics,
    limits, OMPL (those with the SRDF, when it was read), controller files and the distro's
    formats (`check_static` minus the robot)."""
    out = guarded("controller", check_controller_files, pkg)
    out += guarded("distro", check_package_runtime, pkg, None)
    if pkg.srdf_file is None or pkg.srdf is None:
        return out
    return out + guarded("srdf", check_srdf_without_robot, pkg.srdf_file) + check_srdf_files(pkg, None)


def check_srdf_files(pkg: MoveItPackage, robot: RobotModel | None) -> list[Finding]:
    """The SRDF's names, and kinematics, limits and OMPL against its groups (and the robot, when
    it is known), each family on its own."""
    assert pkg.srdf_file is not None and pkg.srdf is not None
    srdf, file = pkg.srdf, pkg.srdf_file.path
    out = guarded("names", check_srdf_names, srdf, file)
    if pkg.kinematics is not None:
        ros1 = pkg.target == Target.ROS1  # a ROS 2 solver's class is declared_param_rules'
        depends = pkg.package_xml.dependencies if pkg.package_xml is not None else ()
        exported = exported_classes(pkg) if ros1 else frozenset()
        out += guarded(
            "kinematics",
            check_kinematics,
            pkg.kinematics,
            srdf,
            robot,
            moveit1=ros1,
            depends=depends,
            exported=exported,
        )
        if not ros1 and pkg.kinematics.top_level_by:
            row = kinematics_distro(pkg)
            out += guarded("kinematics", check_top_level_kinematics, pkg.kinematics, srdf, row)
    if pkg.joint_limits is not None:
        pilz = uses_pilz(pkg.pipelines)
        out += guarded("limits", check_joint_limits, pkg.joint_limits, srdf, robot, pkg.target, pilz=pilz)
        if pilz:
            out += guarded("limits", check_cartesian_limits, pkg.joint_limits)
    if pkg.ompl is not None:
        moveit1 = pkg.target == Target.ROS1
        out += guarded("ompl", check_ompl, pkg.ompl, srdf, ompl_planners(pkg), moveit1=moveit1)
    return out


def kinematics_distro(pkg: MoveItPackage) -> DistroRow | None:
    """The distro whose MoveIt reads the package's kinematics: --ros-distro or marm_setup.yaml's,
    else the one the pipelines' parameter format shows (declared_param_rules.inferred_family),
    else None."""
    from marm_setup.package import received_parameters
    from marm_setup.validate.rules.declared_param_rules import inferred_family

    name = pkg.ros_distro or inferred_family(received_parameters(pkg))
    return DISTROS.get(name) if name else None


def ompl_planners(pkg: MoveItPackage) -> frozenset[str]:
    """The planner types the package's MoveIt registers: its family's (ROS 1: noetic), and with
    no known ROS 2 distro those every ROS 2 family registers."""
    from marm_setup.moveit_params import family_of, load_table

    family = "noetic" if pkg.target == Target.ROS1 else family_of(pkg.ros_distro)
    families = [family] if family else ["humble", "jazzy"]
    found = [frozenset(t for t, _ in load_table(f).ompl_planners) for f in families]
    return frozenset.intersection(*found)


def check_controller_files(pkg: MoveItPackage) -> list[Finding]:
    """MoveIt's controller files on their own (without the robot): listed, named, namespaced,
    typed."""
    out: list[Finding] = check_ros1_list_loaded(pkg) + check_ros1_manager_plugins(pkg)
    if pkg.fake_controllers is not None:
        out += check_listed(pkg.fake_controllers)
    moveit = pkg.moveit_controllers
    if moveit is None or uses_ros_control_interface(moveit):
        return out
    out += _listed_controller_rules(pkg, moveit)
    return out + check_moveit_controllers(moveit, None)


def _listed_controller_rules(pkg: MoveItPackage, moveit: ControllersFile) -> list[Finding]:
    """The simple manager's list on its own: entries listed and named, and where the launch
    files load it (MoveIt 1) or the manager's namespace (MoveIt 2)."""
    ros1_list = moveit.form == "controller_list"
    out = check_listed(moveit)
    out += check_controller_names(moveit.controllers, moveit.where.file, global_names=ros1_list)
    out += check_ros1_namespace(moveit)
    if pkg.target == Target.ROS2 and pkg.layout == "moveit2":
        out += check_ros2_namespace(moveit)
    return out


def _package_hint(exc: InputError) -> str:
    """For a package no path holds, or a `package://` mesh not where its package is: where to
    add one."""
    in_package = isinstance(exc, MeshNotFound) and exc.uri.startswith("package://")
    if isinstance(exc, PackageNotFound) or in_package:
        return "pass --package-path DIR for packages outside this folder"
    return remedy(exc.needs)


def check_static(pkg: MoveItPackage, robot: RobotModel) -> list[Finding]:
    """SRDF, poses, kinematics, limits, OMPL, controller, servo and sensor rules (no collision checking), each
    family on its own: one that fails leaves the others running."""
    assert pkg.srdf_file is not None and pkg.srdf is not None
    out = guarded("srdf", check_srdf, pkg.srdf_file, robot, publishes_static_tfs(pkg))
    out += check_srdf_files(pkg, robot)
    if pkg.initial_positions is not None:
        out += guarded("pose", check_initial_positions, pkg.initial_positions, robot)
    out += guarded("controller", check_controllers, pkg, robot)
    out += guarded("controller", check_hardware_interfaces, pkg, robot)
    out += guarded("distro", check_package_runtime, pkg, robot)
    out += guarded("servo", check_servos, pkg, robot)
    out += guarded("sensors", check_sensors, pkg)
    return out


def check_hardware_interfaces(pkg: MoveItPackage, robot: RobotModel) -> list[Finding]:
    """ROS 2: the driver's trajectory controllers against the interfaces the `<ros2_control>`
    systems of the description the package loads list (validate/rules/interface_rules.py); in
    our layout the package's own ros2_control xacro is part of that description."""
    from marm_setup.robot import described_systems
    from marm_setup.validate.rules.interface_rules import check_controller_interfaces, offered_interfaces

    if pkg.target != Target.ROS2 or pkg.ros2_controllers is None:
        return []
    systems = list(described_systems(robot))
    if pkg.layout == "marm_ros2":
        systems += [s for f in pkg.ros2_control_files for s in f.systems]
    return check_controller_interfaces(pkg.ros2_controllers, offered_interfaces(systems))


def check_controllers(pkg: MoveItPackage, robot: RobotModel) -> list[Finding]:
    """MoveIt's controllers vs robot and groups, then vs every driver file the package has."""
    assert pkg.srdf is not None
    out: list[Finding] = check_ros1_list_loaded(pkg) + check_ros1_manager_plugins(pkg)
    if pkg.fake_controllers is not None:
        out += check_fake_controllers(pkg.fake_controllers, pkg.srdf, robot)
    moveit = pkg.moveit_controllers
    if moveit is None:
        if (
            pkg.fake_controllers is None
            and "trajectory_execution" not in pkg.opaque_methods  # a foreign builder's list
            and not any(f.rule == "controller.runtime-only" for f in pkg.problems)
        ):
            msg = "no MoveIt controller configuration (controllers.yaml / moveit_controllers.yaml)"
            out.append(warning("controller.none", "config", "", msg, "MoveIt can plan but not execute"))
        return out
    simulated = simulator_drivers(pkg, robot)
    if uses_ros_control_interface(moveit):
        driver = pkg.ros2_controllers or pkg.ros_controllers
        if driver is None and simulated:
            driver, simulated = simulated[0], simulated[1:]
        out += check_ros_control_coverage(moveit, driver, pkg.srdf, robot)
        ros1 = driver is pkg.ros_controllers
        return out + (
            check_driver_controllers(moveit, driver, robot, ros1=ros1, simulated=simulated)
            if driver is not None
            else []
        )
    out += _listed_controller_rules(pkg, moveit)
    out += check_moveit_controllers(moveit, robot)
    out += check_coverage(moveit, pkg.srdf, robot, pkg.alt_moveit_controllers)
    if pkg.ros2_controllers is not None:
        out += check_driver_controllers(moveit, pkg.ros2_controllers, robot, simulated=simulated)
    elif simulated and pkg.ros_controllers is None:
        out += check_driver_controllers(moveit, simulated[0], robot, simulated=simulated[1:])
    if pkg.ros_controllers is not None and pkg.ros_controllers.where.file != moveit.where.file:
        out += check_driver_controllers(moveit, pkg.ros_controllers, robot, ros1=True)
    if pkg.arbotix is not None:
        out += check_arbotix(pkg.arbotix, moveit, robot, gripper_nodes(pkg))
    return out


def simulator_drivers(pkg: MoveItPackage, robot: RobotModel) -> tuple[DriverFile, ...]:
    """ROS 2: the controller_manager parameter files the robot description's ros2_control
    simulator plugin loads (`<gazebo><plugin filename="libgazebo_ros2_control.so">
    <parameters>`, or gz_ros2_control's): in simulation, the controllers that run."""
    from marm_setup.package import read_simulator_drivers
    from marm_setup.robot import simulator_parameter_files

    if pkg.target != Target.ROS2:
        return ()
    return read_simulator_drivers(simulator_parameter_files(robot.urdf_xml), pkg.root)


def gripper_nodes(pkg: MoveItPackage) -> dict[str, tuple[str, str]]:
    """ArbotiX `gripper_controller` nodes in the launch files: name -> (file, `joint` param)."""
    out: dict[str, tuple[str, str]] = {}
    for rel, node in launch_nodes({t.file: t for t in pkg.launch}):
        if (node.get("type") or "").startswith("gripper_controller") and node.get("name"):  # type: ignore[attr-defined]
            params = node.iter("param")  # type: ignore[attr-defined]
            joint = next((p.get("value", "") for p in params if p.get("name") == "joint"), "")
            out.setdefault(node.get("name"), (rel, joint))  # type: ignore[attr-defined]
    return out


def check_with_scene(
    pkg: MoveItPackage, robot: RobotModel, *, plan: bool, matrix_trials: int, progress: Progress | None = None
) -> tuple[list[Finding], list[PlannedPair] | None]:
    """Pose collisions, matrix freshness and (when `plan`) the runtime checks, on one scene;
    with the pose pairs the runtime checks planned (None when they did not run)."""
    from marm_setup.collision import CollisionScene
    from marm_setup.validate.rules.matrix_rules import cached_proved, check_matrix_fresh, check_matrix_missing
    from marm_setup.validate.rules.pose_rules import check_pose_collisions, check_start_state

    try:
        scene = CollisionScene(robot)
    except InputError as exc:
        return [error("urdf.collision-geometry", exc.path or "", exc.element or "", exc.message)], None
    start = package_start_values(pkg, robot)
    out = guarded("pose", check_pose_collisions, pkg.srdf, robot, scene, pkg.srdf_path, start)
    if (
        pkg.target == Target.ROS2 and pkg.initial_positions is not None
    ):  # ros1 starts at named poses, checked above
        file = pkg.initial_positions.where.file
        out += guarded("pose", check_start_state, pkg.srdf, robot, scene, file, start)
    # validate's own trial count and seed, never the package's (a package cannot vouch for itself)
    trials = matrix_trials
    out += guarded("matrix", check_matrix_missing, pkg.srdf, robot, scene, pkg.srdf_path, trials=trials)
    proved = cached_proved(pkg.srdf, scene) if pkg.srdf is not None else frozenset()
    out += guarded(
        "matrix", check_matrix_fresh, pkg.srdf, robot, scene, pkg.srdf_path, trials=trials, proved=proved
    )
    if not plan:
        return out, None
    planned: list[PlannedPair] = []
    out += guarded("runtime", run_runtime_checks, pkg, robot, scene, planned, progress)
    return out, planned


def run_runtime_checks(
    pkg: MoveItPackage,
    robot: RobotModel,
    scene: CollisionScene,
    planned: list[PlannedPair],
    progress: Progress | None = None,
) -> list[Finding]:
    """The planner's runtime checks; `planned` receives each pose pair planned."""
    from marm_setup.validate.runtime import check_runtime

    return list(check_runtime(pkg, robot, scene, planned=planned, progress=progress))
