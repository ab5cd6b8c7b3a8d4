"""`init` without a SPEC on every robot description we have: the shared real-world robots
(../shared/realworld*, skipped when absent) and the synthetic fixtures. Each exits 0, and the
package it writes validates with 0 errors, planning included, with at least one pose pair
planned per arm, and per limb of two or more joints (DESIGN §2: a collision-free `home` and a
second pose per limb)."""

from __future__ import annotations

import json

import pytest
import yaml
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import FIXTURES, realworld, realworld2

runner = CliRunner()

# name: (URDF under ../shared, package path roots, xacro args)
SHARED = {
    "panda_ros1": ("realworld/ros1/panda_description/urdf/panda_arm_hand.urdf.xacro", ["realworld/ros1"], []),
    "panda_ros2": ("realworld/ros2/panda_description/urdf/panda.urdf", ["realworld/ros2"], []),
    "pr2": ("realworld/ros1/pr2_description/urdf/robot.xml", ["realworld/ros1"], []),
    "ur5e": ("realworld2/universal_robot/ur_description/urdf/ur5e.xacro", ["realworld2/universal_robot"], []),
    "fanuc_cr7ia": ("realworld2/fanuc/fanuc_cr7ia_support/urdf/cr7ia.xacro", ["realworld2/fanuc"], []),
    "motoman_sda10f": (
        "realworld2/motoman/motoman_sda10f_support/urdf/sda10f.xacro",
        ["realworld2/motoman"],
        [],
    ),
    "kinova_j2n6s300": (
        "realworld2/kinova-ros/kinova_description/urdf/j2n6s300_standalone.xacro",
        ["realworld2/kinova-ros"],
        [],
    ),
    "dual_panda": (
        "realworld2/moveit_resources_master/panda_description/urdf/dual_panda.urdf.xacro",
        ["realworld2/moveit_resources_master"],
        [],
    ),
    "kinova_gen3_robotiq": (
        "realworld2/ros2_kortex/kortex_description/robots/gen3.xacro",
        ["realworld2/ros2_kortex", "realworld2/ros2_robotiq_gripper"],
        ["gripper:=robotiq_2f_85", "dof:=6"],
    ),
}
SYNTHETIC = sorted(p.stem for p in (FIXTURES / "synthetic").glob("*.urdf"))


def _shared(rel: str):
    kind, _, rest = rel.partition("/")
    return realworld(*rest.split("/")) if kind == "realworld" else realworld2(*rest.split("/"))


def _init_and_validate(tmp_path, urdf, roots, xacro_args) -> tuple[dict, dict]:
    out = tmp_path / "pkg"
    paths = [a for root in roots for a in ("--package-path", str(root))]
    args = [a for x in xacro_args for a in ("--xacro-arg", x)]
    made = runner.invoke(
        app, ["init", str(urdf), "--out", str(out), "--trials", "300", "--jobs", "1", *paths, *args]
    )
    assert made.exit_code == 0, made.output
    checked = runner.invoke(app, ["validate", str(out), "--format", "json", *paths])
    return yaml.safe_load((out / "marm_setup.yaml").read_text()), json.loads(checked.stdout)


def _check(setup: dict, report: dict) -> None:
    errors = [
        f"{f['rule']} {f['file']} {f['element']}: {f['message']}"
        for f in report["findings"]
        if f["severity"] == "error"
    ]
    assert errors == []
    # limbs of two or more joints get `home` and `ready` (a one-joint torso lift only `home`)
    limbs = [g["name"] for g in setup["groups"] if "chain" in g]
    poses = {limb: [s for s in setup.get("group_states", []) if s["group"] == limb] for limb in limbs}
    posed = [limb for limb in limbs if len(poses[limb]) >= 2]
    arms = [limb for limb in limbs if "arm" in limb]
    assert set(arms) <= set(posed), {arm: len(poses[arm]) for arm in arms}
    assert report["validated"]["planned_pairs"] >= len(posed)


@pytest.mark.parametrize("name", list(SHARED))
def test_init_on_a_real_robot_validates_and_plans(tmp_path, name):
    urdf, roots, xacro_args = SHARED[name]
    _check(*_init_and_validate(tmp_path, _shared(urdf), [_shared(r) for r in roots], xacro_args))


@pytest.mark.parametrize("name", SYNTHETIC)
def test_init_on_a_synthetic_robot_validates_and_plans(tmp_path, name):
    _check(*_init_and_validate(tmp_path, FIXTURES / "synthetic" / f"{name}.urdf", [], []))
