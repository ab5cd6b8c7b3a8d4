"""compute_collision_matrix: ground truth by construction, MoveIt phases, determinism, properties."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from marm_setup.collision import matrix as matrix_module
from marm_setup.collision.matrix import (
    CHUNK,
    CollisionMatrix,
    compute_collision_matrix,
    plan_shards,
    trial_samples,
)
from marm_setup.collision.pairs import DisabledReason
from marm_setup.collision.scene import CollisionScene
from marm_setup.collision.trials import PairShard
from marm_setup.collision.workers import WorkerFailed
from marm_setup.robot.kinematics import sample_configurations
from marm_setup.robot.load import load_robot
from tests.collision_robots import TOY
from tests.conftest import realworld

A, D, X, N, U = (
    DisabledReason.ADJACENT,
    DisabledReason.DEFAULT,
    DisabledReason.ALWAYS,
    DisabledReason.NEVER,
    DisabledReason.USER,
)


@pytest.fixture(scope="module")
def toy(tmp_path_factory):
    path = tmp_path_factory.mktemp("toy") / "toy.urdf"
    path.write_text(TOY, encoding="utf-8")
    return load_robot(path)


@pytest.fixture(scope="module")
def toy_scene(toy):
    return CollisionScene(toy)


@pytest.fixture(scope="module")
def toy_matrix(toy, toy_scene):
    return compute_collision_matrix(toy, toy_scene, trials=500, seed=0)


def _reasons(matrix: CollisionMatrix) -> dict[tuple[str, str], DisabledReason]:
    return {d.pair: d.reason for d in matrix.disabled}


def test_toy_ground_truth(toy_matrix):
    reasons = _reasons(toy_matrix)
    assert reasons[("block", "slider_a")] is X  # 99 % of the range, not at the default
    assert reasons[("slider_d", "stop")] is D  # touching at q=0
    assert ("post", "slider_c") not in reasons  # 30 % of the range: stays enabled
    assert toy_matrix.enabled == (("post", "slider_c"),)
    assert reasons[("base", "tip")] is A  # through geometry-less hub and hub2
    assert reasons[("base", "far")] is A
    assert reasons[("far", "slider_a")] is N
    assert toy_matrix.count(A) == 8 and toy_matrix.count(D) == 1 and toy_matrix.count(X) == 1
    assert toy_matrix.count(N) == 36 - 8 - 1 - 1 - 1


def test_toy_stats(toy_matrix):
    stats = {s.pair: s for s in toy_matrix.stats}
    enabled = stats[("post", "slider_c")]
    assert enabled.reason is None and enabled.seen_colliding and enabled.samples >= 200
    assert 0.2 < enabled.hits / enabled.samples < 0.4  # 30 % by construction
    always = stats[("block", "slider_a")]
    assert always.reason is X and always.hits / always.samples >= 0.95
    never = stats[("far", "slider_a")]
    assert never.reason is N and not never.seen_colliding
    assert never.min_distance == pytest.approx(np.hypot(9.0, 1.0) - 0.05 - 0.05, abs=0.1)
    assert stats[("base", "tip")].min_distance is None  # only Never pairs get a distance


def test_phase_switches(toy, toy_scene):
    no_default = _reasons(compute_collision_matrix(toy, toy_scene, trials=300, check_default=False))
    assert ("slider_d", "stop") not in no_default  # 13 % of the range: enabled
    no_always = _reasons(compute_collision_matrix(toy, toy_scene, trials=300, check_always=False))
    assert ("block", "slider_a") not in no_always
    q0 = np.zeros(len(toy.active_joints))
    q0[toy.active_joint_names.index("jc")] = 0.5  # a default pose with slider_c in the post
    custom = _reasons(compute_collision_matrix(toy, toy_scene, trials=300, default_q=q0))
    assert custom[("post", "slider_c")] is D


def test_a_lower_fraction_disables_more_as_always(toy, toy_scene):
    reasons = _reasons(compute_collision_matrix(toy, toy_scene, trials=300, min_collision_fraction=0.2))
    assert reasons[("post", "slider_c")] is X


def test_marm_fingers_stay_enabled(marm, marm_scene):
    matrix = compute_collision_matrix(marm, marm_scene, trials=1000, seed=0)
    reasons = _reasons(matrix)
    assert ("gripper_finger_link1", "gripper_finger_link2") in matrix.enabled  # they meet mid-stroke
    assert reasons[("gripper_finger_link1", "link6")] is A
    assert reasons[("base_link", "bottom_link")] is A
    assert reasons[("link1", "link2")] is A
    assert ("link3", "link5") in matrix.enabled  # the elbow folds the wrist back onto link3


def test_same_seed_same_matrix_and_jobs_do_not_matter(marm, marm_scene):
    trials = 2 * CHUNK + 300
    one = compute_collision_matrix(marm, marm_scene, trials=trials, seed=3)
    again = compute_collision_matrix(marm, marm_scene, trials=trials, seed=3)
    two = compute_collision_matrix(marm, marm_scene, trials=trials, seed=3, jobs=2)
    assert one == again == two
    assert [s.min_distance for s in one.stats] == [s.min_distance for s in two.stats]


def test_progress_is_reported_in_trials(toy, toy_scene):
    seen = []
    compute_collision_matrix(toy, toy_scene, trials=CHUNK + 5, progress=lambda d, t: seen.append((d, t)))
    assert seen[0] == (0, CHUNK + 5) and seen[-1] == (CHUNK + 5, CHUNK + 5)


def test_trial_samples_are_a_prefix(marm):
    long = trial_samples(marm, 5, 2 * CHUNK + 10)
    np.testing.assert_array_equal(trial_samples(marm, 5, CHUNK + 3), long[: CHUNK + 3])
    assert not np.array_equal(trial_samples(marm, 6, 10), long[:10])


@given(seed=st.integers(0, 2**16), trials=st.integers(0, 400), more=st.integers(1, 800))
def test_properties(marm, marm_scene, seed, trials, more):
    """Canonical, unique, sorted; Adjacent joined by a joint; same seed, same matrix; more trials
    only shrink Never."""
    fewer = compute_collision_matrix(marm, marm_scene, trials=trials, seed=seed)
    assert compute_collision_matrix(marm, marm_scene, trials=trials, seed=seed) == fewer
    pairs = [d.pair for d in fewer.disabled]
    assert all(a < b for a, b in pairs)
    assert pairs == sorted(set(pairs))
    for d in fewer.disabled:
        if d.reason is A:
            assert _joined_through_geometry_less_links(marm, *d.pair)
    never = {d.pair for d in fewer.disabled if d.reason is N}
    more_matrix = compute_collision_matrix(marm, marm_scene, trials=trials + more, seed=seed)
    assert {d.pair for d in more_matrix.disabled if d.reason is N} <= never
    assert {d for d in fewer.disabled if d.reason is not N} == {
        d for d in more_matrix.disabled if d.reason is not N
    }


def _tree_path(robot, a: str, b: str) -> list[str]:
    """Links on the tree path from `a` to `b`, both included."""
    up_a = [a] + [j.parent for j in robot.path_to_root(a)]
    up_b = [b] + [j.parent for j in robot.path_to_root(b)]
    common = next(link for link in up_a if link in up_b)
    return up_a[: up_a.index(common) + 1] + list(reversed(up_b[: up_b.index(common)]))


def _joined_through_geometry_less_links(robot, a: str, b: str) -> bool:
    return all(not robot.link(name).has_geometry for name in _tree_path(robot, a, b)[1:-1])


def test_adjacent_pairs_are_joined_through_geometry_less_links_only(marm, toy_matrix, toy):
    for a, b in marm.adjacent_geometry_pairs():
        assert _joined_through_geometry_less_links(marm, a, b)
    adjacent = [d.pair for d in toy_matrix.disabled if d.reason is A]
    assert all(_joined_through_geometry_less_links(toy, a, b) for a, b in adjacent)
    assert _tree_path(toy, "base", "tip") == ["base", "hub", "hub2", "tip"]


def test_shared_panda_agrees_with_its_shipped_srdf():
    """The panda's shipped SRDF (MoveIt Setup Assistant) against ours at 10k trials."""
    from lxml import etree

    root = realworld("ros1")
    robot = load_robot(root / "panda_description/urdf/panda_arm_hand.urdf.xacro", package_paths=[root])
    ours = _reasons(compute_collision_matrix(robot, trials=10000, seed=0))
    srdf = etree.parse(str(root / "panda_moveit_config/config/panda.srdf")).getroot()
    theirs = {
        tuple(sorted((e.get("link1"), e.get("link2")))): DisabledReason(e.get("reason"))
        for e in srdf.iter("disable_collisions")
    }
    both = ours.keys() & theirs.keys()
    assert all(ours[p] is theirs[p] for p in both)
    assert len(both) >= 0.9 * len(theirs)
    # Measured: 33 in both (same reasons), ours only: panda_hand/panda_link5 and panda_link5/
    # panda_link7 (Default: these meshes touch at zero), theirs only: panda_link2/panda_link6
    # (Never there; we see it collide in 8 of 10,000 states, joint4 near its lower limit).
    assert set(ours) - set(theirs) <= {("panda_hand", "panda_link5"), ("panda_link5", "panda_link7")}
    assert set(theirs) - set(ours) <= {("panda_link2", "panda_link6")}


def _exact_and_fast(robot, trials: int, padding: float = 0.0, jobs: int = 1):
    """The matrix with every state checked exactly (no hull test, no certificates) and with
    the shortcuts, each on its own scene."""
    exact = compute_collision_matrix(robot, CollisionScene(robot, padding), trials=trials, shortcuts=False)
    fast = compute_collision_matrix(robot, CollisionScene(robot, padding), trials=trials, jobs=jobs)
    return exact, fast


def _same_bytes(exact: CollisionMatrix, fast: CollisionMatrix) -> None:
    from marm_setup.collision.matrix_summary import describe_matrix
    from marm_setup.collision.srdf_update import render_minimal_srdf

    assert fast == exact  # disabled, enabled, per-pair stats (hits, seen, min distance)
    assert describe_matrix(fast, "r") == describe_matrix(exact, "r")
    assert render_minimal_srdf("r", fast.disabled) == render_minimal_srdf("r", exact.disabled)


@pytest.mark.parametrize("padding", [0.0, 0.01])
def test_shortcuts_give_the_exhaustive_matrix_on_the_marm(marm, padding):
    exact, fast = _exact_and_fast(marm, 3000, padding)
    _same_bytes(exact, fast)
    assert fast.narrow_calls <= exact.narrow_calls


def test_shortcuts_give_the_exhaustive_matrix_on_the_panda():
    panda = load_robot(realworld("ros1", "panda_description", "urdf", "panda_arm_hand.urdf.xacro"))
    exact, fast = _exact_and_fast(panda, 3000)
    _same_bytes(exact, fast)
    assert fast.work.hull_rejections > 0 and fast.work.certified > 0


def test_shortcuts_give_the_exhaustive_matrix_on_the_pr2_in_two_processes():
    pr2 = load_robot(realworld("ros1", "pr2_description", "urdf", "robot.xml"))
    exact, fast = _exact_and_fast(pr2, 2000, jobs=2)
    _same_bytes(exact, fast)
    # How many exact checks the shortcuts save depends on measured times (the prover keeps a
    # shortcut while it pays), so only the answer is compared, plus the work counted in workers.
    assert fast.work.certified > 0 and fast.work.hull_rejections > 0


def test_work_of_worker_processes_is_counted(marm, monkeypatch):
    monkeypatch.setattr(matrix_module, "WORTH_A_PROCESS", 0.0)  # two processes even for the marm
    trials = 3 * CHUNK
    one = compute_collision_matrix(marm, CollisionScene(marm), trials=trials, shortcuts=False)
    two = compute_collision_matrix(marm, CollisionScene(marm), trials=trials, shortcuts=False, jobs=2)
    assert two == one
    # each pair is checked by one process over all chunks, so no check is done twice
    assert two.narrow_calls == one.narrow_calls > 0


def test_shards_split_the_pairs_by_estimated_cost():
    pairs = tuple((f"a{i}", f"b{i}") for i in range(7))
    costs = dict(zip(pairs, [5.0, 4.0, 3.0, 1.0, 1.0, 1.0, 1.0], strict=True))
    shards = plan_shards(pairs, costs, 2)
    assert sorted(p for shard in shards for p in shard) == sorted(pairs)  # each pair once
    loads = sorted(sum(costs[p] for p in shard) for shard in shards)
    assert loads == [8.0, 8.0]
    assert all(list(shard) == sorted(shard, key=pairs.index) for shard in shards)  # input order kept
    assert plan_shards(pairs, costs, 2) == shards  # deterministic
    assert plan_shards(pairs, dict.fromkeys(pairs, 0.01), 2) == [pairs]  # too small for processes
    assert plan_shards(pairs, costs, 1) == [pairs] and plan_shards((), costs, 4) == []


def test_a_failing_worker_is_an_error_not_a_hang(marm, monkeypatch):
    def broken(self, index):
        raise ValueError("boom")

    monkeypatch.setattr(matrix_module, "WORTH_A_PROCESS", 0.0)
    monkeypatch.setattr(PairShard, "check", broken)  # forked workers inherit the patch
    with pytest.raises(WorkerFailed, match="boom") as failed:
        compute_collision_matrix(marm, CollisionScene(marm), trials=CHUNK, jobs=2)
    assert str(failed.value) == "ValueError: boom"  # one line; the child's traceback is the detail
    assert "Traceback" in failed.value.detail and "in broken" in failed.value.detail


def test_never_pair_distances_are_measured_only_when_asked(marm, marm_scene):
    measured = compute_collision_matrix(marm, marm_scene, trials=500)
    skipped = compute_collision_matrix(marm, marm_scene, trials=500, distances=False)
    assert skipped.disabled == measured.disabled and skipped.enabled == measured.enabled
    assert all(s.min_distance is None for s in skipped.stats)
    assert any(s.min_distance is not None for s in measured.stats)


@pytest.mark.parametrize(
    "robot_path",
    [
        ("ros1", "panda_description", "urdf", "panda_arm_hand.urdf.xacro"),
        ("ros1", "pr2_description", "urdf", "robot.xml"),
    ],
)
def test_no_break_distance_gives_coals_default_verdicts(robot_path):
    """The scene asks coal for no distance lower bound (break_distance 0): every pair's verdict in
    every state is the one coal's default request (break_distance 1 mm) gives, padded or not."""
    robot = load_robot(realworld(*robot_path))
    q = sample_configurations(robot, np.random.default_rng(7), 60)
    for padding in (0.0, 0.01):
        ours, default = CollisionScene(robot, padding), CollisionScene(robot, padding)
        for request in (default._request, default._hull_request):
            request.break_distance = 1e-3
        ids = ours.pair_ids(ours.candidate_pairs)
        for hulls in (False, True):
            expected = default.collision_counts(default.link_poses(q), ids, hulls)
            np.testing.assert_array_equal(ours.collision_counts(ours.link_poses(q), ids, hulls), expected)
        assert expected.sum() > 0


@pytest.mark.parametrize(("batch", "prove"), [(1, "off"), (7, "off"), (200 * 5, "off"), (7, "on")])
def test_filtering_in_pair_batches_gives_the_same_matrix(marm, monkeypatch, batch, prove):
    """The pairs are filtered in batches of at most PAIR_BATCH (state, pair) entries: any batch
    size gives the same matrix, distances included (proved pairs are only tracked for theirs,
    and batches mix them with checked pairs), and the same first collisions."""
    from marm_setup.collision import scene as scene_module

    whole = compute_collision_matrix(marm, CollisionScene(marm), trials=2000, prove=prove)
    assert prove == "off" or any(s.proof and s.min_distance is not None for s in whole.stats)
    q = sample_configurations(marm, np.random.default_rng(3), 50)
    pairs = CollisionScene(marm).candidate_pairs
    first = CollisionScene(marm).first_collisions(q, pairs)
    monkeypatch.setattr(scene_module, "PAIR_BATCH", batch)
    scene = CollisionScene(marm)
    assert len(scene.pair_batches(200, len(pairs))) > 1
    _same_bytes(whole, compute_collision_matrix(marm, scene, trials=2000, prove=prove))
    assert scene.first_collisions(q, pairs) == first


def test_the_shard_plan_prices_a_pair_seen_in_the_rounds_until_its_expected_first_hit():
    """A pair the Always rounds saw in collision stops being checked at its first hit in the
    trials: it is priced for the chunks until then, not for every trial."""
    rounds = matrix_module._AlwaysRounds(
        counts={("a", "b"): (100, 200), ("a", "c"): (0, 200)},
        open_states={("a", "b"): 200, ("a", "c"): 200},
        seconds={("a", "b"): 0.2, ("a", "c"): 0.2},
    )
    costs = rounds.costs(10000)
    per_state = 0.001 + matrix_module.PAIR_OVERHEAD
    assert costs[("a", "b")] == pytest.approx(per_state * matrix_module.CHUNK)
    assert costs[("a", "c")] == pytest.approx(per_state * 10000)


def test_the_rounds_time_exact_checks_with_the_hulls_already_built(marm):
    """The one-time qhull of a link's hull is not charged to the first state that reaches it."""
    scene = CollisionScene(marm)
    real = scene.collide
    pairs = [p for p in scene.candidate_pairs if scene.has_hulls(scene.pair_ids([p])[0])]
    scene._hulls.clear()
    ids = scene.pair_ids(pairs)

    def collide(poses, pair_id, hulls=False):
        assert {int(scene._pair_a[pair_id]), int(scene._pair_b[pair_id])} <= set(scene._hulls)
        return real(poses, pair_id, hulls)

    scene.collide = collide
    poses = scene.link_poses(sample_configurations(marm, np.random.default_rng(0), 50))
    scene.collision_counts(poses, ids, True, opened=np.zeros(len(ids), np.int64), seconds=np.zeros(len(ids)))
    assert pairs
