"""The matrix cache (collision/matrix_cache.py): a stored matrix reads back field for field; its
key follows the robot, the settings and the code, not --jobs; a broken cache is skipped."""

from __future__ import annotations

import dataclasses
import json
import sqlite3

import pytest

from marm_setup.collision import CollisionScene, compute_cached_matrix, compute_collision_matrix
from marm_setup.collision.matrix_cache import (
    FILE,
    KEEP,
    load_matrix,
    matrix_from_json,
    matrix_key,
    matrix_to_json,
    store_matrix,
)
from tests.helpers import TWO_BOXES

pytestmark = pytest.mark.usefixtures("own_proof_cache")


@pytest.fixture(scope="module")
def proved(marm):
    """A matrix with every kind of field: proofs (proved, collides, unproved), distances."""
    return compute_collision_matrix(marm, CollisionScene(marm), trials=300, prove="on", distances=True)


def _every_field(matrix):
    return {f.name: getattr(matrix, f.name) for f in dataclasses.fields(matrix) if f.name != "stored"}


def test_a_stored_matrix_reads_back_field_for_field(proved):
    back = matrix_from_json(json.loads(json.dumps(matrix_to_json(proved))))
    assert _every_field(back) == _every_field(proved) and back.stored
    assert [s.proof and (s.proof.witness, s.proof.second) for s in back.stats] == [
        s.proof and (s.proof.witness, s.proof.second) for s in proved.stats
    ]
    assert any(s.proof and s.proof.witness for s in proved.stats)  # the fields are exercised
    assert any(s.min_distance is not None for s in proved.stats)


def test_the_key_follows_the_settings_but_not_the_jobs(marm):
    base = {"trials": 300, "seed": 0, "prove": "on", "distances": True}
    key = matrix_key(marm, 0.0, base)
    assert matrix_key(marm, 0.0, {**base, "jobs": 2, "progress": object()}) == key
    for changed in ({"trials": 301}, {"seed": 1}, {"prove": "off"}, {"distances": False}):
        assert matrix_key(marm, 0.0, {**base, **changed}) != key
    assert matrix_key(marm, 0.01, base) != key


def test_the_key_follows_the_robot_and_its_mesh_bytes(tmp_path):
    from marm_setup.robot.load import load_robot

    mesh = tmp_path / "part.stl"
    mesh.write_text(
        "solid p\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "endloop\nendfacet\nendsolid p\n",
        encoding="utf-8",
    )
    path = tmp_path / "r.urdf"
    box_b = '<link name="b"><collision><geometry><box size="0.1 0.1 0.1"/>'
    path.write_text(
        TWO_BOXES.replace(
            box_b, box_b.replace('<box size="0.1 0.1 0.1"/>', f'<mesh filename="file://{mesh}"/>')
        ),
        encoding="utf-8",
    )
    assert "part.stl" in path.read_text()
    key = matrix_key(load_robot(path), 0.0, {"trials": 10})
    mesh.write_text(mesh.read_text().replace("vertex 0 1 0", "vertex 0 2 0"), encoding="utf-8")
    assert matrix_key(load_robot(path), 0.0, {"trials": 10}) != key


def test_compute_cached_matrix_stores_then_serves_the_same_matrix(marm):
    first = compute_cached_matrix(marm, trials=300, prove="on")
    again = compute_cached_matrix(marm, trials=300, prove="on", jobs=2)
    assert not first.stored and again.stored and _every_field(again) == _every_field(first)


def test_a_broken_cache_file_is_skipped_and_only_the_newest_results_are_kept(proved, tmp_path, monkeypatch):
    monkeypatch.setenv("MARM_SETUP_CACHE", str(tmp_path))
    (tmp_path / FILE).write_bytes(b"not a database")
    assert load_matrix("k") is None
    store_matrix("k", proved)  # unwritable: skipped, no error
    (tmp_path / FILE).unlink()
    for n in range(KEEP + 1):
        store_matrix(f"k{n}", proved)
    assert load_matrix("k0") is None and load_matrix(f"k{KEEP}") == proved
    with sqlite3.connect(tmp_path / FILE) as db:
        db.execute("UPDATE matrices SET value = '{\"disabled\": 1}'")
    assert load_matrix(f"k{KEEP}") is None


def test_a_stored_matrix_tells_the_progress_it_is_done(marm):
    """A report's or init's progress shows the matrix stage done, not skipped, when the result
    is stored (tests/cli/test_progress.py reads the stages off a terminal)."""
    compute_cached_matrix(marm, trials=300, prove="on")
    told: list[tuple[int, int]] = []
    stored = compute_cached_matrix(
        marm, trials=300, prove="on", progress=lambda done, total: told.append((done, total))
    )
    assert stored.stored and told == [(300, 300)]
