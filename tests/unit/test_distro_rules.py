"""validate learns what a generated package must get right at run time: the distro's pipeline
format, the planning scene publishing flags, OMPL projection evaluators, one ros2_control system
per joint, a start state out of collision. Each rule: our fresh package passes, one broken fact
is the finding."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import yaml

from marm_setup.flows import with_collision_matrix
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from tests.conftest import FIXTURES
from tests.render_helpers import inferred_marm
from tests.validate_helpers import validate_package


def write(tmp_path: Path, target: str, distro: str | None = None) -> Path:
    out = tmp_path / "marm_moveit_config"
    model, robot = inferred_marm(target, out, distro)
    model = with_collision_matrix(model, robot, trials=300, seed=0)  # a real matrix: poses are checked
    apply_writes(plan_writes(render_package(model, robot), out), out)
    return out


def rules(pkg: Path, plan: bool = False) -> dict[str, list]:
    out: dict[str, list] = {}
    for f in validate_package(pkg, package_paths=[FIXTURES / "marm"], plan=plan, matrix_trials=200):
        out.setdefault(f.rule, []).append(f)
    return out


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new))


@pytest.mark.parametrize(("written", "declared"), [("jazzy", "humble"), ("humble", "jazzy")])
def test_a_package_of_the_other_distro_is_an_error(tmp_path, written, declared):
    pkg = write(tmp_path, "ros2", written)
    assert not [r for r in rules(pkg) if r.startswith("distro.")]
    edit(pkg / "marm_setup.yaml", f"ros_distro: {written}", f"ros_distro: {declared}")
    found = rules(pkg)
    formats = found.get("distro.pipeline-format", [])
    assert {f.element.rsplit(".", 2)[-2] for f in formats} == {"ompl", "pilz_industrial_motion_planner"}
    assert all(f.is_error for f in formats)


def test_adapters_of_the_other_distro_are_errors(tmp_path):
    pkg = write(tmp_path, "ros2", "jazzy")
    edit(
        pkg / "config" / "moveit.yaml",
        "- default_planning_request_adapters/ResolveConstraintFrames",
        "- default_planner_request_adapters/ResolveConstraintFrames",
    )
    assert [f.element for f in rules(pkg)["distro.adapter"]] == [
        "/**.ros__parameters.ompl.request_adapters",
        "/**.ros__parameters.pilz_industrial_motion_planner.request_adapters",
    ]


def test_jazzy_pipelines_validate_their_solutions(tmp_path):
    """Every pipeline a Jazzy package writes ends its responses with ValidateSolution, as
    MoveIt's default configs do; one without it is a warning naming the pipeline."""
    pkg = write(tmp_path, "ros2", "jazzy")
    text = (pkg / "config" / "moveit.yaml").read_text()
    assert text.count("- default_planning_response_adapters/ValidateSolution") == 2  # ompl, pilz
    assert "pipeline.no-validate-solution" not in rules(pkg)
    edit(
        pkg / "config" / "moveit.yaml",
        "        - default_planning_response_adapters/ValidateSolution\n        - default_planning_response_adapters/DisplayMotionPath\n      capabilities",
        "        - default_planning_response_adapters/DisplayMotionPath\n      capabilities",
    )
    (finding,) = rules(pkg)["pipeline.no-validate-solution"]
    assert finding.element == "/**.ros__parameters.pilz_industrial_motion_planner.response_adapters"
    assert not finding.is_error


def test_pipeline_capabilities_on_humble_are_a_warning(tmp_path):
    pkg = write(tmp_path, "ros2", "humble")
    assert "distro.pipeline-capabilities" not in rules(pkg)
    edit(pkg / "config" / "moveit.yaml", "      default_planner_config: PTP\n",
         "      default_planner_config: PTP\n      capabilities: pilz_industrial_motion_planner/MoveGroupSequenceAction\n")  # fmt: skip
    (finding,) = rules(pkg)["distro.pipeline-capabilities"]
    assert not finding.is_error and "MoveGroupSequenceAction" in finding.message
    assert finding.element == "/**.ros__parameters.pilz_industrial_motion_planner.capabilities"


def test_missing_publishing_flags_are_a_warning(tmp_path):
    pkg = write(tmp_path, "ros2")
    assert "moveit.publish-flags" not in rules(pkg)
    edit(pkg / "config" / "moveit.yaml", "    publish_state_updates: true\n", "")
    (finding,) = rules(pkg)["moveit.publish-flags"]
    assert not finding.is_error and "publish_state_updates" in finding.message


@pytest.mark.parametrize("target", ["ros1", "ros2"])
def test_a_default_planner_without_its_projection_is_an_error(tmp_path, target):
    pkg = write(tmp_path, target)
    assert "ompl.projection-missing" not in rules(pkg)
    config = pkg / "config" / ("ompl_planning.yaml" if target == "ros1" else "moveit.yaml")
    config.write_text(re.sub(r"\n *projection_evaluator: joints\(joint1,joint2\)", "", config.read_text()))
    edit(config, "default_planner_config: RRTConnect", "default_planner_config: KPIECE")
    (finding,) = rules(pkg)["ompl.projection-missing"]
    assert finding.is_error and finding.element.endswith("arm") and "joints(joint1,joint2)" in finding.hint


def test_a_joint_in_two_ros2_control_systems_is_an_error(tmp_path):
    pkg = write(tmp_path, "ros2")
    assert "ros2_control.duplicate-joint" not in rules(pkg)
    xacro = pkg / "config" / "marm.ros2_control.xacro"
    text = xacro.read_text()
    start, end = text.index("    <ros2_control"), text.index("</ros2_control>") + len("</ros2_control>\n")
    block = text[start:end].replace('name="${name}"', 'name="second"')
    xacro.write_text(text[:end] + block + text[end:])
    found = rules(pkg)["ros2_control.duplicate-joint"]
    assert {f.element for f in found} >= {"joint[joint1]", "joint[finger_joint1]"}


def colliding_arm_state(pkg: Path) -> dict[str, float]:
    """A seeded arm state in collision under the package's SRDF (real coal checks)."""
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot.kinematics import sample_configurations
    from marm_setup.setup.srdf import allowed_pairs, read_srdf
    from tests.render_helpers import marm_robot

    robot = marm_robot()
    scene = CollisionScene(robot)
    pairs = scene.enabled_pairs(allowed_pairs(read_srdf(pkg / "config" / "marm.srdf"), scene.candidate_pairs))
    q = sample_configurations(robot, np.random.default_rng(3), 400)
    hits = scene.first_collisions(q, pairs)
    i = next(i for i, h in enumerate(hits) if h is not None)
    return dict(zip(robot.active_joint_names, map(float, q[i]), strict=True))


def test_a_start_state_in_collision_is_an_error(tmp_path):
    pkg = write(tmp_path, "ros2")
    assert "pose.start-collision" not in rules(pkg)
    state = colliding_arm_state(pkg)
    path = pkg / "config" / "initial_positions.yaml"
    data = yaml.safe_load(path.read_text())
    data["initial_positions"].update({j: v for j, v in state.items() if j in data["initial_positions"]})
    path.write_text(yaml.safe_dump(data))
    (finding,) = rules(pkg)["pose.start-collision"]
    assert finding.is_error and finding.file == "config/initial_positions.yaml"
