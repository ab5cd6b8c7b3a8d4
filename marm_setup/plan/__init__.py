"""Joint-space planning: the planning problem of a package, RRT-Connect with shortcutting, time
parameterisation, fake execution and trajectory files.

The public API, by module; names load on first use (`marm_setup.exports`).
"""

from marm_setup.exports import lazy_api

__all__, __getattr__, __dir__ = lazy_api(
    __name__,
    {
        "problem": "planning_problem plan_between",
        "planner": "plan_joint_path",
        "space": "PlannerOptions GroupSpace group_space",
        "timing": "time_parameterize",
        "execution": "fake_execute",
        "trajectory_io": "write_trajectory",
    },
)
