"""Time parameterisation: trapezoids with the textbook durations, limits held at every instant,
stops at corners, points consistent with constant acceleration between them; limits read as
MoveIt reads them."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from marm_setup.plan.timing import JointLimits, limits_from_config, merge_collinear, time_parameterize
from marm_setup.robot.load import load_robot
from tests.conftest import MARM_URDF

LIMITS = JointLimits(("a", "b"), np.array([1.0, 2.0]), np.array([2.0, 1.0]))


def test_trapezoid_duration_one_joint():
    # 2 rad at 1 rad/s, 2 rad/s^2: 0.5 s up (0.25 rad), 1.5 s cruise, 0.5 s down
    traj = time_parameterize(np.array([[0.0, 0.0], [2.0, 0.0]]), LIMITS)
    assert traj.duration == pytest.approx(2.5)
    assert np.abs(traj.velocities[:, 0]).max() == pytest.approx(1.0)
    q, v, a = traj.sample(np.array([0.25, 0.5, 1.25, 2.5]))
    np.testing.assert_allclose(q[:, 0], [0.0625, 0.25, 1.0, 2.0])
    np.testing.assert_allclose(v[:, 0], [0.5, 1.0, 1.0, 0.0], atol=1e-12)


def test_triangle_when_the_velocity_limit_is_out_of_reach():
    # 0.1 rad at 2 rad/s^2: t = 2 sqrt(0.1 / 2), peak velocity sqrt(0.1 * 2) < 1
    traj = time_parameterize(np.array([[0.0, 0.0], [0.1, 0.0]]), LIMITS)
    assert traj.duration == pytest.approx(2 * np.sqrt(0.05))
    assert np.abs(traj.velocities[:, 0]).max() == pytest.approx(np.sqrt(0.2))


def test_the_slowest_joint_sets_the_pace_and_all_joints_stay_on_the_line():
    traj = time_parameterize(np.array([[0.0, 0.0], [1.0, 1.0]]), LIMITS)
    # joint b: 1 rad at 2 rad/s, 1 rad/s^2 -> triangle 2 s; joint a alone would need 1.5 s
    assert traj.duration == pytest.approx(2.0)
    q, _, _ = traj.sample(np.linspace(0, traj.duration, 101))
    np.testing.assert_allclose(q[:, 0], q[:, 1], atol=1e-12)


def test_stops_at_corners_and_merges_collinear_waypoints():
    path = np.array([[0.0, 0.0], [0.5, 0.0], [1.0, 0.0], [1.0, 1.0], [1.0, 1.0]])
    np.testing.assert_array_equal(merge_collinear(path), [[0, 0], [1, 0], [1, 1]])
    traj = time_parameterize(path, LIMITS)
    corner = np.flatnonzero(np.all(np.isclose(traj.positions, [1.0, 0.0]), axis=1))
    assert len(corner) == 1 and np.all(traj.velocities[corner] == 0.0)


@given(
    path=arrays(float, st.tuples(st.integers(2, 5), st.just(2)), elements=st.floats(-3, 3)),
    v=st.floats(0.1, 5),
    a=st.floats(0.1, 5),
)
def test_limits_hold_everywhere_and_points_are_consistent(path, v, a):
    if np.linalg.norm(np.diff(path, axis=0), axis=1).max() < 1e-6:
        return  # nothing to move
    limits = JointLimits(("a", "b"), np.array([v, 2 * v]), np.array([a, a / 2]))
    traj = time_parameterize(path, limits, max_period_s=0.05)
    np.testing.assert_allclose(traj.positions[[0, -1]], path[[0, -1]])
    assert np.all(np.diff(traj.times) > 0) and np.all(np.diff(traj.times) <= 0.05 + 1e-12)
    t = np.linspace(0, traj.duration, 2001)
    q, qd, qdd = traj.sample(t)
    assert np.all(np.abs(qd) <= limits.max_velocity * (1 + 1e-9))
    assert np.all(np.abs(qdd) <= limits.max_acceleration * (1 + 1e-9))
    assert np.all(np.abs(traj.accelerations) <= limits.max_acceleration * (1 + 1e-9))
    # positions follow from velocities (constant acceleration between points)
    dt = np.diff(traj.times)[:, None]
    reached = traj.positions[:-1] + 0.5 * (traj.velocities[:-1] + traj.velocities[1:]) * dt
    np.testing.assert_allclose(reached, traj.positions[1:], atol=1e-9)
    # and never leave the bounding box of the waypoints (no overshoot)
    assert np.all(q >= path.min(axis=0) - 1e-9) and np.all(q <= path.max(axis=0) + 1e-9)


LIMITS_YAML = """
joint_limits:
  joint1: {has_velocity_limits: true, max_velocity: 0.5, has_acceleration_limits: true, max_acceleration: 0.2}
  joint2: {has_velocity_limits: false, max_velocity: 9.0, has_acceleration_limits: false, max_acceleration: 9.0}
  joint3: {max_velocity: 0.25, max_acceleration: 0.4}
"""


def _limits(text: str, ros2: bool):
    from marm_setup.package.files import located_text
    from marm_setup.package.joint_limits_file import read_joint_limits
    from marm_setup.package.limits import effective_limits

    return effective_limits(read_joint_limits(located_text(text, "config/joint_limits.yaml")), ros2)


@pytest.mark.parametrize("ros2", [False, True])
def test_limits_from_config_prefers_the_yaml_and_falls_back_like_moveit(ros2):
    """MoveIt 1 takes a max_velocity without its flag, MoveIt 2 reads one only with
    `has_velocity_limits: true` (robot_model_loader.cpp of each)."""
    robot = load_robot(MARM_URDF, {}, [])
    limits = limits_from_config(robot, ("joint1", "joint2", "joint3"), _limits(LIMITS_YAML, ros2), 1.5)
    v3, a3 = (1.0, 1.5) if ros2 else (0.25, 0.4)  # URDF velocity 1.0
    np.testing.assert_array_equal(limits.max_velocity, [0.5, 1.0, v3])
    np.testing.assert_array_equal(limits.max_acceleration, [0.2, 1.5, a3])
    scaled = limits.scaled(0.1, 0.5)
    np.testing.assert_allclose(scaled.max_velocity, [0.05, 0.1, v3 / 10])
    np.testing.assert_allclose(scaled.max_acceleration, [0.1, 0.75, a3 / 2])


def test_a_path_that_does_not_move_is_one_point_at_rest():
    traj = time_parameterize(np.array([[0.3, -0.2], [0.3, -0.2]]), LIMITS)
    assert traj.times.tolist() == [0.0] and traj.duration == 0.0
    np.testing.assert_array_equal(traj.positions, [[0.3, -0.2]])
    q, v, a = traj.sample(np.array([0.0, 1.0]))
    np.testing.assert_array_equal(q, [[0.3, -0.2], [0.3, -0.2]])
    assert not v.any() and not a.any()


def test_ends_exactly_at_the_goal_after_a_waypoint_within_tolerance_of_it():
    path = np.array([[1.0, 0.0], [4.9e-74, 0.0], [0.0, 0.0]])  # found by hypothesis
    traj = time_parameterize(path, LIMITS)
    np.testing.assert_array_equal(traj.positions[-1], [0.0, 0.0])


@pytest.mark.parametrize(
    ("key", "value"), [("max_velocity", '"fast"'), ("max_velocity", "true"), ("max_acceleration", "[2]")]
)
def test_limits_that_are_not_numbers_are_a_value_error_naming_the_joint(key, value):
    """MoveIt cannot read them (MoveIt 1's getParam fails, MoveIt 2's typed parameter throws):
    the planner says so instead of planning with something else."""
    robot = load_robot(MARM_URDF, {}, [])
    text = f"joint_limits:\n  joint1: {{has_velocity_limits: true, has_acceleration_limits: true, {key}: {value}}}\n"
    for ros2 in (False, True):
        with pytest.raises(ValueError, match=f"^{key} of joint joint1 must be a number, got "):
            limits_from_config(robot, ("joint1",), _limits(text, ros2))
