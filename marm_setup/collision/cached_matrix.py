"""compute_cached_matrix: the matrix with what the user's caches hold.

A run the matrix cache (matrix_cache.py) holds, same robot and same settings, is its stored
result: nothing is computed, not even the collision scene. Otherwise the proofs the proof
cache (proof_cache.py) holds are taken (every one the very same run left: its context,
proof_keys.run_context; of other runs, those the screen finished alone where this run's screen
repeats them), the new ones kept: the same matrix as without the caches, for less work. `init`, `collisions` and `report` compute their matrices here, so a
`report` after an `init` with the same settings computes nothing again.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from marm_setup.collision.results import CollisionMatrix
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot import RobotModel

# compute_collision_matrix's options an unproved proof depends on, with their defaults
RUN_SETTINGS = {
    "trials": 10000,
    "seed": 0,
    "min_collision_fraction": 0.95,
    "check_default": True,
    "check_always": True,
    "default_q": None,
    "prove": "off",
}


def compute_cached_matrix(
    robot: RobotModel, scene: CollisionScene | None = None, padding: float = 0.0, **options: Any
) -> CollisionMatrix:
    """compute_collision_matrix(robot, scene, **options) from the caches (the module doc), a new
    result kept there; without `scene`, one with `padding` is built when the matrix is computed.
    A `progress` with a `proofs(proved, in_contact, left)` method (cli/progress.py) is told of
    the proofs too."""
    from marm_setup.collision.matrix_cache import load_matrix, matrix_key, store_matrix
    from marm_setup.collision.proof_cache import cache_dir

    if cache_dir() is None:
        return _with_proof_cache(robot, _scene(robot, scene, padding), options)
    key = matrix_key(robot, padding if scene is None else scene.padding, options)
    stored = load_matrix(key)
    if stored is not None:
        if (progress := options.get("progress")) is not None:  # a stage shown done, not skipped
            progress(stored.trials, stored.trials)
        return stored
    matrix = _with_proof_cache(robot, _scene(robot, scene, padding), options)
    store_matrix(key, matrix)
    return matrix


def _scene(robot: RobotModel, scene: CollisionScene | None, padding: float) -> CollisionScene:
    from marm_setup.collision.scene import CollisionScene

    return CollisionScene(robot, padding) if scene is None else scene


def _with_proof_cache(robot: RobotModel, scene: CollisionScene, options: dict[str, Any]) -> CollisionMatrix:
    """The matrix with the proof cache's proofs, its new proofs kept there."""
    from marm_setup.collision.matrix import compute_collision_matrix
    from marm_setup.collision.proof_cache import cache_dir, remember_proofs, run_proofs
    from marm_setup.collision.proof_keys import run_context

    if options.get("prove", "off") == "off":
        return compute_collision_matrix(robot, scene, **options)
    told = getattr(options.get("progress"), "proofs", None)  # a progress that shows the proofs
    if cache_dir() is None:
        return compute_collision_matrix(robot, scene, proof_progress=told, **options)
    context = run_context(scene, {name: options.get(name, value) for name, value in RUN_SETTINGS.items()})
    known, others = run_proofs(scene, context)
    matrix = compute_collision_matrix(
        robot, scene, known=known, proof_progress=told, reusable=others, **options
    )
    remember_proofs(scene, matrix, context)
    return matrix
