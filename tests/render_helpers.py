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
    from marm_setup.pipeline import InitRequest, build_setup

    robot = marm_robot()
    request = InitRequest(urdf=MARM_URDF, out=Path(out), target=target, ros_distro=distro, spec=MARM_SPEC)
    return build_setup(request, robot), robot


@functools.lru_cache(maxsize=1)
def marm_robot() -> RobotModel:
    return load_robot(MARM_URDF)
