"""MoveIt's declared parameters (marm_setup/moveit_params) and validate's check of every
parameter move_group and servo receive: a fresh package passes, each one-line edit that would
crash or cripple MoveIt is exactly one finding of the right severity."""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

import pytest

from marm_setup.moveit_params import FAMILIES, load_table
from marm_setup.package import read_package
from marm_setup.validate.rules.declared_param_rules import check_declared_parameters
from tests.conftest import FIXTURES
from tests.render_helpers import written_ros2_marms
from tests.validate_helpers import replace_text, validate_package

MOVEIT_YAML = "config/moveit.yaml"
SERVO_YAML = "config/arm_servo.yaml"
PARAMS = "/**.ros__parameters."
CITATION = re.compile(r"^[\w./-]+\.(yaml|cpp|hpp|h|xml|cfg):\d+$")


@pytest.fixture(scope="module")
def fresh(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """A generated ROS 2 marm package per distro, made once."""
    return written_ros2_marms(tmp_path_factory)


def edited(fresh: dict[str, Path], tmp_path: Path, distro: str, rel: str, old: str, new: str) -> Path:
    pkg = tmp_path / "marm_moveit_config"
    shutil.copytree(fresh[distro], pkg)
    replace_text(pkg, rel, old, new)
    return pkg


def findings(pkg: Path, distro: str | None = "from the package") -> list:
    package = read_package(pkg)
    return check_declared_parameters(package, package.ros_distro if distro == "from the package" else distro)


def only(found: list) -> tuple[str, str, str, str]:
    assert len(found) == 1, [(f.rule, f.element, f.message) for f in found]
    f = found[0]
    return f.rule, str(f.severity), f.file, f.element


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_a_generated_package_passes(fresh, distro):
    assert findings(fresh[distro]) == []


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_an_integer_for_a_double_in_trajectory_execution_stops_move_group(fresh, tmp_path, distro):
    key = "allowed_execution_duration_scaling"
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, f"{key}: 1.2", f"{key}: 2")
    found = findings(pkg)
    assert only(found) == ("params.type", "error", MOVEIT_YAML, f"{PARAMS}trajectory_execution.{key}")
    assert "move_group stops at start-up" in found[0].message
    assert "trajectory_execution_manager.cpp:" in found[0].hint


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_an_integer_max_effort_drops_the_gripper_controller(fresh, tmp_path, distro):
    old = "action_ns: gripper_cmd\n"
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, old, old + "        max_effort: 10\n")
    found = findings(pkg)
    element = f"{PARAMS}moveit_simple_controller_manager.gripper_controller.max_effort"
    assert only(found) == ("params.type", "error", MOVEIT_YAML, element)
    assert "drops" in found[0].message


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_an_integer_publish_flag_of_the_semantic_description_stops_move_group(fresh, tmp_path, distro):
    """SynchronizedStringParameter declares `publish_<name>` a bool and reads it into a bool."""
    key = "publish_robot_description_semantic"
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, f"{key}: true", f"{key}: 1")
    found = findings(pkg)
    assert only(found) == ("params.type", "error", MOVEIT_YAML, f"{PARAMS}{key}")
    assert "synchronized_string_parameter.cpp:" in found[0].hint


@pytest.mark.parametrize(("distro", "severity"), [("jazzy", "error"), ("humble", "warning")])
def test_a_listed_pipeline_without_parameters(fresh, tmp_path, distro, severity):
    """Jazzy's PlanningPipeline throws on an empty planning_plugins; Humble guesses a plugin."""
    old = "      - pilz_industrial_motion_planner\n"
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, old, old + "      - chomp\n")
    found = findings(pkg)
    assert only(found) == ("pipeline.not-configured", severity, MOVEIT_YAML, f"{PARAMS}planning_pipelines")
    assert "'chomp'" in found[0].message


def test_a_listed_pipeline_with_its_own_planning_file_is_left_alone(fresh, tmp_path):
    """A launch file may load config/<name>_planning.yaml in ways the package model does not see."""
    old = "      - pilz_industrial_motion_planner\n"
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, old, old + "      - chomp\n")
    (pkg / "config" / "chomp_planning.yaml").write_text("planning_plugins: [chomp_interface/CHOMPPlanner]\n")
    assert findings(pkg) == []


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_a_default_pipeline_not_listed_is_a_warning_naming_the_one_meant(fresh, tmp_path, distro):
    """move_group warns and plans with the first listed pipeline instead."""
    key = "default_planning_pipeline"
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, f"{key}: ompl", f"{key}: omp")
    found = findings(pkg)
    assert only(found) == ("moveit.default-pipeline", "warning", MOVEIT_YAML, f"{PARAMS}{key}")
    assert "'ompl'" in found[0].hint


def test_an_integer_servo_double_on_humble_stops_servo(fresh, tmp_path):
    pkg = edited(fresh, tmp_path, "humble", SERVO_YAML, "publish_period: 0.034", "publish_period: 1")
    found = findings(pkg)
    assert only(found) == ("params.type", "error", SERVO_YAML, f"{PARAMS}moveit_servo.publish_period")
    assert "servo_node stops" in found[0].message


def test_an_integer_ik_timeout_is_refused_on_jazzy_but_read_on_humble(fresh, tmp_path):
    key = "kinematics_solver_timeout"
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, f"{key}: 0.05", f"{key}: 1")
    element = f"{PARAMS}robot_description_kinematics.arm.{key}"
    assert only(findings(pkg)) == ("params.type", "error", MOVEIT_YAML, element)
    humble = edited(fresh, tmp_path / "h", "humble", MOVEIT_YAML, f"{key}: 0.05", f"{key}: 1")
    assert findings(humble) == []  # humble kinematics_plugin_loader.cpp reads an integer too


@pytest.mark.parametrize(
    ("distro", "old", "new", "key", "meant"),
    [
        ("humble", "ompl_interface/OMPLPlanner", "ompl_interface/OMPLPlaner", "ompl.planning_plugin", "ompl_interface/OMPLPlanner"),
        ("jazzy", "ompl_interface/OMPLPlanner", "ompl_interface/OMPLPlaner", "ompl.planning_plugins", "ompl_interface/OMPLPlanner"),
        ("humble", "request_adapters/FixWorkspaceBounds", "request_adapters/FixWorkspaceBound", "ompl.request_adapters",
         "default_planner_request_adapters/FixWorkspaceBounds"),
        ("jazzy", "request_adapters/ValidateWorkspaceBounds", "request_adapters/ValidateWorkspaceBound",
         "ompl.request_adapters", "default_planning_request_adapters/ValidateWorkspaceBounds"),
        ("humble", "kdl_kinematics_plugin/KDLKinematicsPlugin", "kdl_kinematics_plugin/KDLKinematicPlugin",
         "robot_description_kinematics.arm.kinematics_solver", "kdl_kinematics_plugin/KDLKinematicsPlugin"),
        ("jazzy", "kdl_kinematics_plugin/KDLKinematicsPlugin", "kdl_kinematics_plugin/KDLKinematicPlugin",
         "robot_description_kinematics.arm.kinematics_solver", "kdl_kinematics_plugin/KDLKinematicsPlugin"),
    ],
)  # fmt: skip
def test_a_plugin_class_typo_is_an_error_with_the_class_meant(fresh, tmp_path, distro, old, new, key, meant):
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, old, new)
    found = findings(pkg)
    assert only(found) == ("params.plugin", "error", MOVEIT_YAML, f"{PARAMS}{key}")
    assert found[0].hint == f"did you mean {meant}?"


def test_third_party_solvers_are_known(fresh, tmp_path):
    for solver in ("trac_ik_kinematics_plugin/TRAC_IKKinematicsPlugin", "pick_ik/PickIkPlugin"):
        pkg = edited(fresh, tmp_path / solver.split("/")[0], "jazzy", MOVEIT_YAML,
                     "kdl_kinematics_plugin/KDLKinematicsPlugin", solver)  # fmt: skip
        assert findings(pkg) == []


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_an_unknown_trajectory_execution_key_is_a_warning_with_the_name_meant(fresh, tmp_path, distro):
    pkg = edited(fresh, tmp_path, distro, MOVEIT_YAML, "allowed_start_tolerance:", "allowed_start_tolerence:")
    found = findings(pkg)
    element = f"{PARAMS}trajectory_execution.allowed_start_tolerence"
    assert only(found) == ("params.unknown", "warning", MOVEIT_YAML, element)
    assert found[0].hint == "did you mean allowed_start_tolerance?"


def test_a_wrong_type_moveit_only_logs_is_a_warning(fresh, tmp_path):
    old = "publish_transforms_updates: true\n"
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, old, old + "    publish_planning_scene_hz: 4\n")
    assert only(findings(pkg)) == (
        "params.type",
        "warning",
        MOVEIT_YAML,
        f"{PARAMS}publish_planning_scene_hz",
    )


def test_the_kinematics_rules_unknown_solver_warning_gives_way_to_params_plugin(fresh, tmp_path):
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, "KDLKinematicsPlugin", "KDLKinematicPlugin")
    found = validate_package(pkg, package_paths=[FIXTURES / "marm"], plan=False)
    kept = found  # kinematics_rules leaves a ROS 2 solver's class to the declared parameters
    assert [f.rule for f in kept if f.element.endswith("kinematics_solver")] == ["params.plugin"]


def test_without_a_distro_the_format_tells_the_family(fresh, tmp_path):
    key = "kinematics_solver_timeout"
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, f"{key}: 0.05", f"{key}: 1")
    assert [f.rule for f in findings(pkg, None)] == ["params.type"]  # planning_plugins: Jazzy's format


@pytest.mark.parametrize("family", sorted(FAMILIES))
def test_the_tables_load_and_every_row_cites_its_source(family):
    table = load_table(family)
    assert table.parameters and table.plugins and table.pinned
    assert all(len(sha) == 40 for _, _, sha in table.pinned)
    for row in table.parameters:
        assert row.on_wrong in ("throws", "drops", "logs"), row
        assert CITATION.match(row.source) or "ros2_control" in row.source, row
    for rows in (*table.plugins.values(), *table.third_party.values()):
        assert all(source for _, source in rows)
    for prefix, source in table.owned:
        assert CITATION.match(source), prefix


@pytest.mark.skipif("MARM_MOVEIT2_CHECKOUT" not in os.environ, reason="needs a moveit/moveit2 git repository")
def test_regenerating_from_moveit_reproduces_the_committed_tables():
    from marm_setup.moveit_params.regenerate import DATA, render_all

    moveit = os.environ.get("MARM_MOVEIT_CHECKOUT")
    rendered = render_all(Path(os.environ["MARM_MOVEIT2_CHECKOUT"]), Path(moveit) if moveit else None)
    for family, text in rendered.items():
        assert text == (DATA / f"{family}.yaml").read_text(encoding="utf-8"), family


def test_a_plugin_of_a_package_on_the_package_path_is_a_warning(fresh, tmp_path):
    """pluginlib loads another package's class once that package is built: not an error."""
    old, new = "kdl_kinematics_plugin/KDLKinematicsPlugin", "zeta_arm_kinematics/ZetaSolver"
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, old, new)
    element = f"{PARAMS}robot_description_kinematics.arm.kinematics_solver"
    assert only(findings(pkg)) == (
        "params.plugin",
        "error",
        MOVEIT_YAML,
        element,
    )  # no zeta_arm_kinematics anywhere
    (tmp_path / "zeta_arm_kinematics").mkdir()
    (tmp_path / "zeta_arm_kinematics" / "package.xml").write_text(
        "<package><name>zeta_arm_kinematics</name></package>\n"
    )
    assert only(findings(pkg)) == ("params.plugin", "warning", MOVEIT_YAML, element)


def test_chomps_own_namespace_is_checked_where_a_pipeline_loads_chomp(fresh, tmp_path):
    """CHOMP reads `chomp.<name>` with get_parameter_or whatever its pipeline's name
    (chomp_interface.cpp jazzy l.57-87; the table's rows, curated.yaml): a pipeline of another
    name loading CHOMP makes it read the top-level `chomp.max_iterations`, an int, and a double
    there throws; with no pipeline loading CHOMP nothing reads it."""
    top = "    default_planning_pipeline: ompl\n"
    pkg = edited(fresh, tmp_path, "jazzy", MOVEIT_YAML, top, top + "    chomp:\n      max_iterations: 2.5\n")
    assert findings(pkg) == []
    replace_text(
        pkg, MOVEIT_YAML, "pilz_industrial_motion_planner/CommandPlanner", "chomp_interface/CHOMPPlanner"
    )
    found = findings(pkg)
    assert only(found) == ("params.type", "error", MOVEIT_YAML, f"{PARAMS}chomp.max_iterations")
    assert "chomp_interface.cpp:58" in found[0].hint
