"""One "initial state" (`setup.start_state`): what render writes is where plan and validate start,
with MoveIt's precedence per target."""

from __future__ import annotations

import dataclasses

import pytest

from marm_setup.package.read import read_package
from marm_setup.plan.problem import initial_configuration
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from marm_setup.setup.model import Group, GroupState
from marm_setup.setup.srdf import Srdf
from marm_setup.setup.start_state import demo_start_values, initial_pose_values, model_start_values
from tests.render_helpers import inferred_marm

ARM = Group("arm", joints=("joint1", "joint2", "joint3"))
SRDF = Srdf(
    "marm",
    groups=(ARM, Group("one", joints=("joint1",))),
    group_states=(
        GroupState("up", "arm", (("joint1", 0.1), ("joint2", 0.2), ("joint3", 0.3))),
        GroupState("left", "one", (("joint1", -0.5),)),
    ),
)


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_generated_packages_start_where_render_says(tmp_path, target):
    """Reading the written package back (fake controllers' `initial` for ros1,
    initial_positions.yaml for ros2) gives render's start state, as plan and validate use it."""
    out = tmp_path / "pkg"
    model, robot = inferred_marm(target, out)
    states = tuple(
        dataclasses.replace(s, values=tuple((j, 0.3 if j == "joint2" else v) for j, v in s.values))
        if s.name == "home"
        else s
        for s in model.group_states
    )
    model = dataclasses.replace(model, group_states=states)
    apply_writes(plan_writes(render_package(model, robot), out), out)
    expected = model_start_values(model, robot)
    assert expected["joint2"] == 0.3
    q = initial_configuration(read_package(out), robot)
    assert dict(zip(robot.active_joint_names, q.tolist(), strict=True)) == pytest.approx(
        {name: expected[name] for name in robot.active_joint_names}
    )


def test_ros1_applies_initial_poses_in_order_and_ignores_initial_positions(marm):
    fake = [("arm", "up"), ("one", "left"), ("x", "None")]
    positions = {"joint1": 1.0, "joint4": 1.0}
    assert demo_start_values("ros1", SRDF, marm, fake, positions) == {
        "joint1": -0.5,
        "joint2": 0.2,
        "joint3": 0.3,
    }


def test_ros2_takes_initial_positions_and_ignores_fake_initial(marm):
    fake = [("arm", "up")]
    positions = {"joint1": 1.0, "joint9": 2.0, "joint4": "x", "finger_joint2": 0.01}
    assert demo_start_values("ros2", SRDF, marm, fake, positions) == {"joint1": 1.0}  # mimic, unknown out
    assert demo_start_values("ros2", SRDF, marm, fake, {}) == {}


def test_a_pose_sets_only_its_group_active_joints(marm):
    srdf = Srdf(
        "marm", groups=(ARM,), group_states=(GroupState("p", "arm", (("joint1", 0.1), ("joint5", 0.5))),)
    )
    assert initial_pose_values(srdf, marm, [("arm", "p"), ("arm", "missing")]) == {"joint1": 0.1}
