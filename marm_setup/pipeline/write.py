"""Steps `init`, `init --from-package` and `collisions DIR` share: the collision matrix of a setup,
what a setup holds (one line each), rendering and the atomic write."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.robot import RobotModel
from marm_setup.ros import Target
from marm_setup.setup import CollisionSettings, SetupModel

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene, DisabledPair, Progress
    from marm_setup.render import FileChange
    from marm_setup.templating import RenderedFile


def with_collision_matrix(
    model: SetupModel,
    robot: RobotModel,
    *,
    trials: int,
    seed: int,
    jobs: int = 1,
    progress: Progress | None = None,
    scene: CollisionScene | None = None,
) -> SetupModel:
    """Compute the matrix unless the setup already has pairs (from an SRDF or the SPEC)."""
    if model.collision.disabled:
        return model
    fraction = model.collision.min_collision_fraction
    disabled = _disabled_pairs(
        robot, trials=trials, seed=seed, fraction=fraction, jobs=jobs, progress=progress, scene=scene
    )
    settings = CollisionSettings(seed=seed, trials=trials, min_collision_fraction=fraction, disabled=disabled)
    return dataclasses.replace(model, collision=settings)


def _disabled_pairs(
    robot: RobotModel,
    *,
    trials: int,
    seed: int,
    fraction: float,
    jobs: int,
    progress: Progress | None,
    scene: CollisionScene | None = None,
) -> tuple[DisabledPair, ...]:
    from marm_setup.collision import compute_collision_matrix

    matrix = compute_collision_matrix(
        robot,
        scene,
        trials=trials,
        seed=seed,
        min_collision_fraction=fraction,
        jobs=jobs,
        progress=progress,
        distances=False,  # a setup keeps the pairs only
    )
    return matrix.disabled


def describe(model: SetupModel, *, matrix_given: bool) -> list[str]:
    """What the setup holds; the matrix line says whether it was computed or taken as given."""
    from marm_setup.collision import DisabledReason
    from marm_setup.setup import describe_setup

    counts = {r: sum(1 for d in model.collision.disabled if d.reason is r) for r in DisabledReason}
    summary = ", ".join(f"{n} {r.value}" for r, n in counts.items() if n)
    source = (
        "as given (SRDF / SPEC), not recomputed"
        if matrix_given
        else f"{model.collision.trials} trials, seed {model.collision.seed}"
    )
    lines = describe_setup(model)
    lines.append(
        f"collision matrix: {len(model.collision.disabled)} disabled pairs ({summary or 'none'}); {source}"
    )
    return lines


def reused_ros2_control(model: SetupModel, robot: RobotModel) -> list[str]:
    """What the package's ros2_control systems are and what use_mock_hardware does to each
    (ros2): the generated system, each `<ros2_control>` system the description already has
    (reused), and how the demo puts those on mock hardware (render/hardware.py)."""
    if model.target != Target.ROS2:
        return []
    from marm_setup.render import description_hardware, hardware_lines, ros2_control_joints
    from marm_setup.setup import Ros2ControlHardware

    own = model.ros2_control or Ros2ControlHardware()
    joints = len(ros2_control_joints(model, robot))
    return hardware_lines(description_hardware(robot, model.distro), own, joints)


def write_package(model: SetupModel, robot: RobotModel, out: Path, *, force: bool) -> list[FileChange]:
    """Render every file and write them atomically; returns the file changes."""
    from marm_setup.render import apply_writes, check_output_dir, plan_writes

    check_output_dir(out, force=force)
    rendered = _render(model, robot)
    changes = plan_writes(rendered, out)
    apply_writes(changes, out, force=force, require_fresh=not force)
    return changes


def _render(model: SetupModel, robot: RobotModel) -> list[RenderedFile]:
    from marm_setup.render import render_package

    return render_package(model, robot)
