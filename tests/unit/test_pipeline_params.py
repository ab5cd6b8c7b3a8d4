"""Per-pipeline parameters (setup key `pipeline_parameters`, moveit_params/pipeline_params.py): the names
each distro's MoveIt reads in a pipeline's namespace, rendered in that distro's format over
marm-setup's defaults, checked in the setup (unknown names: an error naming the valid ones) and
by validate in any package whose distro is known."""

from __future__ import annotations

import dataclasses
import re
from pathlib import Path

import pytest
import yaml

from marm_setup.flows import with_collision_matrix
from marm_setup.moveit_params.pipeline_params import effective_parameters, known_parameters
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from marm_setup.setup.checks import check_setup, setup_warnings
from marm_setup.setup.yaml_io import setup_from_dict, setup_to_dict
from tests.render_helpers import assert_check_error, marm_with, rendered_files
from tests.unit.test_distro_rules import edit, rules

SEED_LIKE = (
    ("ompl", (("jiggle_fraction", 0.05), ("start_state_max_bounds_error", 0.1))),
    ("stomp", (("num_timesteps", 60), ("exponentiated_cost_sensitivity", 0.8))),
    ("pilz", (("request_adapters", ()), ("default_planner_config", "PTP"))),
)


def moveit_params(model, robot) -> dict:
    text = rendered_files(model, robot)["config/moveit.yaml"]
    return yaml.safe_load(text)["/**"]["ros__parameters"]


def with_params(distro: str, params=SEED_LIKE, pipelines=("ompl", "stomp", "pilz")):
    return marm_with("ros2", distro, planning_pipelines=pipelines, pipeline_parameters=params)


def test_humble_writes_them_in_its_namespaces_and_capabilities_at_the_top():
    model, robot = with_params("humble")
    check_setup(model, robot, "marm_setup.yaml")
    params = moveit_params(model, robot)
    assert params["planning_pipelines"] == ["ompl", "stomp", "pilz_industrial_motion_planner"]
    assert params["ompl"]["jiggle_fraction"] == 0.05
    # STOMP's parameters in the pipeline's namespace, an integer where STOMP declares one
    assert params["stomp"]["num_timesteps"] == 60 and isinstance(params["stomp"]["num_timesteps"], int)
    assert params["stomp"]["exponentiated_cost_sensitivity"] == 0.8 and "stomp_moveit" not in params["stomp"]
    pilz = params["pilz_industrial_motion_planner"]
    assert pilz["request_adapters"] == "" and "capabilities" not in pilz
    assert params["capabilities"].split() == [
        "pilz_industrial_motion_planner/MoveGroupSequenceAction",
        "pilz_industrial_motion_planner/MoveGroupSequenceService",
    ]


def test_jazzy_leaves_out_what_only_humble_reads_with_a_warning_and_no_empty_list():
    model, robot = with_params("jazzy")
    check_setup(model, robot, "marm_setup.yaml")
    params = moveit_params(model, robot)
    assert "jiggle_fraction" not in params["ompl"] and "start_state_max_bounds_error" not in params["ompl"]
    assert "request_adapters" not in params["pilz_industrial_motion_planner"]  # [] gives rcl no value
    assert params["pilz_industrial_motion_planner"]["capabilities"]  # Jazzy reads its own
    assert params["stomp"]["planning_plugins"] == ["stomp_moveit/StompPlanner"]
    assert [w.split(":")[1].strip() for w in setup_warnings(model)] == [
        "pipeline_parameters.ompl.jiggle_fraction",
        "pipeline_parameters.ompl.start_state_max_bounds_error",
    ]


def test_a_sub_namespace_is_written_nested_and_doubles_as_doubles():
    model, robot = with_params(
        "jazzy", (("ompl", (("totg.path_tolerance", 1), ("default_workspace_bounds", 5))),)
    )
    params = moveit_params(model, robot)
    assert params["ompl"]["totg"] == {"path_tolerance": 1.0}
    assert isinstance(params["ompl"]["default_workspace_bounds"], float)


@pytest.mark.parametrize(
    ("distro", "params", "element", "message"),
    [
        ("humble", (("ompl", (("jigle_fraction", 0.1),)),), "pipeline_parameters.ompl.jigle_fraction",
         "unknown parameter 'jigle_fraction' of pipeline ompl (valid on humble: request_adapters, path_tolerance, "
         "resample_dt, min_angle_change, start_state_max_bounds_error, start_state_max_dt, jiggle_fraction"),
        ("humble", (("stomp", (("stomp_moveit.num_timesteps", 60),)),), "pipeline_parameters.stomp.stomp_moveit.num_timesteps",
         "STOMP declares its parameters in the pipeline's namespace: write num_timesteps"),
        ("humble", (("stomp", (("num_timesteps", 60.0),)),), "pipeline_parameters.stomp.num_timesteps",
         "expected an int, got 60.0"),
        ("jazzy", (("stomp", (("num_timesteps", 2),)),), "pipeline_parameters.stomp.num_timesteps",
         "must be at least 3, got 2"),
        ("humble", (("ompl", (("jiggle_fraction", "a"),)),), "pipeline_parameters.ompl.jiggle_fraction",
         "expected a double, got 'a'"),
        ("jazzy", (("ompl", (("request_adapters", ("default_planner_request_adapters/FixStartStateBounds",)),)),),
         "pipeline_parameters.ompl.request_adapters", "is Humble's adapter: Jazzy has none such"),
        ("humble", (("chomp", (("ridge_factor", 0.1),)),), "pipeline_parameters.chomp",
         "'chomp' is not in planning_pipelines (ompl, stomp, pilz)"),
        ("humble", (("chomp", (("trajectory_initialization_method", "spline"),)),), "pipeline_parameters.chomp.trajectory_initialization_method",
         "'spline' is not one of: quintic-spline, linear, cubic, fillTrajectory"),
    ],
)  # fmt: skip
def test_a_bad_parameter_is_one_error_naming_it(distro, params, element, message):
    pipelines = ("ompl", "stomp", "pilz") + (
        ("chomp",) if params[0][0] == "chomp" and "trajectory" in element else ()
    )
    model, robot = with_params(distro, params, pipelines)
    assert_check_error(model, robot, element, message)


def test_ros1_takes_no_pipeline_parameters():
    model, robot = marm_with("ros1", "noetic", pipeline_parameters=(("ompl", (("jiggle_fraction", 0.1),)),))
    assert_check_error(
        model, robot, "pipeline_parameters", "written for ROS 2 (humble, jazzy, kilted, rolling) only"
    )


def test_the_setup_file_takes_them_nested_or_dotted_and_writes_them_back():
    model, _ = with_params("humble")
    data = setup_to_dict(model)
    assert data["pipeline_parameters"]["stomp"] == {
        "num_timesteps": 60,
        "exponentiated_cost_sensitivity": 0.8,
    }
    nested = {**data, "pipeline_parameters": {"ompl": {"totg": {"path_tolerance": 0.2}}}}
    assert setup_from_dict(nested).pipeline_parameters == (("ompl", (("totg.path_tolerance", 0.2),)),)
    assert setup_from_dict(data) == model


def test_the_parameters_are_moveits_declarations_with_their_sources():
    """Each parameter MoveIt reads comes from the declared-parameter tables with its source line;
    CHOMP's defaults marm-setup writes are CHOMP's own fallbacks; STOMP on Humble (built from
    source) is declared as on Jazzy."""
    from marm_setup.moveit_params.pipeline_params import CHOMP_DEFAULTS, parameter

    for distro in ("humble", "jazzy", "rolling"):
        for p in known_parameters("chomp", distro) + known_parameters("stomp", distro):
            assert re.fullmatch(r"[\w./-]+:\d+", p.source) or p.name == "capabilities", (distro, p)
    chomp = {p.name: p for p in known_parameters("chomp", "humble")}
    assert {name: chomp[name].default for name, _ in CHOMP_DEFAULTS} == dict(CHOMP_DEFAULTS)
    assert chomp["max_iterations"].source.startswith(
        "moveit_planners/chomp/chomp_interface/src/chomp_interface.cpp:"
    )
    assert known_parameters("stomp", "humble")[-9:] == known_parameters("stomp", "jazzy")[-9:]
    jiggle = parameter("ompl", "humble", "jiggle_fraction")
    assert jiggle is not None and (jiggle.type, jiggle.default) == ("double", 0.02)
    assert jiggle.source.endswith("fix_start_state_collision.cpp:61")


def test_defaults_are_moveits_own_on_humble():
    """moveit_configs_utils/default_configs/*_planning.yaml (humble): OMPL with the six adapters,
    start_state_max_bounds_error 0.1 and jiggle_fraction 0.05, Pilz without adapters."""
    ompl = dict(effective_parameters("ompl", "humble", ()))
    assert len(ompl["request_adapters"]) == 6
    assert (ompl["start_state_max_bounds_error"], ompl["jiggle_fraction"]) == (0.1, 0.05)
    assert dict(effective_parameters("pilz", "humble", ()))["request_adapters"] == ()
    assert "start_state_max_bounds_error" not in {p.name for p in known_parameters("ompl", "jazzy")}


# -- validate ------------------------------------------------------------------------------------


def write(tmp_path: Path, distro: str) -> Path:
    out = tmp_path / "marm_moveit_config"
    model, robot = with_params(distro)
    model = with_collision_matrix(dataclasses.replace(model), robot, trials=200, seed=0)
    apply_writes(plan_writes(render_package(model, robot), out), out)
    return out


def test_validate_reads_the_parameters_as_the_distro_does(tmp_path):
    pkg = write(tmp_path, "humble")
    found = rules(pkg)
    assert not [r for r in found if r.startswith("pipeline.")]
    (stomp,) = found["distro.planner-from-source"]  # STOMP on Humble: build it, a warning
    assert not stomp.is_error and stomp.element == "/**.ros__parameters.stomp.planning_plugin"
    moveit = pkg / "config" / "moveit.yaml"
    edit(moveit, "jiggle_fraction: 0.05", "jiggle_fraction: 1")  # an integer: rclcpp throws
    edit(moveit, "      num_timesteps: 60\n", "      stomp_moveit:\n        num_timesteps: 60\n")
    edit(moveit, "      num_rollouts: 30", "      num_rollouts: 0")
    edit(
        moveit,
        "      default_planner_config: PTP",
        "      default_planner_config: PTP\n      fix_start_state: true",
    )
    found = rules(pkg)
    (typed,) = found["pipeline.parameter-type"][:1]
    assert typed.is_error and typed.element == "/**.ros__parameters.ompl.jiggle_fraction"
    assert [f.element.rsplit(".", 1)[-1] for f in found["pipeline.parameter-type"]] == [
        "jiggle_fraction",
        "num_rollouts",
    ]
    (nested,) = found["pipeline.stomp-namespace"]
    assert not nested.is_error and nested.element.endswith("stomp.stomp_moveit.num_timesteps")
    (jazzy_only,) = found["pipeline.other-distro-parameter"]
    assert not jazzy_only.is_error and "jazzy's does" in jazzy_only.message


def _jazzy_package(tmp_path: Path, params: tuple, pipelines: tuple[str, ...]) -> tuple[Path, Path]:
    """Our Jazzy marm package with these pipeline parameters and pipelines, clean of pipeline
    findings: its folder and its config/moveit.yaml."""
    out = tmp_path / "marm_moveit_config"
    model, robot = with_params("jazzy", params, pipelines)
    model = with_collision_matrix(model, robot, trials=200, seed=0)
    apply_writes(plan_writes(render_package(model, robot), out), out)
    assert not [r for r in rules(out) if r.startswith("pipeline.")]
    return out, out / "config" / "moveit.yaml"


def test_validate_a_chomp_setting_in_a_pipeline_not_named_chomp_is_never_read(tmp_path):
    """CHOMP reads `chomp.<name>` whatever its pipeline's name (chomp_interface.cpp jazzy
    l.57-87): in a pipeline named otherwise each setting is unread (a warning), and a value of
    the wrong type there stops nothing."""
    out, moveit = _jazzy_package(tmp_path, (), ("ompl", "chomp"))
    edit(moveit, "      - chomp\n", "      - chomp_fast\n")
    edit(moveit, "    chomp:\n", "    chomp_fast:\n")
    edit(moveit, "max_iterations: 200", "max_iterations: 2.5")
    found = rules(out)
    assert "pipeline.parameter-type" not in found
    unread = {f.element.rsplit(".", 1)[-1]: f for f in found["pipeline.unknown-parameter"]}
    assert {"max_iterations", "planning_time_limit", "learning_rate"} <= set(unread)
    assert not unread["max_iterations"].is_error
    assert "CHOMP reads chomp.max_iterations" in unread["max_iterations"].message


def test_validate_checks_jazzys_declarations_types_bounds_and_choices(tmp_path):
    """Jazzy's generate_parameter_library declarations (the jazzy table): an integer for the
    double totg.path_tolerance (default_response_adapter_params.yaml) and a negative
    exponentiated_cost_sensitivity (stomp_moveit.yaml gt_eq 0.0) stop the pipeline; an unknown
    CHOMP initialization method is logged and quintic-spline kept (chomp_interface.cpp)."""
    chomp = (("chomp", (("trajectory_initialization_method", "linear"),)),)
    out, moveit = _jazzy_package(tmp_path, SEED_LIKE[1:] + chomp, ("ompl", "stomp", "chomp"))
    edit(moveit, "    ompl:\n", "    ompl:\n      totg:\n        path_tolerance: 1\n")
    edit(moveit, "exponentiated_cost_sensitivity: 0.8", "exponentiated_cost_sensitivity: -0.5")
    edit(moveit, "trajectory_initialization_method: linear", "trajectory_initialization_method: spline")
    found = rules(out)
    errors = {f.element.rsplit(".", 1)[-1]: f.message for f in found["pipeline.parameter-type"]}
    assert errors.keys() == {"path_tolerance", "exponentiated_cost_sensitivity"}
    assert errors["path_tolerance"].startswith("expected a double, got 1")
    assert errors["exponentiated_cost_sensitivity"].startswith("must be at least 0, got -0.5")
    (method,) = found["pipeline.parameter-value"]
    assert not method.is_error and "uses quintic-spline" in method.message
