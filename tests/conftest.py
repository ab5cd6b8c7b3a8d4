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
    """validate uses the real ROS launcher where ROS is sourced (validate/consumers.py): tests
    see no ROS unless they name one (MARM_SETUP_ROS2_PYTHON, MARM_SETUP_ROSLAUNCH)."""
    for name in ("ROS_DISTRO", "MARM_SETUP_ROS2_PYTHON", "MARM_SETUP_ROSLAUNCH"):
        monkeypatch.delenv(name, raising=False)


@pytest.fixture(autouse=True)
def own_proof_cache(monkeypatch, tmp_path_factory, request):
    """Each test gets its own empty proof cache (collision/proof_cache.py), never the user's."""
    folder = tmp_path_factory.getbasetemp() / "proof-caches" / f"{abs(hash(request.node.nodeid)):x}"
    monkeypatch.setenv("MARM_SETUP_CACHE", str(folder))
    monkeypatch.delenv("XDG_CACHE_HOME", raising=False)


@pytest.fixture(scope="session")
def ros2_packages(tmp_path_factory):
    """Every ROS 2 package the tests generate, made once per session (tests/generated_packages.py)."""
    from tests.generated_packages import GeneratedPackages

    return GeneratedPackages(tmp_path_factory.mktemp("ros2_packages"))
