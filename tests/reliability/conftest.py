"""The generated package the reliability tests start from."""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.conftest import FIXTURES, MARM_URDF
from tests.reliability.checks import assert_clean_exit, run

SPEC = FIXTURES / "marm" / "marm_setup.yaml"


@pytest.fixture
def pkg(tmp_path) -> Path:
    """`tmp_path/pkg`: the marm package init writes from its SPEC (20 trials)."""
    out = tmp_path / "pkg"
    assert_clean_exit(run("init", MARM_URDF, "--out", out, "--setup", SPEC, "--trials", "20"), codes=(0,))
    return out
