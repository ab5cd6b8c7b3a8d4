"""What changes how the robot moves, read from a package model: for diffing a package against
its port (joint limits as MoveIt reads them, scaling factors, MoveIt's controllers, IK solvers
and their options, each group's OMPL settings)."""

from __future__ import annotations

from marm_setup.package.limits import effective_limits
from marm_setup.package.model import MoveItPackage
from marm_setup.robot.model import RobotModel
from marm_setup.setup.groups import planning_joints

# kinematics keys MoveIt does not read (>= 1.0 reads no attempts)
IGNORED_KINEMATICS_KEYS = ("kinematics_solver_attempts",)
# a diff key's prefix -> the port report setting that must explain a difference
REPORTED = {
    "limit": "joint_limits[{}]",
    "controller": "controllers[{}]",
    "kinematics": "kinematics[{}]",
    "planner": "planners[{}]",
}
# a group's OMPL keys the port rewrites by design: the planners offered (every one it writes)
IGNORED_PLANNER_KEYS = ("planner_configs",)


def motion_settings(pkg: MoveItPackage, robot: RobotModel) -> dict[str, object]:
    """{key: value} of every limit, scaling factor, controller and IK option the package loads."""
    out: dict[str, object] = {}
    srdf = pkg.srdf
    assert srdf is not None
    read = effective_limits(pkg.joint_limits, pkg.target == "ros2")
    for joint in planning_joints(tuple(srdf.groups), robot, tuple(srdf.passive_joints)):
        limit = read.get(joint)
        urdf = robot.joint(joint)
        velocity = limit.max_velocity if limit and limit.max_velocity is not None else urdf.velocity
        out[f"limit:{joint}.velocity"] = round(float(velocity or 0), 6)
        if limit is not None and limit.max_acceleration is not None:
            out[f"limit:{joint}.acceleration"] = round(limit.max_acceleration, 6)
        for key, value, fallback in (
            ("min_position", limit and limit.min_position, urdf.lower),
            ("max_position", limit and limit.max_position, urdf.upper),
        ):
            if value is not None:
                out[f"limit:{joint}.{key}"] = round(value, 6)
            elif fallback is not None:
                out[f"limit:{joint}.{key}"] = round(fallback, 6)
        entry = pkg.joint_limits.joint(joint) if pkg.joint_limits is not None else None
        flag, jerk = (entry.param("has_jerk_limits"), entry.param("max_jerk")) if entry else (None, None)
        if flag is not None and flag.flag and jerk is not None and jerk.number:
            out[f"limit:{joint}.jerk"] = round(jerk.number, 6)
    for kind in ("velocity", "acceleration"):
        param = getattr(pkg.joint_limits, f"{kind}_scaling", None)
        if param is not None and param.number is not None:
            out[f"scaling:default_{kind}_scaling"] = param.number
    managed = pkg.managed_controllers
    for c in managed.controllers if managed else ():
        out[f"controller:{c.name}"] = (frozenset(c.joints), c.type)
    for entry in pkg.kinematics.groups or () if pkg.kinematics else ():
        for param in entry.params or ():
            if param.key not in IGNORED_KINEMATICS_KEYS:
                out[f"kinematics:{entry.group}.{param.key}"] = param.value
    out.update(_planner_settings(pkg, {g.name for g in srdf.groups}))
    return out


def _planner_settings(pkg: MoveItPackage, groups: set[str]) -> dict[str, object]:
    """Each SRDF group's OMPL settings; its default planner by type (the port renames configs)."""
    ompl, out = pkg.ompl, {}
    if ompl is None:
        return out
    types = {c.name: c.type for c in ompl.planner_configs or ()}
    for entry in ompl.groups:
        for param in entry.params if entry.group in groups else ():
            if param.key in IGNORED_PLANNER_KEYS:
                continue
            value = (
                types.get(str(param.value), param.value)
                if param.key == "default_planner_config"
                else param.value
            )
            out[f"planner:{entry.group}.{param.key}"] = value
    return out


def unexplained(source: dict, port: dict, items: list[dict]) -> dict[str, tuple]:
    """Settings of `source` the port does not hold as they were and no report line (changed,
    dropped or todo) names."""
    out = {}
    for key, value in source.items():
        if port.get(key) == value:
            continue
        kind, _, rest = key.partition(":")
        name = rest.split(".")[0]
        setting = REPORTED.get(kind, "{}").format(name) if kind != "scaling" else rest
        if not any(i["setting"].startswith(setting) and i["status"] != "carried" for i in items):
            out[key] = (value, port.get(key))
    return out
