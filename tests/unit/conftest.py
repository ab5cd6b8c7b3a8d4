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
