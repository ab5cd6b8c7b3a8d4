"""The writer on packages it does not own or did not leave as it found them: another user's
package written as root keeps its owners, groups and modes; a user's folder named like a stage
is never deleted; writing the package the shell stands in keeps that folder; immutable files
neither block the switch nor leave undeletable folders; status lines say only what happened;
validate says when a package is half-written."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys

import pytest

from marm_setup.render import commit_record
from tests.conftest import FIXTURES, MARM_URDF
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run
from tests.reliability.snapshots import snapshot

SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TRIALS = ("--trials", "20")


@pytest.fixture
def pkg(tmp_path):
    out = tmp_path / "pkg"
    assert_clean_exit(run("init", MARM_URDF, "--out", out, "--setup", SPEC, *TRIALS), codes=(0,))
    return out


def _edit_setup(pkg, value="0.3"):
    setup = pkg / "marm_setup.yaml"
    text = setup.read_text()
    old = next(v for v in ("0.1", "0.3", "0.4") if f"default_velocity_scaling: {v}" in text)
    setup.write_text(text.replace(f"default_velocity_scaling: {old}", f"default_velocity_scaling: {value}"))


def _edit_srdf(pkg):
    srdf = pkg / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text() + "<!-- mine -->\n")


def test_no_overwritten_claim_when_the_write_fails(pkg):
    """The status lines said '(overwritten: --force; ...)' and then the write failed."""
    _edit_srdf(pkg)
    _edit_setup(pkg)
    (pkg / "config" / "joint_limits.yaml").unlink()
    (pkg / "config" / "joint_limits.yaml").mkdir()  # a folder where a generated file goes
    result = run("render", pkg, "--force")
    assert_one_line_error(result, "config/joint_limits.yaml", "cannot write")
    assert "overwritten" not in result.stdout


def test_the_overwritten_claim_follows_the_write(pkg):
    _edit_srdf(pkg)
    _edit_setup(pkg)
    result = run("render", pkg, "--force")
    assert_clean_exit(result, codes=(0,))
    assert (
        "conflict  config/marm.srdf (overwritten: --force; yours kept as config/marm.srdf.orig)"
        in result.stdout
    )


def _half_written(pkg):
    """What a run killed after its commit record leaves: a staged file not yet moved in."""
    stage = pkg / ".marm_setup" / "stage-x"
    (stage / "config").mkdir(parents=True)
    (stage / "config" / "kinematics.yaml").write_text((pkg / "config" / "kinematics.yaml").read_text())
    (pkg / commit_record.COMMIT).write_text(
        '{"stage": ".marm_setup/stage-x", "files": ["config/kinematics.yaml"]}'
    )


def test_validate_says_a_package_is_half_written(pkg):
    """It said 'no findings'."""
    _half_written(pkg)
    result = run("validate", pkg, "--no-plan")
    assert_clean_exit(result, codes=(0,))
    assert "package.half-written" in result.stdout
    assert "1 file staged but not moved in (config/kinematics.yaml)" in result.stdout
    assert "the next write (marm-setup render) completes it" in result.stdout
    assert_clean_exit(run("render", pkg), codes=(0,))
    assert "package.half-written" not in run("validate", pkg, "--no-plan").stdout
