"""Distance certificates: the lever-arm bound holds (property tests with coal), and its parts."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from marm_setup.collision.certificates import CERT_MARGIN, BallStore, joint_levers, pair_motions
from marm_setup.collision.scene import CollisionScene
from marm_setup.robot.kinematics import bounds, sample_configurations
from marm_setup.robot.load import load_robot
from tests.conftest import realworld
from tests.helpers import urdf

ARM = urdf(
    '<link name="base"/>'
    '<link name="arm"><collision><origin xyz="1 0 0"/><geometry><box size="0.2 0.2 0.2"/></geometry></collision></link>'
    '<link name="slide"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>'
    '<link name="twin"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>'
    '<joint name="turn" type="revolute"><parent link="base"/><child link="arm"/><axis xyz="0 0 1"/>'
    '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
    '<joint name="push" type="prismatic"><parent link="arm"/><child link="slide"/><origin xyz="2 0 0"/>'
    '<axis xyz="0 0 1"/><limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>'
    '<joint name="copy" type="revolute"><parent link="base"/><child link="twin"/><origin xyz="0 3 0"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>'
    '<mimic joint="turn" multiplier="-2"/></joint>'
)


@pytest.fixture(scope="module")
def arm(tmp_path_factory):
    path = tmp_path_factory.mktemp("arm") / "arm.urdf"
    path.write_text(ARM, encoding="utf-8")
    return load_robot(path)


def test_levers_by_hand(arm):
    scene = CollisionScene(arm)
    corner = np.hypot(1.1, 0.1)  # farthest box corner from the z axis through the origin
    [(joint, lever)] = joint_levers(arm, "base", "arm", scene.link_points["arm"])
    assert joint.name == "turn" and lever == pytest.approx(corner)
    levers = joint_levers(arm, "base", "slide", scene.link_points["slide"])
    # the sphere's hull points are its bounding cube's corners; above the slide: a ball at x=2
    # of radius sqrt(3)*0.1 grown by half the 0.5 m stroke
    assert [j.name for j, _ in levers] == ["push", "turn"]
    assert levers[0][1] == 1.0
    assert levers[1][1] == pytest.approx(2.0 + np.sqrt(3) * 0.1 + 0.25)


def test_pair_weights_add_both_sides_and_mimic_multipliers(arm):
    scene = CollisionScene(arm)
    (motion,) = pair_motions(arm, scene.link_points, [("arm", "twin")])
    turn = arm.active_joint_names.index("turn")
    twin_lever = np.hypot(0.1, 0.1)  # its cube corners (hull points of the sphere) off its axis
    assert motion.cols.tolist() == [turn]
    assert motion.weights[0] == pytest.approx(np.hypot(1.1, 0.1) + 2.0 * twin_lever)
    (inside,) = pair_motions(arm, scene.link_points, [("arm", "slide")])  # slide rides on arm
    assert inside.cols.tolist() == [arm.active_joint_names.index("push")]
    assert inside.weights.tolist() == [1.0]


def test_ball_store_covers_inside_only(arm):
    scene = CollisionScene(arm)
    (motion,) = pair_motions(arm, scene.link_points, [("arm", "twin")])
    store = BallStore(motion)
    q = np.zeros(len(arm.active_joints))
    assert not store.covers(q[None]).any()
    store.add(q, radius=0.1)
    step = np.zeros_like(q)
    step[motion.cols[0]] = 1.0
    rows = np.array([q, q + 0.99 * 0.1 / motion.weights[0] * step, q + 1.01 * 0.1 / motion.weights[0] * step])
    assert store.covers(rows).tolist() == [True, True, False]


def _check_certificate(robot, scene, data) -> None:
    """Draw a pair and a state; every state inside the certified radius keeps the bound and
    never collides (coal, with the scene's padding)."""
    rng = np.random.default_rng(data.draw(st.integers(0, 2**32 - 1)))
    pair = scene.candidate_pairs[data.draw(st.integers(0, len(scene.candidate_pairs) - 1))]
    pair_id = int(scene.pair_ids([pair])[0])
    (motion,) = pair_motions(robot, scene.link_points, [pair])
    q = sample_configurations(robot, rng, 1)[0]
    d = scene.distance(scene.link_poses(q[None])[0], pair_id)
    radius = d - scene.padding - CERT_MARGIN
    if radius <= 0 or not len(motion.cols):
        return
    lower, upper = bounds(robot)
    for _ in range(6):
        step = np.zeros_like(q)
        step[motion.cols] = rng.standard_normal(len(motion.cols))
        q2 = np.clip(
            q + step * data.draw(st.floats(0.0, 0.999)) * radius / (motion.bound(q + step, q)), lower, upper
        )
        assert motion.bound(q2, q) < radius
        poses = scene.link_poses(q2[None])[0]
        assert scene.distance(poses, pair_id) >= d - motion.bound(q2, q) - 1e-6
        assert not scene.collide(poses, pair_id)


@given(data=st.data())
def test_certified_neighbourhoods_never_collide_on_the_marm(marm, data):
    scene = CollisionScene(marm, padding=data.draw(st.sampled_from([0.0, 0.01])))
    _check_certificate(marm, scene, data)


@pytest.fixture(scope="module")
def pr2_scene():
    robot = load_robot(realworld("ros1", "pr2_description", "urdf", "robot.xml"))
    return robot, CollisionScene(robot)


@given(data=st.data())
def test_certified_neighbourhoods_never_collide_on_the_pr2(pr2_scene, data):
    """Prismatic torso, continuous rolls, mimic fingers, meshes."""
    _check_certificate(*pr2_scene, data)
