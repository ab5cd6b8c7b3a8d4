"""Steps `init`, `init --from-package` and `collisions DIR` share: the collision matrix of a setup,
what a setup holds (one line each), rendering and the atomic write."""

from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any

from marm_setup.robot import RobotModel
from marm_setup.ros import Target
from marm_setup.setup import CollisionSettings, SetupModel

if TYPE_CHECKING:
    from marm_setup.collision import CollisionMatrix, CollisionScene, DisabledPair, Progress
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
    prove: str = "on",
) -> SetupModel:
    """Compute the matrix unless the setup already has pairs (from an SRDF or the SPEC)."""
    if model.collision.disabled:
        return model
    matrix = compute_matrix(
        robot,
        scene,
        trials=trials,
        seed=seed,
        min_collision_fraction=model.collision.min_collision_fraction,
        jobs=jobs,
        progress=progress,
        distances=False,  # a setup keeps the pairs only
        prove=prove,
    )
    return dataclasses.replace(model, collision=collision_settings(matrix, matrix.disabled, robot))


def compute_matrix(robot: RobotModel, scene: CollisionScene | None = None, **options: Any) -> CollisionMatrix:
    """The matrix with the user's proof cache (collision/cached_matrix.py)."""
    from marm_setup.collision import compute_cached_matrix

    return compute_cached_matrix(robot, scene, **options)


def collision_settings(
    matrix: CollisionMatrix, disabled: tuple[DisabledPair, ...], robot: RobotModel
) -> CollisionSettings:
    """The setup's collision section for a computed `matrix` whose final pairs are `disabled`
    (its unproved Never pairs among them keep their note; the proof key ties the proofs to
    `robot`, so validate trusts them only for it)."""
    from marm_setup.collision import DisabledReason, proof_key, unproved_pairs
    from marm_setup.robot import robot_fingerprint

    kept = {p.pair for p in disabled}
    unproved = tuple(u for u in unproved_pairs(matrix) if u.pair in kept)
    key = None
    if matrix.prove != "off":
        never = [p.pair for p in disabled if p.reason is DisabledReason.NEVER]
        key = proof_key(robot_fingerprint(robot), matrix.prove, never, [u.pair for u in unproved])
    return CollisionSettings(
        seed=matrix.seed,
        trials=matrix.trials,
        min_collision_fraction=matrix.min_collision_fraction,
        disabled=disabled,
        prove=matrix.prove,
        unproved=unproved,
        proof_key=key,
    )


def describe(model: SetupModel, *, matrix_given: bool) -> list[str]:
    """What the setup holds; the matrix line says whether it was computed or taken as given."""
    from marm_setup.collision import DisabledReason
    from marm_setup.inference import describe_setup

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
    never = counts[DisabledReason.NEVER]
    if not matrix_given and model.collision.prove not in (None, "off") and never:
        proved = never - len(model.collision.unproved)
        lines.append(
            f"proved collision-free over their whole joint range: {proved} of {never} Never pairs "
            f"(--prove {model.collision.prove}; the SRDF notes the others)"
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
    """Render every file and write them atomically; returns the file changes (with --force, the
    files an earlier init wrote that are no longer generated: removed when unchanged, else listed)."""
    from marm_setup.render import apply_writes, check_output_dir, plan_writes

    check_output_dir(out, force=force)
    rendered = _render(model, robot)
    changes = plan_writes(rendered, out, remove_stale=force)  # --force: the old package's leftovers
    apply_writes(changes, out, force=force, require_fresh=not force)
    return changes


def _render(model: SetupModel, robot: RobotModel) -> list[RenderedFile]:
    from marm_setup.render import render_package

    return render_package(model, robot)
