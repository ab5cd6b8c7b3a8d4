"""Every package we generate validates with 0 errors, for every target and distro, on the marm
(course SPEC), the shared panda and the PR2 (inferred setups; a small matrix sample, the static
rules and pose collisions; the runtime planning checks run on the marm)."""

from __future__ import annotations

import pytest

from marm_setup.flows import InitRequest, RobotInput, build_setup, with_collision_matrix
from marm_setup.render.package import render_package
from marm_setup.render.writer import apply_writes, plan_writes
from marm_setup.robot.load import load_robot
from tests.conftest import FIXTURES, MARM_URDF, realworld
from tests.validate_helpers import validate_package

DISTROS = (("ros1", "noetic"), ("ros2", "humble"), ("ros2", "jazzy"))
# One worker runs them all (`--dist loadgroup`): a robot's matrix is the same for every target and
# distro (300 trials, seed 0), so the session's proof cache (tests/conftest.py) proves it once, not
# three times (the PR2's: 12 s of CPU each). What is tested is validate on the generated package.
pytestmark = pytest.mark.xdist_group("generated_validate")


def robots() -> dict[str, tuple]:
    return {
        "marm": (lambda t: MARM_URDF, lambda t: FIXTURES / "marm", FIXTURES / "marm" / "marm_setup.yaml"),
        "panda": (
            lambda t: realworld(
                t, "panda_description", "urdf", "panda_arm_hand.urdf.xacro" if t == "ros1" else "panda.urdf"
            ),
            lambda t: realworld(t),
            None,
        ),
        "pr2": (
            lambda t: realworld("ros1", "pr2_description", "urdf", "robot.xml"),
            lambda t: realworld("ros1"),
            None,
        ),
    }


@pytest.mark.parametrize("robot_name", ["marm", "panda", "pr2"])
@pytest.mark.parametrize(("target", "distro"), DISTROS)
def test_generated_packages_validate_without_errors(tmp_path, robot_name, target, distro):
    urdf_of, root_of, spec = robots()[robot_name]
    urdf, root = urdf_of(target), root_of(target)
    robot = load_robot(urdf, {}, [root])
    out = tmp_path / f"{robot_name}_moveit_config"
    request = InitRequest(
        RobotInput.parse(urdf, package_paths=(root,)), out=out, target=target, ros_distro=distro, spec=spec
    )
    model = with_collision_matrix(build_setup(request, robot), robot, trials=300, seed=0)
    apply_writes(plan_writes(render_package(model, robot), out), out)
    findings = validate_package(out, package_paths=[root], plan=robot_name == "marm", matrix_trials=100)
    errors = [f for f in findings if f.is_error]
    assert errors == [], "\n".join(f"{f.rule} {f.file} {f.element}: {f.message}" for f in errors)
