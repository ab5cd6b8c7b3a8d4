"""Fake execution accepts what the timing produces and catches each kind of broken trajectory:
too fast, too hard an acceleration, out of bounds, through an obstacle between points,
inconsistent points, missing the goal, wrong joints. Trajectory YAML round trips."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
import yaml

from marm_setup.plan.execution import ExecutionOptions, fake_execute, sample_times
from marm_setup.plan.planner import group_space
from marm_setup.plan.timing import JointLimits, TimedTrajectory, time_parameterize
from marm_setup.plan.trajectory_io import dump_trajectory, write_trajectory
from marm_setup.robot.load import load_robot
from tests.conftest import MARM_URDF

GROUP = ("joint1", "joint2")
LIMITS = JointLimits(GROUP, np.array([1.0, 1.0]), np.array([2.0, 2.0]))


@pytest.fixture(scope="module")
def space():
    robot = load_robot(MARM_URDF, {}, [])
    return group_space(robot, GROUP, np.zeros(len(robot.active_joint_names)))


def free(q):
    return [None] * len(q)


def pillar(q):
    """A thin obstacle at joint1 = 0.5 (+- 0.004), joint2 <= 0.2: thinner than the planner's step."""
    bad = (np.abs(q[:, 0] - 0.5) <= 0.004) & (q[:, 1] <= 0.2)
    return [("link1", "link4") if b else None for b in bad]


def traj_for(path):
    return time_parameterize(np.array(path, dtype=float), LIMITS)


def test_a_timed_path_executes_cleanly(space):
    traj = traj_for([[0, 0], [1, 0.5], [1.2, -0.3]])
    report = fake_execute(traj, space, LIMITS, free, np.array([1.2, -0.3]))
    assert report.ok, report.violations
    assert report.samples >= np.linalg.norm([1, 0.5]) / 0.005 and report.duration_s == traj.duration


def test_finer_sampling_than_the_path_catches_a_thin_obstacle(space):
    traj = traj_for([[0, 0], [1, 0]])
    t = sample_times(traj, 0.005)
    q, _, _ = traj.sample(t)
    assert np.all(np.linalg.norm(np.diff(q, axis=0), axis=1) <= 0.005 + 1e-12)
    coarse = ExecutionOptions(max_step=0.05)
    assert fake_execute(traj, space, LIMITS, pillar, np.array([1.0, 0.0]), coarse).ok  # steps over it
    report = fake_execute(traj, space, LIMITS, pillar, np.array([1.0, 0.0]))
    assert len(report.violations) == 1
    assert report.violations[0].startswith("collision at t=") and report.violations[0].endswith(
        "link1 - link4"
    )


def test_too_fast_is_a_velocity_and_acceleration_violation(space):
    traj = traj_for([[0, 0], [1, 0]])
    fast = TimedTrajectory(GROUP, traj.times / 2, traj.positions, traj.velocities * 2, traj.accelerations * 4)
    report = fake_execute(fast, space, LIMITS, free, np.array([1.0, 0.0]))
    kinds = sorted(v.split(" limit")[0] for v in report.violations)
    assert kinds == ["acceleration", "velocity"]
    assert any("joint1" in v and "> 1" in v for v in report.violations)


def test_inconsistent_points_and_missing_the_goal(space):
    traj = traj_for([[0, 0], [1, 0]])
    positions = traj.positions.copy()
    positions[-1, 1] = 0.01  # the last point claims a place the motion never reaches
    broken = dataclasses.replace(traj, positions=positions)
    report = fake_execute(broken, space, LIMITS, free, np.array([1.0, 0.0]))
    assert any(v.startswith("inconsistent points: joint2") for v in report.violations)
    report = fake_execute(traj, space, LIMITS, free, np.array([1.0, 0.1]))
    assert report.violations == ("misses the goal: joint2 ends at 0, goal 0.1",)


def test_out_of_bounds_and_wrong_joints(space):
    traj = traj_for([[0, 0], [0, 2.5]])  # joint2 upper bound 2.35
    report = fake_execute(traj, space, LIMITS, free, np.array([0.0, 2.5]))
    assert report.violations == (report.violations[0],)
    assert report.violations[0].startswith("position limit: joint2 at t=")
    other = dataclasses.replace(traj, joint_names=("joint1", "joint3"))
    assert "not the group's" in fake_execute(other, space, LIMITS, free, np.array([0.0, 2.5])).violations[0]


def test_yaml_round_trip_executes_the_same(space, tmp_path):
    traj = traj_for([[0, 0], [1, 0.5], [1.2, -0.3]])
    path = tmp_path / "traj.yaml"
    write_trajectory(traj, path)
    text = path.read_text(encoding="utf-8")
    assert text == dump_trajectory(traj) and text.startswith("joint_names: [joint1, joint2]\npoints:\n")
    data = yaml.safe_load(text)
    points = data["points"]
    back = TimedTrajectory(
        tuple(data["joint_names"]),
        *(
            np.array([p[f] for p in points])
            for f in ("time_from_start", "positions", "velocities", "accelerations")
        ),
    )
    assert back.joint_names == GROUP
    np.testing.assert_allclose(back.positions, traj.positions, atol=1e-9)
    np.testing.assert_allclose(back.times, traj.times, atol=1e-9)
    assert fake_execute(back, space, LIMITS, free, np.array([1.2, -0.3])).ok


def test_a_pose_to_itself_executes_as_one_point(space):
    traj = traj_for([[0.4, 0.1], [0.4, 0.1]])
    report = fake_execute(traj, space, LIMITS, free, np.array([0.4, 0.1]))
    assert report.ok and report.samples == 1 and report.duration_s == 0.0
