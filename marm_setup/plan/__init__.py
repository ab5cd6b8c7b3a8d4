"""Joint-space planning: the planning problem of a package, RRT-Connect with shortcutting, time
parameterisation, fake execution and trajectory files.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from typing import TYPE_CHECKING

from marm_setup.exports import lazy_api

API = {
    "problem": "Executed group_names_with_poses plan_between planning_problem PlanningProblem pose",
    "planner": "path_length plan_joint_path PlanFailed state_problem",
    "space": "group_space GroupSpace PlannerOptions",
    "timing": "time_parameterize TimedTrajectory",
    "execution": "fake_execute",
    "trajectory_io": "write_trajectory",
}
__all__, __getattr__, __dir__ = lazy_api(__name__, API)

if TYPE_CHECKING:  # the same names, for type checkers
    from marm_setup.plan.execution import fake_execute as fake_execute
    from marm_setup.plan.planner import PlanFailed as PlanFailed
    from marm_setup.plan.planner import path_length as path_length
    from marm_setup.plan.planner import plan_joint_path as plan_joint_path
    from marm_setup.plan.planner import state_problem as state_problem
    from marm_setup.plan.problem import Executed as Executed
    from marm_setup.plan.problem import PlanningProblem as PlanningProblem
    from marm_setup.plan.problem import group_names_with_poses as group_names_with_poses
    from marm_setup.plan.problem import plan_between as plan_between
    from marm_setup.plan.problem import planning_problem as planning_problem
    from marm_setup.plan.problem import pose as pose
    from marm_setup.plan.space import GroupSpace as GroupSpace
    from marm_setup.plan.space import PlannerOptions as PlannerOptions
    from marm_setup.plan.space import group_space as group_space
    from marm_setup.plan.timing import TimedTrajectory as TimedTrajectory
    from marm_setup.plan.timing import time_parameterize as time_parameterize
    from marm_setup.plan.trajectory_io import write_trajectory as write_trajectory
