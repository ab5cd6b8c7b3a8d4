"""Batched FK against yourdfpy (an independent implementation), sampling and mimic invariants."""

from __future__ import annotations

import io
from functools import cache

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from marm_setup.robot.kinematics import (
    bounds,
    default_configuration,
    forward_kinematics,
    link_index,
    origin_matrix,
    sample_configurations,
)
from marm_setup.robot.load import load_robot
from tests.conftest import MARM_URDF, REALWORLD


@cache
def marm():
    return load_robot(MARM_URDF)


@cache
def panda():
    root = REALWORLD / "ros1"
    return load_robot(root / "panda_description/urdf/panda_arm_hand.urdf.xacro", package_paths=[root])


@cache
def reference(robot):
    import yourdfpy

    return yourdfpy.URDF.load(
        io.StringIO(robot.urdf_xml),
        build_scene_graph=True,
        load_meshes=False,
        filename_handler=lambda fname: fname,
    )


def robots():
    out = [marm]
    if (REALWORLD / "ros1").exists():
        out.append(panda)
    return out


@pytest.mark.parametrize("get_robot", robots(), ids=lambda f: f.__name__)
@given(seed=st.integers(0, 2**32 - 1))
def test_fk_matches_yourdfpy(get_robot, seed):
    robot = get_robot()
    q = sample_configurations(robot, np.random.default_rng(seed), 4)
    poses = forward_kinematics(robot, q)
    ref = reference(robot)
    for k in range(len(q)):
        ref.update_cfg(dict(zip(robot.active_joint_names, q[k], strict=True)))
        for name, i in link_index(robot).items():
            np.testing.assert_allclose(poses[k, i], ref.get_transform(name, robot.root), atol=1e-9)


@pytest.mark.parametrize("get_robot", robots(), ids=lambda f: f.__name__)
@given(seed=st.integers(0, 2**32 - 1), data=st.data())
def test_fk_of_some_links_is_the_whole_fk_of_those(get_robot, seed, data):
    """forward_kinematics(links=...) gives the very poses of those links (and their ancestors)."""
    robot = get_robot()
    q = sample_configurations(robot, np.random.default_rng(seed), 3)
    count = len(link_index(robot))
    links = data.draw(st.lists(st.integers(0, count - 1), min_size=1, max_size=3))
    whole, some = forward_kinematics(robot, q), forward_kinematics(robot, q, links)
    assert np.array_equal(some[:, links], whole[:, links])


@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 50))
def test_samples_lie_within_bounds(seed, n):
    q = sample_configurations(marm(), np.random.default_rng(seed), n)
    lower, upper = bounds(marm())
    assert q.shape == (n, 7)
    assert ((lower <= q) & (q <= upper)).all()


@given(seed=st.integers(0, 2**32 - 1))
def test_mimic_joint_follows_its_leader(seed):
    """finger_joint2 mimics finger_joint1 x-1 on the same origin and axis: the fingers mirror."""
    robot = marm()
    assert "finger_joint2" not in robot.active_joint_names
    poses = forward_kinematics(robot, sample_configurations(robot, np.random.default_rng(seed), 8))
    index = link_index(robot)
    joint_origin = poses[:, index["link6"]] @ origin_matrix(
        robot.parent_joint_of["gripper_finger_link1"].origin
    )
    finger1, finger2 = (
        poses[:, index["gripper_finger_link1"], :3, 3],
        poses[:, index["gripper_finger_link2"], :3, 3],
    )
    np.testing.assert_allclose(finger1 + finger2, 2 * joint_origin[:, :3, 3], atol=1e-12)
    assert np.linalg.norm(finger1 - finger2, axis=1).max() > 0


def test_fk_at_zero_stacks_the_urdf_origins():
    robot = marm()
    poses = forward_kinematics(robot, default_configuration(robot))
    index = link_index(robot)
    expected = np.eye(4)
    for link in ("link1", "link2", "link3", "link4", "link5", "link6", "grasping_frame"):
        expected = expected @ origin_matrix(robot.parent_joint_of[link].origin)
        np.testing.assert_allclose(poses[0, index[link]], expected, atol=1e-12)
    assert poses[0, index["grasping_frame"]][2, 3] == pytest.approx(
        0.04 + 0.10 + 0.14 + 0.22 + 0.06 + 0.06 + 0.08
    )


def test_samples_are_a_prefix_for_the_same_seed():
    a = sample_configurations(marm(), np.random.default_rng(7), 10)
    b = sample_configurations(marm(), np.random.default_rng(7), 25)
    np.testing.assert_array_equal(a, b[:10])


def test_bounds_are_the_urdf_limits():
    lower, upper = bounds(marm())
    assert upper.tolist() == [2.96, 2.35, 2.62, 2.62, 2.62, 6.28, 0.06]
    assert lower.tolist() == [-2.96, -2.35, -2.62, -2.62, -2.62, -6.28, 0.0]
