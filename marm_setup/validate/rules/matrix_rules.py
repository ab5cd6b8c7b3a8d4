"""The SRDF's collision matrix against a quick resample of the robot's states.

Missing: a pair the matrix leaves enabled yet in collision in (nearly) every state (the Setup
Assistant's Always, compute_default_collisions.cpp, `min_collision_fraction` 0.95; typically an
SRDF written for a URDF whose links were renamed since) is an ERROR: MoveIt checks it, finds
the whole robot in collision almost everywhere, and no plan of any group can start or end.

Stale: a pair the SRDF marks Never should not collide in the resample. Nothing a package says
about itself replaces this check (a package could disable a pair colliding in 22 % of states
and record it as "proved", with a proof key anyone can recompute): the only pairs not
resampled are those the user's own proof cache (collision/proof_cache.py, written by the
user's own `init` and `collisions` runs) holds as proved, keyed by every byte their geometry
and joints depend on (`cached_proved`); no state could show those in collision.

A hit is a WARNING with its evidence (hit rate, one colliding configuration, the command that
recomputes the matrix), never an error: MoveIt never checks a disabled pair whatever its reason
label (srdfdom `model.cpp` loadDisabledCollisions keeps only link1/link2 for the allowed
collision matrix; the reason is informational), authors disable touching pairs on purpose (a
gripper linkage), and a pair that collides at the default state is what the Setup Assistant
itself would label Default (compute_default_collisions.cpp, phase "default state").

Covered: a Never pair is not stale in a state where a pair the SRDF leaves enabled between the
same two rigid bodies (links joined by fixed joints) is in collision too: MoveIt finds the state
in collision all the same. Some robots are built that way on purpose: franka_description puts
coarse self-collision shapes on a `*_sc` link fixed to each arm link, and its panda_moveit_config
disables the arm links' own pairs ("handled by sc links") while enabling the `*_sc` pairs. Only
the states where no such pair collides count against the pair; when there are none it passes.

The resample uses the matrix computation's own sampler (`collision.trials.trial_samples`)
with validate's own seed and trial count (DEFAULT_SEED, or what the caller chooses), never the
package's `collision.seed` or `collision.trials` (a package could choose the seed whose states
miss its pair, or `trials: 0`). With init's default seed its states are a prefix of the ones
`init`/`collisions` drew, so a matrix we computed for an unchanged URDF passes; a hit is always
a real, observed collision, whatever made the matrix.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision import DisabledReason
from marm_setup.findings import Evidence, Finding, error, warning
from marm_setup.robot import RobotModel

if TYPE_CHECKING:
    from marm_setup.collision import CollisionScene
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
    (`proved`: pairs the user's proof cache proves collision-free, not resampled). A Never
    pair colliding in at least ALWAYS_FRACTION of them is not stale: recomputing the matrix
    disables it all the same, as Always (moveit2 humble `moveit_setup_srdf_plugins/src/
    compute_default_collisions.cpp` l.147-153, `min_collision_fraction`), and MoveIt reads no reason
    label (srdfdom `model.cpp` loadDisabledCollisions), so MoveIt's behaviour is the same."""
    from marm_setup.collision import trial_samples
    from marm_setup.setup import allowed_pairs

    never = [pair for pair in never_pairs(srdf, scene) if pair not in proved]
    if not never or trials <= 0:
        return []
    q = trial_samples(robot, seed, trials)
    counts = scene.collision_counts(scene.link_poses(q), scene.pair_ids(never))
    enabled = scene.enabled_pairs(allowed_pairs(srdf, scene.candidate_pairs))
    out = []
    for pair, n in zip(never, counts, strict=True):
        if not n or n >= ALWAYS_FRACTION * trials:
            continue
        covers = covering_pairs(pair, enabled, robot)
        rows = _uncovered_rows(pair, covers, q, scene)
        if rows:
            out.append(_stale(pair, len(rows), q[rows], robot, file, trials, covers))
    return out


def covering_pairs(
    pair: tuple[str, str], enabled: Sequence[tuple[str, str]], robot: RobotModel
) -> list[tuple[str, str]]:
    """The enabled pairs between the rigid bodies of `pair`'s two links (each body: the links
    joined to it by fixed joints), the pair itself excepted."""
    body_a, body_b = robot.rigid_body_of[pair[0]], robot.rigid_body_of[pair[1]]
    return [
        p
        for p in enabled
        if p != pair and ((p[0] in body_a and p[1] in body_b) or (p[0] in body_b and p[1] in body_a))
    ]


def _uncovered_rows(
    pair: tuple[str, str], covers: list[tuple[str, str]], q: np.ndarray, scene: CollisionScene
) -> list[int]:
    """The states of `q` where `pair` is in collision and none of `covers` is."""
    rows = [i for i, hit in enumerate(scene.first_collisions(q, [pair])) if hit is not None]
    if not covers or not rows:
        return rows
    return [
        row for row, hit in zip(rows, scene.first_collisions(q[rows], covers), strict=True) if hit is None
    ]


def never_pairs(srdf: Srdf, scene: CollisionScene) -> list[tuple[str, str]]:
    """The SRDF's Never pairs of two links with geometry (a self-pair, link1 == link2, is
    accepted by srdfdom and means nothing to check)."""
    geometry = set(scene.links)
    return [
        p.pair
        for p in srdf.disabled
        if p.reason is DisabledReason.NEVER and p.pair[0] != p.pair[1] and set(p.pair) <= geometry
    ]


def cached_proved(srdf: Srdf, scene: CollisionScene) -> frozenset[tuple[str, str]]:
    """The SRDF's Never pairs the user's proof cache holds as proved for this very geometry
    and these joints (never what a package records about itself)."""
    from marm_setup.collision import known_proofs, link_pair

    pairs = {link_pair(*pair) for pair in never_pairs(srdf, scene)}
    return frozenset(
        pair for pair, proof in known_proofs(scene, sorted(pairs)).items() if proof.outcome == "proved"
    )


def _stale(
    pair: tuple[str, str],
    n: int,
    hits: np.ndarray,
    robot: RobotModel,
    file: str,
    trials: int,
    covers: list[tuple[str, str]],
) -> Finding:
    """The finding for a Never pair in collision in the `n` states `hits` (of `trials`) where no
    pair of `covers` (enabled, between the same rigid bodies) is."""
    state = ", ".join(
        f"{name}={value:.3f}" for name, value in zip(robot.active_joint_names, hits[0], strict=True)
    )
    where = ""
    if covers:
        named = ", ".join(f"{a}/{b}" for a, b in covers[:3]) + (", ..." if len(covers) > 3 else "")
        where = f" where none of the enabled pairs of the same rigid bodies ({named}) is"
    return warning(
        "matrix.stale",
        file,
        f"disable_collisions[{pair[0]} {pair[1]}]",
        f"marked Never but collides in {n} of {trials} random states ({100 * n / trials:.1f} %){where}, "
        f"e.g. {state}; MoveIt never checks this pair",
        hint="recompute the matrix for this URDF (marm-setup collisions URDF --srdf SRDF)",
        evidence=Evidence.of(pair, robot.active_joint_names, hits[0]),
    )
