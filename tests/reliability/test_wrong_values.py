"""Values MoveIt or roslaunch reject, or use wrongly, are findings (issue 36): never `no findings`
with exit 0. NaN fails every bound (it compares false to everything)."""

from __future__ import annotations

import shutil

import pytest

from tests.conftest import MARM_URDF
from tests.reliability.checks import run
from tests.validate_helpers import edit_yaml, generate_marm, validate_package

MOVEIT = "config/moveit.yaml"
SERVO = "config/arm_servo.yaml"


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    """The marm package for each target, generated once (tests edit copies)."""
    root = tmp_path_factory.mktemp("made")
    jazzy = root / "jazzy" / "marm_ros2"
    result = run(
        "init", MARM_URDF, "--out", jazzy, "--target", "ros2", "--ros-distro", "jazzy", "--trials", "20"
    )
    assert result.exit_code == 0, result.output
    return {"ros1": generate_marm(root, "ros1"), "ros2": generate_marm(root, "ros2"), "jazzy": jazzy}


def _copy(made, target: str, tmp_path):
    return shutil.copytree(made[target], tmp_path / made[target].name)


def _params(data: dict) -> dict:
    return data["/**"]["ros__parameters"]


def _found(pkg) -> set[tuple[str, str, str]]:
    """(rule, severity, last element segment) of every finding."""
    return {(f.rule, f.severity, f.element.rsplit(".", 1)[-1]) for f in validate_package(pkg, plan=False)}


@pytest.mark.parametrize("value", [float("nan"), float("inf"), -1.0, 0.0, -1e-300])
@pytest.mark.parametrize("key", ["max_trans_vel", "max_trans_acc", "max_rot_vel"])
def test_a_pilz_cartesian_rate_that_is_not_positive_and_finite_is_an_error(made, tmp_path, key, value):
    pkg = _copy(made, "ros2", tmp_path)
    edit_yaml(
        pkg,
        MOVEIT,
        lambda d: _params(d)["robot_description_planning"]["cartesian_limits"].update({key: value}),
    )
    assert ("limits.cartesian", "error", key) in _found(pkg)


@pytest.mark.parametrize("value", [0.5, 1e-3, 20.0])
def test_a_positive_cartesian_rate_is_no_finding(made, tmp_path, value):
    pkg = _copy(made, "ros2", tmp_path)
    edit_yaml(
        pkg,
        MOVEIT,
        lambda d: _params(d)["robot_description_planning"]["cartesian_limits"].update(max_rot_vel=value),
    )
    assert not {f for f in _found(pkg) if f[0] == "limits.cartesian"}


def test_a_cartesian_rate_that_is_a_string_is_a_type_error(made, tmp_path):
    pkg = _copy(made, "ros2", tmp_path)
    edit_yaml(
        pkg,
        MOVEIT,
        lambda d: _params(d)["robot_description_planning"]["cartesian_limits"].update(max_trans_vel="fast"),
    )
    assert {rule for rule, _, key in _found(pkg) if key == "max_trans_vel"} == {"params.type"}


@pytest.mark.parametrize("value", [5, 0.4, "fast", [1.0, 2.0], True])
def test_a_servo_scale_that_is_not_a_mapping_is_a_finding(made, tmp_path, value):
    """servo declares scale.linear, .rotational, .joint: a `scale` value is never read."""
    pkg = _copy(made, "ros2", tmp_path)
    edit_yaml(pkg, SERVO, lambda d: _params(d)["moveit_servo"].update(scale=value))
    assert ("params.type", "warning", "scale") in _found(pkg)


@pytest.mark.parametrize(
    ("key", "value"),
    [
        ("publish_period", float("nan")),
        ("lower_singularity_threshold", float("nan")),
        ("collision_check_rate", float("nan")),
        ("joint_limit_margins", [float("nan")]),
        ("joint_limit_margins", [-0.1]),
    ],
)
def test_a_nan_servo_setting_fails_its_bound(made, tmp_path, key, value):
    """Jazzy's generate_parameter_library bound gt 0 refuses NaN. (Humble's servo_parameters.cpp
    validate tests `publish_period <= 0.`, which NaN passes: its checks are not in the tables.)"""
    pkg = _copy(made, "jazzy", tmp_path)
    edit_yaml(pkg, SERVO, lambda d: _params(d)["moveit_servo"].update({key: value}))
    assert ("params.bounds", "error", key) in _found(pkg)


@pytest.mark.parametrize("key", ["planning_pipelines", "sensors"])
@pytest.mark.parametrize("value", [5, "ompl", 1.5, True])
def test_a_move_group_list_that_is_not_a_list_is_an_error(made, tmp_path, key, value):
    pkg = _copy(made, "ros2", tmp_path)
    edit_yaml(pkg, MOVEIT, lambda d: _params(d).update({key: value}))
    assert any(
        rule in ("params.type", "sensors.malformed") and sev == "error" for rule, sev, _ in _found(pkg)
    )


@pytest.mark.parametrize("text", ["- a\n- b\n", "42\n", "just text\n"])
@pytest.mark.parametrize("rel", ["config/kinematics.yaml", "config/ompl_planning.yaml"])
def test_a_rosparam_file_that_is_not_a_mapping_is_an_error(made, tmp_path, rel, text):
    """roslaunch's load_rosparam refuses it without a `param` attribute (loader.py l.432-434)."""
    pkg = _copy(made, "ros1", tmp_path)
    (pkg / rel).write_text(text, encoding="utf-8")
    findings = validate_package(pkg, plan=False)
    assert any(f.rule == "launch.rosparam-not-mapping" and f.is_error for f in findings)
