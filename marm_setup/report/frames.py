"""Where the page puts each drawn link: world poses for robot states and for trajectories."""

from __future__ import annotations

import numpy as np

from marm_setup.plan import TimedTrajectory
from marm_setup.robot import RobotModel, forward_kinematics, link_index

FRAME_RATE = 25.0  # [1/s] trajectory samples the page steps through
MAX_FRAMES = 100  # per trajectory: a long one is sampled more sparsely


def link_frames(robot: RobotModel, q: np.ndarray, links: tuple[str, ...]) -> np.ndarray:
    """World poses of `links` as 3x4 row-major blocks: (N, len(links) * 12) float32 for a batch
    of N configurations (one configuration: (len(links) * 12,))."""
    q = np.asarray(q, dtype=float)
    poses = forward_kinematics(robot, q)
    index = link_index(robot)
    rows = poses[:, [index[name] for name in links], :3, :]
    out = rows.reshape(len(poses), -1).astype(np.float32)
    return out[0] if q.ndim == 1 else out


def trajectory_samples(trajectory: TimedTrajectory) -> tuple[np.ndarray, np.ndarray]:
    """(times [s], group positions) at FRAME_RATE, at most MAX_FRAMES, both ends included."""
    duration = trajectory.duration
    count = int(min(MAX_FRAMES, max(2, np.ceil(duration * FRAME_RATE) + 1)))
    times = np.linspace(0.0, duration, count)
    positions, _, _ = trajectory.sample(times)
    return times, positions
