"""The pre-commit hook (.pre-commit-hooks.yaml) run by pre-commit itself in a test repository: it
blocks a commit touching a broken config package and lets one touching a clean package pass.

The hook is taken from this checkout's .pre-commit-hooks.yaml as a `repo: local` hook whose
environment installs this checkout (pre-commit's `language: python`: a venv of its own, the
dependencies from the configured index), so the working tree is what runs, committed or not.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys

import pytest
import yaml

from tests.conftest import ROOT
from tests.validate_helpers import generate_marm, replace_text

pytest.importorskip("pre_commit")
pytestmark = pytest.mark.wheel  # installs the package into pre-commit's own venv


@pytest.fixture(scope="session")
def pre_commit_home(tmp_path_factory):
    """One pre-commit cache for the session: the hook's environment is built once."""
    return tmp_path_factory.mktemp("pre_commit_home")


@pytest.fixture
def repo(tmp_path):
    """A git repository with a clean marm package and its broken copy, and a config using the hook."""
    if shutil.which("git") is None:
        pytest.skip("git is not installed")
    subprocess.run(["git", "init", "-q", str(tmp_path)], check=True)
    hooks = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text(encoding="utf-8"))
    hook = {
        **next(h for h in hooks if h["id"] == "marm-setup-validate"),
        "additional_dependencies": [str(ROOT)],
    }
    config = {"repos": [{"repo": "local", "hooks": [hook]}]}
    (tmp_path / ".pre-commit-config.yaml").write_text(yaml.safe_dump(config), encoding="utf-8")
    (tmp_path / "robots").mkdir()
    clean = generate_marm(tmp_path / "robots", "ros1")
    broken = tmp_path / "robots" / "broken"
    shutil.copytree(clean, broken)
    replace_text(broken, "config/marm.srdf", 'joint name="joint1"', 'joint name="jointX"')
    subprocess.run(["git", "-C", str(tmp_path), "add", "-A"], check=True)
    return tmp_path


def _pre_commit(repo, home, *files: str) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PRE_COMMIT_HOME": str(home), "PRE_COMMIT_COLOR": "never"}
    argv = [sys.executable, "-m", "pre_commit", "run", "--files", *files]
    return subprocess.run(argv, cwd=repo, env=env, capture_output=True, text=True, timeout=900)


def test_the_hook_fails_on_a_broken_package_and_passes_on_a_clean_one(repo, pre_commit_home):
    broken = _pre_commit(repo, pre_commit_home, "robots/broken/config/marm.srdf", "robots/broken/package.xml")
    assert broken.returncode == 1, broken.stdout + broken.stderr
    assert "marm-setup validate" in broken.stdout and "Failed" in broken.stdout
    assert "unknown joint 'jointX' [pose.unknown-joint]" in broken.stdout
    assert broken.stdout.count("validated marm_moveit_config") == 1  # the package once, for two files
    clean = _pre_commit(repo, pre_commit_home, "robots/marm_ros1/config/marm.srdf")
    assert clean.returncode == 0, clean.stdout + clean.stderr
    assert "Passed" in clean.stdout
