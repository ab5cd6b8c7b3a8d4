"""JointTrajectory-shaped YAML: joint_names; points with positions, velocities, accelerations, time_from_start [s]."""

from __future__ import annotations

from os import PathLike
from pathlib import Path

import numpy as np
import yaml

from marm_setup.errors import InputError
from marm_setup.plan.timing import TimedTrajectory

FIELDS = ("positions", "velocities", "accelerations")


def _round(values) -> list[float]:
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


def trajectory_from_dict(data, path: str = "<trajectory>") -> TimedTrajectory:
    """Parse the plain data back; InputError naming the point and field on bad input."""
    if not isinstance(data, dict) or not isinstance(data.get("joint_names"), list):
        raise InputError("expected a mapping with joint_names and points", path=path)
    names = tuple(str(n) for n in data["joint_names"])
    points = data.get("points")
    if not isinstance(points, list) or not points:
        raise InputError("expected a non-empty list", path=path, element="points")
    rows = {f: [] for f in FIELDS}
    times = []
    for k, point in enumerate(points):
        for f in FIELDS:
            values = point.get(f) if isinstance(point, dict) else None
            if not isinstance(values, list) or len(values) != len(names):
                raise InputError(f"expected {len(names)} numbers", path=path, element=f"points[{k}].{f}")
            rows[f].append([_number(v, path, f"points[{k}].{f}") for v in values])
        times.append(_number(point.get("time_from_start"), path, f"points[{k}].time_from_start"))
    arrays = [np.array(rows[f], dtype=float) for f in FIELDS]
    return TimedTrajectory(names, np.array(times), *arrays)


def _number(value, path: str, element: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InputError(f"expected a number, got {value!r}", path=path, element=element)
    return float(value)


def load_trajectory(path: str | PathLike) -> TimedTrajectory:
    """Read a trajectory YAML file."""
    shown = str(path)
    try:
        data = yaml.safe_load(Path(path).read_text(encoding="utf-8"))
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror}", path=shown) from None
    except yaml.YAMLError as exc:
        raise InputError(f"not valid YAML: {exc}", path=shown) from None
    return trajectory_from_dict(data, shown)


def write_trajectory(traj: TimedTrajectory, path: str | PathLike) -> None:
    """Write the YAML file (UTF-8, LF) atomically; InputError naming `path` when it cannot."""
    from marm_setup.render.writer import write_text_atomic

    write_text_atomic(Path(path), dump_trajectory(traj), shown=str(path))
