"""port_package: a MoveIt config package (any layout, as the package model reads it) and its
robot -> a SetupModel for the target, plus the port report of every setting."""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from marm_setup.errors import InputError
from marm_setup.package import MoveItPackage
from marm_setup.port.controllers import port_arbotix, port_controllers, report_driver, report_shared_joints
from marm_setup.port.description_packages import description_packages, report_description_packages
from marm_setup.port.kinematics import port_kinematics
from marm_setup.port.limits import port_joint_limits
from marm_setup.port.move_group import port_move_group
from marm_setup.port.package import (
    port_author,
    read_files,
    report_leftovers,
    report_marm_setup,
    report_metadata,
    robot_source,
)
from marm_setup.port.perception import port_perception
from marm_setup.port.pipelines import port_pipelines
from marm_setup.port.planners import port_planners
from marm_setup.port.port_log import PortItem, PortLog, where
from marm_setup.robot import RobotModel
from marm_setup.ros import Distro, Target
from marm_setup.setup import (
    EndEffector,
    GroupState,
    Kinematics,
    SetupModel,
    VirtualJoint,
    active_group_joints,
    groups_by_name,
    planning_joints,
)

# The SRDF elements the port leaves out when MoveIt fails on or skips them (their setup key).
DROPPABLE = {
    "virtual_joint": "virtual_joints",
    "end_effector": "end_effectors",
    "group_state": "group_states",
}


@dataclass(frozen=True)
class PortRequest:
    """Where the new package goes and what it is written for (target and distro resolved)."""

    out: Path
    target: Target
    ros_distro: Distro
    name: str | None = None
    package_paths: tuple[Path, ...] = ()  # the user's --package-path folders
    notes: tuple[PortItem, ...] = ()  # report items of the steps before the port (finding the package)


@dataclass(frozen=True)
class Ported:
    model: SetupModel
    items: tuple[PortItem, ...]
    source: str  # the package folder as the user typed it
    source_target: Target
    source_layout: str  # moveit1 | moveit2 | marm_ros2


def port_package(pkg: MoveItPackage, robot: RobotModel, request: PortRequest) -> Ported:
    """The setup the package holds, fitted to `request.target`; every setting reported."""
    if pkg.srdf is None:
        raise InputError("no readable SRDF: nothing to port", path=pkg.user_path(pkg.srdf_path or "config"))
    log = PortLog()
    log.items.extend(request.notes)
    model = _base(pkg, robot, request, log)
    model = _with_srdf(pkg, model, log)
    model = _without_srdf_errors(model, robot, pkg.srdf_path or "", log)
    model = _with_settings(pkg, model, robot, log)
    model = _with_controllers(pkg, model, robot, log)
    model = port_pipelines(pkg, model, log)
    model = port_move_group(pkg, model, log)
    model = port_perception(pkg, model, robot, log)
    _report_runtime_files(pkg, log)
    report_leftovers(pkg, read_files(pkg), log)
    return Ported(model, _motion_first(log.items), pkg.shown, pkg.target, pkg.layout)


def _motion_first(items: list[PortItem]) -> tuple[PortItem, ...]:
    """The report opens with what changes how the robot moves (in the order met), then the rest."""
    return (*(i for i in items if i.moves_robot), *(i for i in items if not i.moves_robot))


def _base(pkg: MoveItPackage, robot: RobotModel, request: PortRequest, log: PortLog) -> SetupModel:
    name = request.name or pkg.name
    report_metadata(pkg, name, request.target, log)
    source = robot_source(pkg, request.out, request.package_paths, log)
    needed = description_packages(pkg.description_file, robot)
    report_description_packages(needed, request.target, request.ros_distro, log, os.environ, _as_typed(pkg))
    report_marm_setup(pkg, log)
    marm = pkg.marm_setup
    if marm is not None and marm.kept_error is not None:
        raise marm.kept_error
    kept = marm.kept if marm is not None and marm.kept is not None else None
    base = SetupModel(package_name=name, robot_name=robot.name, robot=source)
    given = (
        dataclasses.replace(
            base, collision=kept.collision, default_acceleration=kept.default_acceleration, driver=kept.driver
        )
        if kept is not None
        else base
    )
    assert pkg.srdf is not None
    return dataclasses.replace(
        given,
        robot_name=pkg.srdf.robot_name or robot.name,
        robot=source,
        target=request.target,
        ros_distro=request.ros_distro,
        author=port_author(pkg, log),
        driver=given.driver or ("arbotix" if pkg.arbotix is not None else None),
    )


def _as_typed(pkg: MoveItPackage) -> Callable[[Path], str]:
    """A folder as the user would type it: from the source package folder as they typed that."""
    return lambda folder: os.path.normpath(
        pkg.user_path(os.path.relpath(folder.resolve(), pkg.root.resolve()))
    )


def _with_srdf(pkg: MoveItPackage, model: SetupModel, log: PortLog) -> SetupModel:
    from marm_setup.setup import srdf_to_setup

    srdf, file = pkg.srdf, pkg.srdf_path or ""
    assert srdf is not None  # port_package refuses a package without one
    if srdf.robot_name and srdf.robot_name != model.robot_name:
        log.changed("robot_name", file, f"{srdf.robot_name}")
    for group in srdf.groups:
        log.carried(f"groups[{group.name}]", where(file, "groups"), "", "srdf")
    for problem in pkg.problems:  # elements srdfdom skips, as the model's SRDF reader did
        if problem.file == file and problem.rule in ("srdf.parse", "srdf.unsupported"):
            log.dropped(problem.element or "srdf", where(file, problem.element), problem.message, "srdf")
    if srdf.passive_joints:
        log.carried("passive_joints", file, ", ".join(srdf.passive_joints))
    log.carried(
        "collision.disabled", where(file, "disable_collisions"), f"{len(srdf.disabled)} pairs, as given"
    )
    extras = srdf.extras
    for kind in (
        "enable_collisions",
        "disable_default_collisions",
        "joint_properties",
        "link_sphere_approximations",
    ):
        n = len(getattr(extras, kind))
        if n:
            log.carried(f"srdf_extras.{kind}", file, f"{n} entries")
    return srdf_to_setup(srdf, model)


def _without_srdf_errors(model: SetupModel, robot: RobotModel, file: str, log: PortLog) -> SetupModel:
    """Drop the virtual joints, end effectors and group states MoveIt fails on or skips (the SRDF
    rules of setup/rules.py that init and validate share), each with a report line: the new
    package must load, and the source never had them working."""
    from marm_setup.setup import check_semantics, setup_element, setup_to_srdf

    drop: dict[tuple[str, str], str] = {}
    for f in check_semantics(setup_to_srdf(model), robot, file, setup_element):
        kind = DROPPABLE.get(f.location.kind)
        if f.is_error and kind is not None:
            drop.setdefault((kind, f.location.name), f.message)
    for (kind, name), message in drop.items():
        log.dropped(f"{kind}[{name}]", where(file, kind), f"{message} (left out of the new package)", "srdf")

    def kept(items: tuple) -> tuple:
        return tuple(i for i in items if (kind_of[type(i)], i.name) not in drop)

    kind_of = {VirtualJoint: "virtual_joints", EndEffector: "end_effectors", GroupState: "group_states"}
    model = dataclasses.replace(
        model,
        virtual_joints=kept(model.virtual_joints),
        end_effectors=kept(model.end_effectors),
        group_states=kept(model.group_states),
    )
    for kind, items in (
        ("group_states", model.group_states),
        ("end_effectors", model.end_effectors),
        ("virtual_joints", model.virtual_joints),
    ):
        for item in items:  # only what the new package holds is carried
            log.carried(f"{kind}[{item.name}]", where(file, kind), _srdf_detail(item), "srdf")
    _report_skipped_virtual_joints(model, robot, file, log)
    return model


def _report_skipped_virtual_joints(model: SetupModel, robot: RobotModel, file: str, log: PortLog) -> None:
    """A virtual joint MoveIt skips (setup.root_virtual_joint) stays in the SRDF as the source had
    it, but the new demo publishes no TF for it: the source's demo gave its child a second TF
    parent (the Setup Assistant's demo publishes one for every virtual joint)."""
    from marm_setup.setup import root_virtual_joint

    root_vj = root_virtual_joint(model.virtual_joints, robot)
    parents = robot.parent_joint_of
    for vj in model.virtual_joints:
        if vj == root_vj or vj.child_link == vj.parent_frame:
            continue
        parent = parents.get(vj.child_link)
        why = (
            f"its child '{vj.child_link}' has the URDF parent joint '{parent.name}'"
            if parent is not None
            else f"MoveIt builds the root joint from '{root_vj.name if root_vj else ''}'"
        )
        detail = (
            f"MoveIt skips it ({why}; moveit_core robot_model.cpp): the demo launch publishes no static "
            f"TF {vj.parent_frame} -> {vj.child_link} for it, so '{vj.child_link}' keeps one TF parent"
        )
        log.changed(f"virtual_joints[{vj.name}].static_tf", where(file, "virtual_joint"), detail, "robot")


def _srdf_detail(item: Any) -> str:
    if hasattr(item, "values"):
        return f"group {item.group}, {len(item.values)} joints"
    if hasattr(item, "parent_link"):
        return f"group {item.group} on {item.parent_link}"
    if hasattr(item, "child_link"):
        return f"{item.type} {item.parent_frame} -> {item.child_link}"
    return ""


def _with_settings(pkg: MoveItPackage, model: SetupModel, robot: RobotModel, log: PortLog) -> SetupModel:
    names = [g.name for g in model.groups]
    kinematics = _without_unsolvable(port_kinematics(pkg.kinematics, names, log), pkg, robot, log)
    planning = planning_joints(model.groups, robot, model.passive_joints)
    ros2 = pkg.target == Target.ROS2
    overrides, scaling = port_joint_limits(
        pkg.joint_limits, robot, planning, model.default_acceleration, ros2, log
    )
    planners = port_planners(pkg.ompl, names, _projections(model, robot), log)
    return dataclasses.replace(
        model,
        kinematics=kinematics,
        joint_limits=overrides,
        planners=planners,
        default_velocity_scaling=scaling.get("default_velocity_scaling", model.default_velocity_scaling),
        default_acceleration_scaling=scaling.get(
            "default_acceleration_scaling", model.default_acceleration_scaling
        ),
    )


def _without_unsolvable(
    kinematics: tuple[Kinematics, ...], pkg: MoveItPackage, robot: RobotModel, log: PortLog
) -> tuple[Kinematics, ...]:
    """Drop chain-only solvers (KDL, LMA, cached KDL) on groups that are no chain: MoveIt cannot
    initialise them there, so the group had no IK solver (validate's kinematics rule)."""
    from marm_setup.moveit_params import CHAIN_ONLY_PLUGINS
    from marm_setup.setup import is_chain

    assert pkg.srdf is not None
    by_name = groups_by_name(pkg.srdf.groups)
    kept = []
    for k in kinematics:
        if k.solver in CHAIN_ONLY_PLUGINS and not is_chain(
            by_name[k.group], by_name, robot, tuple(pkg.srdf.passive_joints)
        ):
            entry = pkg.kinematics.group(k.group) if pkg.kinematics is not None else None
            detail = (
                f"{k.solver} is not written: it needs a serial chain and '{k.group}' is none, so MoveIt "
                "could not load it (the group had no IK); pick a general solver (pick_ik, bio_ik, TRAC-IK) by hand"
            )
            log.changed(
                f"kinematics[{k.group}].kinematics_solver", entry.where if entry else "", detail, "kinematics"
            )
        else:
            kept.append(k)
    return tuple(kept)


def _projections(model: SetupModel, robot: RobotModel) -> Callable[[str], str | None]:
    """The projection_evaluator the new package writes for a group: `joints(<first two active
    joints>)` (render.context GroupInfo.projection_joints), None for a group of fewer."""
    by_name = groups_by_name(model.groups)

    def projection(group: str) -> str | None:
        if group not in by_name:
            return None
        joints = active_group_joints(by_name[group], by_name, robot, model.passive_joints)
        return f"joints({joints[0]},{joints[1]})" if len(joints) >= 2 else None

    return projection


def _with_controllers(pkg: MoveItPackage, model: SetupModel, robot: RobotModel, log: PortLog) -> SetupModel:
    from marm_setup.inference import derive_group_settings

    derived = derive_group_settings(model, robot)
    ported = port_controllers(pkg, model, robot, log)
    controllers = ported or derived.controllers
    if not ported:
        for c in controllers:
            detail = f"written for group {c.group} ({c.type}), as init infers it"
            log.changed(f"controllers[{c.name}]", "", detail, "controllers")
    report_driver(pkg, controllers, model.driver_key, log)
    report_shared_joints(controllers, model.target, log)
    arbotix = port_arbotix(pkg, robot, model.target, log)
    if model.target == Target.ROS1 and model.driver == "arbotix" and not arbotix:
        model = dataclasses.replace(model, controllers=controllers)
        arbotix = derive_group_settings(model, robot).arbotix_joints
        ids = ", ".join(f"{a.joint}={a.id}" for a in arbotix)
        log.todo(
            "arbotix_joints",
            "",
            f"ros1 packages drive an ArbotiX bus: servo ids assigned ({ids}); check them",
        )
    if model.target == Target.ROS1 and model.driver is None:
        log.todo(
            "driver",
            "",
            "the new ros1 package writes no hardware driver files (no arbotix.yaml in the source): "
            "launch your robot's driver so it serves the controllers' actions",
        )
    if model.target == Target.ROS2:
        log.todo(
            "ros2_control hardware",
            "",
            "the new package drives mock_components/GenericSystem: put your robot's hardware plugin in "
            f"config/{model.robot_name}.ros2_control.xacro",
        )
    return dataclasses.replace(model, controllers=controllers, arbotix_joints=arbotix)


def _report_runtime_files(pkg: MoveItPackage, log: PortLog) -> None:
    """Fake controllers and initial positions: the new package writes its own from the setup."""
    for found, what in (
        (pkg.fake_controllers, "fake controllers (one per group) and their initial poses"),
        (pkg.initial_positions, "initial positions (each group's 'home' pose, else its first)"),
    ):
        if found is not None:
            log.changed(found.where.file, found.where.file, f"the new package writes its own {what}")
