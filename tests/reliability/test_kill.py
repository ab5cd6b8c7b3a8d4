"""SIGKILL `init --force` and `render` at random points of a slowed write: the package is always
all old or all new, never a mix. `make fuzz` runs many more kills (RELIABILITY_KILLS)."""

from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import sys
import time

import pytest

from tests.conftest import FIXTURES, MARM_URDF
from tests.reliability.checks import assert_clean_exit, run
from tests.reliability.snapshots import snapshot

SPEC = FIXTURES / "marm" / "marm_setup.yaml"
KILLS = int(os.environ.get("RELIABILITY_KILLS", "3"))
DELAY = "0.03"  # [s] after each file written: a slow disk, so kills land inside the write


def _restore(pkg, files: dict[str, bytes]) -> None:
    shutil.rmtree(pkg, ignore_errors=True)
    for rel, data in files.items():
        path = pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(data)
    for leftover in pkg.parent.glob(".pkg.marm-setup-*"):  # a killed run's build folder and its record
        if leftover.is_dir():
            shutil.rmtree(leftover)
        else:
            leftover.unlink()


def _spec_b(tmp_path):
    text = (
        SPEC.read_text()
        .replace("joint2: 0.4285", "joint2: 0.5")
        .replace("package_name: marm_moveit_config", "")
    )
    path = tmp_path / "b.yaml"
    path.write_text(text + "default_velocity_scaling: 0.3\ndefault_acceleration_scaling: 0.2\n")
    return path


def _kill_at_random(cmd: list[str], rng: random.Random, longest: float) -> None:
    env = {**os.environ, "MARM_SETUP_WRITE_DELAY": DELAY}
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(rng.uniform(0.0, longest))
    proc.send_signal(signal.SIGKILL)
    proc.wait()


@pytest.mark.parametrize("command", ["init --force", "render"])
def test_killed_writes_leave_old_or_new(tmp_path, command):
    pkg = tmp_path / "pkg"
    args = ["--trials", "20", "--target", "ros1"]
    assert_clean_exit(run("init", MARM_URDF, "--out", pkg, "--setup", SPEC, *args), codes=(0,))
    old = snapshot(pkg)
    spec_b = _spec_b(tmp_path)
    if command == "render":
        (pkg / "marm_setup.yaml").write_text(
            (pkg / "marm_setup.yaml")
            .read_text()
            .replace("default_velocity_scaling: 0.1", "default_velocity_scaling: 0.3")
        )
        old = snapshot(pkg)
        cmd = [sys.executable, "-m", "marm_setup", "render", str(pkg)]
    else:
        cmd = [
            sys.executable,
            "-m",
            "marm_setup",
            "init",
            str(MARM_URDF),
            "--out",
            str(pkg),
            "--setup",
            str(spec_b),
            *args,
            "--force",
        ]
    started = time.monotonic()
    subprocess.run(cmd, check=True, capture_output=True, env={**os.environ, "MARM_SETUP_WRITE_DELAY": DELAY})
    longest = time.monotonic() - started
    new = snapshot(pkg)
    assert new != old
    rng = random.Random(0)
    outcomes = {"old": 0, "new": 0}
    for _ in range(KILLS):
        _restore(pkg, old)
        _kill_at_random(cmd, rng, longest)
        now = snapshot(pkg)
        assert now in (old, new), sorted(k for k in set(now) | set(old) if now.get(k) != old.get(k))
        outcomes["old" if now == old else "new"] += 1
    print(f"{command}: {KILLS} kills, {outcomes['old']} old, {outcomes['new']} new, 0 mixed")
