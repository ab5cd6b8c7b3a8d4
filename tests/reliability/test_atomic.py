"""Whole-package writes: the old package or the new one, never a mix; one writer at a time; no
write through a symlink out of the package; --force keeps a hand edit as `<name>.orig`."""

from __future__ import annotations

import json
import os
import shutil
import stat
import subprocess
import sys

import pytest

from marm_setup.render import commit_record, switch, writer
from tests.conftest import FIXTURES, MARM_URDF
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run
from tests.reliability.packages import edit_setup
from tests.reliability.snapshots import snapshot

SPEC = FIXTURES / "marm" / "marm_setup.yaml"
TRIALS = ("--trials", "20")


def test_one_unwritable_file_leaves_the_whole_package_as_it_was(pkg):
    edit_setup(pkg)
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
    edit_setup(pkg)
    assert_one_line_error(run("render", pkg), "edited by hand")
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
    edit_setup(link)
    assert_clean_exit(run("render", link), codes=(0,))
    assert link.is_symlink() and "0.3" in (real / "config" / "joint_limits.yaml").read_text()


def test_the_in_place_switch_and_its_roll_forward(pkg):
    """The path for a package folder that cannot be renamed (mount point, read-only parent)."""
    before = snapshot(pkg)
    with switch.package_lock(pkg, str(pkg)):
        switch._switch_in_place(
            pkg, {"package.xml": "<package/>\n"}, {"package.xml": "package.xml.orig"}, str(pkg)
        )
    after = snapshot(pkg)
    assert after["package.xml"] == b"<package/>\n" and after["package.xml.orig"] == before["package.xml"]
    # a run killed after its commit record: the next write completes it
    stage = pkg / ".marm_setup" / "stage-x"
    (stage / "config").mkdir(parents=True)
    (stage / "config" / "kinematics.yaml").write_text("{}\n")
    (pkg / commit_record.COMMIT).write_text(
        '{"stage": ".marm_setup/stage-x", "files": ["config/kinematics.yaml"]}'
    )
    switch.finish_interrupted(pkg)
    assert (pkg / "config" / "kinematics.yaml").read_text() == "{}\n"
    assert not stage.exists() and not (pkg / commit_record.COMMIT).exists()


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


def _victim(tmp_path):
    """A folder outside the package that a forged commit record aims at."""
    victim = tmp_path / "victim"
    (victim / "sub").mkdir(parents=True)
    (victim / "sub" / "keep.txt").write_text("mine\n")
    return victim


def _stage_with(pkg, rel="config/evil.txt"):
    stage = pkg / ".marm_setup" / "stage-x"
    (stage / rel).parent.mkdir(parents=True, exist_ok=True)
    (stage / rel).write_text("evil\n")
    return stage


def _forge(pkg, victim, case):
    """Plant the commit record (and what it points at) of one forged-record case."""
    record = {"stage": ".marm_setup/stage-x", "files": ["config/evil.txt"]}
    if case == "absolute stage":
        record = {"stage": str(victim), "files": []}
    elif case == "stage up and out":
        record = {"stage": ".marm_setup/../../victim", "files": ["sub/keep.txt"]}
    elif case == "stage not ours, file up and out":
        (pkg / "a" / "b").mkdir(parents=True)
        (pkg / "evil.txt").write_text("evil\n")
        record = {"stage": "a/b", "files": ["../../evil.txt"]}
    elif case == "file up and out":
        _stage_with(pkg, "evil.txt")
        record["files"] = ["../evil.txt"]
    elif case == "absolute file":
        _stage_with(pkg)
        record["files"] = [str(victim / "sub" / "keep.txt")]
    elif case == "symlinked stage":
        (pkg / ".marm_setup" / "stage-x").symlink_to(victim)
        record["files"] = ["sub/keep.txt"]
    elif case == "symlink in the stage":
        (pkg / ".marm_setup" / "stage-x").mkdir()
        (pkg / ".marm_setup" / "stage-x" / "sub").symlink_to(victim / "sub")
        record["files"] = ["sub/keep.txt"]
    elif case == "symlinked destination folder":
        _stage_with(pkg, "out/evil.txt")
        (pkg / "out").symlink_to(victim)
        record["files"] = ["out/evil.txt"]
    elif case == "the writer's own state":
        _stage_with(pkg, ".marm_setup/commit.json")
        record["files"] = [".marm_setup/commit.json"]
    elif case == "not json":
        return '{"stage":'
    elif case == "not a record":
        return "[1]"
    elif case == "wrong types":
        record = {"stage": 3, "files": 1}
    elif case == "a nul byte":
        record["stage"] = ".marm_setup/stage-x\u0000"
    elif case == "the package itself":
        _stage_with(pkg)
        record["files"] = ["."]
    return json.dumps(record)


FORGED = [
    "absolute stage",
    "stage up and out",
    "stage not ours, file up and out",
    "file up and out",
    "absolute file",
    "symlinked stage",
    "symlink in the stage",
    "symlinked destination folder",
    "the writer's own state",
    "not json",
    "not a record",
    "wrong types",
    "a nul byte",
    "the package itself",
]


@pytest.mark.parametrize("case", FORGED)
def test_a_forged_commit_record_is_refused_and_nothing_touched(pkg, tmp_path, case):
    victim = _victim(tmp_path)
    (pkg / commit_record.COMMIT).write_text(_forge(pkg, victim, case))
    edit_setup(pkg)
    before, around = snapshot(pkg), snapshot(tmp_path)
    links = sorted(p for p in pkg.rglob("*") if p.is_symlink())
    assert_one_line_error(run("render", pkg), f"{pkg}/.marm_setup/commit.json: ")
    assert snapshot(pkg) == before and snapshot(tmp_path) == around
    assert sorted(p for p in pkg.rglob("*") if p.is_symlink()) == links
    assert (victim / "sub" / "keep.txt").read_text() == "mine\n"


def test_a_symlinked_state_folder_is_not_cleaned_through(pkg, tmp_path):
    """`.marm_setup` pointing out of the package: no leftover cleanup, no stage, out there."""
    outside = tmp_path / "outside"
    (outside / "stage-abc").mkdir(parents=True)
    (outside / "stage-abc" / "keep.txt").write_text("mine\n")
    (pkg / ".marm_setup" / "manifest.json").rename(outside / "manifest.json")
    (pkg / ".marm_setup").rmdir()
    (pkg / ".marm_setup").symlink_to(outside)
    edit_setup(pkg)
    assert_one_line_error(run("render", pkg), "'.marm_setup' is a symlink")
    assert sorted(p.name for p in outside.iterdir()) == ["manifest.json", "stage-abc"]
    assert (outside / "stage-abc" / "keep.txt").read_text() == "mine\n"


def test_the_in_place_switch_keeps_every_hand_edit(pkg):
    (pkg / "package.xml.orig").write_text("an earlier edit\n")
    before = snapshot(pkg)
    with switch.package_lock(pkg, str(pkg)):
        switch._switch_in_place(
            pkg, {"package.xml": "<package/>\n"}, {"package.xml": "package.xml.orig.1"}, str(pkg)
        )
    after = snapshot(pkg)
    assert after["package.xml.orig"] == b"an earlier edit\n"
    assert after["package.xml.orig.1"] == before["package.xml"]


def _edit_srdf(pkg, mark):
    srdf = pkg / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text() + f"<!-- {mark} -->\n")
    return srdf.read_text()


@pytest.mark.parametrize("command", ["init", "render"])
def test_force_twice_keeps_both_hand_edits(pkg, command):
    again = ("init", MARM_URDF, "--out", pkg, "--setup", SPEC, *TRIALS, "--force")
    edits = []
    for n, scaling in ((1, "0.3"), (2, "0.4")):
        edits.append(_edit_srdf(pkg, f"mine {n}"))
        if command == "render":
            setup = pkg / "marm_setup.yaml"
            setup.write_text(
                setup.read_text().replace(
                    f"default_velocity_scaling: {'0.1' if n == 1 else '0.3'}",
                    f"default_velocity_scaling: {scaling}",
                )
            )
        assert_clean_exit(run(*again) if command == "init" else run("render", pkg, "--force"), codes=(0,))
    assert (pkg / "config" / "marm.srdf.orig").read_text() == edits[0]
    assert (pkg / "config" / "marm.srdf.orig.1").read_text() == edits[1]


@pytest.mark.parametrize("command", ["init", "render"])
def test_force_says_which_file_keeps_the_hand_edit(pkg, command):
    (pkg / "config" / "marm.srdf.orig").write_text("an earlier edit\n")
    _edit_srdf(pkg, "mine")
    edit_setup(pkg)
    args = (
        ("init", MARM_URDF, "--out", pkg, "--setup", SPEC, *TRIALS) if command == "init" else ("render", pkg)
    )
    result = run(*args, "--force")
    assert_clean_exit(result, codes=(0,))
    line = "conflict  config/marm.srdf (overwritten: --force; yours kept as config/marm.srdf.orig.1)"
    assert line in result.stdout.splitlines()
    assert (pkg / "config" / "marm.srdf.orig").read_text() == "an earlier edit\n"


def test_init_checks_again_under_the_lock_that_its_folder_is_new(tmp_path, monkeypatch):
    """Deterministic form of two concurrent inits: the other one finishes between this one's
    folder check and its planning."""
    out = tmp_path / "pkg"
    plan_writes = writer.plan_writes

    def other_run_first(rendered, out_dir, **options):
        cmd = [sys.executable, "-m", "marm_setup", "init", str(MARM_URDF), "--out", str(out), *TRIALS]
        subprocess.run([*cmd, "--target", "ros1"], check=True, capture_output=True)
        return plan_writes(rendered, out_dir, **options)

    monkeypatch.setattr(writer, "plan_writes", other_run_first)
    result = run("init", MARM_URDF, "--out", out, "--target", "ros2", *TRIALS)
    assert_one_line_error(result, f"{out}: directory exists and is not empty")
    files = set(snapshot(out))
    assert "launch/demo.launch" in files and "config/moveit.yaml" not in files  # ros1's alone


def _in_mount_namespace(script: str) -> subprocess.CompletedProcess[str]:
    if shutil.which("unshare") is None or subprocess.run(["unshare", "-m", "true"]).returncode != 0:
        pytest.skip("needs a private mount namespace (unshare -m, root)")
    return subprocess.run(["unshare", "-m", "sh", "-c", "set -e\n" + script], capture_output=True, text=True)


@pytest.mark.parametrize("mount", ["tmpfs", "bind"])
def test_a_file_system_mounted_inside_the_package_is_left_alone(pkg, tmp_path, mount):
    """A mount point inside the package: written in place; nothing on it deleted or moved."""
    source = tmp_path / "source"
    source.mkdir()
    (pkg / "data").mkdir()
    how = f"mount -t tmpfs tmpfs {pkg}/data" if mount == "tmpfs" else f"mount --bind {source} {pkg}/data"
    edit_setup(pkg)
    script = f"""{how}
echo precious > {pkg}/data/f
{sys.executable} -m marm_setup render {pkg} > /dev/null
grep -q 'default_velocity_scaling_factor: 0.3' {pkg}/config/joint_limits.yaml
mountpoint -q {pkg}/data
cat {pkg}/data/f
ls -A {pkg}/.marm_setup
ls -A {tmp_path}
"""
    result = _in_mount_namespace(script)
    assert result.returncode == 0, result.stderr
    assert "Traceback" not in result.stderr
    assert result.stdout.split() == ["precious", "manifest.json", "pkg", "source"]  # no stage, record, build
    assert list(source.iterdir()) == ([source / "f"] if mount == "bind" else [])


@pytest.mark.parametrize("where", ["sibling build", "in-package stage"])
def test_cleaning_leftovers_stops_at_a_mount_point(pkg, tmp_path, where):
    """A killed run's leftovers are removed, but never what a file system mounted in them holds."""
    leftover = (
        tmp_path / ".pkg.marm-setup-abcd1234"
        if where == "sibling build"
        else pkg / ".marm_setup" / "stage-abcd1234"
    )
    (leftover / "m").mkdir(parents=True)
    (leftover / "old.txt").write_text("old\n")
    if where == "sibling build":  # the record a killed run leaves with it (render.stage_folders)
        (tmp_path / ".pkg.marm-setup-abcd1234.record").touch()
    edit_setup(pkg)
    script = f"""mount -t tmpfs tmpfs {leftover}/m
echo precious > {leftover}/m/f
{sys.executable} -m marm_setup render {pkg} > /dev/null
cat {leftover}/m/f
ls -A {leftover}
"""
    result = _in_mount_namespace(script)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["precious", "m"]


def test_leftover_names_that_are_symlinks_are_not_followed(pkg, tmp_path):
    """A killed run's leftovers are dropped; links named like them are not followed out."""
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "keep.txt").write_text("mine\n")
    (tmp_path / ".pkg.marm-setup-abcd1234").symlink_to(outside)
    (tmp_path / ".pkg.marm-setup-abcd1234.record").touch()
    (pkg / ".marm_setup" / "stage-abcd1234").symlink_to(outside)
    (pkg / ".marm_setup" / "stage-efgh5678" / "sub").mkdir(parents=True)
    (pkg / ".marm_setup" / "stage-efgh5678" / "sub" / "out").symlink_to(outside)
    switch.finish_interrupted(pkg)
    assert [p.name for p in outside.iterdir()] == ["keep.txt"]
    assert not (pkg / ".marm_setup" / "stage-efgh5678").exists()


class _Killed(BaseException):
    """A run killed (SIGKILL) in the middle of moving its staged files in."""


@pytest.mark.parametrize("moved", [0, 1, 5])
def test_a_killed_in_place_switch_is_completed_by_the_next_render(pkg, tmp_path, monkeypatch, moved):
    """Killed after its commit record, `moved` files in: the next render plans against the
    package as the roll-forward leaves it (no false conflict, no 'run again') and completes it."""
    from marm_setup.flows.render import load_package_setup
    from marm_setup.render.package import SETUP_FILE, render_package

    edit_setup(pkg)
    reference = tmp_path / "reference"
    shutil.copytree(pkg, reference)
    assert_clean_exit(run("render", reference), codes=(0,))
    finish = switch.finish_interrupted

    def killed_while_moving(real, shown=None):
        if not (real / commit_record.COMMIT).exists():
            return finish(real, shown)
        record = json.loads((real / commit_record.COMMIT).read_text())
        for rel in record["files"][:moved]:
            os.replace(real / record["stage"] / rel, real / rel)
        raise _Killed

    monkeypatch.setattr(switch, "mount_points_below", lambda root: {root / "a-mount-elsewhere"})
    monkeypatch.setattr(switch, "finish_interrupted", killed_while_moving)
    rendered = [f for f in render_package(*load_package_setup(pkg)) if f.path != SETUP_FILE]
    with pytest.raises(_Killed):
        writer.apply_writes(writer.plan_writes(rendered, pkg), pkg)
    monkeypatch.undo()
    assert (pkg / commit_record.COMMIT).exists()
    result = run("render", pkg)
    assert_clean_exit(result, codes=(0,))
    assert not [line for line in result.stdout.splitlines() if line.startswith("conflict")]
    assert snapshot(pkg) == snapshot(reference)
    assert sorted(os.listdir(pkg / ".marm_setup")) == ["manifest.json"]
