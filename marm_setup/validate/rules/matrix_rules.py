"""Collision-matrix freshness: a pair the SRDF marks Never must not collide in a quick resample.

The resample uses the matrix computation's own sampler (`collision_matrix.trial_samples`) and
the seed in marm_setup.yaml (else 0), so its states are a prefix of the ones `init`/`collisions`
drew: a matrix we computed for an unchanged URDF can never fail it, while a URDF change (new
geometry, wider limits) shows up at once. For a matrix from the Setup Assistant (another
sampler) a hit is still a real, observed collision.
"""

from __future__ import annotations

import numpy as np

from marm_setup.collision.pairs import DisabledReason
from marm_setup.findings import Finding, error
from marm_setup.robot.model import RobotModel

DEFAULT_TRIALS = 1000
DEFAULT_SEED = 0


def check_matrix_fresh(
    srdf, robot: RobotModel, scene, file: str, *, trials: int = DEFAULT_TRIALS, seed: int = DEFAULT_SEED
) -> list[Finding]:
    """Resample `trials` random states; every Never pair seen colliding means a stale matrix."""
    from marm_setup.collision.matrix import trial_samples

    geometry = set(scene.links)
    never = [p.pair for p in srdf.disabled if p.reason is DisabledReason.NEVER and set(p.pair) <= geometry]
    if not never or trials <= 0:
        return []
    q = trial_samples(robot, seed, trials)
    counts = scene.collision_counts(scene.link_poses(q), scene.pair_ids(never))
    out = []
    for pair, n in zip(never, counts, strict=True):
        if n:
            out.append(_stale(pair, int(n), q, robot, scene, file, trials))
    return out


def _stale(pair, n: int, q: np.ndarray, robot: RobotModel, scene, file: str, trials: int) -> Finding:
    hits = scene.first_collisions(q, [pair])
    row = next(i for i, hit in enumerate(hits) if hit is not None)
    state = ", ".join(
        f"{name}={value:.3f}" for name, value in zip(robot.active_joint_names, q[row], strict=True)
    )
    return error(
        "matrix.stale",
        file,
        f"disable_collisions[{pair[0]} {pair[1]}]",
        f"marked Never but collides in {n} of {trials} random states, e.g. {state}",
        hint="recompute the matrix for this URDF (marm-setup collisions URDF --srdf SRDF)",
    )
