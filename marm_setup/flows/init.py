"""`init`: build the setup (`build`), compute the collision matrix, choose poses the demo can
start at, render and write the package."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING

from marm_setup.flows.build import InitRequest, build
from marm_setup.flows.write import describe, reused_ros2_control, with_collision_matrix, write_package
from marm_setup.robot import RobotModel
from marm_setup.setup import SetupModel

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene, DisabledPair, Progress


@dataclass(frozen=True)
class InitResult:
    model: SetupModel
    inferred: tuple[str, ...]  # what the setup holds, one line each
    status_lines: tuple[str, ...]  # one line per written file
    notes: tuple[str, ...] = ()  # what inference guessed, one line each


def run_init(request: InitRequest, robot: RobotModel, progress: Progress | None = None) -> InitResult:
    """`progress(done, total)` is called while the matrix samples (see compute_collision_matrix)."""
    from marm_setup.collision import CollisionScene

    built = build(request, robot)
    model, user = _matrix_to_compute(built.model, request)
    given = bool(model.collision.disabled)
    settings = request.matrix.over(model.collision)
    seed = settings.seed
    scene = CollisionScene(robot)
    model = with_collision_matrix(
        model,
        robot,
        trials=settings.trials,
        seed=seed,
        jobs=settings.jobs,
        progress=progress,
        scene=scene,
        prove=settings.prove,
    )
    model = _with_user_pairs(model, user)
    notes = built.notes
    if not built.poses_given:
        model, pose_notes = _with_poses(model, robot, scene, seed, request)
        notes += pose_notes
    model, start_notes = _with_start_poses(model, robot, scene)
    notes += start_notes
    lines = describe(model, matrix_given=given) + reused_ros2_control(model, robot)
    changes = write_package(model, robot, request.out, force=request.force)
    from marm_setup.render import format_change

    return InitResult(
        model, tuple(lines), tuple(format_change(c, forced=request.force) for c in changes), notes
    )


def _with_poses(
    model: SetupModel, robot: RobotModel, scene: CollisionScene, seed: int, request: InitRequest
) -> tuple[SetupModel, tuple[str, ...]]:
    """The setup with inferred collision-free poses (home, ready), and notes on what was guessed:
    poses within the limits of a setup already checked (build), so not checked again."""
    from marm_setup.inference import infer_poses

    poses = infer_poses(model, robot, scene, seed=seed)
    return dataclasses.replace(model, group_states=poses.states), poses.notes


def _with_start_poses(
    model: SetupModel, robot: RobotModel, scene: CollisionScene
) -> tuple[SetupModel, tuple[str, ...]]:
    """The setup with start poses the demo can start at out of collision (inference/poses.py)."""
    from marm_setup.inference import choose_start_poses

    starts, notes = choose_start_poses(model, robot, scene)
    return dataclasses.replace(model, start_poses=starts), notes


def _matrix_to_compute(
    model: SetupModel, request: InitRequest
) -> tuple[SetupModel, tuple[DisabledPair, ...]]:
    """A SPEC's matrix (an old marm_setup.yaml's, maybe stale) is computed again unless
    --keep-disabled, its User pairs kept; an imported SRDF's matrix is the import: kept."""
    from marm_setup.collision import DisabledReason

    if request.from_srdf is not None or request.matrix.keep_disabled or not model.collision.disabled:
        return model, ()
    user = tuple(p for p in model.collision.disabled if p.reason is DisabledReason.USER)
    return dataclasses.replace(model, collision=dataclasses.replace(model.collision, disabled=())), user


def _with_user_pairs(model: SetupModel, user: tuple[DisabledPair, ...]) -> SetupModel:
    """The computed matrix with the given User pairs (they stay User: never recomputed)."""
    if not user:
        return model
    mine = {p.pair for p in user}
    disabled = tuple(sorted((*(p for p in model.collision.disabled if p.pair not in mine), *user)))
    return dataclasses.replace(model, collision=dataclasses.replace(model.collision, disabled=disabled))
