"""Joint limits as the package gives them to MoveIt, and the one rule on which of them MoveIt can
time a trajectory with: `init` and `render` run it on the setup before writing (setup/checks.py),
`validate` and `plan` on the package's files (plan/timing.py, plan/problem.py), with one message.

A limit is timeable when it is absent (MoveIt then times at its default) or, scaled by the
package's default scaling factor, at least MIN_RATE: below it the durations overflow (MoveIt's
time parameterisations divide by the limit; 1e-320 rad/s is 1 rad in 3e312 years).
"""

from __future__ import annotations

from dataclasses import dataclass

from marm_setup.robot import MIN_RATE, RobotModel
from marm_setup.setup.groups import planning_joints
from marm_setup.setup.model import SetupModel


@dataclass(frozen=True, slots=True)
class JointLimit:
    """One `joint_limits.yaml` entry; velocity in [rad/s] or [m/s], acceleration per [s^2]."""

    joint: str
    max_velocity: float | None
    max_acceleration: float | None
    max_jerk: float | None = None
    min_position: float | None = None
    max_position: float | None = None


def joint_limits(model: SetupModel, robot: RobotModel) -> list[JointLimit]:
    """URDF velocity limits, the setup's default acceleration, then the setup's overrides."""
    overrides = {o.joint: o for o in model.joint_limits}
    out = []
    for name in planning_joints(model.groups, robot, model.passive_joints):
        joint = robot.joint(name)
        o = overrides.get(name)
        velocity = o.max_velocity if o and o.max_velocity is not None else joint.velocity
        accel = o.max_acceleration if o and o.max_acceleration is not None else model.default_acceleration
        jerk = o.max_jerk if o else None
        positions = (o.min_position, o.max_position) if o else (None, None)
        out.append(JointLimit(name, velocity if velocity else None, accel, jerk, *positions))
    return out


def timing_problem(joint: str, key: str, rate: float | None, scaling: float = 1.0) -> str:
    """Why no trajectory can be timed with `key` (max_velocity, max_acceleration) of `joint` at
    `rate` scaled by `scaling`; '' when it can (no limit at all is MoveIt's default)."""
    if rate is None or not rate > 0:
        return ""
    if rate < MIN_RATE:
        return f"{key} {rate:g} of joint {joint} is below {MIN_RATE:g}: no trajectory can be timed"
    if rate * scaling < MIN_RATE:
        return f"{key} {rate:g} of joint {joint} scaled by {scaling:g} is below {MIN_RATE:g}: no trajectory can be timed"
    return ""
