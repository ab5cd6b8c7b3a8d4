"""`$(eval)` batched (issue 36): every `$(eval)` of a package read runs in one child process,
bounded as before (each evaluation's deadline, the child's memory, the 1 MiB substitution
bound), and none is left running once the package is read."""

from __future__ import annotations

import os
import time

import pytest

from marm_setup.package import eval_child, substitution
from marm_setup.package.substitution import Scope, SubstitutionError, SubstitutionTooLarge, substitute
from tests.reliability.checks import assert_clean_exit, run
from tests.reliability.hostile_launch import with_args
from tests.validate_helpers import generate_marm


def _evals(ros2: bool, n: int) -> str:
    """`n` args, each `$(eval)` of the one before (ROS 1 whole-attribute form, ROS 2 inline)."""
    use = "var" if ros2 else "arg"
    lines = ['<arg name="e0" default="1"/>']
    for i in range(1, n + 1):
        expr = f"$(var e{i - 1}) + 1" if ros2 else f"e{i - 1} + 1"
        lines.append(f'<arg name="e{i}" default="$(eval {expr})"/>')
    lines.append(f'<param name="evaluated" value="$({use} e{n})"/>')
    return "\n".join(lines)


def _forks(monkeypatch) -> list[int]:
    """The pids of the eval children forked from now on."""
    forked: list[int] = []
    start = eval_child.EvalChild.__init__

    def counting(self, *args, **kwargs) -> None:
        start(self, *args, **kwargs)
        forked.append(self.pid)

    monkeypatch.setattr(eval_child.EvalChild, "__init__", counting)
    return forked


@pytest.mark.parametrize("ros2", [False, True])
def test_a_packages_evals_run_in_one_child_left_running_by_none(tmp_path, monkeypatch, ros2):
    pkg = generate_marm(tmp_path, "ros2" if ros2 else "ros1")
    with_args(pkg, ros2, _evals(ros2, 2000))
    substitution._MEMO.clear()
    forked = _forks(monkeypatch)
    start = time.monotonic()
    result = run("validate", pkg, "--no-plan")
    seconds = time.monotonic() - start
    assert_clean_exit(result)
    assert "launch.substitution" not in result.stdout, result.stdout[-600:]
    assert len(forked) == 1 and eval_child._child is None  # one child for the read, then killed
    with pytest.raises(ChildProcessError):
        os.waitpid(forked[0], os.WNOHANG)  # reaped
    assert seconds < 60, seconds  # a child each: 2000 x ~50 ms


def test_a_session_evaluates_many_in_one_child_and_keeps_the_bounds(monkeypatch, tmp_path):
    substitution._MEMO.clear()
    forked = _forks(monkeypatch)
    monkeypatch.setattr(substitution, "EVAL_SECONDS", 2.0)
    with eval_child.eval_session():
        values = [substitute(f"$(eval {k} * 2)", Scope()) for k in range(300)]
        with pytest.raises(SubstitutionTooLarge, match="grows past 1,048,576 characters"):
            substitute("$(eval [123456789.123456789] * 100000)", Scope())  # str(): 2M characters
        assert len(forked) == 1
        found = substitute("$(eval find('pkg') + '/x')", Scope(find=lambda name: f"/ws/{name}"))
        with pytest.raises(SubstitutionError, match="stopped"):
            monkeypatch.setattr(eval_child.EvalChild, "evaluate", _too_slow)
            substitute("$(eval 1 + 2)", Scope())
        monkeypatch.undo()
        assert substitute("$(eval 2 + 2)", Scope()) == "4"  # a new child after the killed one
    assert values == [str(2 * k) for k in range(300)] and found == "/ws/pkg/x"
    assert eval_child._child is None


def _too_slow(self, request, find, seconds):
    raise eval_child.TimeLimitExceeded(f"did not finish within {seconds:g} s")
