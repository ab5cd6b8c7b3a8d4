"""Fixtures shared by the unit tests: the marm robot (frozen, so one per session) and its scene."""

from __future__ import annotations

import pytest

from marm_setup.robot.load import load_robot
from tests.conftest import MARM_URDF


@pytest.fixture(scope="session")
def marm():
    return load_robot(MARM_URDF)


@pytest.fixture(scope="session")
def marm_scene(marm):
    from marm_setup.collision.scene import CollisionScene

    return CollisionScene(marm)


@pytest.fixture(scope="session")
def panda1():
    """(SRDF, robot) of the real MoveIt 1 panda package in ../shared/realworld (skipped if absent)."""
    from marm_setup.package.read import read_package
    from marm_setup.validate.runner import load_package_robot
    from tests.validate_helpers import panda

    good = panda("ros1")
    pkg = read_package(good.path, package_paths=good.package_paths)
    robot, problems = load_package_robot(pkg)
    assert not problems
    return pkg.srdf, robot
