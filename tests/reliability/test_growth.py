"""Bounds before spending (issue 36): launch args and Python launch values that double themselves,
launch files that include themselves, Python launch files too large or nested too deeply end in
one finding, within the bounds, never an internal error or MemoryError."""

from __future__ import annotations

import pytest

from marm_setup.package.launch_python import MAX_AST_DEPTH, PYTHON_LAUNCH_BYTES, STATIC_ITEMS
from marm_setup.package.substitution import SUBSTITUTED_CHARS
from tests.reliability.checks import assert_clean_exit, run
from tests.reliability.hostile_launch import growing_args, python_launch, self_including, with_args
from tests.validate_helpers import generate_marm


@pytest.mark.parametrize("ros2", [False, True])
@pytest.mark.parametrize(("steps", "copies"), [(39, 2), (13, 3), (6, 10), (3, 100)])
def test_args_built_from_themselves_stop_at_the_bound(tmp_path, ros2, steps, copies):
    pkg = generate_marm(tmp_path, "ros2" if ros2 else "ros1")
    with_args(pkg, ros2, growing_args(ros2, steps, copies))
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result)
    grows = 2 * copies**steps > SUBSTITUTED_CHARS
    assert ("launch.substitution-bound" in result.stdout) == grows, result.stdout[-600:]


@pytest.mark.parametrize("ros2", [False, True])
@pytest.mark.parametrize(("copies", "new_args"), [(2, False), (5, False), (2, True), (3, True)])
def test_a_launch_file_including_itself_is_walked_once_per_args(tmp_path, ros2, copies, new_args):
    pkg = generate_marm(tmp_path, "ros2" if ros2 else "ros1")
    self_including(pkg, ros2, copies, new_args)
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result)
    assert "launch.missing-file" not in result.stdout
    assert ("launch.include-bound" in result.stdout) == new_args, result.stdout[-600:]


CASES = [
    ("sum", 20_000, "nest too deeply"),
    ("unary", 3_000, "nest too deeply"),
    ("negations", 3_000, "nest"),
    ("unary", MAX_AST_DEPTH + 5, "nested more than"),
    ("string", 40, "grows past"),
    ("list", 40, "grows past"),
    ("fstring", 40, "grows past"),
    ("size", PYTHON_LAUNCH_BYTES + 1, "too large"),
]


@pytest.mark.parametrize(("kind", "n", "says"), CASES)
def test_a_python_launch_file_past_the_bounds_is_one_finding(tmp_path, kind, n, says):
    pkg = generate_marm(tmp_path, "ros2")
    (pkg / "launch" / "x.launch.py").write_text(python_launch(kind, n), encoding="utf-8")
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result)
    assert result.stdout.count("[launch.python-unread]") == 1 and says in result.stdout, result.stdout[-600:]


@pytest.mark.parametrize("kind", ["string", "list", "fstring", "nested list"])
def test_a_python_launch_value_under_the_bound_is_read(tmp_path, kind):
    """Under the bound the file is read; a list nested by reference is never printed whole."""
    pkg = generate_marm(tmp_path, "ros2")
    steps = 60 if kind == "nested list" else (STATIC_ITEMS // 4).bit_length() - 2
    (pkg / "launch" / "x.launch.py").write_text(python_launch(kind, steps), encoding="utf-8")
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result)
    assert "launch.python-unread" not in result.stdout


@pytest.mark.parametrize("outcome", ["proved", "unproved"])
def test_the_proof_summary_compares_no_pairs(outcome):
    """The summary's proved/unproved split is one pass over the pairs (it was a list membership
    test per pair: quadratic, 18.5 s at 150 links): pairs that refuse comparison still summarise."""
    from dataclasses import dataclass

    from marm_setup.collision.matrix import CollisionMatrix, PairStats
    from marm_setup.collision.proof import PairProof
    from marm_setup.collision.proof_summary import proof_lines
    from marm_setup.setup.model import DisabledReason

    @dataclass(frozen=True, eq=False)
    class Incomparable(PairStats):
        def __eq__(self, other):
            raise AssertionError("a pair compared with another")

        __hash__ = object.__hash__

    never = DisabledReason.NEVER
    stats = tuple(
        Incomparable(
            f"a{i:04d}", f"b{i:04d}", never, proof=PairProof(outcome, 1.0 if outcome == "proved" else 0.5)
        )
        for i in range(2000)
    )
    matrix = CollisionMatrix(
        (), (), stats, trials=100, seed=0, min_collision_fraction=0.95, padding=0.0, prove="on"
    )
    lines = proof_lines(matrix, {s.pair: never for s in stats})
    proved = 2000 if outcome == "proved" else 0
    assert lines[0].startswith(f"proof (--prove on): {proved} of 2000 Never pairs proved")
    assert len(lines) == 1 + (2000 - proved)
