"""`marm-setup plan`: plans between named poses of generated (marm ros1/ros2) and real (panda
ros1/ros2) packages; every trajectory written is re-checked independently with pinocchio + coal
at a finer step than the planner's; bad input exits 2 with one line, an unplannable query 1."""

from __future__ import annotations

import numpy as np
import pytest
import yaml
from typer.testing import CliRunner

from marm_setup.cli.app import app
from marm_setup.plan.planner import PlannerOptions
from marm_setup.robot.load import load_robot
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.trajectory_recheck import pinocchio_models, recheck

runner = CliRunner()
FINE_STEP = PlannerOptions().max_step / 5


@pytest.fixture(scope="module", params=["ros1", "ros2"])
def marm_package(request, tmp_path_factory):
    out = tmp_path_factory.mktemp(f"marm_{request.param}") / "marm_moveit_config"
    spec = FIXTURES / "marm" / "marm_setup.yaml"
    args = ["init", str(MARM_URDF), "--out", str(out), "--setup", str(spec), "--target", request.param]
    result = runner.invoke(app, [*args, "--trials", "2000"])
    assert result.exit_code == 0, result.output
    return out


def _plan(package, *args):
    return runner.invoke(app, ["plan", str(package), *args])


def _meshes(robot) -> dict[str, str]:
    return {
        shape.geometry.uri: shape.geometry.path
        for link in robot.links
        for shape in link.collisions
        if hasattr(shape.geometry, "uri")
    }


def _held_state(model, package, robot):
    """Pinocchio's q with the joints outside the group where the planner holds them: the
    package's initial state (e.g. the panda's open fingers), mimic joints following."""
    import pinocchio as pin

    from marm_setup.package.read import read_package
    from marm_setup.plan.problem import initial_configuration

    q = pin.neutral(model)
    values = dict(
        zip(robot.active_joint_names, initial_configuration(read_package(package), robot), strict=True)
    )
    for joint in robot.joints:
        if joint.is_actuated and joint.mimic is not None:
            values[joint.name] = joint.mimic.multiplier * values[joint.mimic.joint] + joint.mimic.offset
    for name, value in values.items():
        joint = model.joints[model.getJointId(name)] if model.existJointName(name) else None
        if joint is not None and joint.nq == 1:
            q[joint.idx_q] = value
    return q


def _assert_rechecked(traj, robot, srdf, start, goal, tmp_path, package, limits_yaml=None):
    """The pinocchio re-check: collision-free, within bounds and limits, from start to goal,
    with the other joints held where the planner held them."""
    model, geom = pinocchio_models(robot.urdf_xml, _meshes(robot), srdf, tmp_path)
    q_base = _held_state(model, package, robot)
    found = recheck(traj, model, geom, q_base, FINE_STEP)
    assert found["max_step"] <= FINE_STEP + 1e-9 and found["states"] > 10
    assert found["inconsistency"] <= 1e-6
    assert found["colliding"] == [], found["colliding"][:3]
    assert not found["below_lower"] and not found["above_upper"]
    assert np.all(found["max_velocity"] <= found["velocity_limit"] * (1 + 1e-6))
    idx = [model.joints[model.getJointId(n)].idx_q for n in found["joint_names"]]
    np.testing.assert_allclose(found["start"], model.referenceConfigurations[start][idx], atol=1e-6)
    np.testing.assert_allclose(found["end"], model.referenceConfigurations[goal][idx], atol=1e-6)
    if limits_yaml is not None:
        entries = yaml.safe_load(limits_yaml.read_text(encoding="utf-8"))["joint_limits"]
        for name, v, a in zip(
            found["joint_names"], found["max_velocity"], found["max_acceleration"], strict=True
        ):
            assert v <= entries[name]["max_velocity"] * (1 + 1e-6)
            assert a <= entries[name]["max_acceleration"] * (1 + 1e-6)
    return found


def test_marm_home_to_forward_and_back(marm_package, tmp_path):
    robot = load_robot(MARM_URDF, {}, [])
    limits = marm_package / "config" / "joint_limits.yaml"
    for start, goal in (("home", "forward"), ("forward", "home")):
        traj = tmp_path / f"{start}_{goal}.yaml"
        result = _plan(marm_package, "--group", "arm", "--from", start, "--to", goal, "--output", str(traj))
        assert result.exit_code == 0, result.output
        lines = result.stdout.splitlines()
        assert lines[0] == f"planned arm: {start} -> {goal} (joint1, joint2, joint3, joint4, joint5, joint6)"
        assert [line.split(":")[0].strip() for line in lines[1:]] == [
            "waypoints",
            "path length",
            "duration",
            "planning time",
            "fake execution",
            f"wrote {traj}",
        ]
        srdf = marm_package / "config" / "marm.srdf"
        limits_yaml = limits if limits.exists() else None
        _assert_rechecked(traj, robot, srdf, start, goal, tmp_path, marm_package, limits_yaml)


def test_same_seed_same_bytes(marm_package, tmp_path):
    a, b = tmp_path / "a.yaml", tmp_path / "b.yaml"
    for out in (a, b):
        args = ["--group", "arm", "--from", "forward", "--to", "home", "--seed", "3", "--output", str(out)]
        assert _plan(marm_package, *args).exit_code == 0
    assert a.read_bytes() == b.read_bytes()


def test_a_pose_to_itself_is_one_point(marm_package, tmp_path):
    traj = tmp_path / "stay.yaml"
    result = _plan(marm_package, "--group", "arm", "--from", "home", "--to", "home", "--output", str(traj))
    assert result.exit_code == 0, result.output
    points = yaml.safe_load(traj.read_text(encoding="utf-8"))["points"]
    assert len(points) == 1 and points[0]["time_from_start"] == 0.0


def test_an_output_that_cannot_be_written_is_one_line_exit_2(marm_package, tmp_path):
    result = _plan(
        marm_package, "--group", "arm", "--from", "home", "--to", "forward", "--output", str(tmp_path)
    )
    assert result.exit_code == 2
    assert result.stderr == f"error: {tmp_path}: cannot write: is a folder\n"
    assert list(tmp_path.iterdir()) == []  # no temporary file left behind


def test_a_limit_that_is_not_a_number_is_one_line_exit_2(tmp_path):
    package = tmp_path / "marm_moveit_config"
    spec = FIXTURES / "marm" / "marm_setup.yaml"
    args = ["init", str(MARM_URDF), "--out", str(package), "--setup", str(spec), "--target", "ros1"]
    assert runner.invoke(app, [*args, "--trials", "300"]).exit_code == 0
    limits = package / "config" / "joint_limits.yaml"
    data = yaml.safe_load(limits.read_text(encoding="utf-8"))
    data["joint_limits"]["joint2"]["max_velocity"] = "fast"
    limits.write_text(yaml.safe_dump(data), encoding="utf-8")
    result = _plan(package, "--group", "arm", "--from", "home", "--to", "forward")
    assert result.exit_code == 2, result.output
    assert result.stderr == f"error: {limits}: max_velocity of joint joint2 must be a number, got 'fast'\n"


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_panda_ready_to_extended_rechecked_by_pinocchio(target, tmp_path):
    package = realworld(target, "panda_moveit_config")
    traj = tmp_path / "traj.yaml"
    result = _plan(
        package, "--group", "panda_arm", "--from", "ready", "--to", "extended", "--output", str(traj)
    )
    assert result.exit_code == 0, result.output
    from marm_setup.package.read import read_package

    pkg = read_package(package)
    robot = load_robot(pkg.urdf, dict(pkg.xacro_args), list(pkg.package_paths))
    srdf = tmp_path / "panda.srdf"
    srdf.write_text(pkg.srdf_text, encoding="utf-8")  # ros2 ships a .srdf.xacro: use the expanded text
    _assert_rechecked(traj, robot, srdf, "ready", "extended", tmp_path, package)


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (
            ["--group", "arms", "--from", "home", "--to", "forward"],
            "unknown group 'arms' (did you mean 'arm'?)",
        ),
        (["--group", "arm", "--from", "home", "--to", "nowhere"], "unknown pose 'nowhere' for group 'arm'"),
    ],
)
def test_bad_input_is_one_line_exit_2(marm_package, args, message):
    result = _plan(marm_package, *args)
    assert result.exit_code == 2
    assert len(result.stderr.splitlines()) == 1 and message in result.stderr
    assert result.stderr.startswith(f"error: {marm_package / 'config/marm.srdf'}: ")
    assert "Traceback" not in result.output


def test_a_negative_seed_is_one_line_exit_2(marm_package):
    result = _plan(marm_package, "--group", "arm", "--from", "home", "--to", "forward", "--seed", "-1")
    assert result.exit_code == 2 and result.stderr == "error: --seed: must be >= 0, got -1\n"


def test_not_a_package_is_exit_2(tmp_path):
    result = _plan(tmp_path, "--group", "arm", "--from", "a", "--to", "b")
    assert result.exit_code == 2 and len(result.stderr.splitlines()) == 1


def test_pose_in_collision_is_exit_1_naming_the_pair(tmp_path):
    package = realworld("ros1", "panda_moveit_config")
    result = _plan(package, "--group", "panda_arm", "--from", "ready", "--to", "transport")
    assert result.exit_code == 1
    assert result.stderr.strip() == (
        f"error: {package / 'config/panda.srdf'}: group[panda_arm]/ready -> transport: "
        "no plan: goal in collision: panda_link5 - panda_link7"
    )


def test_the_recheck_itself_catches_a_colliding_trajectory(tmp_path):
    """Guard against a re-check that passes anything: a straight line into panda's `transport`."""
    package = realworld("ros1", "panda_moveit_config")
    from marm_setup.package.read import read_package

    pkg = read_package(package)
    robot = load_robot(pkg.urdf, dict(pkg.xacro_args), list(pkg.package_paths))
    model, geom = pinocchio_models(robot.urdf_xml, _meshes(robot), package / pkg.srdf_path, tmp_path)
    import pinocchio as pin

    names = [f"panda_joint{i}" for i in range(1, 8)]
    idx = [model.joints[model.getJointId(n)].idx_q for n in names]
    ready, transport = (model.referenceConfigurations[p][idx].tolist() for p in ("ready", "transport"))
    zero = [0.0] * 7
    v_end = [
        2 * (b - a) / 5.0 for a, b in zip(ready, transport, strict=True)
    ]  # consistent: accelerate all the way
    doc = {
        "joint_names": names,
        "points": [
            {"positions": ready, "velocities": zero, "accelerations": zero, "time_from_start": 0.0},
            {"positions": transport, "velocities": v_end, "accelerations": zero, "time_from_start": 5.0},
        ],
    }
    traj = tmp_path / "bad.yaml"
    traj.write_text(yaml.safe_dump(doc), encoding="utf-8")
    found = recheck(traj, model, geom, pin.neutral(model), FINE_STEP)
    assert found["inconsistency"] < 1e-9
    assert ("panda_link5_0", "panda_link7_0") in found["colliding"]
    doc["points"][1]["velocities"] = zero  # now the points disagree with the motion between them
    traj.write_text(yaml.safe_dump(doc), encoding="utf-8")
    assert recheck(traj, model, geom, pin.neutral(model), FINE_STEP)["inconsistency"] > 0.1
