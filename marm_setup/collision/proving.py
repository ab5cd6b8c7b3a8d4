"""The proofs of many link pairs (`collision/proof.py`), in this process or in a pool of
`jobs` processes: `screen_pairs` before the trials, `settle_pairs` after them.

Each pair's proof depends on the pair, the seed and its budget alone (the settling's budget on
how many pairs share its pool too), so which process proves it, and how many there are, never
changes a result. Pairs go out longest first (by how many variables move them), one at a time,
to whichever process is free.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from typing import TYPE_CHECKING, Any

from marm_setup.collision.pairs import PROVE_MODES
from marm_setup.collision.proof import SCREEN, SETTLE, SETTLE_POOL, Budget, PairProof, prove_pair

if TYPE_CHECKING:
    from marm_setup.collision.pair_chain import PairChain
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot import RobotModel

Pair = tuple[str, str]
WORTH_A_POOL = 12  # pairs below which the proofs run in this process

_STATE: dict[str, Any] = {}  # in a pool process: its scene, chains, budget and seed


def screen_pairs(
    scene: CollisionScene, pairs: Sequence[Pair], mode: str, seed: int = 0, jobs: int = 1
) -> dict[Pair, PairProof]:
    """Pair -> its proof within the screen's budget (branch and bound only)."""
    return prove_pairs(scene, pairs, SCREEN[_checked(mode)], seed, jobs)


def settle_pairs(
    scene: CollisionScene, pairs: Sequence[Pair], mode: str, seed: int = 0, jobs: int = 1
) -> dict[Pair, PairProof]:
    """Pair -> its proof within the settling's budget (its share of the pool)."""
    budget = SETTLE[_checked(mode)]
    pool = SETTLE_POOL[mode]
    whole = len(pairs) * (budget.boxes + budget.descent)
    if pool is not None and whole > pool:
        budget = budget.scaled(pool / whole)
    return prove_pairs(scene, pairs, budget, seed, jobs)


def prove_pairs(
    scene: CollisionScene, pairs: Sequence[Pair], budget: Budget, seed: int = 0, jobs: int = 1
) -> dict[Pair, PairProof]:
    """Pair -> its proof within `budget`, for every pair of `pairs`."""
    if not pairs:
        return {}
    chains = _chains(scene, pairs)
    order = sorted(pairs, key=lambda p: (-chains[p].dims, p))
    if jobs <= 1 or len(pairs) < WORTH_A_POOL:
        return {p: prove_pair(scene, chains[p], budget, seed) for p in order}
    return dict(_pooled(scene, chains, order, budget, seed, jobs))


def _checked(mode: str) -> str:
    if mode not in SCREEN:
        raise ValueError(f"unknown prove mode {mode!r}; expected one of {', '.join(PROVE_MODES)}")
    return mode


def _chains(scene: CollisionScene, pairs: Sequence[Pair]) -> dict[Pair, PairChain]:
    from marm_setup.collision.pair_chain import pair_chain

    levers = {link: scene.lever_points(link) for pair in pairs for link in pair}
    return {pair: pair_chain(scene.robot, pair, levers) for pair in pairs}


def _pooled(
    scene: CollisionScene,
    chains: dict[Pair, PairChain],
    order: list[Pair],
    budget: Budget,
    seed: int,
    jobs: int,
) -> Iterator[tuple[Pair, PairProof]]:
    import multiprocessing

    fork = "fork" in multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if fork else "spawn")
    initargs: tuple = ()
    if fork:  # the children inherit the built scene and chains
        _STATE.update(scene=scene, chains=chains, budget=budget, seed=seed)
    else:
        initargs = (scene.robot, scene.padding, order, budget, seed)
    try:
        with context.Pool(min(jobs, len(order)), None if fork else _rebuild, initargs) as pool:
            yield from pool.imap(_prove_one, order, chunksize=1)
    finally:
        _STATE.clear()


def _rebuild(robot: RobotModel, padding: float, pairs: list[Pair], budget: Budget, seed: int) -> None:
    """A spawned pool process: build the scene and chains again (coal objects do not pickle)."""
    from marm_setup.collision.scene import CollisionScene

    scene = CollisionScene(robot, padding)
    _STATE.update(scene=scene, chains=_chains(scene, pairs), budget=budget, seed=seed)


def _prove_one(pair: Pair) -> tuple[Pair, PairProof]:
    state = _STATE
    return pair, prove_pair(state["scene"], state["chains"][pair], state["budget"], state["seed"])
