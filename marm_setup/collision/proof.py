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
Budgets count coal queries (an exact mesh query counts several hull queries, what it costs
about: `collision/meter.py`), never time: the outcome depends on the pair, the seed and the
budget only (not --jobs nor the machine).
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision.certificates import CERT_MARGIN, RELATIVE_MARGIN
from marm_setup.collision.meter import Meter
from marm_setup.collision.pair_chain import PairChain
from marm_setup.collision.results import COLLIDES, PROVED, UNPROVED, PairProof, SearchState

if TYPE_CHECKING:
    from marm_setup.collision.scene import CollisionScene

BATCH = 256  # boxes split per round (their children are evaluated in one numpy batch: a batch
MIN_CHILDREN = 128  # costs about 1 ms however small, a box in it about 15 us); a round cuts its
MAX_LEVELS = 5  # few boxes in more parts, up to 2**MAX_LEVELS each (a proof's boxes are the same
SLACK = 64  # in any order); SLACK: open boxes beyond what the budget left can split
WITNESS_DECIMALS = 6  # a witness is rounded to 1e-6 [rad, m], then checked at those values
TINY = 1e-9  # [m] a box whose whole displacement bound is below this is not split further


@dataclass(frozen=True, slots=True)
class Budget:
    """Work units for the branch and bound (a box evaluated or a hull distance: 1; an exact
    mesh distance: meter.EXACT_UNITS) and for the witness search (see collision/meter.py)."""

    boxes: int
    descent: int


# Per prove mode, units per pair. SCREEN, the branch and bound before the trials: at least (a
# pair offered less waits for the settling), at most, and a pool the candidates share (None: no
# pool). A robot with few candidates gives each more (the panda: 500 of 40); on one with many
# (the PR2: 1300) only the reach balls screen, and the trials go first.
SCREEN = {"on": (64, 600, 20_000), "exhaustive": (50_000, 50_000, None)}


@dataclass(frozen=True, slots=True)
class Settle:
    """The settling of the pairs the trials never saw in collision: the branch and bound goes
    on, at most `again` units a pair, with what the screen's pool has left; then the witness
    search, `descent` units a pair at most from a `pool` they share; the pairs whose search
    ended within `close` [m] of contact get a second round, at most `second` units a pair from
    a `second_pool` (on the PR2 the 26 pairs a 1M-trial run sees colliding that a first round
    of 150 units a pair missed all ended within 3.1 mm; of the 318 that never collide, 10 %
    within 5.8 mm). The nearest 40 % get a second round, from a pool of 120,000: with the
    nearest 25 % from 80,000, seeds 1 and 2 left Never 2 and 1 pairs a 1M-trial run sees in
    contact (their first rounds ended 4 to 12 cm away); with these, none on seeds 0, 1, 2, for
    the same CPU and the same proved pairs (benchmarks/bench_proofs.py --against-1m)."""

    again: int
    descent: int
    pool: int | None
    close: float
    nearest: float  # the share of the pairs (nearest first) a second round gets at least
    second: int
    second_pool: int | None


SETTLE = {
    "on": Settle(10_000, 1_000, 80_000, 0.005, 0.4, 1_500, 120_000),
    "exhaustive": Settle(0, 30_000, None, 0.0, 0.0, 0, None),
}
CLOSEST = 8  # closest box centres a proof keeps for the witness search


class PairSearch:
    """The branch and bound of one pair in one scene (see the module doc), new or going on
    from an earlier one's `state`; `budget.boxes` counts from the start of the first."""

    def __init__(
        self, scene: CollisionScene, chain: PairChain, budget: Budget, state: SearchState | None = None
    ) -> None:
        self.scene, self.chain, self.budget = scene, chain, budget
        self.pair_id = int(scene.pair_ids((chain.pair,))[0])
        self.meter = Meter(scene, self.pair_id)
        self.threshold = scene.padding + CERT_MARGIN
        self.width = np.where(chain.upper > chain.lower, chain.upper - chain.lower, 1.0)
        self.certified = 0.0  # volume share of the certified boxes
        self.witness: tuple[tuple[str, float], ...] = ()
        self.measured: list[tuple[float, int, np.ndarray]] = []  # (distance, order, centre)
        self._heap: list = []
        self._sequence = 0
        self._stuck = False  # a box too small to split is still undecided
        self._started = state is not None
        self.near: list = []  # the witness search's nearest end states (see witness.py)
        self._least = 0  # the smallest budget whose run is this one, step for step (see `least`)
        self._exact = state is not None  # only this very budget gives this run
        self._checked = 0  # the most units an overrun test saw (each passed: budget + SLACK above)
        if state is not None:
            self._heap, self.certified, self.measured = (
                list(state.heap),
                state.certified,
                list(state.measured),
            )
            self.meter.units, (self.meter.extra_tries, self.meter.extra_wins) = state.units, state.extra
            self._sequence, self._stuck = state.sequence, state.stuck

    def run(self) -> PairProof:
        """The branch and bound, until its boxes are decided or the budget's boxes are spent."""
        if not self._started:
            chain = self.chain
            self._evaluate(chain.lower[None], chain.upper[None], np.array([np.inf]), np.array([-np.inf]))
            self._started = True
        while self._heap and not self.witness and self._can_finish():
            self._note_round()
            batch = [heapq.heappop(self._heap) for _ in range(min(BATCH, len(self._heap)))]
            wanted = min(MIN_CHILDREN, self.budget.boxes - self.meter.units)  # no more than is left
            levels = max(1, min(MAX_LEVELS, int(np.ceil(np.log2(max(1.0, wanted / len(batch)))))))
            splittable = [item for item in batch if item[6]]
            self._stuck = self._stuck or len(splittable) < len(batch)
            if splittable:
                self._evaluate(*_split(splittable, levels))
        if self.witness:
            return self._result(COLLIDES)
        return self._result(PROVED if not self._heap and not self._stuck else UNPROVED)

    def _note_round(self) -> None:
        """Before a round: what a budget must be for this round to go as it does (the loop test
        passed and MIN_CHILDREN wanted); a round the budget cut short is this budget's alone."""
        units, open_boxes = self.meter.units, len(self._heap)
        if self.budget.boxes - units < MIN_CHILDREN:
            self._exact = True
        self._least = max(self._least, units + max(MIN_CHILDREN, 2 * open_boxes - 2 * SLACK))

    def least(self) -> int | None:
        """The smallest budget (boxes) whose branch and bound is this one, step for step, so
        gives the same finished proof with the same units; None when only this very budget does
        (a round it cut short, an overrun, a search gone on from a state). The run depends on
        the budget only through the loop's test, the children a round wants and the overrun."""
        if self._exact:
            return None
        return max(self._least, self._checked - SLACK + 1, 0)

    def _can_finish(self) -> bool:
        """Whether the budget (and the one round it may overrun by) could still certify every
        open box: each needs splitting, so two more boxes (units) apiece at least; when it
        cannot, going on proves nothing."""
        left = self.budget.boxes - self.meter.units
        return left > 0 and 2 * len(self._heap) <= left + 2 * SLACK

    def settle(self, seed: int, starts: np.ndarray | None = None) -> PairProof:
        """The witness search of this unproved pair within the budget's descent units, from
        the robot states `starts` (the box's variables of each), then the nearest-looking
        random states, then its closest centres (see `collision/witness.py`)."""
        from marm_setup.collision.witness import search_witness

        self._exact = True  # the witness search's outcome is its seed's, starts' and budget's
        first = [] if starts is None or not len(starts) else list(self.chain.box_values(starts))
        closest = [np.array(centre) for centre in self._closest()]
        self.witness = search_witness(self, first, closest, seed, self.meter.units + self.budget.descent)
        return self._result(COLLIDES if self.witness else UNPROVED, keep=False)

    def _closest(self) -> list[np.ndarray]:
        return [centre for _, _, centre in heapq.nsmallest(CLOSEST, self.measured, key=lambda m: m[:2])]

    def _result(self, outcome: str, keep: bool = True) -> PairProof:
        fraction = 1.0 if outcome == PROVED else min(1.0, float(self.certified))
        if outcome != UNPROVED:
            return PairProof(outcome, fraction, self.witness, int(self.meter.units), least=self.least())
        closest = self._closest()
        state = None
        if keep:
            kept = heapq.nsmallest(CLOSEST, self.measured, key=lambda m: m[:2])
            meter = self.meter
            extra = (meter.extra_tries, meter.extra_wins)
            state = SearchState(
                list(self._heap), self.certified, kept, meter.units, extra, self._sequence, self._stuck
            )
        centres = tuple(tuple(float(v) for v in centre) for centre in closest)
        near = tuple(self.near)
        return PairProof(outcome, fraction, self.witness, int(self.meter.units), centres, state, near)

    def _evaluate(self, lo: np.ndarray, hi: np.ndarray, reach: np.ndarray, floor: np.ndarray) -> None:
        """Decide each box of the batch or put it on the heap with its lower bound. `reach`:
        per box, the most its certifying distance can be at the centre (from an ancestor's);
        a box whose motion exceeds it cannot be certified, so it is split without a query
        (its lower bound stays `floor`, its parent's)."""
        centers, halves = (lo + hi) / 2.0, (hi - lo) / 2.0
        bounds = self.chain.evaluate(centers, halves, self.threshold)
        shares = bounds.shares
        batch = self.meter.batch(bounds.frames[0].pose, bounds.frames[1].pose)
        self.meter.units += len(lo)  # a box's kinematics and bounds cost about a hull query
        # the loop reads Python floats (numpy's scalars cost far more per test; same values)
        gaps = np.maximum(bounds.ball_gap, bounds.axis_gap).tolist()
        motion, reach, floor = bounds.motion.tolist(), reach.tolist(), floor.tolist()
        volumes = np.prod((hi - lo) / self.width, axis=1).tolist()
        splittable = (shares.max(axis=1, initial=0.0) >= TINY).tolist()
        for k in range(len(lo)):
            if gaps[k] > self.threshold:
                self.certified += volumes[k]
                continue
            box = (lo[k], hi[k], shares[k])
            if reach[k] - motion[k] <= self.threshold:
                self._push(floor[k], box, reach[k], splittable[k])
                continue
            bound, measured = self._distance_bound(batch, k, motion[k], centers[k])
            if self.witness:
                return
            if bound is None:
                self.certified += volumes[k]
            else:
                self._push(bound, box, measured, splittable[k])

    def _push(self, bound: float, box: tuple, reach: float, splittable: bool) -> None:
        """A box (lo, hi, shares) on the heap with its lower bound, reach and whether any of
        its shares is worth a split (at least TINY)."""
        heapq.heappush(self._heap, (bound, self._sequence, *box, reach, splittable))
        self._sequence += 1

    def _distance_bound(
        self, batch: tuple, row: int, motion: float, center: np.ndarray
    ) -> tuple[float | None, float]:
        """(None when the box `row` of a meter's `batch` is certified, else a lower bound of its
        distance: the distance at the centre less coal's tolerance and the motion; the most the
        certifying distance can be at the centre). A centre within the padding is tried as a
        witness. Once a round has overrun the budget by SLACK units the hulls alone decide:
        the last round may overrun it by boxes, not by exact queries (on the PR2, 32 boxes of
        two nested meshes cost 400 units of a 30-unit budget; no pair's proof took more than 80)."""
        meter = self.meter
        hull = None
        if meter.hulls:
            hull = meter.hull(batch, row)
            if _kept(hull) - motion > self.threshold:
                return None, np.inf
            overrun = meter.units >= self.budget.boxes + SLACK
            self._exact = self._exact or overrun
            self._checked = max(self._checked, meter.units)
            if hull > self.threshold and (overrun or not meter.extra_pays()):  # the hulls decide
                self._measured(hull, center)
                return _kept(hull) - motion, _most(hull)
            if overrun:  # the hulls touch: a lower bound, and nothing known of the real distance
                return _kept(hull) - motion, np.inf
        distance = meter.exact(batch, row)
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
        if not scene.collide(scene.link_poses(q[None], self.pair_id)[0], self.pair_id):
            return ()
        names = scene.robot.active_joint_names
        return tuple((names[c], float(v)) for c, v in zip(chain.columns, values, strict=True))


def _kept(distance: float) -> float:
    """A coal distance less its tolerance: a sure lower bound of the distance."""
    return distance - CERT_MARGIN - RELATIVE_MARGIN * abs(distance)


def _most(distance: float) -> float:
    """A coal distance plus its tolerance: a sure upper bound of what coal measures there."""
    return distance + CERT_MARGIN + RELATIVE_MARGIN * abs(distance)


def _split(items: list[tuple], levels: int = 1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Heap items' boxes each cut in 2**levels (lo, hi, reach, floor per part, each box's parts
    together), each cut halving the part's largest share of the displacement bound (a halved
    share counts as half); a part's reach is the most its centre's distance can be (the box's
    plus the shares its centre moved by: moving one variable by up to its half-width moves the
    geometry by at most its share), its floor the box's lower bound."""
    floor = np.array([item[0] for item in items])
    lo, hi, shares = (np.array([item[i] for item in items]) for i in (2, 3, 4))
    reach = np.array([item[5] for item in items])
    for _ in range(levels):
        rows = np.arange(len(lo))
        k = np.argmax(shares, axis=1)
        mid = (lo[rows, k] + hi[rows, k]) / 2.0
        left_hi, right_lo = hi.copy(), lo.copy()
        left_hi[rows, k], right_lo[rows, k] = mid, mid
        reach = np.repeat(reach + shares[rows, k], 2)
        shares = shares.copy()
        shares[rows, k] /= 2.0
        lo = np.stack([lo, right_lo], axis=1).reshape(-1, lo.shape[1])
        hi = np.stack([left_hi, hi], axis=1).reshape(-1, hi.shape[1])
        shares, floor = np.repeat(shares, 2, axis=0), np.repeat(floor, 2)
    return lo, hi, reach, floor


def prove_pair(
    scene: CollisionScene,
    chain: PairChain,
    budget: Budget,
    seed: int = 0,
    prior: PairProof | None = None,
    starts: np.ndarray | None = None,
) -> PairProof:
    """The proof of one pair (see the module doc): the branch and bound within `budget.boxes`;
    with `prior` (an unproved pair's earlier proof) its branch and bound goes on for
    `budget.boxes` more units, then, still unproved, the witness search gets `budget.descent`
    (from the robot states `starts` first)."""
    if prior is None:
        return PairSearch(scene, chain, budget).run()
    limit = Budget(prior.units + budget.boxes, budget.descent)
    search = PairSearch(scene, chain, limit, prior.state)
    search.near, search._exact = list(prior.near), True  # a search gone on: its budgets' alone
    if prior.state is None:  # no boxes left to go on from (or none started): its counts stay
        search.certified, search.meter.units = prior.proved_fraction, prior.units
    proof = search.run() if budget.boxes > 0 else prior
    if proof.outcome != UNPROVED or budget.descent <= 0:
        return proof
    return search.settle(seed, starts)
