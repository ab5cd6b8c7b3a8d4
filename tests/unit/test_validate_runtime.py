"""Runtime rules: every pose pair of every group is planned and fake-executed; findings name the
pair and the reason. Clean on marm, one skipped pose on the real panda; an unplannable pair, a
trajectory the fake controller rejects and unusable limits each give their rule."""

from __future__ import annotations

import dataclasses
import math

import pytest
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.collision.scene import CollisionScene
from marm_setup.package.read import read_package
from marm_setup.plan.planner import PlannerOptions
from marm_setup.plan.problem import group_names_with_poses, initial_configuration, planning_problem
from marm_setup.robot.load import load_robot
from marm_setup.validate.runtime import _check_group, check_runtime
from tests.conftest import FIXTURES, MARM_URDF, realworld


@pytest.fixture(scope="module")
def marm(tmp_path_factory):
    out = tmp_path_factory.mktemp("marm") / "marm_moveit_config"
    spec = FIXTURES / "marm" / "marm_setup.yaml"
    result = CliRunner().invoke(
        app, ["init", str(MARM_URDF), "--out", str(out), "--setup", str(spec), "--trials", "2000"]
    )
    assert result.exit_code == 0, result.output
    package = read_package(out)
    robot = load_robot(package.urdf, dict(package.xacro_args), list(package.package_paths))
    return package, robot, CollisionScene(robot)


def test_marm_is_clean(marm):
    package, robot, scene = marm
    assert group_names_with_poses(package) == ("arm",)
    assert check_runtime(package, robot, scene) == []


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_panda_skips_the_pose_in_collision(target):
    package = read_package(realworld(target, "panda_moveit_config"))
    robot = load_robot(package.urdf, dict(package.xacro_args), list(package.package_paths))
    findings = check_runtime(package, robot, CollisionScene(robot))
    assert [(f.rule, f.severity, f.element) for f in findings] == [
        ("runtime.pose-skipped", "warning", "group_state[transport]")
    ]
    assert findings[0].message == (
        "plans from and to 'transport' skipped: pose in collision: panda_link5 - panda_link7"
    )


def test_initial_state_comes_from_the_package():
    package = read_package(realworld("ros1", "panda_moveit_config"))
    robot = load_robot(package.urdf, dict(package.xacro_args), list(package.package_paths))
    q = initial_configuration(package, robot)
    names = robot.active_joint_names
    assert q[names.index("panda_joint4")] == pytest.approx(-2.356)  # fake_controllers initial: ready
    assert q[names.index("panda_finger_joint1")] == pytest.approx(0.035)  # and hand: open


def test_unplannable_pair_and_rejected_execution(marm):
    package, robot, scene = marm
    problem = planning_problem(package, robot, scene, "arm")
    i1 = robot.active_joint_names.index("joint2")
    home, forward = problem.poses["home"][i1], problem.poses["forward"][i1]
    middle = (home + forward) / 2

    def wall(q):  # joint2 can never cross the middle between the two poses
        return [("link2", "link4") if abs(row[i1] - middle) < 0.05 else None for row in q]

    walled = dataclasses.replace(problem, check=wall)
    findings = _check_group(walled, robot, "config/marm.srdf", 0, PlannerOptions(max_iterations=20))
    assert [(f.rule, f.element) for f in findings] == [
        ("runtime.no-plan", "group[arm]/forward -> home"),
        ("runtime.no-plan", "group[arm]/home -> forward"),
    ]
    assert findings[0].message.startswith("no plan: no path within budget (20 iterations")
    # a trajectory timed for looser limits than the hard ones is caught by the fake controller
    loose = dataclasses.replace(problem, velocity_scaling=100.0, acceleration_scaling=100.0)
    findings = _check_group(loose, robot, "config/marm.srdf", 0, PlannerOptions())
    assert [f.rule for f in findings] == ["runtime.execution", "runtime.execution"]
    assert all(f.message.startswith("fake execution failed: velocity limit: joint") for f in findings)
    assert all("acceleration limit: joint" in f.message for f in findings)


def test_missing_velocity_limits_are_moveits_default_and_a_warning(marm, tmp_path):
    """MoveIt's time parameterisations time a joint without a velocity bound at 1 rad/s: the
    plans still run, and validate says which joints got the default."""
    package, robot, scene = marm
    stripped = robot.__class__(
        robot.name,
        robot.links,
        tuple(dataclasses.replace(j, velocity=None) for j in robot.joints),
        robot.root,
        robot.source,
        robot.urdf_xml,
    )
    bare = dataclasses.replace(package, joint_limits=None)
    findings = check_runtime(bare, stripped, scene)
    assert [(f.rule, f.severity, f.element) for f in findings] == [
        ("runtime.default-velocity", "warning", "group[arm]")
    ]
    assert findings[0].message.startswith(
        "no velocity limit for joint1, joint2, joint3, joint4, joint5, joint6: MoveIt"
    )


def test_two_named_poses_with_the_same_values_are_clean(marm):
    # SRDFs often name one configuration twice (home, ready): a plan between them does not move
    package, robot, scene = marm
    problem = planning_problem(package, robot, scene, "arm")
    twin = dataclasses.replace(problem, poses={**problem.poses, "ready": problem.poses["home"].copy()})
    assert _check_group(twin, robot, "config/marm.srdf", 0, PlannerOptions()) == []


def test_a_continuous_joint_pose_beyond_pi_is_the_same_angle_wrapped(marm):
    # pose rules accept any value of a continuous joint; the planner must too (MoveIt wraps it)
    package, robot, scene = marm
    spun = robot.__class__(
        robot.name,
        robot.links,
        tuple(dataclasses.replace(j, type="continuous") if j.name == "joint1" else j for j in robot.joints),
        robot.root,
        robot.source,
        robot.urdf_xml,
    )
    states = tuple(
        dataclasses.replace(
            s, values=tuple((n, v + 2 * math.pi if n == "joint1" else v) for n, v in s.values)
        )
        if s.name == "forward"
        else s
        for s in package.srdf.group_states
    )
    srdf_file = dataclasses.replace(
        package.srdf_file, srdf=dataclasses.replace(package.srdf, group_states=states)
    )
    turned = dataclasses.replace(package, srdf_file=srdf_file)
    problem = planning_problem(turned, spun, CollisionScene(spun), "arm")
    assert -math.pi <= problem.poses["forward"][spun.active_joint_names.index("joint1")] < math.pi
    assert _check_group(problem, spun, "config/marm.srdf", 0, PlannerOptions()) == []


def test_one_unusable_scaling_factor_does_not_reset_the_other(marm):
    package, robot, scene = marm
    limits = package.joint_limits
    settings = tuple(
        dataclasses.replace(p, value=1.5) if p.key == "default_velocity_scaling_factor" else p
        for p in limits.settings
    )
    edited = dataclasses.replace(package, joint_limits=dataclasses.replace(limits, settings=settings))
    problem = planning_problem(edited, robot, scene, "arm")
    assert (problem.velocity_scaling, problem.acceleration_scaling) == (1.0, 0.1)
