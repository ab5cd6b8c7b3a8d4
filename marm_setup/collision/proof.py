"""Proved Never: branch and bound over a pair's joint box, with coal distances.

A pair's box is the product of the bounds of the variables that move its two links relative
to each other (`collision/pair_chain.py`). At a box, coal measures the distance d at its centre
(the meshes' convex hulls first: a lower bound of the surface distance, cheap; the real
meshes and primitives, the surfaces the matrix checks, when the hulls are not enough); the
pair's geometry moves at most E between the centre and any state of the box, and its two
swept balls bound it too. The box is collision-free under the padding when the balls' gap, or
d - E, exceeds padding + a margin for coal's distance tolerance. Otherwise it is split in two
on the variable whose share of E is largest. Boxes are taken lowest lower bound first. A
centre within the padding is checked with the matrix's own exact collide (same padding, same
predicate, at the centre rounded to 1e-6): in contact, it is the witness.

When the budget runs out first, `collision/witness.py` looks for a witness by descending the
distance from the closest centres measured and from seeded random states.

Outcomes: `proved` (every box certified), `collides` (a witness state, checked exactly),
`unproved` (budget spent; `proved_fraction` is the share of the box's volume certified).
Budgets count coal queries (an exact mesh query counts EXACT_UNITS hull queries), never time:
the outcome depends on the pair, the seed and the budget only (not --jobs nor the machine).
"""

from __future__ import annotations

import heapq
import itertools
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision.certificates import CERT_MARGIN
from marm_setup.collision.pair_chain import PairChain

if TYPE_CHECKING:
    from marm_setup.collision.scene import CollisionScene

PROVED, COLLIDES, UNPROVED = "proved", "collides", "unproved"
BATCH = 64  # boxes split per round (their children are evaluated in one numpy batch)
MIN_CHILDREN = 48  # a round cuts its few boxes in more parts, up to 2**MAX_LEVELS each: a numpy
MAX_LEVELS = 5  # batch costs about 1 ms however small, a box in it about 15 us
RELATIVE_MARGIN = 1e-5  # coal's GJK stops within a relative 1e-6 of the distance (VDB criterion)
WITNESS_DECIMALS = 6  # a witness is rounded to 1e-6 [rad, m], then checked at those values
TINY = 1e-9  # [m] a box whose whole displacement bound is below this is not split further
EXACT_UNITS = 10  # an exact mesh distance costs about 10 to 40 hull distances
PROBE = 8  # exact queries beyond the hulls tried before their use is judged by what they certify


@dataclass(frozen=True, slots=True)
class Budget:
    """Work units for the branch and bound (a box evaluated or a hull distance: 1; an exact
    mesh distance: EXACT_UNITS) and for the witness search."""

    boxes: int
    descent: int


# Per prove mode, units per pair: the screen before the trials (the branch and bound: at least,
# at most, a pool the candidates share, and at most again for a second try of the pairs left
# open with what the pool has left), then the settling of the pairs the trials never saw in
# collision (the witness search: per pair, and a pool they share). None: no pool. A robot with
# few candidates gives each more (the panda: 600 of 30; the UR5e's two hard pairs get the rest);
# one with many, less (the PR2: 60 of 1300, where most pairs are far apart: a handful each).
SCREEN = {"on": (60, 600, 20_000, 10_000), "exhaustive": (50_000, 50_000, None, 0)}
SETTLE = {"on": (600, 25_000), "exhaustive": (30_000, None)}
CLOSEST = 8  # closest box centres a proof keeps for the witness search


@dataclass(frozen=True, slots=True)
class PairProof:
    """What the proof of one pair found; `witness`: (joint, value) in contact (collides only)."""

    outcome: str
    proved_fraction: float
    witness: tuple[tuple[str, float], ...] = ()
    units: int = 0  # work done, in hull-query units
    closest: tuple[tuple[float, ...], ...] = field(default=(), compare=False, repr=False)  # centres


class Meter:
    """Coal distance queries of one pair, in work units, and whether exact queries beyond the
    hulls still pay (they are tried while at least 1 in PROBE certifies what the hull did not)."""

    def __init__(self, scene: CollisionScene, pair_id: int) -> None:
        self.scene, self.pair_id = scene, pair_id
        self.hulls = scene.has_hulls(pair_id)
        self.units = 0
        self.extra_tries = 0
        self.extra_wins = 0

    def hull(self, pose_a: np.ndarray, pose_b: np.ndarray) -> float:
        self.units += 1
        return self.scene.shape_distance(self.pair_id, pose_a, pose_b, hulls=True)

    def exact(self, pose_a: np.ndarray, pose_b: np.ndarray) -> float:
        self.units += EXACT_UNITS if self.hulls else 1
        return self.scene.shape_distance(self.pair_id, pose_a, pose_b)

    def nearest(
        self, pose_a: np.ndarray, pose_b: np.ndarray, hulls: bool
    ) -> tuple[float, np.ndarray, np.ndarray]:
        self.units += 1 if hulls or not self.hulls else EXACT_UNITS
        return self.scene.nearest_points(self.pair_id, pose_a, pose_b, hulls=hulls)

    def extra_pays(self) -> bool:
        return self.extra_tries < PROBE or self.extra_wins * PROBE >= self.extra_tries


class PairSearch:
    """The branch and bound of one pair in one scene (see the module doc)."""

    def __init__(self, scene: CollisionScene, chain: PairChain, budget: Budget) -> None:
        self.scene, self.chain, self.budget = scene, chain, budget
        self.pair_id = int(scene.pair_ids((chain.pair,))[0])
        self.meter = Meter(scene, self.pair_id)
        self.threshold = scene.padding + CERT_MARGIN
        self.width = np.where(chain.upper > chain.lower, chain.upper - chain.lower, 1.0)
        self.certified = 0.0  # volume share of the certified boxes
        self.witness: tuple[tuple[str, float], ...] = ()
        self.measured: list[tuple[float, int, np.ndarray]] = []  # (distance, order, centre)
        self._heap: list = []
        self._sequence = itertools.count()

    def run(self) -> PairProof:
        """The branch and bound, within the budget's boxes."""
        chain = self.chain
        self._evaluate(chain.lower[None], chain.upper[None], np.array([np.inf]), np.array([-np.inf]))
        stuck = False  # a box too small to split is still undecided
        while self._heap and not self.witness and self._can_finish():
            batch = [heapq.heappop(self._heap) for _ in range(min(BATCH, len(self._heap)))]
            levels = max(1, min(MAX_LEVELS, int(np.ceil(np.log2(MIN_CHILDREN / len(batch))))))
            halves = [_split(item, levels) for item in batch]
            stuck = stuck or any(not h for h in halves)
            children = [child for h in halves for child in h]
            if children:
                lo, hi, reach, floor = (np.array([c[i] for c in children]) for i in range(4))
                self._evaluate(lo, hi, reach, floor)
        if self.witness:
            return self._result(COLLIDES)
        return self._result(PROVED if not self._heap and not stuck else UNPROVED)

    def _can_finish(self) -> bool:
        """Whether the budget (and the one round it may overrun by) could still certify every
        open box: each needs splitting, so two more boxes (units) apiece at least; when it
        cannot, going on proves nothing."""
        left = self.budget.boxes - self.meter.units
        return left > 0 and 2 * len(self._heap) <= left + 2 * BATCH

    def settle(self, prior: PairProof, seed: int) -> PairProof:
        """The witness search of an unproved pair, from its closest centres, within the
        budget's descent units."""
        from marm_setup.collision.witness import search_witness

        self.certified = prior.proved_fraction
        self.meter.units = prior.units
        starts = [np.array(c) for c in prior.closest]
        self.witness = search_witness(self, starts, seed, prior.units + self.budget.descent)
        return self._result(COLLIDES if self.witness else UNPROVED)

    def _result(self, outcome: str) -> PairProof:
        fraction = 1.0 if outcome == PROVED else min(1.0, float(self.certified))
        closest = (
            ()
            if outcome != UNPROVED
            else tuple(
                tuple(float(v) for v in centre)
                for _, _, centre in sorted(self.measured, key=lambda m: m[:2])[:CLOSEST]
            )
        )
        return PairProof(outcome, fraction, self.witness, int(self.meter.units), closest)

    def _evaluate(self, lo: np.ndarray, hi: np.ndarray, reach: np.ndarray, floor: np.ndarray) -> None:
        """Decide each box of the batch or put it on the heap with its lower bound. `reach`:
        per box, the most its certifying distance can be at the centre (from an ancestor's);
        a box whose motion exceeds it cannot be certified, so it is split without a query
        (its lower bound stays `floor`, its parent's)."""
        centers, halves = (lo + hi) / 2.0, (hi - lo) / 2.0
        bounds = self.chain.evaluate(centers, halves)
        gaps, motion, shares = np.maximum(bounds.ball_gap, bounds.axis_gap), bounds.motion, bounds.shares
        poses = (bounds.frames[0].pose, bounds.frames[1].pose)
        volumes = np.prod((hi - lo) / self.width, axis=1)
        self.meter.units += len(lo)  # a box's kinematics and bounds cost about a hull query
        for k in range(len(lo)):
            if gaps[k] > self.threshold:
                self.certified += volumes[k]
                continue
            if reach[k] - motion[k] <= self.threshold:
                self._push(floor[k], lo[k], hi[k], shares[k], reach[k])
                continue
            bound, measured = self._distance_bound(poses[0][k], poses[1][k], motion[k], centers[k])
            if self.witness:
                return
            if bound is None:
                self.certified += volumes[k]
            else:
                self._push(bound, lo[k], hi[k], shares[k], measured)

    def _push(self, bound: float, lo: np.ndarray, hi: np.ndarray, shares: np.ndarray, reach: float) -> None:
        heapq.heappush(self._heap, (bound, next(self._sequence), lo, hi, shares, reach))

    def _distance_bound(
        self, pose_a: np.ndarray, pose_b: np.ndarray, motion: float, center: np.ndarray
    ) -> tuple[float | None, float]:
        """(None when the box is certified, else a lower bound of its distance: the distance at
        the centre less coal's tolerance and the motion; the most the certifying distance can
        be at the centre). A centre within the padding is tried as a witness."""
        meter = self.meter
        hull = None
        if meter.hulls:
            hull = meter.hull(pose_a, pose_b)
            if _kept(hull) - motion > self.threshold:
                return None, np.inf
            if hull > self.threshold and not meter.extra_pays():  # the hulls alone decide
                self._measured(hull, center)
                return _kept(hull) - motion, _most(hull)
        distance = meter.exact(pose_a, pose_b)
        self._measured(distance, center)
        if distance <= self.threshold:
            self.witness = self.check_witness(center)
        bound = _kept(distance) - motion
        certified = bound > self.threshold
        if hull is not None and hull > self.threshold:
            meter.extra_tries += 1
            meter.extra_wins += certified
        return (None if certified else bound), _most(distance)

    def _measured(self, distance: float, center: np.ndarray) -> None:
        self.measured.append((distance, len(self.measured), center))

    def check_witness(self, values: np.ndarray) -> tuple[tuple[str, float], ...]:
        """The matrix's own exact check at `values` (box columns, rounded; other joints at
        their default): the witness, or () when not in contact."""
        from marm_setup.robot import default_configuration

        chain, scene = self.chain, self.scene
        values = np.clip(np.round(values, WITNESS_DECIMALS), chain.lower, chain.upper) + 0.0
        q = default_configuration(scene.robot)
        q[chain.columns] = values
        if not scene.collide(scene.link_poses(q[None])[0], self.pair_id):
            return ()
        names = scene.robot.active_joint_names
        return tuple((names[c], float(v)) for c, v in zip(chain.columns, values, strict=True))


def _kept(distance: float) -> float:
    """A coal distance less its tolerance: a sure lower bound of the distance."""
    return distance - CERT_MARGIN - RELATIVE_MARGIN * abs(distance)


def _most(distance: float) -> float:
    """A coal distance plus its tolerance: a sure upper bound of what coal measures there."""
    return distance + CERT_MARGIN + RELATIVE_MARGIN * abs(distance)


def _split(item: tuple, levels: int = 1) -> list[tuple[np.ndarray, np.ndarray, float, float]]:
    """The box cut in 2**levels, each cut halving its largest share of the displacement bound
    (a halved share counts as half), each part with the most its centre's distance can be (the
    box's plus the shares its centre moved by: moving one variable by up to its half-width moves
    the geometry by at most its share) and the box's lower bound."""
    bound, _, lo, hi, shares, reach = item
    if not len(lo) or shares.max(initial=0.0) < TINY:
        return []
    parts = [(lo, hi, shares.copy(), reach)]
    for _ in range(levels):
        cut = []
        for part_lo, part_hi, part_shares, part_reach in parts:
            k = int(np.argmax(part_shares))
            mid = (part_lo[k] + part_hi[k]) / 2.0
            left_hi, right_lo = part_hi.copy(), part_lo.copy()
            left_hi[k], right_lo[k] = mid, mid
            halved = part_shares.copy()
            halved[k] /= 2.0
            moved = part_reach + part_shares[k]
            cut += [(part_lo, left_hi, halved, moved), (right_lo, part_hi, halved, moved)]
        parts = cut
    return [(part_lo, part_hi, part_reach, bound) for part_lo, part_hi, _, part_reach in parts]


def prove_pair(
    scene: CollisionScene, chain: PairChain, budget: Budget, seed: int = 0, prior: PairProof | None = None
) -> PairProof:
    """The proof of one pair (see the module doc): the branch and bound, or with `prior` (an
    unproved pair's earlier proof) the witness search."""
    search = PairSearch(scene, chain, budget)
    return search.run() if prior is None else search.settle(prior, seed)
