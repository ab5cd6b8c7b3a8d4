"""compute_cached_matrix: the matrix with the proofs of the user's proof cache (proof_cache.py).

The proofs the cache holds are taken (finished ones from any run; unproved ones from the very
same run: its context, proof_keys.run_context), the new ones kept: the same matrix as without
the cache, for less work. `init`, `collisions` and `report` compute their matrices here, so a
`report` after an `init` with the same settings proves nothing again.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from marm_setup.collision.matrix import CollisionMatrix
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
    robot: RobotModel, scene: CollisionScene | None = None, **options: Any
) -> CollisionMatrix:
    """compute_collision_matrix(robot, scene, **options) with the proof cache's proofs, its new
    ones kept there. A `progress` with a `proofs(proved, in_contact, left)` method
    (cli/progress.py) is told of the proofs too."""
    from marm_setup.collision.matrix import compute_collision_matrix
    from marm_setup.collision.proof_cache import cache_dir, known_proofs, remember_proofs
    from marm_setup.collision.proof_keys import run_context
    from marm_setup.collision.scene import CollisionScene

    scene = CollisionScene(robot) if scene is None else scene
    if options.get("prove", "off") == "off":
        return compute_collision_matrix(robot, scene, **options)
    told = getattr(options.get("progress"), "proofs", None)  # a progress that shows the proofs
    if cache_dir() is None:
        return compute_collision_matrix(robot, scene, proof_progress=told, **options)
    context = run_context(scene, {name: options.get(name, value) for name, value in RUN_SETTINGS.items()})
    known = known_proofs(scene, context=context)
    matrix = compute_collision_matrix(robot, scene, known=known, proof_progress=told, **options)
    remember_proofs(scene, matrix, context)
    return matrix
