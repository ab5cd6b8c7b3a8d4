"""Batched forward kinematics: time for 10,000 configurations (marm, and the shared panda).

Run: .venv/bin/python benchmarks/bench_fk.py
"""

from __future__ import annotations

import io
import time
from pathlib import Path

import numpy as np

from marm_setup.robot.kinematics import forward_kinematics, sample_configurations
from marm_setup.robot.load import load_robot

ROOT = Path(__file__).resolve().parent.parent
PANDA = ROOT.parent / "shared" / "realworld" / "ros1"


def best_of(fn, repeat: int = 5) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def bench(name: str, robot, n: int = 10_000) -> None:
    import yourdfpy

    q = sample_configurations(robot, np.random.default_rng(0), n)
    batched = best_of(lambda: forward_kinematics(robot, q))
    ref = yourdfpy.URDF.load(
        io.StringIO(robot.urdf_xml), load_meshes=False, filename_handler=lambda fname: fname
    )
    names = robot.active_joint_names
    m = 200
    start = time.perf_counter()
    for row in q[:m]:
        ref.update_cfg(dict(zip(names, row, strict=True)))
    per_config_ref = (time.perf_counter() - start) / m
    print(
        f"{name:6s} {len(robot.links):3d} links  batched FK {n} configs: {batched * 1e3:7.1f} ms"
        f"  ({batched / n * 1e6:.2f} us/config)   yourdfpy: {per_config_ref * 1e6:7.1f} us/config"
        f"  -> {per_config_ref * n / batched:6.0f}x"
    )


def main() -> None:
    bench("marm", load_robot(ROOT / "fixtures/marm/urdf/marm.urdf.xacro"))
    if PANDA.exists():
        bench(
            "panda",
            load_robot(PANDA / "panda_description/urdf/panda_arm_hand.urdf.xacro", package_paths=[PANDA]),
        )


if __name__ == "__main__":
    main()
