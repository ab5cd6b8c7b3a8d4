"""No input reaches an internal error (issue 36): a package's own matrix settings (a negative
seed, 1e12 trials) never reach `report`'s matrix, and a NaN or infinite pipeline setting is not carried
by a port nor taken from a setup file (marm-setup writes finite numbers only)."""

from __future__ import annotations

import pytest
import yaml

from tests.conftest import MARM_URDF
from tests.reliability.checks import assert_clean_exit, assert_one_line_error, run
from tests.validate_helpers import generate_marm, replace_text


@pytest.mark.parametrize("trials", [1_000_000_000_000, 10**30, 1e12, "y"])
def test_report_takes_no_trial_count_from_the_package(tmp_path, trials):
    pkg = generate_marm(tmp_path, "ros1")
    data = yaml.safe_load((pkg / "marm_setup.yaml").read_text(encoding="utf-8"))
    data["collision"].update(trials=trials)
    (pkg / "marm_setup.yaml").write_text(yaml.safe_dump(data), encoding="utf-8")
    page = tmp_path / "r.html"
    result = run("report", pkg, "-o", page, "--no-plan", "--trials", "20")
    assert_clean_exit(result)
    assert "internal error" not in result.output and page.is_file()


@pytest.mark.parametrize("value", [".inf", "-.inf", ".nan"])
@pytest.mark.parametrize("name", ["planning_time_limit", "learning_rate", "ridge_factor"])
def test_a_port_does_not_carry_a_number_that_is_not_finite(tmp_path, value, name):
    pkg = generate_marm(tmp_path, "ros2")
    moveit = "config/moveit.yaml"
    replace_text(
        pkg,
        moveit,
        "      - pilz_industrial_motion_planner\n",
        "      - pilz_industrial_motion_planner\n      - chomp\n",
    )
    block = f"    chomp:\n      planning_plugins:\n        - chomp_interface/CHOMPPlanner\n      {name}: {value}\n\n"
    replace_text(
        pkg, moveit, "    robot_description_kinematics:", block + "    robot_description_kinematics:"
    )
    out = tmp_path / "out"
    result = run("init", "--from-package", pkg, "--out", out)
    assert_clean_exit(result, codes=(0,))
    assert f"dropped chomp.{name}: must be a finite number" in result.output
    assert value not in (out / moveit).read_text(encoding="utf-8")


@pytest.mark.parametrize("value", [".inf", ".nan"])
def test_a_setup_file_with_an_infinite_pipeline_setting_is_one_line(tmp_path, value):
    spec = tmp_path / "spec.yaml"
    spec.write_text(
        "target: ros2\nros_distro: jazzy\nplanning_pipelines: [ompl, chomp]\n"
        f"pipeline_parameters:\n  chomp:\n    planning_time_limit: {value}\n",
        encoding="utf-8",
    )
    result = run("init", MARM_URDF, "--out", tmp_path / "o", "--setup", spec, "--trials", "10")
    assert_clean_exit(result, codes=(2,))
    assert "finite" in result.stderr


@pytest.mark.parametrize("seed", [-1, -(2**70)])
@pytest.mark.parametrize("command", ["validate", "report"])
def test_a_negative_package_seed_is_no_internal_error(tmp_path, seed, command):
    """numpy's SeedSequence refuses a negative seed: validate and report read it as absent."""
    pkg = generate_marm(tmp_path, "ros2")
    setup = pkg / "marm_setup.yaml"
    data = yaml.safe_load(setup.read_text(encoding="utf-8"))
    data["collision"].update(seed=seed)
    setup.write_text(yaml.safe_dump(data), encoding="utf-8")
    extra = ["-o", tmp_path / "r.html", "--trials", "20"] if command == "report" else []
    result = run(command, pkg, "--no-plan", *extra)
    assert_clean_exit(result, codes=(0,))
    assert "internal" not in result.output


@pytest.mark.parametrize(("key", "value"), [("seed", -1), ("seed", -(2**64))])
def test_a_setup_file_with_a_negative_count_is_one_line(tmp_path, key, value):
    spec = tmp_path / "spec.yaml"
    spec.write_text(f"collision:\n  {key}: {value}\n", encoding="utf-8")
    result = run("init", MARM_URDF, "--out", tmp_path / "o", "--setup", spec, "--trials", "10")
    assert_one_line_error(result, f"collision.{key}: must be >= 0")
    assert not (tmp_path / "o").exists()
