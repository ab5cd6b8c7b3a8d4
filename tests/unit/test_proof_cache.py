"""The proof cache (collision/proof_cache.py, proof_keys.py): the same run replays every proof it
left and gives the same matrix, whatever other runs left; the key follows every byte and joint a
proof depends on, and nothing else; progress tells the proofs as they end."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from marm_setup.collision import (
    CollisionScene,
    compute_collision_matrix,
    known_proofs,
    pair_keys,
    remember_proofs,
)
from marm_setup.robot.load import load_robot
from tests.conftest import realworld

pytestmark = pytest.mark.usefixtures("own_proof_cache")  # each test fills its own cache

PANDA = realworld("ros1", "panda_description", "urdf", "panda_arm_hand.urdf.xacro")


@pytest.mark.parametrize("jobs", [1, 2])
def test_a_cached_run_gives_the_same_matrix_with_no_proof_redone(marm, jobs):
    cold = compute_collision_matrix(marm, CollisionScene(marm), trials=2000, prove="on", jobs=jobs)
    remember_proofs(CollisionScene(marm), cold)
    scene = CollisionScene(marm)
    known = known_proofs(scene)
    finished = {s.pair for s in cold.stats if s.proof is not None and s.proof.outcome != "unproved"}
    assert set(known) == finished and finished
    warm = compute_collision_matrix(marm, scene, trials=2000, prove="on", jobs=jobs, known=known)
    assert warm == cold
    unproved = [s for s in cold.stats if s.proof is not None and s.proof.outcome == "unproved"]
    assert warm.work.exact_checks <= cold.work.exact_checks
    assert warm.work.proof_units - sum(k.units for k in known.values()) <= sum(
        s.proof.units for s in unproved
    )


def test_the_same_run_reuses_its_unproved_pairs_too_and_proves_nothing(marm):
    """Within one run's context the unproved proofs come back as well: nothing is proved again
    and the matrix is the same; another seed's context reuses the finished proofs only."""
    from marm_setup.collision import run_context

    def context(seed):
        return run_context(CollisionScene(marm), {"trials": 2000, "seed": seed, "prove": "on"})

    cold = compute_collision_matrix(marm, CollisionScene(marm), trials=2000, prove="on")
    assert any(s.proof is not None and s.proof.outcome == "unproved" for s in cold.stats)
    remember_proofs(CollisionScene(marm), cold, context(0))
    known = known_proofs(CollisionScene(marm), context=context(0))
    assert {p for p, k in known.items() if k.outcome != "seen"} == {s.pair for s in cold.stats if s.proof}
    assert {p for p, k in known.items() if k.outcome == "seen"} <= {
        s.pair for s in cold.stats if s.seen_colliding
    }
    warm = compute_collision_matrix(marm, CollisionScene(marm), trials=2000, prove="on", known=known)
    assert warm == cold and warm.work.proof_units == sum(k.units for k in known.values())
    assert known_proofs(CollisionScene(marm), context=context(1)) == {}  # another run replays nothing


def test_what_other_runs_left_does_not_change_a_matrix(marm):
    """A matrix is the same bytes whatever the cache holds: the proofs runs with other trial
    counts left are not served (their budgets were theirs), its own run's are."""
    from marm_setup.collision import compute_cached_matrix

    fresh = compute_cached_matrix(marm, trials=1000, prove="on")
    for trials in (20, 300):
        compute_cached_matrix(marm, trials=trials, prove="on")
    again = compute_cached_matrix(marm, trials=1000, prove="on")
    assert again == fresh and again.work.proof_units == fresh.work.proof_units


def test_another_proof_budget_is_another_run(marm, monkeypatch):
    """An unproved outcome is its budget's: a cache filled under another plan (an older
    marm-setup) must not serve it, so the plan is part of the run's context."""
    import dataclasses

    from marm_setup.collision import proof, run_context

    settings = {"trials": 2000, "seed": 0, "prove": "on"}
    before = run_context(CollisionScene(marm), settings)
    monkeypatch.setitem(proof.SETTLE, "on", dataclasses.replace(proof.SETTLE["on"], second_pool=1))
    assert run_context(CollisionScene(marm), settings) != before


@pytest.mark.skipif(not PANDA.exists(), reason="../shared/realworld absent")
def test_the_panda_cached_with_distances_is_the_same_matrix():
    robot = load_robot(PANDA)
    cold = compute_collision_matrix(robot, CollisionScene(robot), prove="on", distances=True)
    remember_proofs(CollisionScene(robot), cold)
    scene = CollisionScene(robot)
    warm = compute_collision_matrix(robot, scene, prove="on", distances=True, known=known_proofs(scene))
    assert warm == cold and [s.min_distance for s in warm.stats] == [s.min_distance for s in cold.stats]


def test_prove_off_and_a_cache_that_is_off_or_broken_change_nothing(marm, monkeypatch, tmp_path):
    cold = compute_collision_matrix(marm, CollisionScene(marm), trials=500, prove="on")
    monkeypatch.setenv("MARM_SETUP_CACHE", "off")
    remember_proofs(CollisionScene(marm), cold)
    assert known_proofs(CollisionScene(marm)) == {}
    broken = tmp_path / "broken"
    broken.mkdir()
    (broken / "proofs.sqlite").write_bytes(b"not a database" * 100)
    monkeypatch.setenv("MARM_SETUP_CACHE", str(broken))
    remember_proofs(CollisionScene(marm), cold)  # skipped, no error
    assert known_proofs(CollisionScene(marm)) == {}


TETRA = np.array([[0.0, 0.0, 0.0], [0.05, 0.0, 0.0], [0.0, 0.05, 0.0], [0.0, 0.0, 0.05]])


def _gltf_robot(folder, tool_size: float, upper: float):
    """Base, an arm link (a glTF tetrahedron, its vertices in the .bin buffer) on a revolute
    joint up to `upper`, and a tool box of `tool_size` on another joint; the robot and the
    mesh's file names."""
    import trimesh

    files = trimesh.Trimesh(TETRA, [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]).export(file_type="gltf")
    for name, data in files.items():
        (folder / name).write_bytes(data)
    urdf = f"""<robot name="r">
  <link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="arm"><collision><geometry><mesh filename="model.gltf"/></geometry></collision></link>
  <link name="tool"><collision><geometry><box size="{tool_size} 0.02 0.02"/></geometry></collision></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 0.2"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="{upper}" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="arm"/><child link="tool"/><origin xyz="0.1 0 0"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""
    (folder / "r.urdf").write_text(urdf, encoding="utf-8")
    robot = load_robot(folder / "r.urdf")
    return robot, sorted(files)


def test_the_key_follows_every_byte_and_joint_the_proof_depends_on(tmp_path):
    """Base/arm's key: the same with another tool; another when the joint's range changes, or
    when only the glTF's .bin buffer (not the file the URDF names) does."""
    keys = {}
    for case, (tool, upper) in {
        "first": (0.05, 1.0),
        "other tool": (0.09, 1.0),
        "wider joint": (0.05, 1.5),
    }.items():
        folder = tmp_path / case.replace(" ", "_")
        folder.mkdir()
        robot, _ = _gltf_robot(folder, tool, upper)
        keys[case] = pair_keys(CollisionScene(robot), [("arm", "base"), ("base", "tool")])
    folder = tmp_path / "other_buffer"
    folder.mkdir()
    robot, files = _gltf_robot(folder, 0.05, 1.0)
    vertices = TETRA.astype(np.float32).tobytes()
    buffer = next(folder / name for name in files if vertices in (folder / name).read_bytes())
    assert buffer.suffix == ".bin"
    data = buffer.read_bytes()
    buffer.write_bytes(data.replace(vertices, (TETRA * 0.9).astype(np.float32).tobytes()))
    keys["other buffer"] = pair_keys(CollisionScene(load_robot(folder / "r.urdf")), [("arm", "base")])
    base_arm = {case: k[("arm", "base")] for case, k in keys.items()}
    assert base_arm["other tool"] == base_arm["first"]
    assert base_arm["wider joint"] != base_arm["first"] and base_arm["other buffer"] != base_arm["first"]
    assert keys["other tool"][("base", "tool")] != keys["first"][("base", "tool")]


def test_a_variant_reuses_the_proofs_of_its_unchanged_pairs(marm):
    """The marm with a wider last joint: pairs away from that joint keep their cached proofs."""
    cold = compute_collision_matrix(marm, CollisionScene(marm), trials=500, prove="on")
    remember_proofs(CollisionScene(marm), cold)
    joint = marm.active_joints[-1]
    wider = dataclasses.replace(joint, upper=joint.upper + 0.1)
    variant = dataclasses.replace(marm, joints=tuple(wider if j is joint else j for j in marm.joints))
    known = known_proofs(CollisionScene(variant))
    driven = [j for j in variant.joints if j.name == joint.name or (j.mimic and j.mimic.joint == joint.name)]
    moved = {link for j in driven for link in variant.subtree_links(j.child)}
    finished = {s.pair for s in cold.stats if s.proof is not None and s.proof.outcome != "unproved"}
    assert set(known) == {p for p in finished if not moved & set(p)}
    assert known and set(known) < finished


def test_progress_tells_the_proofs_as_they_end(marm):
    told: list[tuple[int, int, int]] = []
    matrix = compute_collision_matrix(
        marm, CollisionScene(marm), trials=500, prove="on", proof_progress=lambda *c: told.append(c)
    )
    outcomes = [s.proof.outcome for s in matrix.stats if s.proof is not None]
    assert told and told[-1][:2] == (outcomes.count("proved"), outcomes.count("collides"))
    assert all(b[0] >= a[0] and b[1] >= a[1] for a, b in zip(told, told[1:], strict=False))


def test_an_arm_on_a_cart_takes_the_proofs_the_screen_finished_for_the_arm_alone(marm, tmp_path, monkeypatch):
    """The marm's pairs keep their keys on a cart (a box under base_link): the proofs its own
    run's screen finished are taken where the cart's screen budget repeats them step for step
    (proof.PairSearch.least), and the matrix is the one a run without the cache computes."""
    from marm_setup.collision import compute_cached_matrix, describe_matrix
    from marm_setup.collision import matrix as matrix_module
    from tests.conftest import MARM_URDF

    cart = tmp_path / "marm_on_a_cart.urdf.xacro"
    cart.write_text(
        '<robot name="marm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        f'  <xacro:include filename="{MARM_URDF}"/>\n'
        '  <link name="cart"><collision><origin xyz="0 0 -0.3"/><geometry><box size="0.5 0.5 0.5"/>'
        "</geometry></collision></link>\n"
        '  <joint name="cart_joint" type="fixed"><parent link="cart"/><child link="base_link"/></joint>\n'
        "</robot>\n",
        encoding="utf-8",
    )
    robot = load_robot(cart, package_paths=[MARM_URDF.parent.parent.parent])
    compute_cached_matrix(marm, trials=1000, prove="on")
    taken: dict = {}
    real = matrix_module._repeated

    def spy(*args):
        taken.update(real(*args))
        return taken

    monkeypatch.setattr(matrix_module, "_repeated", spy)
    reused = compute_cached_matrix(robot, trials=1000, prove="on", distances=True)
    monkeypatch.setenv("MARM_SETUP_CACHE", "off")
    fresh = compute_cached_matrix(robot, trials=1000, prove="on", distances=True)
    assert taken and not any("cart" in pair for pair in taken)
    assert reused == fresh and describe_matrix(reused, "marm", reused.disabled) == describe_matrix(
        fresh, "marm", fresh.disabled
    )
