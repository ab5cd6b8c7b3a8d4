"""move_group's own parameters a setup may give over marm-setup's defaults
(`move_group_parameters`): trajectory execution, controller management, planning scene
publishing. Keyed by their MoveIt 2 names (moveit_params/data/humble.yaml, jazzy.yaml: the same
declarations); a ros1 package writes each under its MoveIt 1 name (moveit_params/data/noetic.yaml
and the .cfg files below), same meaning.
"""

from __future__ import annotations

from dataclasses import dataclass

# a value of a move_group parameter (`move_group_problem` checks its name and type)
MoveGroupValue = bool | int | float | str


@dataclass(frozen=True, slots=True)
class MoveGroupParam:
    """One parameter: its MoveIt 2 name, its MoveIt 1 name, what marm-setup writes where the setup
    gives none (None: nothing, MoveIt's own default holds) and MoveIt 1's default."""

    name: str
    ros1: str
    type: type
    written: MoveGroupValue | None
    moveit1_default: MoveGroupValue
    source: str  # where MoveIt 2 reads it (moveit2 humble), and MoveIt 1


_TEM2 = "moveit_ros/planning/trajectory_execution_manager/src/trajectory_execution_manager.cpp"
_TEM1 = "moveit_ros/planning/trajectory_execution_manager/cfg/TrajectoryExecutionDynamicReconfigure.cfg"
_PSM2 = "moveit_ros/planning/planning_scene_monitor/src/planning_scene_monitor.cpp"
_PSM1 = "moveit_ros/planning/planning_scene_monitor/cfg/PlanningSceneMonitorDynamicReconfigure.cfg"
_TE, _PS = "trajectory_execution", "planning_scene_monitor"
MOVE_GROUP_PARAMS = (
    MoveGroupParam(f"{_TE}.allowed_execution_duration_scaling", f"{_TE}/allowed_execution_duration_scaling",
                   float, 1.2, 1.1, f"moveit2 {_TEM2} l.197; moveit {_TEM1} l.7"),
    MoveGroupParam(f"{_TE}.allowed_goal_duration_margin", f"{_TE}/allowed_goal_duration_margin",
                   float, 0.5, 0.5, f"moveit2 {_TEM2} l.199; moveit {_TEM1} l.8"),
    MoveGroupParam(f"{_TE}.allowed_start_tolerance", f"{_TE}/allowed_start_tolerance",
                   float, 0.01, 0.01, f"moveit2 {_TEM2} l.201; moveit {_TEM1} l.10"),
    MoveGroupParam(f"{_TE}.execution_duration_monitoring", f"{_TE}/execution_duration_monitoring",
                   bool, True, True, f"moveit2 {_TEM2} l.195; moveit {_TEM1} l.6"),
    MoveGroupParam(f"{_TE}.execution_velocity_scaling", f"{_TE}/execution_velocity_scaling",
                   float, None, 1.0, f"moveit2 {_TEM2} l.220; moveit {_TEM1} l.9"),
    MoveGroupParam(f"{_TE}.wait_for_trajectory_completion", f"{_TE}/wait_for_trajectory_completion",
                   bool, None, True, f"moveit2 {_TEM2} l.224; moveit {_TEM1} l.11"),
    MoveGroupParam("moveit_manage_controllers", "moveit_manage_controllers", bool, None, False,
                   f"moveit2 {_TEM2} l.62; moveit trajectory_execution_manager.cpp l.89"),
    MoveGroupParam("allow_trajectory_execution", "allow_trajectory_execution", bool, None, True,
                   "moveit2 moveit_ros/move_group/src/move_group.cpp l.78; moveit move_group.cpp l.80"),
    MoveGroupParam("publish_planning_scene", f"{_PS}/publish_planning_scene", bool, True, False,
                   f"moveit2 {_PSM2} l.260; moveit {_PSM1} l.6"),
    MoveGroupParam("publish_geometry_updates", f"{_PS}/publish_geometry_updates", bool, True, True,
                   f"moveit2 {_PSM2} l.261; moveit {_PSM1} l.8"),
    MoveGroupParam("publish_state_updates", f"{_PS}/publish_state_updates", bool, True, False,
                   f"moveit2 {_PSM2} l.264; moveit {_PSM1} l.9"),
    MoveGroupParam("publish_transforms_updates", f"{_PS}/publish_transforms_updates", bool, True, False,
                   f"moveit2 {_PSM2} l.265; moveit {_PSM1} l.10"),
)  # fmt: skip
# What the ros1 launch templates write where the setup gives nothing (as the Setup Assistant's
# move_group.launch and trajectory_execution.launch.xml do): templates/ros1/launch/*.j2
ROS1_WRITTEN: dict[str, MoveGroupValue] = {
    "moveit_manage_controllers": True,
    "allow_trajectory_execution": True,
}
BY_NAME = {p.name: p for p in MOVE_GROUP_PARAMS}


def written_values(target: str) -> dict[str, MoveGroupValue]:
    """{MoveIt 2 name: value} a package of `target` writes where the setup gives nothing."""
    out = {p.name: p.written for p in MOVE_GROUP_PARAMS if p.written is not None}
    return {**out, **ROS1_WRITTEN} if target == "ros1" else out


BY_ROS1_NAME = {p.ros1: p for p in MOVE_GROUP_PARAMS}


def move_group_values(given: tuple[tuple[str, MoveGroupValue], ...]) -> dict[str, MoveGroupValue]:
    """{MoveIt 2 name: value} a package writes: marm-setup's defaults, the setup's over them."""
    out: dict[str, MoveGroupValue] = {p.name: p.written for p in MOVE_GROUP_PARAMS if p.written is not None}
    for name, value in given:
        known = BY_NAME.get(name)
        # an int given for a double: rclcpp's typed get_parameter would throw, so write a float
        out[name] = float(value) if known is not None and known.type is float else value
    return out


def move_group_problem(name: str, value: object) -> str | None:
    """Why `name: value` cannot be a move_group parameter of the setup, else None."""
    known = BY_NAME.get(name)
    if known is None:
        return f"not a move_group parameter marm-setup writes (valid: {', '.join(BY_NAME)})"
    ok = (
        isinstance(value, bool)
        if known.type is bool
        else isinstance(value, int | float) and not isinstance(value, bool)
    )
    return None if ok else f"{value!r} is not a {known.type.__name__}"
