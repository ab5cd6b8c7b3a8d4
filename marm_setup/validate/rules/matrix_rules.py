"""The SRDF's collision matrix against a quick resample of the robot's states.

Missing: a pair the matrix leaves enabled yet in collision in (nearly) every state (the Setup
Assistant's Always, compute_default_collisions.cpp, `min_collision_fraction` 0.95; typically an
SRDF written for a URDF whose links were renamed since) is an ERROR: MoveIt checks it, finds
the whole robot in collision almost everywhere, and no plan of any group can start or end.

Stale: a pair the SRDF marks Never should not collide in the resample. Pairs a setup file
(marm_setup.yaml) records as proved collision-free over their whole joint range are not
resampled while its proof key matches this very robot (`proved_pairs`; any change to the
robot's joints or collision geometry, or to the file's pairs, breaks the key): no state could
show them in collision, so the findings are the resample's, found with less work.

A hit is a WARNING with its evidence (hit rate, one colliding configuration, the command that
recomputes the matrix), never an error: MoveIt never checks a disabled pair whatever its reason
label (srdfdom `model.cpp` loadDisabledCollisions keeps only link1/link2 for the allowed
collision matrix; the reason is informational), authors disable touching pairs on purpose (a
gripper linkage), and a pair that collides at the default state is what the Setup Assistant
itself would label Default (compute_default_collisions.cpp, phase "default state").

The resample uses the matrix computation's own sampler (`collision.trials.trial_samples`) and
the seed in marm_setup.yaml (else 0), so its states are a prefix of the ones `init`/`collisions`
drew: a matrix we computed for an unchanged URDF can never fail it, while a URDF change (new
geometry, wider limits) shows up at once. For a matrix from the Setup Assistant (another
sampler) a hit is still a real, observed collision.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision import DisabledReason
from marm_setup.findings import Evidence, Finding, error, warning
from marm_setup.robot import RobotModel

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene
    from marm_setup.package import RecordedProofs
    from marm_setup.setup import Srdf

DEFAULT_TRIALS = 1000
DEFAULT_SEED = 0
ALWAYS_FRACTION = 0.95  # the Setup Assistant's default min_collision_fraction


def check_matrix_missing(
    srdf: Srdf,
    robot: RobotModel,
    scene: CollisionScene,
    file: str,
    *,
    trials: int = DEFAULT_TRIALS,
    seed: int = DEFAULT_SEED,
) -> list[Finding]:
    """Enabled pairs in collision in at least ALWAYS_FRACTION of the first (at most) ROUND
    resampled states, the size of one Always round."""
    from marm_setup.collision import ROUND, trial_samples
    from marm_setup.setup import allowed_pairs

    pairs = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    samples = min(trials, ROUND)
    if not pairs or samples <= 0:
        return []
    adjacent = robot.adjacent_geometry_pairs()
    q = trial_samples(robot, seed, samples)
    counts = scene.collision_counts(scene.link_poses(q), scene.pair_ids(pairs))
    return [
        error(
            "matrix.always-colliding",
            file,
            f"disable_collisions[{pair[0]} {pair[1]}]",
            f"missing: the pair collides in {n} of {samples} random states, so MoveIt finds the robot "
            "in collision almost everywhere and no plan can start or end",
            hint=f'add it with reason="{"Adjacent" if pair in adjacent else "Always"}" '
            "(or recompute: marm-setup collisions URDF --srdf SRDF)",
        )
        for pair, n in zip(pairs, counts.tolist(), strict=True)
        if n >= ALWAYS_FRACTION * samples
    ]


def check_matrix_fresh(
    srdf: Srdf,
    robot: RobotModel,
    scene: CollisionScene,
    file: str,
    *,
    trials: int = DEFAULT_TRIALS,
    seed: int = DEFAULT_SEED,
    proved: frozenset[tuple[str, str]] = frozenset(),
) -> list[Finding]:
    """Resample `trials` random states; every Never pair seen colliding means a stale matrix
    (`proved`: pairs proved collision-free for this robot, not resampled)."""
    from marm_setup.collision import trial_samples

    geometry = set(scene.links)
    never = [
        p.pair
        for p in srdf.disabled
        if p.reason is DisabledReason.NEVER
        and p.pair[0] != p.pair[1]
        and set(p.pair) <= geometry
        and p.pair not in proved
    ]  # a self-pair (link1 == link2) is accepted by srdfdom and means nothing to check
    if not never or trials <= 0:
        return []
    q = trial_samples(robot, seed, trials)
    counts = scene.collision_counts(scene.link_poses(q), scene.pair_ids(never))
    out = []
    for pair, n in zip(never, counts, strict=True):
        if n:
            out.append(_stale(pair, int(n), q, robot, scene, file, trials))
    return out


def proved_pairs(recorded: RecordedProofs | None, robot: RobotModel) -> frozenset[tuple[str, str]]:
    """The Never pairs a setup file records as proved, when its proof key matches `robot`;
    else none."""
    found = recorded_proofs(recorded, robot) or {}
    return frozenset(pair for pair, (outcome, _) in found.items() if outcome == "proved")


def recorded_proofs(
    recorded: RecordedProofs | None, robot: RobotModel
) -> dict[tuple[str, str], tuple[str, float]] | None:
    """Never pair -> ("proved" or "unproved", the share of its joint range proved) as a setup
    file records them (the package model's `RecordedProofs`), when its proof key matches
    `robot`; None when it records no proofs or they were made for another robot or matrix."""
    from marm_setup.collision import link_pair, proof_key
    from marm_setup.robot import robot_fingerprint

    if recorded is None:
        return None
    unproved = [pair for pair, _ in recorded.unproved]
    if recorded.key != proof_key(robot_fingerprint(robot), recorded.prove, recorded.never, unproved):
        return None
    shares = {link_pair(*pair): share for pair, share in recorded.unproved}
    return {
        link_pair(*p): ("unproved", shares[link_pair(*p)]) if link_pair(*p) in shares else ("proved", 1.0)
        for p in recorded.never
    }


def _stale(
    pair: tuple[str, str],
    n: int,
    q: np.ndarray,
    robot: RobotModel,
    scene: CollisionScene,
    file: str,
    trials: int,
) -> Finding:
    hits = scene.first_collisions(q, [pair])
    row = next(i for i, hit in enumerate(hits) if hit is not None)
    state = ", ".join(
        f"{name}={value:.3f}" for name, value in zip(robot.active_joint_names, q[row], strict=True)
    )
    return warning(
        "matrix.stale",
        file,
        f"disable_collisions[{pair[0]} {pair[1]}]",
        f"marked Never but collides in {n} of {trials} random states ({100 * n / trials:.1f} %), "
        f"e.g. {state}; MoveIt never checks this pair",
        hint="recompute the matrix for this URDF (marm-setup collisions URDF --srdf SRDF)",
        evidence=Evidence.of(pair, robot.active_joint_names, q[row]),
    )
