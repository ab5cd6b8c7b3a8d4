"""PairProver: "is this pair ever in collision in these states?" with fewer exact checks.

Same answer as checking every state with coal: the shortcuts only ever prove "no collision",
never guess. Per state still open, in order:
1. certificates of earlier distance queries (see `certificates`) that cover it;
2. a cheap certificate: the distance of the meshes' convex hulls (a lower bound of the true
   distance; for primitives it is the distance), while at least every other such query proves
   something for this pair;
3. a costly certificate: the exact mesh distance, while each query proves about YIELD states
   over the run: the other states it proves in this chunk times the chunks this process has
   still to check (its ball covers as many in each); near pairs whose gap is small next to
   their lever arms get only PROBE queries;
4. the exact coal check, after the hull test (scene.collide(hulls=True)) while that rejects
   at least HULL_YIELD of the states it sees.
A pair stops at its first collision. The first EXACT_FIRST states of a chunk (deepest
bounding-sphere overlap) go straight to the exact check: sometimes-colliding pairs end there.

State (the certified balls, per pair) lives in the process; under --jobs each worker keeps
its own, so the counts of work differ with --jobs but the answer does not.
"""

from __future__ import annotations

import numpy as np

from marm_setup.collision.certificates import CERT_MARGIN, BallStore, pair_motions

EXACT_FIRST = 2  # states per chunk checked exactly first (deepest overlap: finds hits fast)
PROBE = 8  # queries of each kind a pair always gets
CHEAP_YIELD = 0.5  # then: states proven per hull-distance query needed to keep asking
YIELD = 8  # and per exact-distance query
HULL_YIELD = 0.25  # share of hull tests that must prove a state apart to keep testing hulls


class PairProver:
    """Decides pairs over batches of states for one CollisionScene (which counts the work)."""

    def __init__(self, scene) -> None:
        self.scene = scene
        self._stores: dict[int, BallStore] = {}
        self._tally: dict[tuple[int, str], list[float]] = {}  # (pair, kind) -> [queries, value]
        self._levers: dict = {}  # (ancestor, link) -> joint levers, shared by the pairs
        self._horizon = 1.0

    def any_collision(
        self, q: np.ndarray, poses: np.ndarray, pair_id: int, rows: np.ndarray, horizon: float = 1.0
    ) -> bool:
        """Whether pair `pair_id` collides in any state `rows` of `q`/`poses` (in that order);
        `horizon`: how many chunks like this one this process will still check."""
        self._horizon = max(horizon, 1.0)
        scene = self.scene
        if not len(rows):
            return False
        store = self._store(pair_id)
        if len(store):
            covered = store.covers(q[rows])
            scene.certified += int(covered.sum())
            rows = rows[~covered]
        for n in rows[:EXACT_FIRST]:
            if scene.collide(poses[n], pair_id):
                return True
        rows = rows[EXACT_FIRST:]
        alive = np.ones(len(rows), dtype=bool)
        for i, n in enumerate(rows):
            if (
                alive[i]
                and not self._certified(q, poses, pair_id, rows, i, alive)
                and self._collide(poses[n], pair_id)
            ):
                return True
        return False

    def _collide(self, poses: np.ndarray, pair_id: int) -> bool:
        """The exact check, behind the hull test while that rejects often enough (HULL_YIELD)."""
        tally = self._tally.setdefault((pair_id, "hull test"), [0, 0])
        if tally[0] >= PROBE and tally[1] < HULL_YIELD * tally[0]:
            return self.scene.collide(poses, pair_id)
        before = self.scene.hull_rejections
        hit = self.scene.collide(poses, pair_id, hulls=True)
        tally[0] += 1
        tally[1] += self.scene.hull_rejections - before
        return hit

    def _certified(self, q, poses, pair_id: int, rows, i: int, alive) -> bool:
        """Try the cheap, then the costly certificate at state rows[i] (when they pay)."""
        scene, n = self.scene, rows[i]
        kinds = (("hull", scene.hull_distance, CHEAP_YIELD), ("exact", scene.distance, YIELD))
        for kind, measure, needed in kinds:
            tally = self._tally.setdefault((pair_id, kind), [0, 0])
            if tally[0] >= PROBE and tally[1] < needed * tally[0]:
                continue
            tally[0] += 1
            scene.certificate_queries += 1
            radius = measure(poses[n], pair_id) - scene.padding - CERT_MARGIN
            if radius > 0:
                others = self._add_ball(q, pair_id, rows, i, alive, radius)
                tally[1] += 1 + others if kind == "hull" else others * self._horizon
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
