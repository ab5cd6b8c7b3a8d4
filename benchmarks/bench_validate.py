"""`validate` timings: each stage, in one process, for the shared panda packages, and marm and
the panda as init writes them (init fills a proof cache, in a temporary folder here: the matrix
check skips the Never pairs the cache proves, never those a package says it proved; the figure
beside it resamples them all).

Run: .venv/bin/python benchmarks/bench_validate.py
(The command-line figure adds interpreter start-up and imports, about 0.5 s.)
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

from marm_setup.package.read import read_package
from marm_setup.validate.rules.matrix_rules import cached_proved, check_matrix_fresh, check_matrix_missing
from marm_setup.validate.runner import check_static, load_package_robot, run_runtime_checks, validate

ROOT = Path(__file__).resolve().parent.parent
REALWORLD = ROOT.parent / "shared" / "realworld"
MARM_URDF = ROOT / "fixtures" / "marm" / "urdf" / "marm.urdf.xacro"


def timed(fn):
    start = time.perf_counter()
    value = fn()
    return value, time.perf_counter() - start


def stages(path: Path, package_paths: tuple[Path, ...]) -> None:
    from marm_setup.collision.scene import CollisionScene

    pkg, t_discover = timed(lambda: read_package(path, package_paths=package_paths))
    (robot, _), t_robot = timed(lambda: load_package_robot(pkg))
    _, t_static = timed(lambda: check_static(pkg, robot))
    scene, t_scene = timed(lambda: CollisionScene(robot))
    proved, t_key = timed(lambda: cached_proved(pkg.srdf, scene))
    _, t_every = timed(lambda: check_matrix_fresh(pkg.srdf, robot, scene, pkg.srdf_path))
    _, t_matrix = timed(lambda: check_matrix_fresh(pkg.srdf, robot, scene, pkg.srdf_path, proved=proved))
    _, t_missing = timed(lambda: check_matrix_missing(pkg.srdf, robot, scene, pkg.srdf_path))
    _, t_runtime = timed(lambda: run_runtime_checks(pkg, robot, scene, []))
    found, t_total = timed(lambda: validate(path, package_paths=package_paths).findings)
    _, t_noplan = timed(lambda: validate(path, package_paths=package_paths, plan=False))
    print(
        f"{path.parent.name}/{path.name}: discover+SRDF {t_discover:.2f} s, robot {t_robot:.2f} s, "
        f"static rules {t_static:.3f} s, scene {t_scene:.2f} s, matrix (1000 states) {t_matrix:.2f} s "
        f"({len(proved)} pairs the cache proves skipped, cache read in {t_key:.3f} s; all resampled {t_every:.2f} s), "
        f"enabled pairs (200 states) {t_missing:.2f} s, "
        f"runtime {t_runtime:.2f} s | whole (warm) {t_total:.2f} s, --no-plan {t_noplan:.2f} s, "
        f"{len(found)} findings"
    )


def main() -> None:
    import os

    from typer.testing import CliRunner

    os.environ["MARM_SETUP_CACHE"] = tempfile.mkdtemp(prefix="marm-proof-cache-")  # not the user's

    from marm_setup.cli.app import app

    for target in ("ros1", "ros2"):
        panda = REALWORLD / target / "panda_moveit_config"
        if panda.exists():
            stages(panda, (REALWORLD / target,))
    with tempfile.TemporaryDirectory() as tmp:
        for target in ("ros1", "ros2"):
            out = Path(tmp) / target / "marm_moveit_config"
            CliRunner().invoke(app, ["init", str(MARM_URDF), "--out", str(out), "--target", target])
            stages(out, ())
        description = REALWORLD / "ros1"
        if description.exists():
            out = Path(tmp) / "ros1" / "panda_moveit_config"
            urdf = description / "panda_description" / "urdf" / "panda_arm_hand.urdf.xacro"
            args = ["init", str(urdf), "--package-path", str(description), "--out", str(out)]
            CliRunner().invoke(app, [*args, "--target", "ros1"])
            stages(out, (description,))


if __name__ == "__main__":
    main()
