"""`report` timings and page sizes: each stage, in one process, for the marm (init), the panda
(the Setup Assistant's MoveIt 1 package), the PR2 (init) and the Kinova Gen3 + Robotiq (a
vendor's MoveIt 2 package). Robots under ../shared are skipped when absent.

Run: .venv/bin/python benchmarks/bench_report.py
(The command-line figure adds interpreter start-up and imports, about 1 s.)
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

from marm_setup.report.build import build_report

ROOT = Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared"
MARM_URDF = ROOT / "fixtures" / "marm" / "urdf" / "marm.urdf.xacro"
JOBS = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def init(urdf: Path, out: Path, *args: str) -> Path:
    from typer.testing import CliRunner

    from marm_setup.cli.app import app

    result = CliRunner().invoke(app, ["init", str(urdf), "--out", str(out), *args])
    assert result.exit_code == 0, result.output
    return out


def measure(name: str, package: Path, package_paths: tuple[Path, ...] = ()) -> None:
    marks: dict[str, float] = {}
    started = time.perf_counter()

    def progress(stage: str, done: int, total: int) -> None:
        marks[stage] = time.perf_counter() - started

    report = build_report(package, package_paths=package_paths, jobs=JOBS, progress=progress)
    total = time.perf_counter() - started
    faces = sum(len(m.indices) for m in report.meshes)
    before = sum(m.faces_before for m in report.meshes)
    stages = ", ".join(f"{stage} done at {t:.1f} s" for stage, t in marks.items())
    print(
        f"{name:12s} {len(report.html.encode()) / 1e6:5.2f} MB  {total:5.1f} s  "
        f"{len(report.meshes)} meshes, {faces} of {before} triangles  ({stages})"
    )


def main() -> None:
    os.environ["MARM_SETUP_CACHE"] = "off"  # every run proves from scratch, the user's cache untouched
    with tempfile.TemporaryDirectory() as tmp:
        measure(
            "marm",
            init(MARM_URDF, Path(tmp) / "marm", "--setup", str(ROOT / "fixtures/marm/marm_setup.yaml")),
        )
        ros1 = SHARED / "realworld" / "ros1"
        if ros1.is_dir():
            measure("panda", ros1 / "panda_moveit_config", (ros1,))
            measure("pr2", init(ros1 / "pr2_description" / "urdf" / "robot.xml", Path(tmp) / "pr2"))
        kortex = SHARED / "realworld2" / "ros2_kortex"
        if kortex.is_dir():
            package = kortex / "kortex_moveit_config" / "kinova_gen3_6dof_robotiq_2f_85_moveit_config"
            measure("kinova_gen3", package, (kortex, kortex.parent / "ros2_robotiq_gripper"))


if __name__ == "__main__":
    main()
