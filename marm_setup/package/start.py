"""The state a package's demo starts in (`setup.start_state`), from its files."""

from __future__ import annotations

from marm_setup.package.model import MoveItPackage
from marm_setup.robot import RobotModel
from marm_setup.setup import demo_start_values


def package_start_values(pkg: MoveItPackage, robot: RobotModel) -> dict[str, float]:
    """ros1: fake_controllers.yaml's `initial` poses; ros2: initial_positions.yaml."""
    fake, positions = pkg.fake_controllers, pkg.initial_positions
    initial = [(i.group, i.pose) for i in fake.initial or ()] if fake is not None else []
    values = {p.key: p.value for p in positions.values or ()} if positions is not None else {}
    return demo_start_values(pkg.target, pkg.srdf, robot, initial, values)
