"""Joint-space planning: the planning problem of a package, RRT-Connect with shortcutting, time
parameterisation, fake execution and trajectory files.

Public API below (name -> module); names load on first use (see `marm_setup.exports`).
"""

from __future__ import annotations

from typing import Any

from marm_setup.exports import load_export

_API = {
    "planning_problem": "problem",
    "plan_between": "problem",
    "PlannerOptions": "planner",
    "plan_joint_path": "planner",
    "time_parameterize": "timing",
    "fake_execute": "execution",
    "write_trajectory": "trajectory_io",
    "load_trajectory": "trajectory_io",
}
__all__ = sorted(_API)


def __getattr__(name: str) -> Any:
    return load_export(__name__, _API, name)


def __dir__() -> list[str]:
    return sorted({*globals(), *_API})
