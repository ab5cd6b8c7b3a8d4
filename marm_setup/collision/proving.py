"""The proofs of many link pairs (`collision/proof.py`), in this process or in a pool of
`jobs` processes: `screen_pairs` before the trials, `settle_pairs` after them.

Each pair's proof depends on the pair, the seed and its budget alone (and a budget on how many
pairs share its pool), so which process proves it, and how many there are, never changes a
result. Pairs go out longest first (by how many variables move them), one at a time,
to whichever process is free (`collision/proof_pool.py`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Iterator, Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision.certificates import CERT_MARGIN
from marm_setup.collision.pair_chain import pair_chains
from marm_setup.collision.pairs import PROVE_MODES
from marm_setup.collision.proof import (
    COLLIDES,
    PROVED,
    SCREEN,
    SETTLE,
    UNPROVED,
    Budget,
    PairProof,
    prove_pair,
)

if TYPE_CHECKING:
    from marm_setup.collision.pair_chain import PairChain
    from marm_setup.collision.scene import CollisionScene

Pair = tuple[str, str]
WORTH_A_POOL = 40_000  # units of work below which the proofs run in this process (a pool of
# forked processes costs about 0.1 s of CPU; 40,000 units take about 0.5 s)


def screen_pairs(
    scene: CollisionScene,
    pairs: Sequence[Pair],
    mode: str,
    seed: int = 0,
    jobs: int = 1,
    known: frozenset[Pair] = frozenset(),
    tally: ProofTally | None = None,
    budget: tuple[set[Pair], int] | None = None,
) -> dict[Pair, PairProof]:
    """Pair -> its proof before the trials (see proof.SCREEN): pairs whose links' reach balls
    are apart are proved at once (`collision/reach_balls.py`); the others get a branch and
    bound of their own when the screen's pool gives each at least SCREEN_LEAST units, else they
    wait for `settle_pairs` (an unproved proof keeps its state, to go on from). The `known`
    pairs (proofs from the cache) share the pool as they would, but are not proved."""
    far, boxes = budget or screen_budget(scene, pairs, mode)
    proofs = {pair: PairProof(PROVED, 1.0, units=1) for pair in pairs if pair in far and pair not in known}
    open_pairs = [pair for pair in pairs if pair not in far and pair not in known]
    if tally is not None:
        tally.start(tally.proved + len(proofs), tally.in_contact, len(open_pairs) if boxes else 0)
    if not boxes:
        return proofs | {pair: PairProof(UNPROVED, 0.0) for pair in open_pairs}
    return proofs | prove_pairs(scene, open_pairs, Budget(boxes, 0), seed, jobs, tally=tally)


def screen_budget(scene: CollisionScene, pairs: Sequence[Pair], mode: str) -> tuple[set[Pair], int]:
    """The pairs of `pairs` the reach balls prove apart, and the boxes the screen's branch and
    bound gives each of the others from its pool (0: fewer than SCREEN's least, no branch and
    bound before the trials)."""
    from marm_setup.collision.reach_balls import far_apart

    least, most, pool = SCREEN[_checked(mode)]
    levers = {link: scene.lever_points(link) for pair in pairs for link in pair}
    far = far_apart(scene.robot, pairs, levers, scene.padding + CERT_MARGIN)
    rest = len(pairs) - len(far)
    boxes = most if pool is None else int(min(most, pool // max(1, rest)))
    return far, boxes if boxes >= least else 0


def settle_pairs(
    scene: CollisionScene,
    priors: dict[Pair, PairProof],
    mode: str,
    seed: int = 0,
    jobs: int = 1,
    spent: int = 0,
    starts: dict[Pair, np.ndarray] | None = None,
    known: Mapping[Pair, float | None] | None = None,
    tally: ProofTally | None = None,
) -> dict[Pair, PairProof]:
    """Pair -> its proof after its unproved screen `priors[pair]` (see proof.Settle): the branch
    and bound goes on with what the screen's pool has left after `spent` units, then the witness
    search (first from `starts[pair]`, robot states: the pair's closest trial states), then a
    second round of it for the pairs whose first ended close to contact (a proof the first round
    left open keeps where it ended: `second`). `known`: more pairs (proofs from the cache) that
    share the pools and the choice of the second round as they would, each with its `second`
    (None: the first round finished it)."""
    known = known or {}
    plan = SETTLE[_checked(mode)]
    screen_pool = SCREEN[mode][2]
    count = max(1, len(priors) + len(known))
    boxes = plan.again if screen_pool is None else min(plan.again, max(0, screen_pool - spent) // count)
    if tally is not None:
        tally.start(tally.proved, tally.in_contact, len(priors))
    chains = pair_chains(scene, sorted(priors))  # both rounds' (a chain costs about 0.25 ms)
    proofs = prove_pairs(
        scene,
        sorted(priors),
        Budget(boxes, _share(plan.descent, plan.pool, count)),
        seed,
        jobs,
        priors,
        starts,
        tally,
        chains,
    )
    reached = {pair: proof.reached for pair, proof in proofs.items() if proof.outcome == UNPROVED}
    proofs.update(
        {pair: dataclasses.replace(proofs[pair], second=distance) for pair, distance in reached.items()}
    )
    reached.update({pair: second for pair, second in known.items() if second is not None})
    close = _nearest(reached, scene.padding + plan.close, plan.nearest)
    if close and plan.second:
        descent = _share(plan.second, plan.second_pool, len(close))
        todo = [pair for pair in close if pair not in known]
        if tally is not None:
            tally.start(tally.proved, tally.in_contact, len(todo))
        again = prove_pairs(
            scene, todo, Budget(0, descent), seed + 1, jobs, proofs, tally=tally, chains=chains
        )
        proofs.update(
            {pair: dataclasses.replace(proof, second=reached[pair]) for pair, proof in again.items()}
        )
    return {pair: dataclasses.replace(proof, state=None, near=()) for pair, proof in proofs.items()}


def _nearest(reached: Mapping[Pair, float], close: float, share: float) -> list[Pair]:
    """Of the unproved pairs (and where their witness search ended [m]), those that ended
    within `close` [m] of contact, and at least the nearest `share` of them all, in pair order."""
    open_pairs = sorted((distance, pair) for pair, distance in reached.items())
    least = int(np.ceil(share * len(open_pairs)))
    return sorted(pair for k, (reached, pair) in enumerate(open_pairs) if reached <= close or k < least)


def _share(most: int, pool: int | None, count: int) -> int:
    return most if pool is None else min(most, pool // max(1, count))


def prove_pairs(
    scene: CollisionScene,
    pairs: Sequence[Pair],
    budget: Budget,
    seed: int = 0,
    jobs: int = 1,
    priors: dict[Pair, PairProof] | None = None,
    starts: dict[Pair, np.ndarray] | None = None,
    tally: ProofTally | None = None,
    chains: Mapping[Pair, PairChain] | None = None,
) -> dict[Pair, PairProof]:
    """Pair -> its proof within `budget` (with `priors`: going on from each; `starts`: robot
    states each pair's witness search starts from; `tally` hears of each proof as it ends;
    `chains`: the pairs' PairChains, when the caller has them)."""
    if not pairs:
        return {}
    priors, starts = priors or {}, starts or {}
    chains = {pair: chains[pair] for pair in pairs} if chains is not None else pair_chains(scene, pairs)
    order = sorted(pairs, key=lambda p: (-chains[p].dims, p))
    found: Iterator[tuple[Pair, PairProof]]
    if jobs <= 1 or len(pairs) < 2 or len(pairs) * (budget.boxes + budget.descent) < WORTH_A_POOL:
        found = ((p, prove_pair(scene, chains[p], budget, seed, priors.get(p), starts.get(p))) for p in order)
    else:
        from marm_setup.collision.proof_pool import pooled_proofs

        found = pooled_proofs(scene, chains, order, (budget, seed, priors, starts), jobs)
    out = {}
    for pair, proof in found:
        out[pair] = proof
        if tally is not None:
            tally(proof)
    return {pair: out[pair] for pair in order}


class ProofTally:
    """Pairs proved, found in contact and left in the current stage, told to
    `report(proved, in_contact, left)` as each proof ends (the progress of `collisions` and
    `init`)."""

    def __init__(self, report: Callable[[int, int, int], None] | None) -> None:
        self.report = report
        self.proved = self.in_contact = self.left = 0

    def start(self, proved: int, in_contact: int, left: int) -> None:
        """A stage begins with `left` pairs to prove (and the counts so far)."""
        self.proved, self.in_contact, self.left = proved, in_contact, left
        self._tell()

    def __call__(self, proof: PairProof) -> None:
        self.left = max(0, self.left - 1)
        self.proved += proof.outcome == PROVED
        self.in_contact += proof.outcome == COLLIDES
        self._tell()

    def _tell(self) -> None:
        if self.report is not None:
            self.report(self.proved, self.in_contact, self.left)


def _checked(mode: str) -> str:
    if mode not in SCREEN:
        raise ValueError(f"unknown prove mode {mode!r}; expected one of {', '.join(PROVE_MODES)}")
    return mode
