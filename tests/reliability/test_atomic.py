"""Whole-package writes: the old package or the new one, never a mix; one writer at a time; no
write through a symlink out of the package; --force keeps a hand edit as `<name>.orig`."""

from __future__ import annotations

import os
import shutil
import stat
import subprocess
import sys

import pytest

from marm_setup.render import switch
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


def _edit_setup(pkg):
    setup = pkg / "marm_setup.yaml"
    setup.write_text(
        setup.read_text().replace("default_velocity_scaling: 0.1", "default_velocity_scaling: 0.3")
    )


def test_one_unwritable_file_leaves_the_whole_package_as_it_was(pkg):
    _edit_setup(pkg)
    (pkg / "config" / "joint_limits.yaml").unlink()
    (pkg / "config" / "joint_limits.yaml").mkdir()  # a folder where a generated file goes
    before = snapshot(pkg)
    assert_one_line_error(run("render", pkg), "config/joint_limits.yaml", "cannot write")
    assert snapshot(pkg) == before
    assert [p.name for p in pkg.parent.iterdir()] == ["pkg"]


def test_a_symlinked_folder_out_of_the_package_is_not_written_through(pkg, tmp_path):
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    for item in (pkg / "launch").iterdir():
        item.rename(outside / item.name)
    (pkg / "launch").rmdir()
    (pkg / "launch").symlink_to(outside)
    for item in outside.iterdir():
        item.unlink()
    assert_one_line_error(run("render", pkg), "'launch' is a symlink")
    assert list(outside.iterdir()) == []


def test_force_keeps_a_hand_edit_as_orig(pkg):
    srdf = pkg / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text() + "<!-- mine -->\n")
    edited = srdf.read_text()
    _edit_setup(pkg)
    assert_one_line_error(run("render", pkg), "hand-edited")
    result = run("render", pkg, "--force")
    assert_clean_exit(result, codes=(0,))
    assert "yours kept as config/marm.srdf.orig" in result.stdout
    assert (pkg / "config" / "marm.srdf.orig").read_text() == edited
    assert "mine" not in srdf.read_text()


def test_modes_follow_the_umask_and_scripts_stay_executable(tmp_path):
    old = os.umask(0o027)
    try:
        out = tmp_path / "pkg"
        assert_clean_exit(run("init", MARM_URDF, "--out", out, "--setup", SPEC, *TRIALS), codes=(0,))
    finally:
        os.umask(old)
    assert stat.S_IMODE((out / "package.xml").stat().st_mode) == 0o640
    assert stat.S_IMODE((out / "scripts" / "trajectory_demo.py").stat().st_mode) == 0o750


def test_a_symlinked_out_stays_a_symlink(tmp_path):
    real = tmp_path / "real"
    real.mkdir()
    link = tmp_path / "link"
    link.symlink_to(real)
    assert_clean_exit(run("init", MARM_URDF, "--out", link, "--setup", SPEC, *TRIALS, "--force"), codes=(0,))
    assert link.is_symlink() and (real / "package.xml").is_file()
    _edit_setup(link)
    assert_clean_exit(run("render", link), codes=(0,))
    assert link.is_symlink() and "0.3" in (real / "config" / "joint_limits.yaml").read_text()


def test_the_in_place_switch_and_its_roll_forward(pkg):
    """The path for a package folder that cannot be renamed (mount point, read-only parent)."""
    before = snapshot(pkg)
    with switch.package_lock(pkg, str(pkg)):
        switch._switch_in_place(pkg, {"package.xml": "<package/>\n"}, {"package.xml"}, str(pkg))
    after = snapshot(pkg)
    assert after["package.xml"] == b"<package/>\n" and after["package.xml.orig"] == before["package.xml"]
    # a run killed after its commit record: the next write completes it
    stage = pkg / ".marm_setup" / "stage-x"
    (stage / "config").mkdir(parents=True)
    (stage / "config" / "kinematics.yaml").write_text("{}\n")
    (pkg / switch.COMMIT).write_text('{"stage": ".marm_setup/stage-x", "files": ["config/kinematics.yaml"]}')
    switch.finish_interrupted(pkg)
    assert (pkg / "config" / "kinematics.yaml").read_text() == "{}\n"
    assert not stage.exists() and not (pkg / switch.COMMIT).exists()


def test_two_concurrent_inits_into_one_new_folder(tmp_path):
    out = tmp_path / "pkg"
    env = {**os.environ, "MARM_SETUP_WRITE_DELAY": "0.05"}
    cmds = [
        [
            sys.executable,
            "-m",
            "marm_setup",
            "init",
            str(MARM_URDF),
            "--out",
            str(out),
            "--target",
            t,
            *TRIALS,
        ]
        for t in ("ros1", "ros2")
    ]
    procs = [
        subprocess.Popen(c, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for c in cmds
    ]
    results = [(p.wait(timeout=300), p.stderr.read()) for p in procs]
    assert all(code in (0, 2) for code, _ in results), results
    assert [code for code, _ in results].count(0) == 1, results
    assert all("Traceback" not in err for _, err in results)
    files = set(snapshot(out))
    ros2 = "config/moveit.yaml" in files
    assert ros2 != ("launch/demo.launch" in files), sorted(files)  # one target's files, not both


def test_a_package_that_is_a_mount_point(tmp_path):
    """The folder cannot be renamed (EBUSY): init and render still write it, in place."""
    if shutil.which("unshare") is None or subprocess.run(["unshare", "-m", "true"]).returncode != 0:
        pytest.skip("needs a private mount namespace (unshare -m, root)")
    out = tmp_path / "pkg"
    out.mkdir()
    cli = f"{sys.executable} -m marm_setup"
    script = f"""set -e
mount -t tmpfs tmpfs {out}
{cli} init {MARM_URDF} --out {out} --setup {SPEC} --trials 20 --force > /dev/null
sed -i 's/default_velocity_scaling: 0.1/default_velocity_scaling: 0.3/' {out}/marm_setup.yaml
{cli} render {out} > /dev/null
grep -q 'default_velocity_scaling_factor: 0.3' {out}/config/joint_limits.yaml
mountpoint -q {out}
ls -A {out}/.marm_setup
"""
    result = subprocess.run(["unshare", "-m", "sh", "-c", script], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout.split() == ["manifest.json"]  # no stage or commit record left
