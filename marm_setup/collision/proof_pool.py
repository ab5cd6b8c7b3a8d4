"""The proofs of many pairs in a few worker processes, each pair to whichever process is free.

A worker gets one pair at a time through its own pipe and answers with the pair's proof; the
parent waits on the pipes (multiprocessing.connection.wait) and hands the next pair to the
worker that answered. multiprocessing.Pool did the same with three helper threads, one of which
polls while results wait to be read: on the PR2 it burnt 0.36 s of CPU in 1.5 s of proofs.
Forked workers inherit the scene and the chains; spawned ones build them again (coal objects
do not pickle). Which worker proves a pair never changes its proof.
"""

from __future__ import annotations

import traceback
from collections.abc import Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Any, cast

from marm_setup.collision.pair_chain import pair_chains
from marm_setup.collision.proof import PairProof, prove_pair
from marm_setup.collision.workers import receive

if TYPE_CHECKING:
    from multiprocessing.connection import Connection

    from marm_setup.collision.pair_chain import PairChain
    from marm_setup.collision.scene import CollisionScene
    from marm_setup.robot import RobotModel

Pair = tuple[str, str]


def pooled_proofs(
    scene: CollisionScene, chains: Mapping[Pair, PairChain], order: Sequence[Pair], task: tuple, jobs: int
) -> Iterator[tuple[Pair, PairProof]]:
    """(pair, proof) of each pair of `order` as its worker finishes it (`task`: budget, seed,
    priors, starts), the pairs handed out in `order` to `jobs` worker processes."""
    import multiprocessing
    from multiprocessing.connection import wait

    fork = "fork" in multiprocessing.get_all_start_methods()
    context = multiprocessing.get_context("fork" if fork else "spawn")
    spec = (scene, chains, task) if fork else (scene.robot, scene.padding, tuple(order), task)  # (rebuilt)
    workers: list[tuple[Any, Any]] = []  # (process, parent end of its pipe)
    try:
        for _ in range(min(jobs, len(order))):
            ours, theirs = context.Pipe()
            proc = context.Process(target=_serve, args=(spec, fork, theirs), daemon=True)  # type: ignore[attr-defined]
            proc.start()
            theirs.close()
            workers.append((proc, ours))
        pending = iter(order)
        busy = {conn: proc for proc, conn in workers}
        for conn in list(busy):
            _hand_out(conn, next(pending, None), busy)
        while busy:
            for ready in wait(list(busy)):
                conn = cast("Connection", ready)
                yield _answer(conn, busy[conn])
                _hand_out(conn, next(pending, None), busy)
    finally:
        for proc, conn in workers:
            if proc.is_alive():
                proc.terminate()
            proc.join()
            conn.close()


def _hand_out(conn: Connection, pair: Pair | None, busy: dict) -> None:
    """Send a worker its next pair, or None (it stops, and is no longer waited on)."""
    conn.send(pair)
    if pair is None:
        del busy[conn]


def _answer(conn: Connection, proc: Any) -> tuple[Pair, PairProof]:
    """A worker's answer: its pair and proof; WorkerFailed when it raised or died."""
    return receive(conn, proc, "proof worker")


def _serve(spec: tuple, forked: bool, conn: Connection) -> None:
    """A worker process: prove each pair it is sent until it is sent None; an exception is
    sent as (its last line, the traceback)."""
    try:
        scene, chains, (budget, seed, priors, starts) = spec if forked else _rebuilt(*spec)
        while (pair := conn.recv()) is not None:
            proof = prove_pair(scene, chains[pair], budget, seed, priors.get(pair), starts.get(pair))
            conn.send(("ok", (pair, proof)))
    except BaseException as exc:  # report, then end: the parent raises WorkerFailed
        last = traceback.format_exception_only(exc)[-1].strip()
        conn.send(("error", (last, traceback.format_exc())))
    finally:
        conn.close()


def _rebuilt(robot: RobotModel, padding: float, pairs: tuple[Pair, ...], task: tuple) -> tuple:
    """A spawned worker's scene and chains, built again, and its task."""
    from marm_setup.collision.scene import CollisionScene

    scene = CollisionScene(robot, padding)
    return scene, pair_chains(scene, pairs), task
