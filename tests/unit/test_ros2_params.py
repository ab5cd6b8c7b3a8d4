"""The parameters each ROS 2 distro's move_group, planning pipelines and controller managers read,
checked on our rendered package for that distro (tests/goldens/ros2-<distro>).

What each reads, from the sources (moveit/moveit2 humble and jazzy branches, ros-controls/ros2_control):
- move_group: the `planning_pipelines` list (moveit_ros/move_group/src/move_group.cpp, main;
  what MoveItConfigsBuilder writes, moveit_configs_utils moveit_configs_builder.py l.464; MoveItCpp
  also reads `planning_pipelines.pipeline_names`, moveit_cpp.h PlanningPipelineOptions::load, and
  move_group appends one to the other: one form only) and `default_planning_pipeline`, which
  must be one of them, else move_group warns and falls back (same file, main).
- Humble PlanningPipeline: `<pipeline>.planning_plugin` (one string; empty -> the first declared
  plugin class, whichever that is) and `<pipeline>.request_adapters` read into ONE std::string and
  split at spaces (a YAML list there is a parameter type exception: move_group dies)
  (humble moveit_ros/planning/planning_pipeline/src/planning_pipeline.cpp l.58-77).
- Jazzy PlanningPipeline: `<pipeline>.planning_plugins`, `request_adapters`, `response_adapters`
  string arrays; an empty planning_plugins throws "Planning plugin name is empty or not defined"
  (jazzy planning_pipeline.cpp, PlanningPipeline::configure; planning_pipeline_parameters.yaml).
- Planning scene monitor: `publish_planning_scene`, `publish_geometry_updates`,
  `publish_state_updates`, `publish_transforms_updates`, declared false by default
  (moveit_ros/planning/planning_scene_monitor/src/planning_scene_monitor.cpp, initialize()).
- move_group capabilities: the top-level `capabilities` string (both distros) plus, per pipeline,
  Jazzy's `<pipeline>.capabilities` (jazzy move_group.cpp, configureCapabilities); Humble looks
  for "planning_pipelines/<pipeline>/capabilities", which is no valid ROS 2 parameter name, so
  a pipeline's own capabilities never load there (moveit/moveit2#1393, #2707).
- MoveItSimpleControllerManager: `moveit_simple_controller_manager.controller_names`, then per
  controller `type` (FollowJointTrajectory | GripperCommand), `action_ns`, `joints`, `default`
  (moveit_plugins/moveit_simple_controller_manager/src/moveit_simple_controller_manager.cpp, initialize()).
- ros2_control controller_manager: `update_rate` (an integer) and `<controller>.type`
  (controller_manager/src/controller_manager.cpp; controller_manager_parameters.yaml); the
  controllers' own parameters (`joints`, `command_interfaces`, `state_interfaces` of
  JointTrajectoryController, `joint` of GripperActionController) via the spawner's --param-file.
"""

from __future__ import annotations

import re

import pytest
import yaml

from tests.unit.test_package_render import rendered

# The adapter plugins each distro's moveit_ros_planning exports (its default_*_adapters plugin XML).
HUMBLE_REQUEST_ADAPTERS = {
    f"default_planner_request_adapters/{name}"
    for name in (
        "AddIterativeSplineParameterization",
        "AddRuckigTrajectorySmoothing",
        "AddTimeOptimalParameterization",
        "Empty",
        "FixStartStateBounds",
        "FixStartStateCollision",
        "FixStartStatePathConstraints",
        "FixWorkspaceBounds",
        "ResolveConstraintFrames",
    )
}
JAZZY_REQUEST_ADAPTERS = {
    f"default_planning_request_adapters/{name}"
    for name in (
        "CheckForStackedConstraints",
        "CheckStartStateBounds",
        "CheckStartStateCollision",
        "ResolveConstraintFrames",
        "ValidateWorkspaceBounds",
    )
}
JAZZY_RESPONSE_ADAPTERS = {
    f"default_planning_response_adapters/{name}"
    for name in (
        "AddRuckigTrajectorySmoothing",
        "AddTimeOptimalParameterization",
        "DisplayMotionPath",
        "ValidateSolution",
    )
}
PLANNER_PLUGINS = {
    "ompl": "ompl_interface/OMPLPlanner",
    "pilz_industrial_motion_planner": "pilz_industrial_motion_planner/CommandPlanner",
    "chomp": "chomp_interface/CHOMPPlanner",
    "stomp": "stomp_moveit/StompPlanner",
}


def move_group_params(distro: str) -> dict:
    return yaml.safe_load(rendered("ros2", distro)["config/moveit.yaml"])["/**"]["ros__parameters"]


def humble_pipeline(entry: dict) -> tuple[list[str], list[str], list[str]]:
    """(planner plugins, request adapters, response adapters) as Humble's PlanningPipeline reads them."""
    plugin = entry.get("planning_plugin")
    adapters = entry.get("request_adapters", "")
    assert isinstance(plugin, str) and plugin, "Humble needs one planning_plugin string"
    assert isinstance(adapters, str), "Humble reads request_adapters into one string"
    return [plugin], adapters.split(), []


def jazzy_pipeline(entry: dict) -> tuple[list[str], list[str], list[str]]:
    """(planner plugins, request adapters, response adapters) as Jazzy's PlanningPipeline reads them."""
    lists = [entry.get(key, []) for key in ("planning_plugins", "request_adapters", "response_adapters")]
    for value in lists:
        assert isinstance(value, list) and all(isinstance(v, str) for v in value), "Jazzy reads string arrays"
    assert lists[0], "Jazzy throws on an empty planning_plugins"
    return lists[0], lists[1], lists[2]


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_planning_pipelines_load_on_the_distro(distro):
    params = move_group_params(distro)
    names = params["planning_pipelines"]
    assert params["default_planning_pipeline"] in names
    read = humble_pipeline if distro == "humble" else jazzy_pipeline
    requests = HUMBLE_REQUEST_ADAPTERS if distro == "humble" else JAZZY_REQUEST_ADAPTERS
    responses = set() if distro == "humble" else JAZZY_RESPONSE_ADAPTERS
    for name in names:
        planners, request, response = read(params[name])
        assert planners == [PLANNER_PLUGINS[name]], name
        assert set(request) <= requests and set(response) <= responses, name
    other = jazzy_pipeline if distro == "humble" else humble_pipeline
    with pytest.raises(AssertionError):  # the other distro's reader refuses this file
        other(params["ompl"])


PILZ_CAPABILITIES = {
    "pilz_industrial_motion_planner/MoveGroupSequenceAction",
    "pilz_industrial_motion_planner/MoveGroupSequenceService",
}


def loaded_capabilities(params: dict, distro: str) -> set[str]:
    """The extra capabilities move_group loads from these parameters on `distro`."""
    out = set(params.get("capabilities", "").split())
    if distro != "humble":
        for name in params["planning_pipelines"]:
            out |= set(params[name].get("capabilities", "").split())
    return out


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_pilz_sequence_capabilities_load_on_the_distro(distro):
    params = move_group_params(distro)
    assert "pilz_industrial_motion_planner" in params["planning_pipelines"]
    assert loaded_capabilities(params, distro) == PILZ_CAPABILITIES


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_moveit_controller_manager_reads_every_controller(distro):
    params = move_group_params(distro)
    assert (
        params["moveit_controller_manager"]
        == "moveit_simple_controller_manager/MoveItSimpleControllerManager"
    )
    manager = params["moveit_simple_controller_manager"]
    controllers = yaml.safe_load(rendered("ros2", distro)["config/ros2_controllers.yaml"])
    ros2_manager = controllers["controller_manager"]["ros__parameters"]
    assert isinstance(ros2_manager["update_rate"], int)
    for name in manager["controller_names"]:
        entry = manager[name]
        assert entry["type"] in ("FollowJointTrajectory", "GripperCommand")
        assert isinstance(entry["action_ns"], str) and isinstance(entry["default"], bool)
        assert entry["joints"] and all(isinstance(j, str) for j in entry["joints"])
        assert "type" in ros2_manager[name]
        own = controllers[name]["ros__parameters"]
        if entry["type"] == "FollowJointTrajectory":
            assert own["joints"] == entry["joints"] and own["command_interfaces"] and own["state_interfaces"]
        else:
            assert own["joint"] == entry["joints"][0]


@pytest.mark.parametrize("distro", ["humble", "jazzy"])
def test_every_pipeline_loads_on_its_distro(distro):
    import dataclasses

    from marm_setup.render.package import render_package
    from tests.render_helpers import inferred_marm

    names = ("ompl", "chomp", "pilz", "stomp")  # STOMP on Humble built from source
    model, robot = inferred_marm("ros2", __import__("pathlib").Path("pkg"), distro)
    files = {
        f.path: f.content for f in render_package(dataclasses.replace(model, planning_pipelines=names), robot)
    }
    params = yaml.safe_load(files["config/moveit.yaml"])["/**"]["ros__parameters"]
    read = humble_pipeline if distro == "humble" else jazzy_pipeline
    namespaces = params["planning_pipelines"]
    assert len(namespaces) == len(names)
    for namespace in namespaces:
        planners, request, response = read(params[namespace])
        assert planners == [PLANNER_PLUGINS[namespace]]
        assert set(request) <= (HUMBLE_REQUEST_ADAPTERS if distro == "humble" else JAZZY_REQUEST_ADAPTERS)
        assert set(response) <= JAZZY_RESPONSE_ADAPTERS


@pytest.mark.parametrize(
    ("target", "distro", "pipelines", "message"),
    [
        (
            "ros1",
            "noetic",
            ("stomp",),
            "'stomp' is not in MoveIt's noetic binaries (only humble, jazzy, kilted, rolling)",
        ),
        ("ros2", "jazzy", ("ompl", "ompl"), "'ompl' is listed twice"),
        ("ros2", "jazzy", ("omp",), "unknown planning pipeline 'omp'"),
        ("ros2", "jazzy", (), "no planning pipeline"),
    ],
)
def test_pipelines_a_distro_cannot_load_are_input_errors(target, distro, pipelines, message):
    import dataclasses
    from pathlib import Path

    from marm_setup.errors import InputError
    from marm_setup.setup.checks import check_setup
    from tests.render_helpers import inferred_marm

    model, robot = inferred_marm(target, Path("pkg"), distro)
    with pytest.raises(InputError, match=re.escape(message)):
        check_setup(dataclasses.replace(model, planning_pipelines=pipelines), robot, "marm_setup.yaml")


def test_stomp_on_humble_is_one_warning_line_saying_what_to_build():
    """moveit2's humble branch has no moveit_planners/stomp (Iron on): Humble users build it
    from source (moveit/moveit2#2550, #2742), so a Humble package may name it, with a warning."""
    import dataclasses
    from pathlib import Path

    from marm_setup.setup.checks import check_setup, setup_warnings
    from tests.render_helpers import inferred_marm

    for distro, warned in (("humble", True), ("jazzy", False)):
        model, robot = inferred_marm("ros2", Path("pkg"), distro)
        model = dataclasses.replace(model, planning_pipelines=("ompl", "stomp"))
        check_setup(model, robot, "marm_setup.yaml")
        lines = setup_warnings(model)
        assert len(lines) == int(warned)
    (line,) = setup_warnings(dataclasses.replace(model, ros_distro="humble"))
    assert line.startswith("warning: planning_pipelines[1]: 'stomp' is not in MoveIt's humble binaries")
    assert (
        "build moveit_planners_stomp from moveit2's source" in line and "moveit/moveit2#2550, #2742" in line
    )
