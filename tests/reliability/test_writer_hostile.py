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
from tests.conftest import FIXTURES
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run
from tests.reliability.packages import edit_setup
from tests.reliability.snapshots import snapshot

SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TRIALS = ("--trials", "20")


def _edit_srdf(pkg):
    srdf = pkg / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text() + "<!-- mine -->\n")


def test_no_overwritten_claim_when_the_write_fails(pkg):
    """The status lines said '(overwritten: --force; ...)' and then the write failed."""
    _edit_srdf(pkg)
    edit_setup(pkg)
    (pkg / "config" / "joint_limits.yaml").unlink()
    (pkg / "config" / "joint_limits.yaml").mkdir()  # a folder where a generated file goes
    result = run("render", pkg, "--force")
    assert_one_line_error(result, "config/joint_limits.yaml", "cannot write")
    assert "overwritten" not in result.stdout


def test_the_overwritten_claim_follows_the_write(pkg):
    _edit_srdf(pkg)
    edit_setup(pkg)
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


def _cli(*args, cwd):
    return subprocess.run(
        [sys.executable, "-m", "marm_setup", *map(str, args)], cwd=cwd, capture_output=True, text=True
    )


def test_render_from_inside_the_package_keeps_its_folder(pkg):
    """`render .` swapped a new folder in and deleted the old one: the shell stood in a deleted
    folder and its next `validate .` was an internal error. A package holding the current
    folder is written in place."""
    before = os.stat(pkg).st_ino
    edit_setup(pkg)
    result = _cli("render", ".", cwd=pkg)
    assert result.returncode == 0, result.stderr
    assert os.stat(pkg).st_ino == before
    assert "default_velocity_scaling_factor: 0.3" in (pkg / "config" / "joint_limits.yaml").read_text()
    assert sorted(os.listdir(pkg / ".marm_setup")) == ["manifest.json"]
    assert _cli("validate", ".", "--no-plan", cwd=pkg).returncode == 0
    edit_setup(pkg, "0.4")  # from a folder inside it, too
    assert _cli("render", "..", cwd=pkg / "config").returncode == 0
    assert os.stat(pkg).st_ino == before


def test_a_command_run_in_a_deleted_folder_is_one_line(tmp_path):
    gone = tmp_path / "gone"
    gone.mkdir()
    script = f"cd {gone} && rmdir {gone} && exec {sys.executable} -m marm_setup validate ."
    result = subprocess.run(["sh", "-c", script], capture_output=True, text=True)
    assert result.returncode == 2
    assert result.stderr.strip().splitlines() == [
        "error: the current folder no longer exists (deleted or replaced, e.g. by a write of the "
        "package it was); cd into it again"
    ]


def _owners(root):
    """{relative path: (uid, gid, mode bits)} of every folder and file below `root`, itself too."""
    paths = [root, *sorted(root.rglob("*"))]
    return {p.relative_to(root).as_posix(): _owner(p) for p in paths if not p.is_symlink()}


def _owner(path):
    info = os.lstat(path)
    return info.st_uid, info.st_gid, stat.S_IMODE(info.st_mode)


@pytest.mark.skipif(os.geteuid() != 0, reason="giving files to another user needs root")
@pytest.mark.parametrize("how", ["swapped", "in place"])
def test_root_keeps_the_owners_groups_and_modes_of_someone_elses_package(pkg, monkeypatch, how):
    """Run as root (sudo) on a package owned by someone else: every folder became root:root and a
    setgid folder lost its group."""
    user, team, other = 4321, 4322, 4323
    for path in [pkg, *pkg.rglob("*")]:
        os.lchown(path, user, team)
    os.chown(pkg / "config", user, other)
    os.chmod(pkg / "config", 0o2775)  # setgid: new files belong to the folder's group
    os.chmod(pkg, 0o750)
    os.chmod(pkg / "config" / "joint_limits.yaml", 0o640)
    before = _owners(pkg)
    edit_setup(pkg)
    if how == "in place":
        monkeypatch.chdir(pkg)  # a package holding the current folder is written in place
    result = run("render", pkg)
    assert_clean_exit(result, codes=(0,))
    assert "update    config/joint_limits.yaml" in result.stdout
    after = _owners(pkg)
    assert {k: v for k, v in after.items() if k in before} == before
    assert after["config/joint_limits.yaml"] == (user, team, 0o640)  # the new version, as the old
    assert os.stat(pkg / "config").st_mode & stat.S_ISGID


@pytest.mark.parametrize(
    "name", [".pkg.marm-setup-abcd1234", ".pkg.marm-setup-backup", ".pkg.marm-setup-x.record"]
)
def test_a_users_folder_named_like_a_build_folder_is_kept(pkg, name):
    """Every write deleted any sibling named like a build folder (`.<pkg>.marm-setup-*`)."""
    mine = pkg.parent / name
    mine.mkdir()
    (mine / "keep.txt").write_text("mine\n")
    edit_setup(pkg)
    assert_clean_exit(run("render", pkg), codes=(0,))
    assert (mine / "keep.txt").read_text() == "mine\n"
    assert sorted(p.name for p in pkg.parent.iterdir()) == sorted([name, "pkg"])


def test_a_killed_runs_recorded_build_folder_is_removed(pkg):
    """A build folder with its record (a run killed before it removed them): the next write
    removes both; the record alone (killed before the folder was made) goes too."""
    build = pkg.parent / ".pkg.marm-setup-0123abcd"
    (build / "config").mkdir(parents=True)
    (build / "config" / "old.yaml").write_text("old\n")
    (pkg.parent / ".pkg.marm-setup-0123abcd.record").touch()
    (pkg.parent / ".pkg.marm-setup-4567cdef.record").touch()
    edit_setup(pkg)
    assert_clean_exit(run("render", pkg), codes=(0,))
    assert [p.name for p in pkg.parent.iterdir()] == ["pkg"]


def _chattr(flag: str, *paths) -> None:
    if shutil.which("chattr") is None:
        pytest.skip("needs chattr")
    result = subprocess.run(["chattr", flag, *map(str, paths)], capture_output=True, text=True)
    if result.returncode != 0:
        pytest.skip(f"chattr {flag} not possible here: {result.stderr.strip()}")


@pytest.fixture
def unpin():
    pinned: list = []
    yield pinned
    for path in pinned:
        subprocess.run(["chattr", "-i", "-a", str(path)], capture_output=True)


@pytest.mark.parametrize("flag", ["+i", "+a"])
def test_an_immutable_file_is_left_as_it_is(pkg, unpin, flag):
    """An unchanged immutable file was copied into the new package (its flag lost) and left in an
    undeletable build folder beside it. Now the package is written in place around it."""
    kinematics = pkg / "config" / "kinematics.yaml"
    unpin.append(kinematics)
    _chattr(flag, kinematics)
    before = os.stat(kinematics).st_ino
    edit_setup(pkg)
    assert_clean_exit(run("render", pkg), codes=(0,))
    assert os.stat(kinematics).st_ino == before  # the same file, flag and all
    assert "default_velocity_scaling_factor: 0.3" in (pkg / "config" / "joint_limits.yaml").read_text()
    assert [p.name for p in pkg.parent.iterdir()] == ["pkg"]
    assert sorted(os.listdir(pkg / ".marm_setup")) == ["manifest.json"]


@pytest.mark.parametrize("what", ["file", "folder"])
def test_an_immutable_file_to_be_written_is_one_line_and_nothing_changes(pkg, unpin, what):
    limits = pkg / "config" / "joint_limits.yaml"
    pinned = limits if what == "file" else limits.parent
    unpin.append(pinned)
    edit_setup(pkg)
    before = snapshot(pkg)
    _chattr("+i", pinned)
    relative = "config/joint_limits.yaml" if what == "file" else "config"
    result = run("render", pkg)
    assert_one_line_error(result, f"'{relative}' is immutable or append-only (chattr +i, +a)")
    assert snapshot(pkg) == before
    assert [p.name for p in pkg.parent.iterdir()] == ["pkg"]
