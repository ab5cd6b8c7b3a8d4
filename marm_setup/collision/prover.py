"""PairProver: "is this pair ever in collision in these states?" with fewer exact checks.

Same answer as checking every state with coal: the shortcuts only ever prove "no collision",
never guess. Per state still open, in order:
1. certificates of earlier distance queries (see `certificates`) that cover it;
2. a cheap certificate: the distance of the meshes' convex hulls (a lower bound of the true
   distance; for primitives it is the distance);
3. a costly certificate: the exact mesh distance;
4. the exact coal check, behind the hull test (scene.collide(hulls=True)).
Each shortcut is used for a pair while it pays on that pair: after PROBE tries, while the exact
checks it saves (measured time of this pair's exact check) cost more than it does (its own
measured time). A certificate saves its state plus the other states it proves in this chunk
times the chunks this process has still to check (its ball covers as many in each). So near
pairs whose gap is small next to their lever arms, or whose exact check is cheap anyway, go
straight to the exact check. Timing decides only how much work is done, never the answer.

A pair stops at its first collision. The first EXACT_FIRST states of a chunk (deepest
bounding-sphere overlap) go straight to the exact check: sometimes-colliding pairs end there.
State (the certified balls, per pair) lives in the process; under --jobs each worker keeps
its own, so the counts of work differ with --jobs but the answer does not.
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np

from marm_setup.collision.certificates import CERT_MARGIN, BallStore, pair_motions

EXACT_FIRST = 2  # states per chunk checked exactly first (deepest overlap: finds hits fast)
PROBE = 8  # tries each shortcut gets on a pair before its pay is judged


class _Ledger:
    """Per (pair, shortcut): tries, exact checks saved, seconds spent."""

    def __init__(self) -> None:
        self.rows: dict[tuple[int, str], list[float]] = {}

    def entry(self, pair_id: int, kind: str) -> list[float]:
        return self.rows.setdefault((pair_id, kind), [0, 0.0, 0.0])

    def pays(self, pair_id: int, kind: str, exact_seconds: float) -> bool:
        tries, saved, seconds = self.entry(pair_id, kind)
        return tries < PROBE or saved * exact_seconds >= seconds


class PairProver:
    """Decides pairs over batches of states for one CollisionScene (which counts the work)."""

    def __init__(self, scene) -> None:
        self.scene = scene
        self._stores: dict[int, BallStore] = {}
        self._ledger = _Ledger()
        self._exact: dict[int, list[float]] = {}  # pair -> [exact checks, seconds]
        self._levers: dict = {}  # (ancestor, link) -> joint levers, shared by the pairs
        self._horizon = 1.0

    def any_collision(
        self, q: np.ndarray, poses: np.ndarray, pair_id: int, rows: np.ndarray, horizon: float = 1.0
    ) -> bool:
        """Whether pair `pair_id` collides in any state `rows` of `q`/`poses` (in that order);
        `horizon`: how many chunks like this one this process will still check."""
        self._horizon = max(horizon, 1.0)
        if not len(rows):
            return False
        store = self._store(pair_id)
        if len(store):
            covered = store.covers(q[rows])
            self.scene.certified += int(covered.sum())
            rows = rows[~covered]
        if self._exact_only(poses, pair_id, rows[:EXACT_FIRST]):
            return True
        rows = rows[EXACT_FIRST:]
        if not self._any_shortcut_pays(pair_id):
            return self._exact_only(poses, pair_id, rows)
        alive = np.ones(len(rows), dtype=bool)
        for i, n in enumerate(rows):
            if (
                alive[i]
                and not self._certified(q, poses, pair_id, rows, i, alive)
                and self._collide(poses[n], pair_id)
            ):
                return True
        return False

    def _any_shortcut_pays(self, pair_id: int) -> bool:
        """Whether a certificate or the hull test still pays on this pair (one that does not at
        the start of a chunk will not start to within it: its ledger only grows when it is used)."""
        exact = self._exact_seconds(pair_id)
        kinds = ("hull", "exact", "hull test") if self.scene.has_hulls(pair_id) else ("hull", "exact")
        return any(self._ledger.pays(pair_id, kind, exact) for kind in kinds)

    def _exact_only(self, poses: np.ndarray, pair_id: int, rows: np.ndarray) -> bool:
        """The exact check of each state in turn, timed as a whole (no shortcut pays here)."""
        collide, started, done = self.scene.collide, time.perf_counter(), 0
        hit = False
        for n in rows:
            done += 1
            if collide(poses[n], pair_id):
                hit = True
                break
        self._record_exact(pair_id, done, time.perf_counter() - started)
        return hit

    def _record_exact(self, pair_id: int, checks: int, seconds: float) -> None:
        record = self._exact.setdefault(pair_id, [0, 0.0])
        record[0] += checks
        record[1] += seconds

    def _exact_seconds(self, pair_id: int) -> float:
        count, seconds = self._exact.get(pair_id, (0, 0.0))
        return seconds / count if count else 0.0

    def _timed_exact(self, poses: np.ndarray, pair_id: int) -> bool:
        """The exact check at one state's link poses, timed for this pair's ledger."""
        started = time.perf_counter()
        hit = self.scene.collide(poses, pair_id)
        self._record_exact(pair_id, 1, time.perf_counter() - started)
        return hit

    def _collide(self, poses: np.ndarray, pair_id: int) -> bool:
        """The exact check, behind the hull test while that pays for this pair."""
        if not self.scene.has_hulls(pair_id) or not self._ledger.pays(
            pair_id, "hull test", self._exact_seconds(pair_id)
        ):
            return self._timed_exact(poses, pair_id)
        entry = self._ledger.entry(pair_id, "hull test")
        started = time.perf_counter()
        apart = self.scene.hulls_apart(poses, pair_id)
        entry[0] += 1
        entry[2] += time.perf_counter() - started
        if apart:
            entry[1] += 1
            return False
        return self._timed_exact(poses, pair_id)

    def _certified(self, q, poses, pair_id: int, rows, i: int, alive) -> bool:
        """Try the cheap, then the costly certificate at state rows[i] (while they pay)."""
        scene, n = self.scene, rows[i]
        measures: tuple[tuple[str, Callable], ...] = (
            ("hull", scene.hull_distance),
            ("exact", scene.distance),
        )
        for kind, measure in measures:
            if not self._ledger.pays(pair_id, kind, self._exact_seconds(pair_id)):
                continue
            entry = self._ledger.entry(pair_id, kind)
            scene.certificate_queries += 1
            started = time.perf_counter()
            radius = measure(poses[n], pair_id) - scene.padding - CERT_MARGIN
            entry[0] += 1
            entry[2] += time.perf_counter() - started
            if radius > 0:
                others = self._add_ball(q, pair_id, rows, i, alive, radius)
                entry[1] += 1 + others * self._horizon
                return True
        return False

    def _add_ball(self, q, pair_id: int, rows, i: int, alive, radius: float) -> int:
        """Certify state rows[i] and every later open state within `radius`; how many others."""
        store, n = self._stores[pair_id], rows[i]
        store.add(q[n], radius)
        later = rows[i + 1 :]
        newly = alive[i + 1 :] & (store.motion.bound(q[later], q[n]) < radius)
        alive[i + 1 :] &= ~newly
        others = int(newly.sum())
        self.scene.certified += 1 + others
        return others

    def _store(self, pair_id: int) -> BallStore:
        store = self._stores.get(pair_id)
        if store is None:
            pair = self.scene.candidate_pairs[pair_id]
            (motion,) = pair_motions(self.scene.robot, self.scene.link_points, [pair], self._levers)
            store = self._stores[pair_id] = BallStore(motion)
        return store
