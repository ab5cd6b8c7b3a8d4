"""Every real package in ../shared/realworld*: validate prints JSON, never crashes, and its
errors are exactly the known real ones (a new false error, or a lost real one, fails here).

Why each remaining error is real:
- panda (MoveIt 1 and 2) `transport`: the collision meshes of panda_link5 and panda_link7 overlap
  with panda_joint6 at 0 (pinocchio agrees: test_validate_packages.py).
- motoman_sda10f `arms`, `sda10f`, `torso`: KDL on groups that are not one serial chain (two arms;
  torso_joint_b1/b2 are siblings under base_link): KDLKinematicsPlugin refuses to initialise
  for them, so MoveIt has no IK solver there.
- motoman_sda10f `torso_base_link torso_link_b1`: adjacent links whose meshes overlap in every
  state, left enabled (the SRDF disables base_link - torso_link_b1, and base_link has no
  geometry), so MoveIt sees the robot in collision everywhere; the Setup Assistant says Adjacent.
"""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import REALWORLD, REALWORLD2

PACKAGES = {  # name: (config package, package paths), as README's commands type them
    "panda_ros1": (REALWORLD / "ros1/panda_moveit_config", (REALWORLD / "ros1",)),
    "panda_ros2": (REALWORLD / "ros2/panda_moveit_config", (REALWORLD / "ros2",)),
    "ur5e": (REALWORLD2 / "universal_robot/ur5e_moveit_config", (REALWORLD2 / "universal_robot",)),
    "fanuc_cr7ia": (REALWORLD2 / "fanuc/moveit_cfgs/fanuc_cr7ia_moveit_config", (REALWORLD2 / "fanuc",)),
    "motoman_sda10f": (REALWORLD2 / "motoman/motoman_sda10f_moveit_config", (REALWORLD2 / "motoman",)),
    "kinova_j2n6s300": (
        REALWORLD2 / "kinova-ros/kinova_moveit/robot_configs/j2n6s300_moveit_config",
        (REALWORLD2 / "kinova-ros",),
    ),
    "dual_panda": (
        REALWORLD2 / "moveit_resources_master/dual_panda_moveit_config",
        (REALWORLD2 / "moveit_resources_master",),
    ),
    "kortex_gen3": (
        REALWORLD2 / "ros2_kortex/kortex_moveit_config/kinova_gen3_6dof_robotiq_2f_85_moveit_config",
        (REALWORLD2 / "ros2_kortex", REALWORLD2 / "ros2_robotiq_gripper"),
    ),
}
TRANSPORT = ("pose.collision", "group_state[transport]")
EXPECTED_ERRORS = {
    "panda_ros1": {("config/panda.srdf", *TRANSPORT)},
    "panda_ros2": {("config/panda_arm_hand.srdf.xacro", *TRANSPORT)},
    "motoman_sda10f": {
        *(
            ("config/kinematics.yaml", "kinematics.kdl-needs-chain", f"{group}.kinematics_solver")
            for group in ("arms", "sda10f", "torso")
        ),
        (
            "config/motoman_sda10f.srdf",
            "matrix.always-colliding",
            "disable_collisions[torso_base_link torso_link_b1]",
        ),
    },
}


@pytest.mark.parametrize("name", sorted(PACKAGES))
def test_real_packages_have_only_their_real_errors(name):
    path, package_paths = PACKAGES[name]
    if not path.is_dir():
        pytest.skip(f"{path} not present")
    args = ["validate", str(path), "--no-plan", "--format", "json"]
    for folder in package_paths:
        args += ["--package-path", str(folder)]
    result = CliRunner().invoke(app, args)
    assert result.exception is None or isinstance(result.exception, SystemExit), result.exception
    doc = json.loads(result.stdout)
    errors = {(f["file"], f["rule"], f["element"]) for f in doc["findings"] if f["severity"] == "error"}
    assert errors == EXPECTED_ERRORS.get(name, set())
    assert result.exit_code == (1 if errors else 0)
