"""compute_collision_matrix: MoveIt Setup Assistant's self-collision matrix, seeded and fast.

Phases in MoveIt's order (a pair keeps the first reason it gets): Adjacent, Default (in
collision at the default state), Always (in collision in >= `min_collision_fraction` of a
round of 200 samples; rounds repeat until one adds nothing), Never (not seen in collision in
`trials` random states). Pairs seen in collision in any sample stay enabled.

Proved Never (`prove` "on" or "exhaustive", beyond MoveIt): before the trials, every pair
still a candidate is screened by a cheap proof over its joint box (`collision/proof.py`):
`proved` pairs are Never without a trial (no state could show them in collision), `collides`
pairs stay enabled (their witness is a state in contact); the others go through the trials
as MoveIt's rule says. Those the trials never saw in collision are then settled by a longer
proof and a witness search: `collides` enables them, else they are Never, `proved` or
`unproved`. "off" is MoveIt's sampling alone, byte for byte.

Known proofs (`known`: proofs from the user's cache, collision/proof_cache.py) are taken as
they are, before the trials: such a pair is neither screened nor sampled nor settled again (a
known screen of a pair the same run's trials saw in collision, outcome SEEN, spares its screen
only). The other pairs get the very budgets they would get without them (a known pair still
counts where it would have shared a pool), so for the same robot and settings the matrix is
the same, byte for byte, with or without the cache.

Randomness: the Always rounds draw from `SeedSequence(seed, spawn_key=(0,))`; the trials come
in fixed chunks (`collision/trials.py`), streamed, the same whoever checks them (`--jobs`).

Exactness: the answer is "does coal find the pair in collision in any sampled state". The
shortcuts (hull test, distance certificates; `collision/prover.py`) only skip exact checks
they prove would say "no collision", so `shortcuts=False` gives the same bytes.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.proof import COLLIDES, PROVED, UNPROVED, PairProof
from marm_setup.collision.results import ROUND, CollisionMatrix, PairStats, Work
from marm_setup.collision.trials import CHUNK, trial_samples
from marm_setup.collision.workers import Workers
from marm_setup.robot import RobotModel, default_configuration, sample_configurations

if TYPE_CHECKING:
    from marm_setup.collision.cached_proof import CachedProof

__all__ = ["CHUNK", "CollisionMatrix", "PairStats", "compute_collision_matrix", "trial_samples"]

Pair = tuple[str, str]
Progress = Callable[[int, int], None]
PAIR_OVERHEAD = 5e-8  # [s] numpy filtering of one pair in one trial state (for the shard plan)
WORTH_A_PROCESS = 0.3  # [s] estimated Never-phase work below which extra processes do not pay


def compute_collision_matrix(
    robot: RobotModel,
    scene=None,
    *,
    trials: int = 10000,
    seed: int = 0,
    min_collision_fraction: float = 0.95,
    check_default: bool = True,
    check_always: bool = True,
    default_q: np.ndarray | None = None,
    jobs: int = 1,
    progress: Progress | None = None,
    shortcuts: bool = True,
    distances: bool = True,
    prove: str = "off",
    known: Mapping[Pair, CachedProof] | None = None,
    proof_progress: Callable[[int, int, int], None] | None = None,
    reusable: Mapping[Pair, CachedProof] | None = None,
) -> CollisionMatrix:
    """MoveIt's matrix for `robot` (scene: a CollisionScene, built when None).

    `shortcuts=False` checks every state that passes the bounding volumes exactly (no hull
    test, no certificates): the reference the shortcuts must match byte for byte.
    `distances=False` leaves each Never pair's `min_distance` None (only the json and report
    outputs show it; measuring it costs a distance query per pair and closest state).
    `prove`: "off" (MoveIt's rule), "on" or "exhaustive" (the proof budget; see the module doc).
    `known`: finished proofs of pairs, taken as they are (see the module doc; ignored when off).
    `reusable`: proofs of other runs the screen's branch and bound finished alone
    (CachedProof.screened_alone), taken as known where this run's screen budget repeats them.
    `proof_progress(proved, in_contact, left)`: told as each proof ends.
    """
    if scene is None:
        from marm_setup.collision.scene import CollisionScene

        scene = CollisionScene(robot)
    before = Work.of(scene)
    reasons = {pair: DisabledReason.ADJACENT for pair in robot.adjacent_geometry_pairs()}
    if check_default:
        q0 = default_configuration(robot) if default_q is None else np.asarray(default_q, dtype=float)
        _disable_default(scene, q0, reasons, shortcuts)
    always = (
        _disable_always(scene, seed, min_collision_fraction, reasons, shortcuts) if check_always else None
    )
    counts = always.counts if always else {}
    remaining = tuple(p for p in scene.candidate_pairs if p not in reasons)
    seen = {p for p, (hits, _) in counts.items() if hits}  # hit in an Always round: no more checks
    unseen_pairs = tuple(p for p in remaining if p not in seen)
    budget = None  # the screen's, when the reusable proofs need it first
    if reusable and prove != "off":
        from marm_setup.collision.proving import screen_budget

        budget = screen_budget(scene, unseen_pairs, prove)
        known = {**_repeated(unseen_pairs, budget[1], reusable), **(known or {})}
    screens = {p: known[p] for p in unseen_pairs if p in known} if known and prove != "off" else {}
    cached = {p: c for p, c in screens.items() if c.outcome != "seen"}  # "seen": its screen only
    tally = _tally(proof_progress, cached, prove)
    screened = _screen(scene, unseen_pairs, prove, (seed, jobs), frozenset(screens), tally, budget)
    screened.update({p: PairProof(c.screen[0], 0.0, units=c.screen[1]) for p, c in screens.items()})
    proofs = {p: proof for p, proof in screened.items() if proof.outcome != UNPROVED and p not in screens}
    proofs.update(
        {p: PairProof(c.outcome, c.fraction, c.witness, c.units, second=c.second) for p, c in cached.items()}
    )
    trial_pairs = tuple(p for p in remaining if p not in seen and p not in proofs)
    costs = always.costs(trials) if always else {p: PAIR_OVERHEAD * trials for p in trial_pairs}
    followed = _followed(remaining, proofs, cached) if distances else ()
    shards = _with_tracked(plan_shards(trial_pairs, costs, jobs), followed)
    nearest = prove != "off"
    closest, rows, work = _never_phase(
        scene, shards, seen, (seed, trials), shortcuts, (distances, nearest), progress
    )
    unseen = {p: screened[p] for p in trial_pairs if p not in seen and p in screened}
    spent = sum(p.units for p in screened.values())
    settled = {p: c.second for p, c in cached.items() if c.settled}
    proofs.update(_settle(scene, unseen, prove, (seed, trials), jobs, (spent, settled), rows, tally))
    enabled = seen | {p for p, proof in proofs.items() if proof.outcome == COLLIDES}
    reasons.update(dict.fromkeys((p for p in remaining if p not in enabled), DisabledReason.NEVER))
    stats = tuple(
        PairStats(
            p[0], p[1], reasons.get(p), *counts.get(p, (0, 0)), p in seen, closest.get(p), proofs.get(p)
        )
        for p in scene.candidate_pairs
    )
    units = sum(proof.units for proof in proofs.values())
    return CollisionMatrix(
        disabled=tuple(sorted(DisabledPair.of(*p, r) for p, r in reasons.items())),
        enabled=tuple(p for p in remaining if p in enabled),
        stats=stats,
        trials=trials,
        seed=seed,
        min_collision_fraction=min_collision_fraction,
        padding=scene.padding,
        work=Work.of(scene) - before + work + Work(proof_units=units),
        prove=prove,
        screened={p: (proof.outcome, proof.units) for p, proof in screened.items()},
    )


def _repeated(
    pairs: tuple[Pair, ...], boxes: int, reusable: Mapping[Pair, CachedProof]
) -> dict[Pair, CachedProof]:
    """The `reusable` proofs of `pairs` this run's screen would repeat step for step: its budget
    `boxes` (proving.screen_budget; 0: no branch and bound) at least the least that gives each
    (proof.PairSearch.least)."""
    if not boxes:
        return {}
    return {
        p: reusable[p]
        for p in pairs
        if p in reusable and (least := reusable[p].least) is not None and least <= boxes
    }


def _followed(
    remaining: tuple[Pair, ...], proofs: dict[Pair, PairProof], cached: Mapping[Pair, CachedProof]
) -> tuple[Pair, ...]:
    """The pairs proved before the trials, followed through them for their Never distance, and
    the known pairs a run without them would have sampled (settled after the trials)."""
    return tuple(
        p
        for p in remaining
        if (
            (cached[p].settled or cached[p].outcome == PROVED)
            if p in cached
            else (p in proofs and proofs[p].outcome == PROVED)
        )
    )


def _tally(report, cached: Mapping[Pair, CachedProof], prove: str):
    """A ProofTally for `report` (None without one), counting the `cached` proofs first."""
    if report is None or prove == "off":
        return None
    from marm_setup.collision.proving import ProofTally

    tally = ProofTally(report)
    outcomes = [c.outcome for c in cached.values()]
    tally.start(outcomes.count(PROVED), outcomes.count(COLLIDES), 0)
    return tally


def _screen(
    scene,
    pairs: tuple[Pair, ...],
    prove: str,
    run: tuple[int, int],
    known: frozenset[Pair],
    tally,
    budget=None,
) -> dict[Pair, PairProof]:
    """The branch and bound of `pairs` before the trials (but of the `known` ones, which count
    for the budgets only); none when `prove` is "off". `run`: (seed, jobs); `budget`: the
    screen's (proving.screen_budget), when already known."""
    if prove == "off" or all(p in known for p in pairs):  # nothing to prove: no budget to share
        return {}
    from marm_setup.collision.proving import screen_pairs

    return screen_pairs(scene, pairs, prove, *run, known, tally, budget)


def _settle(
    scene,
    priors: dict[Pair, PairProof],
    prove: str,
    draw: tuple[int, int],
    jobs: int,
    spent: tuple[int, Mapping[Pair, float | None]],
    rows,
    tally=None,
) -> dict[Pair, PairProof]:
    """The rest of the proof of the unproved pairs the trials never saw in collision (`spent`:
    the screen's units, and the known pairs that would have been settled too, with where their
    first round ended when a second settled them; `rows`: each pair's closest trial states, of
    `draw` (seed, trials))."""
    if prove == "off" or not priors:
        return {}
    from marm_setup.collision.proving import settle_pairs
    from marm_setup.collision.trials import trial_states

    wanted = sorted({i for p in priors for i in rows.get(p, ())})
    states = dict(zip(wanted, trial_states(scene.robot, *draw, wanted), strict=True))
    starts = {p: np.array([states[i] for i in rows.get(p, ())]) for p in priors}
    return settle_pairs(scene, priors, prove, draw[0], jobs, spent[0], starts, spent[1], tally)


def _with_tracked(shards: list[tuple[Pair, ...]], tracked: tuple[Pair, ...]) -> list:
    """(checked pairs, tracked pairs) per shard: the proved pairs, dealt round the shards, are
    not checked, only followed to their closest trial states (for their Never distance)."""
    out = [(pairs, list[Pair]()) for pairs in shards] or ([((), [])] if tracked else [])
    for k, pair in enumerate(tracked):
        out[k % len(out)][1].append(pair)
    return [(pairs, tuple(extra)) for pairs, extra in out]


def _never_phase(
    scene,
    shards,
    seen: set[Pair],
    draw: tuple[int, int],
    shortcuts: bool,
    wanted: tuple[bool, bool],
    progress,
) -> tuple[dict[Pair, float], dict[Pair, tuple[int, ...]], Work]:
    """The trials (`draw`: seed, count) over `shards` of pairs (one process each when several):
    adds the pairs seen colliding to `seen`; returns each never-seen pair's smallest distance
    (when `wanted[0]`), its closest trial states' indices (when `wanted[1]`) and the work of
    worker processes."""
    seed, trials = draw
    with Workers(scene, seed, trials, shortcuts, shards, *wanted) as workers:
        work = _run_trials(workers, seen, trials, progress)
        closest, rows, closest_work = workers.closest() if any(wanted) else ({}, {}, Work())
    return closest, rows, work + closest_work


def _disable_default(scene, q0: np.ndarray, reasons: dict[Pair, DisabledReason], hulls: bool) -> None:
    pairs = tuple(p for p in scene.candidate_pairs if p not in reasons)
    if not pairs:
        return
    hits = scene.collision_counts(scene.link_poses(q0[None, :]), scene.pair_ids(pairs), hulls)
    reasons.update({p: DisabledReason.DEFAULT for p, h in zip(pairs, hits, strict=True) if h})


@dataclass
class _AlwaysRounds:
    """What the Always rounds saw per pair: (hits, samples), and the states that passed the
    bounding volumes with the seconds their exact checks took (for the shard plan)."""

    counts: dict[Pair, tuple[int, int]] = field(default_factory=dict)
    open_states: dict[Pair, int] = field(default_factory=dict)
    seconds: dict[Pair, float] = field(default_factory=dict)

    def costs(self, trials: int) -> dict[Pair, float]:
        """Estimated Never-phase seconds per pair: its share of states that reach the exact
        check, times its measured exact-check time, times the states it will be checked in:
        `trials`, or for a pair the rounds saw in collision (`hits` of `samples`) the chunks
        until its expected first hit (samples / hits states), after which it is not checked."""
        out = {}
        for pair, (hits, samples) in self.counts.items():
            opened = self.open_states.get(pair, 0)
            per_check = self.seconds.get(pair, 0.0) / opened if opened else 0.0
            checked = min(trials, CHUNK * math.ceil(samples / hits / CHUNK)) if hits else trials
            out[pair] = (opened / samples * per_check + PAIR_OVERHEAD) * checked
        return out


def _disable_always(scene, seed: int, fraction: float, reasons, hulls: bool) -> _AlwaysRounds:
    """Rounds of ROUND samples until a round disables nothing."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(0,)))
    rounds = _AlwaysRounds()
    while True:
        pairs = tuple(p for p in scene.candidate_pairs if p not in reasons)
        if not pairs:
            return rounds
        poses = scene.link_poses(sample_configurations(scene.robot, rng, ROUND))
        ids = scene.pair_ids(pairs)
        opened, seconds = np.zeros(len(ids), dtype=np.int64), np.zeros(len(ids))
        hits = scene.collision_counts(poses, ids, hulls, opened=opened, seconds=seconds)
        added = 0
        for k, (pair, h) in enumerate(zip(pairs, hits.tolist(), strict=True)):
            old_hits, old_samples = rounds.counts.get(pair, (0, 0))
            rounds.counts[pair] = (old_hits + h, old_samples + ROUND)
            rounds.open_states[pair] = rounds.open_states.get(pair, 0) + int(opened[k])
            rounds.seconds[pair] = rounds.seconds.get(pair, 0.0) + float(seconds[k])
            if h >= fraction * ROUND - 1e-9:
                reasons[pair] = DisabledReason.ALWAYS
                added += 1
        if not added:
            return rounds


def plan_shards(pairs: tuple[Pair, ...], costs: dict[Pair, float], jobs: int) -> list[tuple[Pair, ...]]:
    """`pairs` split into at most `jobs` shards of about equal estimated cost (longest first
    to the least loaded shard); one shard when the whole is too small to pay for processes.
    Which shard checks a pair changes the work, never the answer."""
    estimate = {p: costs.get(p, 0.0) for p in pairs}
    total = sum(estimate.values())
    count = max(1, min(jobs, len(pairs)))
    if count == 1 or total < WORTH_A_PROCESS:
        return [pairs] if pairs else []
    loads = [0.0] * count
    members: list[list[Pair]] = [[] for _ in range(count)]
    for pair in sorted(pairs, key=lambda p: (-estimate[p], p)):
        k = loads.index(min(loads))
        loads[k] += estimate[pair]
        members[k].append(pair)
    order = {p: i for i, p in enumerate(pairs)}
    return [tuple(sorted(m, key=order.__getitem__)) for m in members if m]


def _run_trials(workers: Workers, seen: set[Pair], trials: int, progress: Progress | None) -> Work:
    """Adds the pairs seen colliding in the trial states to `seen`; returns the work of
    worker processes (the parent's own is on its scene)."""
    work = Work()
    if progress:
        progress(0, trials)
    for index, (chunk_seen, chunk_work) in enumerate(workers.chunks()):
        seen |= chunk_seen
        work += chunk_work
        if progress:
            progress(min(trials, (index + 1) * CHUNK), trials)
    return work
