"""Planner invariants (pyroboplan style): the path starts at q_start and ends at q_goal, its
discretisation has steps <= max_step, every state is valid, joints outside the group are held,
the same seed gives the same path, failures carry a reason. Synthetic joint-space obstacles,
then the real marm scene under a generated SRDF."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from marm_setup.collision.scene import CollisionScene
from marm_setup.plan.planner import (
    PlanFailed,
    PlanFound,
    PlannerOptions,
    discretize_path,
    group_space,
    path_length,
    plan_joint_path,
    state_problem,
)
from marm_setup.plan.rrt import shortcut
from marm_setup.robot.load import load_robot
from tests.conftest import MARM_URDF

ARM = ("joint1", "joint2", "joint3", "joint4", "joint5", "joint6")
OPTIONS = PlannerOptions(max_step=0.05, max_time_s=30.0)


@pytest.fixture(scope="module")
def robot():
    return load_robot(MARM_URDF, {}, [])


def wall_checker(robot, seen: list | None = None):
    """joint1 in [-0.4, 0.4] is forbidden unless joint2 < -1.0 (a wall with one gap)."""
    i1, i2 = robot.active_joint_names.index("joint1"), robot.active_joint_names.index("joint2")

    def check(q: np.ndarray):
        if seen is not None:
            seen.append(q.copy())
        bad = (np.abs(q[:, i1]) <= 0.4) & (q[:, i2] >= -1.0)
        return [("link1", "link3") if b else None for b in bad]

    return check


def full(robot, **values) -> np.ndarray:
    q = np.zeros(len(robot.active_joint_names))
    for name, value in values.items():
        q[robot.active_joint_names.index(name)] = value
    return q


def assert_valid_path(robot, result, q_start, q_goal, check, options=OPTIONS):
    assert isinstance(result, PlanFound), result.reason
    space = group_space(robot, result.joint_names, q_start)
    np.testing.assert_array_equal(result.q_path[0], q_start[space.index])
    np.testing.assert_array_equal(result.q_path[-1], q_goal[space.index])
    dense = discretize_path(result.q_path, options.max_step)
    assert np.all(np.linalg.norm(np.diff(dense, axis=0), axis=1) <= options.max_step + 1e-12)
    assert all(hit is None for hit in check(space.to_full(dense)))
    assert np.all(dense >= space.lower - 1e-12) and np.all(dense <= space.upper + 1e-12)


@given(
    y1=st.floats(-2.0, 2.0),
    y2=st.floats(-2.0, 2.0),
    seed=st.integers(0, 2**16),
)
def test_path_through_the_gap_keeps_every_invariant(robot, y1, y2, seed):
    check = wall_checker(robot)
    q_start, q_goal = full(robot, joint1=-1.0, joint2=y1), full(robot, joint1=1.0, joint2=y2)
    result = plan_joint_path(robot, check, q_start, q_goal, ARM, np.random.default_rng(seed), OPTIONS)
    assert_valid_path(robot, result, q_start, q_goal, check)
    # joint1 runs -1 -> 1, so the straight line is inside the wall's band |joint1| <= 0.4 for
    # t in [0.3, 0.7]; it is blocked when joint2 reaches -1.0 there: the path must bend
    if max(y1 + 0.3 * (y2 - y1), y1 + 0.7 * (y2 - y1)) >= -1.0:
        assert len(result.q_path) >= 3


def test_same_seed_same_path_and_other_joints_held(robot):
    seen: list[np.ndarray] = []
    check = wall_checker(robot, seen)
    q_start = full(robot, joint1=-1.0, joint4=0.3, finger_joint1=0.02)
    q_goal = full(robot, joint1=1.0, joint4=-0.3, finger_joint1=0.05)
    group = ("joint1", "joint2", "joint4")
    a = plan_joint_path(robot, check, q_start, q_goal, group, np.random.default_rng(7), OPTIONS)
    b = plan_joint_path(robot, check, q_start, q_goal, group, np.random.default_rng(7), OPTIONS)
    np.testing.assert_array_equal(a.q_path, b.q_path)
    assert a.joint_names == group and a.q_path.shape[1] == 3
    states = np.concatenate(seen)
    held = [robot.active_joint_names.index(n) for n in robot.active_joint_names if n not in group]
    np.testing.assert_array_equal(states[:, held], np.broadcast_to(q_start[held], (len(states), len(held))))


def test_straight_line_when_free(robot):
    check = wall_checker(robot)
    q_start, q_goal = full(robot, joint1=0.5), full(robot, joint1=1.5, joint3=1.0)
    result = plan_joint_path(robot, check, q_start, q_goal, ARM, np.random.default_rng(0), OPTIONS)
    assert len(result.q_path) == 2 and result.iterations == 0


def test_start_in_collision_names_the_pair(robot):
    result = plan_joint_path(
        robot, wall_checker(robot), full(robot), full(robot, joint1=1.0), ARM, np.random.default_rng(0)
    )
    assert isinstance(result, PlanFailed)
    assert result.reason == "start in collision: link1 - link3"
    assert result.colliding_pair == ("link1", "link3")


def test_goal_out_of_limits_names_the_joint(robot):
    q_goal = full(robot, joint2=3.0)
    result = plan_joint_path(
        robot, wall_checker(robot), full(robot, joint1=1.0), q_goal, ARM, np.random.default_rng(0)
    )
    assert isinstance(result, PlanFailed)
    assert result.reason == "goal out of limits: joint2 = 3 not in [-2.35, 2.35]"


def test_walled_off_goal_fails_within_the_budget(robot):
    def closed(q):
        return [("link1", "link3") if abs(row[0]) <= 0.4 else None for row in q]

    options = PlannerOptions(max_iterations=50)
    result = plan_joint_path(
        robot,
        closed,
        full(robot, joint1=-1.0),
        full(robot, joint1=1.0),
        ARM,
        np.random.default_rng(0),
        options,
    )
    assert isinstance(result, PlanFailed)
    assert result.reason.startswith("no path within budget (50 iterations")


def test_unknown_group_joint_is_refused(robot):
    with pytest.raises(ValueError, match="finger_joint2"):
        group_space(robot, ("joint1", "finger_joint2"), full(robot))  # a mimic joint is no variable


def test_shortcut_never_lengthens(robot):
    check = wall_checker(robot)
    space = group_space(robot, ARM, full(robot))

    class Checker:
        options = OPTIONS

        def __init__(self):
            self.space = space

        def first_invalid(self, q):
            hits = check(space.to_full(q))
            k = next((i for i, h in enumerate(hits) if h is not None), None)
            return (None, None) if k is None else (k, hits[k])

        def line_valid(self, a, b):
            from marm_setup.plan.rrt import interpolate

            return self.first_invalid(interpolate(a, b, OPTIONS.max_step))[0] is None

    zigzag = np.array([[-1.0, 0, 0, 0, 0, 0], [-1.0, -1.5, 0, 0, 0, 0], [-0.5, -1.2, 1, 0, 0, 0]])
    zigzag = np.concatenate([zigzag, zigzag[::-1] * [-1, 1, 1, 1, 1, 1]])
    zigzag = np.concatenate([zigzag[:3], zigzag[4:]])  # -1,0 -> ... -> mirrored -> 1,0
    assert all(h is None for h in check(space.to_full(discretize_path(zigzag, 0.01))))
    shorter = shortcut(Checker(), zigzag, np.random.default_rng(0))
    assert path_length(shorter) <= path_length(zigzag) + 1e-12
    np.testing.assert_array_equal(shorter[[0, -1]], zigzag[[0, -1]])
    assert all(h is None for h in check(space.to_full(discretize_path(shorter, 0.01))))


# -- the real marm scene -----------------------------------------------------------------------


@pytest.fixture(scope="module")
def marm_scene(robot):
    scene = CollisionScene(robot)
    pairs = scene.enabled_pairs(robot.adjacent_geometry_pairs())
    return scene, pairs


def test_marm_random_queries_are_collision_free_at_a_finer_step(robot, marm_scene):
    scene, pairs = marm_scene

    def check(q):
        return scene.first_collisions(q, pairs)

    rng = np.random.default_rng(3)
    base = full(robot)
    space = group_space(robot, ARM, base)
    q = space.to_full(space.lower + rng.random((200, 6)) * (space.upper - space.lower))
    free = q[[hit is None for hit in check(q)]][:6]
    for k in range(0, len(free) - 1, 2):
        result = plan_joint_path(robot, check, free[k], free[k + 1], ARM, np.random.default_rng(k))
        assert_valid_path(robot, result, free[k], free[k + 1], check, PlannerOptions())
        fine = discretize_path(result.q_path, PlannerOptions().max_step / 4)
        assert all(hit is None for hit in check(space.to_full(fine)))


def test_marm_gripper_plans_over_the_leader_of_its_mimic_joint(robot, marm_scene):
    scene, pairs = marm_scene
    calls: list[np.ndarray] = []

    def check(q):
        calls.append(q)
        return scene.first_collisions(q, pairs)

    q_start, q_goal = full(robot, finger_joint1=0.0), full(robot, finger_joint1=0.05)
    found = state_problem(robot, check, q_start, ("finger_joint1",))
    assert found is None or "collision" in found[0]
    result = plan_joint_path(robot, check, q_start, q_goal, ("finger_joint1",), np.random.default_rng(0))
    assert isinstance(result, PlanFound), result.reason
    assert calls and all(c.shape[1] == len(robot.active_joint_names) for c in calls)
    assert "finger_joint2" not in robot.active_joint_names  # FK moves it with its leader
