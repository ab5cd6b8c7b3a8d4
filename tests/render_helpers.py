"""The marm setup as `init --setup fixtures/marm/marm_setup.yaml` builds it (real inference plus
the course's SPEC), and the marm robot, for render tests."""

from __future__ import annotations

import functools
from pathlib import Path

from marm_setup.robot.load import load_robot
from marm_setup.robot.model import RobotModel
from marm_setup.setup.model import SetupModel
from tests.conftest import FIXTURES, MARM_URDF

MARM_SPEC = FIXTURES / "marm" / "marm_setup.yaml"


def inferred_marm(target: str, out: Path, distro: str | None = None) -> tuple[SetupModel, RobotModel]:
    """The marm setup as `init --setup fixtures/marm/marm_setup.yaml --out out
    [--ros-distro distro]` builds it (no $ROS_DISTRO: the target's default distro).

    The collision matrix is left empty: render tests check templates, not sampling.
    """
    return _inferred(target, str(out), distro)


@functools.lru_cache(maxsize=8)
def _inferred(target: str, out: str, distro: str | None) -> tuple[SetupModel, RobotModel]:
    from marm_setup.flows import InitRequest, RobotInput, build_setup

    robot = marm_robot()
    request = InitRequest(
        RobotInput.parse(MARM_URDF), out=Path(out), target=target, ros_distro=distro, spec=MARM_SPEC
    )
    return build_setup(request, robot), robot


@functools.lru_cache(maxsize=1)
def marm_robot() -> RobotModel:
    return load_robot(MARM_URDF)


def marm_with(target: str = "ros2", distro: str | None = None, **changes) -> tuple[SetupModel, RobotModel]:
    """The inferred marm setup for `target` / `distro` with some fields replaced."""
    import dataclasses

    model, robot = inferred_marm(target, Path(f"/nonexistent/{target}-{distro}"), distro)
    return dataclasses.replace(model, **changes), robot


def rendered_files(model: SetupModel, robot: RobotModel) -> dict[str, str]:
    from marm_setup.render.package import render_package

    return {f.path: f.content for f in render_package(model, robot)}


def assert_check_error(model: SetupModel, robot: RobotModel, element: str, message: str) -> None:
    """check_setup refuses the setup with one InputError naming `element` and saying `message`."""
    import pytest

    from marm_setup.errors import InputError
    from marm_setup.setup.checks import check_setup

    with pytest.raises(InputError) as err:
        check_setup(model, robot, "marm_setup.yaml")
    assert (err.value.path, err.value.element) == ("marm_setup.yaml", element)
    assert message in err.value.message


def assert_yaml_errors(model: SetupModel, cases: list[tuple[dict, str, str]]) -> None:
    """Each (top-level keys, element, message): the setup's YAML with those keys replaced fails to
    load with an InputError naming `element` and saying `message`."""
    import pytest

    from marm_setup.errors import InputError
    from marm_setup.setup.yaml_io import setup_from_dict, setup_to_dict

    data = setup_to_dict(model)
    for extra, element, message in cases:
        with pytest.raises(InputError) as err:
            setup_from_dict({**data, **extra}, "spec.yaml")
        assert err.value.element == element and message in err.value.message, (element, err.value)


def written_ros2_marms(tmp_path_factory) -> dict[str, Path]:
    """A generated ROS 2 marm package per distro (humble, jazzy), matrix of 50 trials, written
    under `tmp_path_factory` (a module fixture's: made once, copied by the tests that edit)."""
    from marm_setup.flows import with_collision_matrix
    from marm_setup.render.package import render_package
    from marm_setup.render.writer import apply_writes, plan_writes

    out = {}
    for distro in ("humble", "jazzy"):
        pkg = tmp_path_factory.mktemp(distro) / "marm_moveit_config"
        model, robot = inferred_marm("ros2", pkg, distro)
        model = with_collision_matrix(model, robot, trials=50, seed=0)
        apply_writes(plan_writes(render_package(model, robot), pkg), pkg)
        out[distro] = pkg
    return out
