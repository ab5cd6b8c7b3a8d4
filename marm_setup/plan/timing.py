"""Time parameterisation of a joint-space polyline within velocity and acceleration limits.

Each segment of the path gets a synchronised trapezoidal (or triangular) velocity profile and
the robot stops at every waypoint: a polyline has corners, and following it exactly forces
zero velocity there, so this is the time-optimal exact following of the planned path (no
corner cutting, hence no motion outside what the planner checked). Collinear waypoints are
merged first. Pure numpy: toppra/ruckig would only help with smooth paths or blends, which
would leave the collision-checked polyline.

A `TimedTrajectory` holds JointTrajectory points. Between two points the acceleration is
constant, (v1 - v0) / dt; points sit at every profile knot, so that model is exact.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from marm_setup.errors import InputError
from marm_setup.package import LoadedLimit
from marm_setup.plan.rrt import merge_collinear
from marm_setup.robot import RobotModel
from marm_setup.setup import timing_problem

__all__ = [
    "JointLimits",
    "TimedTrajectory",
    "limits_from_config",
    "merge_collinear",
    "time_parameterize",
]


# [rad/s or m/s] what MoveIt's time parameterisations take for a joint without a velocity bound
# (iterative_time_parameterization.cpp DEFAULT_VEL_MAX, time_optimal_trajectory_generation.cpp,
# ruckig_traj_smoothing.cpp DEFAULT_MAX_VELOCITY, which warns "Joint velocity limits are not
# defined. Using the default")
DEFAULT_VELOCITY = 1.0


@dataclass(frozen=True, eq=False)
class JointLimits:
    """Per joint maximum velocity [rad/s or m/s] and acceleration [rad/s^2 or m/s^2]; `unbounded`
    names the joints without a velocity limit, timed at MoveIt's DEFAULT_VELOCITY."""

    joint_names: tuple[str, ...]
    max_velocity: np.ndarray
    max_acceleration: np.ndarray
    unbounded: tuple[str, ...] = ()

    def scaled(self, velocity: float, acceleration: float) -> JointLimits:
        return JointLimits(
            self.joint_names,
            self.max_velocity * velocity,
            self.max_acceleration * acceleration,
            self.unbounded,
        )


@dataclass(frozen=True, eq=False)
class TimedTrajectory:
    """JointTrajectory points: times (K,) [s] from start, positions/velocities/accelerations (K, n)."""

    joint_names: tuple[str, ...]
    times: np.ndarray
    positions: np.ndarray
    velocities: np.ndarray
    accelerations: np.ndarray

    @property
    def duration(self) -> float:
        return float(self.times[-1])

    def sample(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions, velocities, accelerations (len(t), n) under constant acceleration per interval."""
        t = np.clip(np.asarray(t, dtype=float), self.times[0], self.times[-1])
        if len(self.times) == 1:  # a pose to itself: one point, at rest
            rows = np.zeros(len(t), dtype=int)
            return self.positions[rows], self.velocities[rows], self.accelerations[rows]
        k = np.clip(np.searchsorted(self.times, t, side="right") - 1, 0, len(self.times) - 2)
        dt_seg = np.diff(self.times)
        acc = np.diff(self.velocities, axis=0) / np.where(dt_seg > 0, dt_seg, 1.0)[:, None]
        tau = (t - self.times[k])[:, None]
        q = self.positions[k] + self.velocities[k] * tau + 0.5 * acc[k] * tau**2
        return q, self.velocities[k] + acc[k] * tau, acc[k]


def limits_from_config(
    robot: RobotModel,
    joint_names: Sequence[str],
    joint_limits: Mapping[str, LoadedLimit],
    default_acceleration: float = 1.0,
) -> JointLimits:
    """Limits as MoveIt reads them: the joint_limits file's values (`package.limits`, as MoveIt
    reads them) over the URDF's velocity.

    Acceleration falls back to `default_acceleration` where none is given (as MoveIt does);
    a joint with no positive velocity limit anywhere gets MoveIt's DEFAULT_VELOCITY.
    """
    v_max, a_max, unbounded = [], [], []
    for name in joint_names:
        given = joint_limits.get(name)
        for key, value in given.unreadable if given is not None else ():
            raise ValueError(f"{key} of joint {name} must be a number, got {value!r}")
        v = given.max_velocity if given is not None else None
        v = v if v is not None else robot.joint(name).velocity
        if v is None or v <= 0:
            v = DEFAULT_VELOCITY
            unbounded.append(name)
        a = given.max_acceleration if given is not None else None
        for key, rate in (("max_velocity", v), ("max_acceleration", a)):
            if problem := timing_problem(name, key, rate):
                raise ValueError(problem)
        a_max.append(a if a is not None and a > 0 else default_acceleration)
        v_max.append(float(v))
    return JointLimits(tuple(joint_names), np.array(v_max), np.array(a_max), tuple(unbounded))


def _segment_knots(d: np.ndarray, limits: JointLimits) -> list[tuple[float, float, float, float]]:
    """(dt, s, s_dot, s_ddot) knots of a trapezoid in s in [0, 1] for displacement `d`."""
    moving = np.abs(d) > 0
    sd_max = np.min(limits.max_velocity[moving] / np.abs(d[moving]))
    sdd_max = np.min(limits.max_acceleration[moving] / np.abs(d[moving]))
    if sd_max**2 / sdd_max >= 1.0:  # triangular: never reaches the velocity limit
        ta = np.sqrt(1.0 / sdd_max)
        return [(0.0, 0.0, 0.0, sdd_max), (ta, 0.5, sdd_max * ta, -sdd_max), (ta, 1.0, 0.0, 0.0)]
    ta = sd_max / sdd_max
    s_a = 0.5 * sdd_max * ta**2
    tc = (1.0 - 2 * s_a) / sd_max
    return [
        (0.0, 0.0, 0.0, sdd_max),
        (ta, s_a, sd_max, 0.0),
        (tc, 1.0 - s_a, sd_max, -sdd_max),
        (ta, 1.0, 0.0, 0.0),
    ]


MAX_SEGMENT_S = 3600.0  # [s]: beyond an hour per segment the limits are nonsense (and the points pile up)


def time_parameterize(q_path: np.ndarray, limits: JointLimits, max_period_s: float = 0.1) -> TimedTrajectory:
    """Trapezoidal profile per segment, stopping at waypoints; points every <= max_period_s [s].

    A path that does not move (start = goal) gives one point at t = 0.
    """
    q_path = merge_collinear(np.asarray(q_path, dtype=float))
    times, pos, vel = [0.0], [q_path[0]], [np.zeros(q_path.shape[1])]
    for q0, q1 in zip(q_path[:-1], q_path[1:], strict=True):
        d = q1 - q0
        if not np.any(d):
            continue
        knots = _segment_knots(d, limits)
        for (_, s0, sd0, sdd0), (dt, _, _, _) in zip(knots[:-1], knots[1:], strict=True):
            if dt <= 1e-12:
                continue
            if dt > MAX_SEGMENT_S:
                raise InputError(
                    f"a trajectory segment would take {dt:.3g} s at these limits (a velocity or "
                    "acceleration limit near 0?)",
                    element="joint_limits",
                )
            t_start, n = times[-1], max(1, int(np.ceil(dt / max_period_s)))
            for tau in dt * np.arange(1, n + 1) / n:
                times.append(t_start + tau)
                pos.append(q0 + (s0 + sd0 * tau + 0.5 * sdd0 * tau**2) * d)
                vel.append((sd0 + sdd0 * tau) * d)
        pos[-1], vel[-1] = q1.copy(), np.zeros_like(q1)
    t, v = np.array(times), np.array(vel)
    acc = np.concatenate([np.diff(v, axis=0) / np.diff(t)[:, None], np.zeros((1, v.shape[1]))])
    return TimedTrajectory(limits.joint_names, t, np.array(pos), v, acc)
