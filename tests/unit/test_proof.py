"""Proved Never (collision/proof.py, pair_chain.py, witness.py): sound bounds, proofs that hold
over random states, witnesses in contact, contacts sampling misses, --prove off unchanged.

PROOF_STATES (default 2000) random states check each proved pair of each random robot; the
long run (`make fuzz`) sets 1,000,000.
"""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from marm_setup.collision.matrix import compute_collision_matrix
from marm_setup.collision.pair_chain import pair_chain
from marm_setup.collision.pairs import DisabledReason
from marm_setup.collision.proof import COLLIDES, PROVED, UNPROVED, Budget, PairSearch, prove_pair
from marm_setup.collision.scene import CollisionScene
from marm_setup.collision.witness import descend
from marm_setup.robot.kinematics import bounds, default_configuration
from marm_setup.robot.load import load_robot
from tests.proof_robots import random_robots, rare_urdf, speck_urdf, tilting_bar_urdf, write_meshes

STATES = int(os.environ.get("PROOF_STATES", "2000"))
BLOCK = 20_000  # states checked at a time


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    return write_meshes(tmp_path_factory.mktemp("meshes"))


@pytest.fixture(scope="module")
def rare(tmp_path_factory, meshes):
    path = tmp_path_factory.mktemp("rare") / "rare.urdf"
    path.write_text(rare_urdf(meshes["big_cube"]), encoding="utf-8")
    robot = load_robot(path)
    return robot, CollisionScene(robot)


def _load(tmp_path_factory, text: str):
    path = tmp_path_factory.mktemp("random") / "random.urdf"
    path.write_text(text, encoding="utf-8")
    return load_robot(path)


def _witness_in_contact(scene, pair, witness) -> bool:
    q = default_configuration(scene.robot)
    names = list(scene.robot.active_joint_names)
    for joint, value in witness:
        q[names.index(joint)] = value
    return scene.collide(scene.link_poses(q[None])[0], int(scene.pair_ids([pair])[0]))


def _collisions_in_random_states(scene, pairs, count: int, seed: int) -> dict:
    """Pair -> how many of `count` uniform random states have it in collision."""
    rng = np.random.default_rng(seed)
    lower, upper = bounds(scene.robot)
    ids = scene.pair_ids(pairs)
    hits = np.zeros(len(pairs), dtype=np.int64)
    for start in range(0, count, BLOCK):
        q = lower + rng.random((min(BLOCK, count - start), len(lower))) * (upper - lower)
        hits += scene.collision_counts(scene.link_poses(q), ids)
    return dict(zip(pairs, hits.tolist(), strict=True))


def test_contacts_sampling_misses_are_found_with_their_witness(rare):
    robot, scene = rare
    off = compute_collision_matrix(robot, scene, trials=50, seed=0, prove="off")
    on = compute_collision_matrix(robot, scene, trials=50, seed=0, prove="on")
    rare_pairs = [("nub", "pointer"), ("follower", "stop")]
    never = {d.pair for d in off.disabled if d.reason is DisabledReason.NEVER}
    assert set(rare_pairs) <= never  # 50 trials miss both (about 0.2 % and 0.4 % of their ranges)
    assert set(rare_pairs) <= set(on.enabled)
    stats = {s.pair: s for s in on.stats}
    for pair in rare_pairs:
        proof = stats[pair].proof
        assert proof is not None and proof.outcome == COLLIDES
        assert _witness_in_contact(scene, pair, proof.witness)
    assert dict(stats[("follower", "stop")].proof.witness).keys() == {"slide"}  # the mimic's leader


def test_every_other_pair_of_the_toy_is_proved_surfaces_included(rare):
    robot, scene = rare
    on = compute_collision_matrix(robot, scene, trials=50, seed=0, prove="on")
    never = [s for s in on.stats if s.reason is DisabledReason.NEVER]
    assert never and all(s.proof.outcome == PROVED and s.proof.proved_fraction == 1.0 for s in never)
    # the ball inside the mesh shell: their hulls overlap everywhere, their surfaces never meet
    assert ("inside", "shell") in {s.pair for s in never}


def test_a_witness_comes_from_the_descent_when_the_boxes_run_out(rare):
    robot, scene = rare
    chain = pair_chain(
        robot, ("nub", "pointer"), {link: scene.lever_points(link) for link in ("nub", "pointer")}
    )
    screened = prove_pair(scene, chain, Budget(boxes=1, descent=0))
    assert screened.outcome == UNPROVED and screened.closest  # the root box only
    proof = prove_pair(scene, chain, Budget(boxes=0, descent=2000), seed=3, prior=screened)
    assert proof.outcome == COLLIDES and _witness_in_contact(scene, ("nub", "pointer"), proof.witness)
    assert all(round(v, 6) == v for _, v in proof.witness)  # checked at the values it reports
    assert proof.units > screened.units and proof.proved_fraction == screened.proved_fraction
    assert prove_pair(scene, chain, Budget(boxes=0, descent=2000), seed=3, prior=screened) == proof


def test_a_descent_lands_a_speck_on_a_surface(tmp_path_factory, meshes):
    """A 1 mm cube touches a mesh surface only within a shell 1 mm thick: the descent's steps
    aimed far beyond contact (AIM, halved) pass through it from either side, and only the
    steps aimed just beyond contact (FINE) land in it."""
    robot = _load(tmp_path_factory, speck_urdf(meshes["big_cube"]))
    scene = CollisionScene(robot)
    pair = ("shell", "speck")
    chain = pair_chain(robot, pair, {link: scene.lever_points(link) for link in pair})
    search = PairSearch(scene, chain, Budget(0, 0))
    starts = np.array([[0.3, 0.2], [-0.5, 0.4], [0.1, 1.9], [0.05, 1.3]])  # (turn, out); the last inside
    for start in starts:
        witness, _ = descend(search, start[None].copy(), limit=search.meter.units + 500)
        assert witness and _witness_in_contact(scene, pair, witness), start


@settings(max_examples=int(os.environ.get("PROOF_EXAMPLES", "25")), deadline=None)
@given(data=st.data())
def test_proved_pairs_never_collide_and_witnesses_touch(tmp_path_factory, meshes, data):
    robot = _load(tmp_path_factory, data.draw(random_robots(meshes)))
    padding = data.draw(st.sampled_from((0.0, 0.0, 0.01)))
    scene = CollisionScene(robot, padding)
    matrix = compute_collision_matrix(robot, scene, trials=100, seed=0, prove="on", distances=False)
    proofs = {s.pair: s.proof for s in matrix.stats if s.proof is not None}
    proved = [p for p, proof in proofs.items() if proof.outcome == PROVED]
    if proved:
        hits = _collisions_in_random_states(scene, proved, STATES, seed=data.draw(st.integers(0, 2**16)))
        assert not any(hits.values()), hits
    for pair, proof in proofs.items():
        if proof.outcome == COLLIDES:
            assert pair in matrix.enabled and _witness_in_contact(scene, pair, proof.witness)
        assert 0.0 <= proof.proved_fraction <= 1.0


@settings(deadline=None)
@given(data=st.data())
def test_box_bounds_hold_at_every_state_of_the_box(tmp_path_factory, meshes, data):
    robot = _load(tmp_path_factory, data.draw(random_robots(meshes)))
    scene = CollisionScene(robot)
    pair = data.draw(st.sampled_from(scene.candidate_pairs))
    chain = pair_chain(robot, pair, {link: scene.lever_points(link) for link in pair})
    if not chain.dims:
        return
    rng = np.random.default_rng(data.draw(st.integers(0, 2**16)))
    width = chain.upper - chain.lower
    center = chain.lower + rng.random(chain.dims) * width
    half = width * rng.random(chain.dims) ** 2 / 2
    lo, hi = np.maximum(center - half, chain.lower), np.minimum(center + half, chain.upper)
    box = chain.evaluate(((lo + hi) / 2)[None], ((hi - lo) / 2)[None])
    pair_id = int(scene.pair_ids([pair])[0])
    at_center = scene.shape_distance(pair_id, box.frames[0].pose[0], box.frames[1].pose[0])
    states = lo + rng.random((30, chain.dims)) * (hi - lo)
    states[:8] = np.where(rng.random((8, chain.dims)) < 0.5, lo, hi)  # corners too
    frames = chain.frames(states)
    for k in range(len(states)):
        distance = scene.shape_distance(pair_id, frames[0].pose[k], frames[1].pose[k])
        assert distance >= at_center - box.motion[0] - 1e-6
        assert distance >= box.ball_gap[0] - 1e-6
        assert distance >= box.axis_gap[0] - 1e-6


def test_the_separating_direction_bound_holds_and_is_tight(tmp_path_factory):
    """The bar pans over the plate and tilts towards it: along the plate's normal (the pan
    axis) the bound is the gap less the tilt's share; it holds at every state of small boxes
    and comes within a few per cent of the smallest distance there (a share halved would not
    hold); the pan alone never changes the gap, so a box of the whole pan range is proved."""
    robot = _load(tmp_path_factory, tilting_bar_urdf())
    scene = CollisionScene(robot)
    pair = ("bar", "plate")
    chain = pair_chain(robot, pair, {link: scene.lever_points(link) for link in pair})
    pair_id = int(scene.pair_ids([pair])[0])
    rng = np.random.default_rng(5)
    slack = []
    for _ in range(20):
        center = chain.lower + rng.random(2) * (chain.upper - chain.lower)
        half = np.array([0.5, 0.02])
        box = chain.evaluate(center[None], half[None])
        states = center + (2 * rng.random((200, 2)) - 1) * half
        states[:4] = center + half * np.array([[-1, -1], [-1, 1], [1, -1], [1, 1]])
        frames = chain.frames(states)
        smallest = min(
            scene.shape_distance(pair_id, frames[0].pose[k], frames[1].pose[k]) for k in range(len(states))
        )
        assert smallest >= box.axis_gap[0] - 1e-9
        slack.append((smallest - box.axis_gap[0]) / smallest)
    assert min(slack) < 0.05
    whole = chain.evaluate(((chain.lower + chain.upper) / 2)[None], np.array([[3.0, 0.0]]))
    assert whole.axis_gap[0] == pytest.approx(0.2 - 0.01 - 0.005, abs=1e-6)
    assert whole.ball_gap[0] < 0 and whole.motion[0] > 0.5


def test_jobs_and_repeats_do_not_change_proofs(marm, marm_scene):
    one = compute_collision_matrix(marm, marm_scene, trials=500, seed=2, prove="on", jobs=1)
    two = compute_collision_matrix(marm, CollisionScene(marm), trials=500, seed=2, prove="on", jobs=2)
    assert one == two and [s.proof for s in one.stats] == [s.proof for s in two.stats]
    assert any(s.proof is not None for s in one.stats)


@pytest.mark.parametrize("start", ["fork", "spawn"])
def test_a_pool_of_workers_proves_what_one_process_does(marm, marm_scene, monkeypatch, start):
    """Pairs handed out to forked or spawned workers (collision/proof_pool.py) get the very
    proofs one process gives them, in the same order."""
    import multiprocessing

    from marm_setup.collision import proving

    pairs = list(marm_scene.candidate_pairs[::5])
    alone = proving.prove_pairs(marm_scene, pairs, Budget(300, 200), seed=1, jobs=1)
    monkeypatch.setattr(proving, "WORTH_A_POOL", 0)
    monkeypatch.setattr(multiprocessing, "get_all_start_methods", lambda: [start])
    pooled = proving.prove_pairs(CollisionScene(marm), pairs, Budget(300, 200), seed=1, jobs=2)
    assert list(pooled) == list(alone) and pooled == alone
    assert {proof.outcome for proof in alone.values()} >= {PROVED}


def test_a_worker_that_raises_fails_the_pool_with_its_message(marm_scene, monkeypatch):
    from marm_setup.collision import proof_pool, proving
    from marm_setup.collision.workers import WorkerFailed

    def broken(*args, **kwargs):
        raise ValueError("no proof today")

    monkeypatch.setattr(proving, "WORTH_A_POOL", 0)
    monkeypatch.setattr(proof_pool, "prove_pair", broken)  # forked workers inherit it
    with pytest.raises(WorkerFailed, match="no proof today"):
        proving.prove_pairs(marm_scene, list(marm_scene.candidate_pairs[:4]), Budget(50, 0), jobs=2)


def test_the_pair_box_folds_turning_joints_to_one_turn(tmp_path_factory):
    text = (
        '<?xml version="1.0"?><robot name="r"><link name="a"><collision><geometry><box size="0.1 0.1 0.1"/>'
        '</geometry></collision></link><link name="b"><collision><origin xyz="0.3 0 0"/><geometry>'
        '<sphere radius="0.05"/></geometry></collision></link><joint name="j" type="revolute"><parent link="a"/>'
        '<child link="b"/><axis xyz="0 0 1"/><limit lower="-6.2832" upper="6.2832" velocity="1" effort="1"/>'
        "</joint></robot>"
    )
    robot = _load(tmp_path_factory, text)
    scene = CollisionScene(robot)
    chain = pair_chain(robot, ("a", "b"), {link: scene.lever_points(link) for link in "ab"})
    assert chain.upper[0] - chain.lower[0] == pytest.approx(2 * np.pi)


@settings(max_examples=int(os.environ.get("PROOF_EXAMPLES", "25")), deadline=None)
@given(data=st.data())
def test_a_finished_branch_and_bound_is_the_same_at_every_budget_from_its_least(
    tmp_path_factory, meshes, data
):
    """What lets another run take a proof the screen finished (proof_cache, matrix._repeated):
    from `least` boxes up, the branch and bound goes step for step as it did, so its outcome,
    share and units are the same."""
    from marm_setup.collision.pair_chain import pair_chains

    robot = _load(tmp_path_factory, data.draw(random_robots(meshes)))
    scene = CollisionScene(robot, data.draw(st.sampled_from((0.0, 0.01))))
    pairs = [p for p in scene.candidate_pairs if p not in robot.adjacent_geometry_pairs()]
    chains = pair_chains(scene, pairs)
    for pair in pairs:
        budget = data.draw(st.sampled_from((64, 150, 600, 3000)))
        proof = PairSearch(scene, chains[pair], Budget(budget, 0)).run()
        if proof.outcome == UNPROVED or proof.least is None:
            continue
        assert proof.least <= budget
        for again in sorted({proof.least, proof.least + 1, budget, 4 * budget}):
            redone = PairSearch(scene, chains[pair], Budget(again, 0)).run()
            fields = (redone.outcome, redone.proved_fraction, redone.witness, redone.units, redone.least)
            assert fields == (proof.outcome, proof.proved_fraction, proof.witness, proof.units, proof.least)
