"""JointTrajectory-shaped YAML: joint_names; points with positions, velocities, accelerations, time_from_start [s]."""

from __future__ import annotations

from collections.abc import Iterable
from os import PathLike
from pathlib import Path

import yaml

from marm_setup.plan.timing import TimedTrajectory


def _round(values: Iterable[float]) -> list[float]:
    return [float(round(float(x), 9)) + 0.0 for x in values]


def trajectory_to_dict(traj: TimedTrajectory) -> dict:
    """The trajectory as plain data in `trajectory_msgs/JointTrajectory` field order."""
    points = [
        {
            "positions": _round(traj.positions[k]),
            "velocities": _round(traj.velocities[k]),
            "accelerations": _round(traj.accelerations[k]),
            "time_from_start": float(round(float(traj.times[k]), 9)),
        }
        for k in range(len(traj.times))
    ]
    return {"joint_names": list(traj.joint_names), "points": points}


def dump_trajectory(traj: TimedTrajectory) -> str:
    """YAML text, number lists inline, stable across runs."""
    return yaml.safe_dump(trajectory_to_dict(traj), sort_keys=False, default_flow_style=None, width=200)


def write_trajectory(traj: TimedTrajectory, path: str | PathLike) -> None:
    """Write the YAML file (UTF-8, LF) atomically; InputError naming `path` when it cannot."""
    from marm_setup.render import write_text_atomic

    write_text_atomic(Path(path), dump_trajectory(traj), shown=str(path))
