"""The generated package the reliability tests start from."""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from marm_setup.collision.proof_cache import FILE as PROOF_CACHE_FILE
from tests.conftest import FIXTURES, MARM_URDF
from tests.reliability.checks import assert_clean_exit, run

SPEC = FIXTURES / "marm" / "marm_setup.yaml"


@pytest.fixture(scope="session")
def built_pkg(tmp_path_factory) -> tuple[Path, Path]:
    """(the marm package init writes from its SPEC (20 trials), the proof cache that init left),
    made once per session: never handed to a test, only copied."""
    root = tmp_path_factory.mktemp("built_pkg")
    cache = root / "proof-cache"
    with pytest.MonkeyPatch.context() as patch:
        patch.setenv("MARM_SETUP_CACHE", str(cache))
        result = run("init", MARM_URDF, "--out", root / "pkg", "--setup", SPEC, "--trials", "20")
    assert_clean_exit(result, codes=(0,))
    return root / "pkg", cache


@pytest.fixture
def pkg(tmp_path, built_pkg) -> Path:
    """`tmp_path/pkg`: the marm package init writes from its SPEC (20 trials), as if this test had
    run that init: a copy of the session's (same depth, so its relative package path holds), and
    the proofs that init cached in this test's own proof cache."""
    source, cache = built_pkg
    out = tmp_path / "pkg"
    assert len(out.parts) == len(source.parts)
    shutil.copytree(source, out, symlinks=True)
    assert (cache / PROOF_CACHE_FILE).is_file()
    shutil.copytree(cache, Path(os.environ["MARM_SETUP_CACHE"]), dirs_exist_ok=True)
    return out
