"""The Never phase's states and the check of one chunk of them (run in any process).

Trial chunk i (fixed size CHUNK) is drawn from `SeedSequence(seed, spawn_key=(1, i))` where it
is checked: N trials are a prefix of N + k and memory does not grow with the trials. Work is
shared out by pair (a PairShard per process goes through every chunk for its pairs), so
whether a pair is seen colliding does not depend on who checks it.
"""

from __future__ import annotations

import math

import numpy as np

from marm_setup.collision.scene import HULL_MARGIN
from marm_setup.robot import RobotModel, sample_configurations

Pair = tuple[str, str]
CHUNK = 1000  # trial samples per chunk (fixed: independent of jobs and CPU count)
CLOSEST = 8  # samples per Never pair (smallest bounding-sphere gap) where the distance is measured


def trial_chunk(robot: RobotModel, seed: int, index: int, trials: int) -> np.ndarray:
    """Chunk `index` of the Never phase's random states (rows index*CHUNK ... of all trials)."""
    rng = np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(1, index)))
    return sample_configurations(robot, rng, max(0, min(CHUNK, trials - index * CHUNK)))


def trial_samples(robot: RobotModel, seed: int, trials: int) -> np.ndarray:
    """All (trials, n_active) random states of the Never phase (the matrix streams them)."""
    parts = [trial_chunk(robot, seed, i, trials) for i in range(math.ceil(trials / CHUNK))]
    return np.concatenate(parts) if parts else np.empty((0, len(robot.active_joints)))


def trial_states(robot: RobotModel, seed: int, trials: int, rows: list[int]) -> np.ndarray:
    """The trial states of indices `rows` (each from its chunk, drawn again)."""
    chunks = {c: trial_chunk(robot, seed, c, trials) for c in {i // CHUNK for i in rows}}
    return np.array([chunks[i // CHUNK][i % CHUNK] for i in rows]).reshape(len(rows), -1)


class PairShard:
    """One process's share of the Never phase: a fixed set of pairs, checked over every trial
    chunk in order. A pair leaves at its first collision; with `shortcuts` a PairProver's
    certificates build up over all the chunks; with `closest` each unseen pair keeps its
    CLOSEST states (for `distances`: a Python step per pair and chunk, skipped when unwanted),
    and so does each `tracked` pair (proved: never checked, only followed for its distance)."""

    def __init__(
        self,
        scene,
        seed: int,
        trials: int,
        shortcuts: bool,
        pairs: tuple[Pair, ...],
        tracked: tuple[Pair, ...] = (),
        closest: bool = True,
    ) -> None:
        self.scene, self.seed, self.trials, self.shortcuts = scene, seed, trials, shortcuts
        self.unseen, self.tracked = pairs, tracked if closest else ()
        self.keep_closest = closest
        self.closest: dict[Pair, list[tuple[float, int]]] = (
            {p: [] for p in (*pairs, *self.tracked)} if closest else {}
        )
        self.prover = None
        if shortcuts:
            from marm_setup.collision.prover import PairProver

            self.prover = PairProver(scene)

    @property
    def chunks(self) -> int:
        return math.ceil(self.trials / CHUNK)

    def check(self, index: int) -> set[Pair]:
        """Check chunk `index` (chunks go in order); the pairs first seen colliding in it."""
        q = trial_chunk(self.scene.robot, self.seed, index, self.trials)
        horizon = self.chunks - index
        seen, closest = check_chunk(
            self.scene, q, self.unseen, self.prover, horizon, self.keep_closest, self.tracked
        )
        self.unseen = tuple(p for p in self.unseen if p not in seen)
        start = index * CHUNK
        for pair, items in closest.items():
            merged = self.closest[pair] + [(g, i + start) for g, i in items]
            self.closest[pair] = sorted(merged)[:CLOSEST]
        return seen

    def nearest_rows(self) -> dict[Pair, tuple[int, ...]]:
        """Each never-seen pair's CLOSEST trial states (their indices), smallest gap first."""
        return {p: tuple(i for _, i in self.closest[p]) for p in self.unseen if self.closest.get(p)}

    def distances(self) -> dict[Pair, float]:
        """Smallest exact distance [m] of each never-seen pair over its closest trial states."""
        every = (*self.unseen, *self.tracked)
        items = [(p, [i for _, i in self.closest[p]]) for p in every if self.closest.get(p)]
        rows = sorted({i for _, pair_rows in items for i in pair_rows})
        if not rows:
            return {}
        q = trial_states(self.scene.robot, self.seed, self.trials, rows)
        poses = dict(zip(rows, self.scene.link_poses(q), strict=True))
        out = {}
        for pair, pair_rows in items:
            pair_id = int(self.scene.pair_ids((pair,))[0])
            states = [poses[i] for i in pair_rows]
            if self.shortcuts:
                out[pair] = _smallest_distance(self.scene, states, pair_id)
            else:
                out[pair] = min(self.scene.distance(p, pair_id) for p in states)
        return out


def _smallest_distance(scene, poses: list[np.ndarray], pair_id: int) -> float:
    """min of scene.distance over `poses`, skipping states whose hull distance (a lower bound,
    cheap) already exceeds the smallest found by more than coal's tolerance: same minimum."""
    if not scene.has_hulls(pair_id):
        return min(scene.distance(p, pair_id) for p in poses)
    lower = [scene.hull_distance(p, pair_id) for p in poses]
    best = np.inf
    for k in np.argsort(lower, kind="stable"):
        if lower[k] - HULL_MARGIN >= best:
            break
        best = min(best, scene.distance(poses[k], pair_id))
    return best


def check_chunk(
    scene,
    q: np.ndarray,
    pairs: tuple[Pair, ...],
    prover=None,
    horizon: float = 1.0,
    closest: bool = True,
    tracked: tuple[Pair, ...] = (),
):
    """Pairs of `pairs` seen colliding in states `q`, and (when `closest`) each unseen pair's
    CLOSEST smallest-gap states (those of `tracked` pairs too, which are not checked).

    A pair stops being checked at its first collision; its candidate states are tried in order of
    deepest bounding-sphere overlap, so sometimes-colliding pairs are found in a few calls.
    `prover` (a PairProver): the same answer with fewer exact checks (`horizon`: the chunks
    this process has still to check, this one included).
    """
    if not (pairs or tracked) or not len(q):
        return set(), {}
    poses = scene.link_poses(q)
    centers = scene.link_centers(poses)
    every = (*pairs, *tracked)
    ids = scene.pair_ids(every)
    seen: set[Pair] = set()
    nearest: dict[Pair, list[tuple[float, int]]] = {}
    for part in scene.pair_batches(len(q), len(every)):  # bounded memory for any number of pairs
        gaps = scene.sphere_gaps(poses, ids[part], centers)
        checked = slice(part.start, min(part.stop, len(pairs)))  # the batch's pairs not tracked
        if checked.start < checked.stop:
            width = checked.stop - checked.start
            seen |= _seen(scene, q, poses, pairs[checked], ids[checked], gaps[:, :width], prover, horizon)
        if closest:
            nearest.update(_closest(gaps, every[part], seen))
    return seen, nearest


def _seen(scene, q, poses, pairs, ids: np.ndarray, gaps: np.ndarray, prover, horizon: float) -> set[Pair]:
    """The pairs of `pairs` (ids `ids`, sphere gaps `gaps`) in collision in some state of `q`."""
    maybe = scene.maybe_colliding(poses, ids, gaps)
    seen = set()
    for k in np.flatnonzero(maybe.any(axis=0)):  # a pair no state may touch is not seen
        candidates = np.flatnonzero(maybe[:, k])
        rows = candidates[np.argsort(gaps[candidates, k], kind="stable")]
        pair_id = int(ids[k])
        if prover is not None:
            hit = prover.any_collision(q, poses, pair_id, rows, horizon)
        else:
            hit = any(scene.collide(poses[n], pair_id) for n in rows)
        if hit:
            seen.add(pairs[k])
    return seen


def _closest(gaps: np.ndarray, pairs, seen) -> dict[Pair, list[tuple[float, int]]]:
    """Per unseen pair its CLOSEST smallest-gap rows (ties: lower row first, as a stable sort)."""
    kth = min(CLOSEST, len(gaps)) - 1
    threshold = np.partition(gaps, kth, axis=0)[kth]
    out = {}
    for k, pair in enumerate(pairs):
        if pair in seen:
            continue
        rows = np.flatnonzero(gaps[:, k] <= threshold[k])
        rows = rows[np.argsort(gaps[rows, k], kind="stable")][:CLOSEST]
        out[pair] = [(float(gaps[n, k]), int(n)) for n in rows]
    return out
