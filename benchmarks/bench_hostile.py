"""Huge and hostile inputs (issue 23's bounds): wall time and peak memory of whole CLI runs.

Each case is one `marm-setup` process on an input built in a temporary folder (sparse files
cost no disk); the figures are the process's wall time and its peak resident memory.

Run: .venv/bin/python benchmarks/bench_hostile.py
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from tests.reliability.inputs import chain_urdf, many_poses  # noqa: E402

MARM = ROOT / "fixtures" / "marm" / "urdf" / "marm.urdf.xacro"
SPEC = ROOT / "fixtures" / "marm" / "marm_setup.yaml"


def measure(name: str, *args: object) -> None:
    """One CLI run: its exit code, wall time and peak memory (os.wait4: this child's own)."""
    started = time.perf_counter()
    proc = subprocess.Popen(
        [sys.executable, "-m", "marm_setup", *map(str, args)],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    _, status, usage = os.wait4(proc.pid, 0)
    seconds = time.perf_counter() - started
    code = os.waitstatus_to_exitcode(status)
    print(f"{name:<48} exit {code}  {seconds:6.2f} s  peak {usage.ru_maxrss / 1024:6.0f} MB")


def sparse(path: Path, size: int, head: bytes = b"") -> Path:
    with open(path, "wb") as out:
        out.write(head)
        out.truncate(size)
    return path


def main() -> None:
    work = Path(tempfile.mkdtemp(prefix="bench-hostile-"))
    measure("inspect: a sparse 6 GB URDF", "inspect", sparse(work / "big.urdf", 6 << 30))
    stl = sparse(work / "m.stl", 84 + 50 * 5_000_000, b"\0" * 80 + (5_000_000).to_bytes(4, "little"))
    mesh_robot = work / "mesh.urdf"
    mesh_robot.write_text(
        f'<robot name="m"><link name="a"><collision><geometry><mesh filename="{stl}"/>'
        "</geometry></collision></link></robot>"
    )
    measure("collisions: a 5M-triangle STL (250 MB)", "collisions", mesh_robot, "--trials", "10")
    (work / "chain20k.urdf").write_text(chain_urdf(20_000, geometry_every=100_000))
    measure("inspect: a 20,000-link chain", "inspect", work / "chain20k.urdf")
    (work / "chain1000.urdf").write_text(chain_urdf(1000))
    measure(
        "collisions: 1000 links with geometry, 10 trials",
        "collisions",
        work / "chain1000.urdf",
        "--trials",
        "10",
    )
    measure("collisions: --trials 1000000000 (refused)", "collisions", MARM, "--trials", "1000000000")
    srdf = work / "r.srdf"
    two = work / "two.urdf"
    two.write_text(chain_urdf(1).replace('name="chain"', 'name="test_robot"'))
    srdf.write_text(
        '<robot name="test_robot">\n'
        + "".join(
            f'  <disable_collisions link1="u{i}" link2="v{i}" reason="{"User" if i % 2 else "Never"}"/>\n'
            for i in range(100_000)
        )
        + "</robot>\n"
    )
    measure(
        "collisions --srdf: 100,000 entries", "collisions", two, "--srdf", srdf, "--trials", "10", "--force"
    )
    ws = work / "ws"
    ws.mkdir()
    for i in range(150):
        os.symlink(".", ws / f"loop{i}")
    measure("inspect --package-path: 150 symlinks to '.'", "inspect", MARM, "--package-path", ws)
    pkg = work / "pkg"
    subprocess.run(
        [sys.executable, "-m", "marm_setup", "init", MARM, "--out", pkg, "--setup", SPEC, "--trials", "100"],
        check=True,
        capture_output=True,
    )
    srdf = pkg / "config" / "marm.srdf"
    srdf.write_text(srdf.read_text().replace("<end_effector", many_poses(198) + "<end_effector", 1))
    measure("validate: 200 named poses of one group", "validate", pkg)


if __name__ == "__main__":
    main()
