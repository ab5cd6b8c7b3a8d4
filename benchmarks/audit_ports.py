"""Audit: ports of published MoveIt config packages keep what moves the robot.

Run: `MARM_AUDIT_PACKAGES=DIR .venv/bin/python benchmarks/audit_ports.py [--only NAME ...]`
(prints a note and exits 0 when DIR is unset or absent).

DIR holds the published repositories, one folder per repository (e.g. extracted from their git
snapshots; never copied into the project). For each package below it runs `init --from-package`
to ros1 and to ros2 (humble), diffs `motion_settings` of the source's package model against the
port's (tests/package_diff.py) and prints, per package and target: the settings in the source,
those carried, those the port report names (changed, dropped or todo), those silently lost,
the report's counts of what moves the robot, and the new package's validation errors.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from typer.testing import CliRunner  # noqa: E402

from marm_setup.cli.app import app  # noqa: E402
from marm_setup.package.read import read_package  # noqa: E402
from marm_setup.robot.load import load_robot  # noqa: E402
from tests.package_diff import motion_settings, unexplained  # noqa: E402

# name -> (layout, config package folder, package path folders), relative to DIR; URDFS: the
# robot description to give (`init URDF --from-package PKG`) where the package does not name it
# (its launch files take it from another package's launch, or build it with xacro by hand)
PACKAGES = {
    "j2s7s300": ("ros1 xml", "kinova-ros/kinova_moveit/robot_configs/j2s7s300_moveit_config", ["kinova-ros"]),
    "m1n6s300": ("ros1 xml", "kinova-ros/kinova_moveit/robot_configs/m1n6s300_moveit_config", ["kinova-ros"]),
    "fanuc_lrmate200id": ("ros1 xml", "fanuc/moveit_cfgs/fanuc_lrmate200id_moveit_config", ["fanuc"]),
    "fanuc_m10ia": ("ros1 xml", "fanuc/moveit_cfgs/fanuc_m10ia_moveit_config", ["fanuc"]),
    "motoman_sia20d": ("ros1 xml", "motoman/motoman_sia20d_moveit_config", ["motoman"]),
    "motoman_ma2010": ("ros1 xml", "motoman/motoman_ma2010_moveit_config", ["motoman"]),
    "abb_irb2400": ("ros1 xml", "abb/abb_irb2400_moveit_config", ["abb"]),
    "abb_irb120": ("ros1 xml", "abb_experimental/abb_irb120_moveit_config", ["abb_experimental", "abb"]),
    "ur10": ("ros1 xml", "universal_robot/ur10_moveit_config", ["universal_robot"]),
    "gen3_7dof": (
        "ros2 python (builder)",
        "ros2_kortex/kortex_moveit_config/kinova_gen3_7dof_robotiq_2f_85_moveit_config",
        ["ros2_kortex", "ros2_robotiq_gripper"],
    ),
    "gen3_lite": (
        "ros2 python (builder)",
        "ros2_kortex/kortex_moveit_config/kinova_gen3_lite_moveit_config",
        ["ros2_kortex", "ros2_robotiq_gripper"],
    ),
    "open_manipulator": (
        "ros2 python",
        "open_manipulator/open_manipulator_moveit_config",
        ["open_manipulator"],
    ),
    "ur_moveit_config": (
        "ros2 python",
        "Universal_Robots_ROS2_Driver/ur_moveit_config",
        ["Universal_Robots_ROS2_Driver", "Universal_Robots_ROS2_Description"],
    ),
    "franka_ros2": ("ros2 python", "franka_ros2/franka_moveit_config", ["franka_ros2"]),
    "fanuc_ros2": ("ros2 python (builder)", "moveit_resources/fanuc_moveit_config", ["moveit_resources"]),
    "dual_arm_panda_ros2": (
        "ros2 python (builder)",
        "moveit_resources/dual_arm_panda_moveit_config",
        ["moveit_resources"],
    ),
    "abb_irb1200_ros2": (
        "ros2 python",
        "abb_ros2/robot_specific_config/abb_irb1200_5_90_moveit_config",
        ["abb_ros2"],
    ),
    "prbt": ("ros2 python (builder)", "moveit2/moveit_planners/test_configs/prbt_moveit_config", ["moveit2"]),
}


URDFS = {
    "open_manipulator": ("open_manipulator/open_manipulator_description/urdf/omx_f/omx_f.urdf.xacro", ()),
    "ur_moveit_config": (
        "Universal_Robots_ROS2_Description/urdf/ur.urdf.xacro",
        ("ur_type:=ur5e", "name:=ur"),
    ),
    "prbt": ("moveit2/moveit_planners/test_configs/prbt_support/urdf/prbt.xacro", ()),
    "franka_ros2": ("franka_ros2/franka_description/robots/panda_arm.urdf.xacro", ("hand:=true",)),
}


# other options a user gives: a package whose description is its own file needs another name
OPTIONS = {"dual_arm_panda_ros2": ("--name", "dual_arm_panda_ported_moveit_config")}


def port(source: Path, paths: list[Path], out: Path, target: str, urdf: list[str]) -> tuple[int, dict | str]:
    args = [a for p in paths for a in ("--package-path", str(p))]
    cmd = ["init", *urdf, "--from-package", str(source), "--out", str(out), "--target", target, "--no-plan"]
    result = CliRunner().invoke(app, [*cmd, *args, "--format", "json", "--jobs", "1"])
    if result.exit_code not in (0, 1):
        return result.exit_code, (result.stdout + result.stderr).strip()[-400:]
    return result.exit_code, json.loads(result.stdout)


def audit(name: str, root: Path, work: Path) -> list[str]:
    layout, folder, paths = PACKAGES[name]
    source, roots = root / folder, [root / p for p in paths]
    urdf, xacro_args = URDFS.get(name, (None, ()))
    given = dict(a.split(":=", 1) for a in xacro_args)
    src = read_package(source, urdf=urdf and root / urdf, package_paths=roots, xacro_args=given or None)
    cli = [a for x in xacro_args for a in ("--xacro-arg", x)] + ([str(root / urdf)] if urdf else [])
    cli += OPTIONS.get(name, ())
    robot = load_robot(src.description_file, dict(src.xacro_args), src.package_paths)
    before = motion_settings(src, robot)
    rows = []
    for target in ("ros1", "ros2"):
        out = work / f"{name}_{target}"
        code, doc = port(source, roots, out, target, cli)
        if isinstance(doc, str):
            rows.append(f"{name} | {layout} | {target} | {len(before)} | CRASH exit {code}: {doc}")
            continue
        after = motion_settings(read_package(out), robot)
        items = doc["port"]["items"]
        lost = unexplained(before, after, items)
        carried = sum(1 for k, v in before.items() if after.get(k) == v)
        named = len(before) - carried - len(lost)
        counts = doc["port"].get("motion_counts")
        errors = doc["validation"]["errors"]
        rows.append(
            f"{name} | {layout} | {target} | {len(before)} | {carried} | {named} | {len(lost)} "
            f"| {counts} | {errors} | {sorted(lost.items())[:6]}"
        )
    return rows


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--only", nargs="*", default=None)
    options = parser.parse_args()
    root = Path(os.environ.get("MARM_AUDIT_PACKAGES", "/nonexistent"))
    if not root.is_dir():
        print("MARM_AUDIT_PACKAGES is unset or absent: nothing audited")
        return
    print(
        "package | layout | target | source settings | carried | named by report | lost | motion counts "
        "| new package's validation errors | lost keys"
    )
    with tempfile.TemporaryDirectory() as work:
        for name in options.only or sorted(PACKAGES):
            if not (root / PACKAGES[name][1]).is_dir():
                print(f"{name} | absent")
                continue
            try:
                rows = audit(name, root, Path(work))
            except Exception as exc:  # an audit reports every package, whatever one does
                rows = [f"{name} | {PACKAGES[name][0]} | - | ERROR {type(exc).__name__}: {exc}"]
            print("\n".join(rows), flush=True)


if __name__ == "__main__":
    main()
