"""Shared fixtures: paths, the golden-file protocol (pytest-regressions style), hypothesis profile."""

from __future__ import annotations

import difflib
from pathlib import Path

import pytest
from hypothesis import settings

ROOT = Path(__file__).resolve().parent.parent
FIXTURES = ROOT / "fixtures"
MARM_URDF = FIXTURES / "marm" / "urdf" / "marm.urdf.xacro"
GOLDENS = Path(__file__).resolve().parent / "goldens"
REALWORLD = ROOT.parent / "shared" / "realworld"
REALWORLD2 = ROOT.parent / "shared" / "realworld2"

settings.register_profile("ci", derandomize=True, deadline=None, max_examples=25)
settings.register_profile("dev", deadline=None, max_examples=50)
settings.load_profile("dev")  # a plain `pytest FILE` on a loaded machine: no 200 ms deadline to trip


def pytest_addoption(parser):
    parser.addoption("--update-goldens", action="store_true", help="rewrite golden files (fails once)")


def realworld(*parts: str) -> Path:
    """A path under ../shared/realworld, skipping the test when it is absent."""
    path = REALWORLD.joinpath(*parts)
    if not path.exists():
        pytest.skip(f"{path} not present")
    return path


def realworld2(*parts: str) -> Path:
    """A path under ../shared/realworld2 (vendor packages), skipping the test when it is absent."""
    path = REALWORLD2.joinpath(*parts)
    if not path.exists():
        pytest.skip(f"{path} not present")
    return path


_GOLDENS_READ: set[str] = set()

# The slow tests (marker `slow`): `make check` leaves them out, `make test` and CI run them.
SLOW = (
    "tests/integration/test_ros2_consumer.py",  # the real ROS 2 launch frontend and rcl
    "tests/integration/test_roslaunch.py",  # the real roslaunch
    "tests/integration/test_launch_defects.py",
    "tests/integration/test_wheel.py",  # builds and installs the wheel
    "tests/integration/test_pre_commit_hook.py",  # installs marm-setup into pre-commit's venv
    "tests/integration/test_report_browser.py",  # chromium
    "tests/integration/test_init_every_robot.py",
    "tests/reliability/test_kill.py",  # SIGKILLs during writes
    "tests/reliability/test_bounds.py",  # the 1000- and 3000-link inputs
    "tests/reliability/test_fuzz.py",
    "tests/unit/test_collision_matrix.py::test_shortcuts_give_the_exhaustive_matrix_on_the_pr2_in_two_processes",
)


def pytest_collection_modifyitems(config, items):
    for item in items:
        if item.nodeid.startswith(SLOW):
            item.add_marker(pytest.mark.slow)
    _xdist_groups(config, items)


def _xdist_groups(config, items) -> None:
    """`--dist loadgroup` on pytest >= 9.2: pytest-xdist (3.8) names a test's group by setting
    `item._nodeid`, which pytest 9.2 no longer reads (the id is `item._id`), so every group was
    spread over the workers. Do what it meant to: the test's id ends in `@<group>`."""
    if not getattr(config.option, "loadgroup", False):
        return
    for item in items:
        names = sorted(
            {
                str(m.args[0] if m.args else m.kwargs.get("name", "default"))
                for m in item.iter_markers("xdist_group")
            }
        )
        suffix = "@" + "_".join(names)
        if names and not item.nodeid.endswith(suffix) and hasattr(item, "_id"):
            from _pytest.nodeid import coerce_node_id

            item._id = coerce_node_id(item.nodeid + suffix)
    # the groups first: each runs whole on one worker (the browser's, about 80 s), so started last
    # one would keep that worker busy after the other ran out of tests
    items.sort(key=lambda item: "@" not in item.nodeid)


def pytest_sessionfinish(session):
    """Under pytest-xdist, a worker hands the controller what the summary below reports."""
    from tests.ros2_harness import RUNS

    output = getattr(session.config, "workeroutput", None)
    if output is not None:
        output["ros2_runs"] = list(RUNS)
        output["goldens_read"] = sorted(_GOLDENS_READ)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """pytest-xdist: gather each worker's harness runs and golden files read."""
    from tests.ros2_harness import RUNS

    output = getattr(node, "workeroutput", {})
    RUNS.extend(tuple(run) for run in output.get("ros2_runs", ()))
    _GOLDENS_READ.update(output.get("goldens_read", ()))


def pytest_terminal_summary(terminalreporter):
    """Report golden files no test read (never deleted) and the ROS 2 consumer harness's figures."""
    from tests.ros2_harness import RUNS

    if RUNS:
        total = sum(seconds for _, seconds in RUNS)
        terminalreporter.write_line(
            f"ros2-consumer harness: {len(RUNS)} runs on {len({name for name, _ in RUNS})} packages, "
            f"{total:.1f} s (median {sorted(s for _, s in RUNS)[len(RUNS) // 2]:.2f} s per run)"
        )
    if not _GOLDENS_READ:
        return
    on_disk = {p.relative_to(GOLDENS).as_posix() for p in GOLDENS.rglob("*") if p.is_file()}
    orphans = sorted(p for p in on_disk - _GOLDENS_READ if not p.endswith(".obtained"))
    if orphans:
        terminalreporter.write_sep("-", "golden files no test of this run read (remove them if stale)")
        for path in orphans:
            terminalreporter.write_line(f"  tests/goldens/{path}")


@pytest.fixture
def assert_golden(request):
    """Compare text with tests/goldens/<relpath>; write .obtained and fail with a diff on mismatch."""
    update = request.config.getoption("--update-goldens")

    def check(relpath: str, text: str) -> None:
        _GOLDENS_READ.add(relpath)
        golden = GOLDENS / relpath
        obtained = golden.with_name(golden.name + ".obtained")
        if update or not golden.exists():
            existed = golden.exists()
            old = golden.read_text(encoding="utf-8") if existed else None
            golden.parent.mkdir(parents=True, exist_ok=True)
            golden.write_text(text, encoding="utf-8", newline="\n")
            obtained.unlink(missing_ok=True)
            if old != text:
                pytest.fail(f"golden {relpath} {'updated' if existed else 'created'}: review and commit")
            return
        expected = golden.read_text(encoding="utf-8")
        if expected != text:
            obtained.write_text(text, encoding="utf-8", newline="\n")
            diff = "".join(
                difflib.unified_diff(
                    expected.splitlines(True),
                    text.splitlines(True),
                    f"golden/{relpath}",
                    "obtained",
                )
            )
            pytest.fail(f"golden mismatch for {relpath} (see {obtained.name}):\n{diff}")
        obtained.unlink(missing_ok=True)

    return check


@pytest.fixture(autouse=True)
def no_sourced_ros(monkeypatch):
    """validate uses the real ROS launcher it finds (validate/consumers.py: a sourced ROS, or
    roslaunch / ros2 on PATH): tests see no ROS unless they name one (MARM_SETUP_ROS2_PYTHON,
    MARM_SETUP_ROSLAUNCH; empty turns each off)."""
    monkeypatch.delenv("ROS_DISTRO", raising=False)
    for name in ("MARM_SETUP_ROS2_PYTHON", "MARM_SETUP_ROSLAUNCH"):
        monkeypatch.setenv(name, "")


@pytest.fixture(autouse=True, scope="session")
def session_proof_cache(tmp_path_factory):
    """Tests and fixtures of any scope share a proof cache of the session's (one per pytest-xdist
    worker; collision/proof_cache.py), never the user's: a matrix replays only its own run's
    proofs and gives the same bytes as without the cache, so each run of a robot is proved once
    per worker, not once per test. A test about proving or the cache takes `own_proof_cache`."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MARM_SETUP_CACHE", str(tmp_path_factory.mktemp("proof-cache")))
        patch.delenv("XDG_CACHE_HOME", raising=False)
        yield


@pytest.fixture
def own_proof_cache(monkeypatch, tmp_path_factory, session_proof_cache):
    """This test's own empty proof cache: what it proves, it proves itself."""
    monkeypatch.setenv("MARM_SETUP_CACHE", str(tmp_path_factory.mktemp("proof-cache")))


@pytest.fixture(scope="session")
def ros2_packages(tmp_path_factory):
    """Every ROS 2 package the tests generate, made once per session and shared by the
    pytest-xdist workers (tests/generated_packages.py)."""
    import os

    from tests.generated_packages import GeneratedPackages

    worker = os.environ.get("PYTEST_XDIST_WORKER", "")
    if not worker:
        return GeneratedPackages(tmp_path_factory.mktemp("ros2_packages"))
    # the folder all workers of this run share (each has its own basetemp below it)
    return GeneratedPackages(tmp_path_factory.getbasetemp().parent / "ros2_packages", worker)
