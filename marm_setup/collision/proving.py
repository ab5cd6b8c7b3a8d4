"""The proofs of many link pairs (`collision/proof.py`), in this process or in a pool of
`jobs` processes: `screen_pairs` before the trials, `settle_pairs` after them.

Each pair's proof depends on the pair, the seed and its budget alone (and a budget on how many
pairs share its pool), so which process proves it, and how many there are, never changes a
result. Pairs go out longest first (by how many variables move them), one at a time,
to whichever process is free.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

from marm_setup.collision.pairs import PROVE_MODES
from marm_setup.collision.proof import SCREEN, SETTLE, Budget, PairProof, prove_pair

if TYPE_CHECKING:
    from marm_setup.collision.pair_chain import PairChain
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot import RobotModel

Pair = tuple[str, str]
WORTH_A_POOL = 40_000  # units of work below which the proofs run in this process (a pool of
# forked processes costs about 0.1 s of CPU; 40,000 units take about 0.5 s)

_STATE: dict[str, Any] = {}  # in a pool process: its scene, chains and task


def screen_pairs(
    scene: CollisionScene, pairs: Sequence[Pair], mode: str, seed: int = 0, jobs: int = 1
) -> dict[Pair, PairProof]:
    """Pair -> its branch and bound, within the screen's units (see proof.SCREEN); an
    unproved one keeps its state, for `settle_pairs` to go on from."""
    least, most, pool = SCREEN[_checked(mode)]
    boxes = most if pool is None else int(min(most, max(least, pool // max(1, len(pairs)))))
    return prove_pairs(scene, pairs, Budget(boxes, 0), seed, jobs)


def settle_pairs(
    scene: CollisionScene,
    priors: dict[Pair, PairProof],
    mode: str,
    seed: int = 0,
    jobs: int = 1,
    spent: int = 0,
) -> dict[Pair, PairProof]:
    """Pair -> its proof after its unproved screen `priors[pair]` (see proof.SETTLE): the branch
    and bound goes on with what the screen's pool has left after `spent` units (shared, up to
    a most a pair), then the witness search."""
    again, descent, pool = SETTLE[_checked(mode)]
    screen_pool = SCREEN[mode][2]
    count = max(1, len(priors))
    boxes = again if screen_pool is None else min(again, max(0, screen_pool - spent) // count)
    if pool is not None:
        descent = min(descent, pool // count)
    proofs = prove_pairs(scene, sorted(priors), Budget(boxes, descent), seed, jobs, priors)
    return {pair: dataclasses.replace(proof, state=None) for pair, proof in proofs.items()}


def prove_pairs(
    scene: CollisionScene,
    pairs: Sequence[Pair],
    budget: Budget,
    seed: int = 0,
    jobs: int = 1,
    priors: dict[Pair, PairProof] | None = None,
) -> dict[Pair, PairProof]:
    """Pair -> its proof within `budget` (with `priors`: each pair's witness search after it)."""
    if not pairs:
        return {}
    priors = priors or {}
    chains = _chains(scene, pairs)
    order = sorted(pairs, key=lambda p: (-chains[p].dims, p))
    if jobs <= 1 or len(pairs) < 2 or len(pairs) * (budget.boxes + budget.descent) < WORTH_A_POOL:
        return {p: prove_pair(scene, chains[p], budget, seed, priors.get(p)) for p in order}
    return dict(_pooled(scene, chains, order, (budget, seed, priors), jobs))


def _checked(mode: str) -> str:
    if mode not in SCREEN:
        raise ValueError(f"unknown prove mode {mode!r}; expected one of {', '.join(PROVE_MODES)}")
    return mode


def _chains(scene: CollisionScene, pairs: Sequence[Pair]) -> dict[Pair, PairChain]:
    from marm_setup.collision.pair_chain import pair_chain

    levers = {link: scene.lever_points(link) for pair in pairs for link in pair}
    return {pair: pair_chain(scene.robot, pair, levers) for pair in pairs}


def _pooled(
    scene: CollisionScene, chains: dict[Pair, PairChain], order: list[Pair], task: tuple, jobs: int
) -> Iterator[tuple[Pair, PairProof]]:
    """The proofs in a pool; `task`: (budget, seed, priors)."""
    import multiprocessing

    fork = "fork" in multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if fork else "spawn")
    initargs: tuple = ()
    if fork:  # the children inherit the built scene and chains
        _STATE.update(scene=scene, chains=chains, task=task)
    else:
        initargs = (scene.robot, scene.padding, order, task)
    try:
        with context.Pool(min(jobs, len(order)), None if fork else _rebuild, initargs) as pool:
            yield from pool.imap(_prove_one, order, chunksize=1)
    finally:
        _STATE.clear()


def _rebuild(robot: RobotModel, padding: float, pairs: list[Pair], task: tuple) -> None:
    """A spawned pool process: build the scene and chains again (coal objects do not pickle)."""
    from marm_setup.collision.scene import CollisionScene

    scene = CollisionScene(robot, padding)
    _STATE.update(scene=scene, chains=_chains(scene, pairs), task=task)


def _prove_one(pair: Pair) -> tuple[Pair, PairProof]:
    budget, seed, priors = _STATE["task"]
    return pair, prove_pair(_STATE["scene"], _STATE["chains"][pair], budget, seed, priors.get(pair))
