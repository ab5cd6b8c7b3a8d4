"""Workers: the Never phase's pair shards, in this process or one process per shard.

Each shard (a PairShard) lives in one process for the whole phase and goes through every trial
chunk in order, so its certificates and its "seen" pairs carry over from chunk to chunk and no
work is done twice. A worker process sends one message per chunk, then its distances, through
its own pipe; the parent reads them in chunk order, so the result does not depend on `jobs`.
Each message carries the work its process did, so the counts add up.
"""

from __future__ import annotations

import traceback
from collections.abc import Iterator
from typing import Any

from marm_setup.collision.results import Work
from marm_setup.collision.trials import Pair, PairShard


class WorkerFailed(RuntimeError):
    """A worker process raised (the message is its exception's last line; `detail` the child's
    traceback, which --debug prints) or died without an answer."""

    def __init__(self, message: str, detail: str = "") -> None:
        super().__init__(message)
        self.detail = detail


class Workers:
    """A context manager over pair shards of one scene: `chunks` then `distances`, in this
    process when there is one shard, else in one process per shard (forked workers inherit
    the built scene; spawned ones build it again)."""

    def __init__(
        self,
        scene,
        seed: int,
        trials: int,
        shortcuts: bool,
        shards: list[tuple[tuple[Pair, ...], tuple[Pair, ...]]],
        distances: bool = True,
        nearest: bool = False,
    ):
        self.distances_wanted = distances  # each shard's Never distances, after its chunks
        self.nearest_wanted = nearest  # each never-seen pair's closest trial states (indices)
        self.shards = [
            PairShard(
                scene, seed, trials, shortcuts, pairs, tracked if distances else (), distances or nearest
            )
            for pairs, tracked in shards
        ]
        self._procs: list[tuple[Any, Any]] = []  # (process, parent end of its pipe)

    @property
    def count(self) -> int:
        return self.shards[0].chunks if self.shards else 0

    def __enter__(self) -> Workers:
        if len(self.shards) > 1:
            import multiprocessing

            fork = "fork" in multiprocessing.get_all_start_methods()
            context = multiprocessing.get_context("fork" if fork else "spawn")
            for shard in self.shards:
                ours, theirs = context.Pipe(duplex=False)
                spec = shard if fork else _ShardSpec.of(shard)
                args = (spec, theirs, self.distances_wanted, self.nearest_wanted)
                proc = context.Process(target=_work, args=args, daemon=True)  # type: ignore[attr-defined]
                proc.start()
                theirs.close()
                self._procs.append((proc, ours))
        return self

    def __exit__(self, *exc) -> None:
        for proc, conn in self._procs:
            if proc.is_alive():  # done (or abandoned on an error): stop it before its pipe closes
                proc.terminate()
            proc.join()
            conn.close()
        self._procs = []

    def chunks(self) -> Iterator[tuple[set[Pair], Work]]:
        """(pairs first seen in the chunk, work of worker processes) per chunk, in order."""
        for index in range(self.count):
            if not self._procs:
                yield set().union(*(shard.check(index) for shard in self.shards)), Work()
                continue
            seen: set[Pair] = set()
            work = Work()
            for shard_seen, shard_work in self._receive():
                seen |= shard_seen
                work += shard_work
            yield seen, work

    def closest(self) -> tuple[dict[Pair, float], dict[Pair, tuple[int, ...]], Work]:
        """After the chunks: each shard's never-seen pairs' smallest distance over their
        closest states (when distances are wanted), those states' indices (when nearest are),
        and the work of worker processes."""
        found: dict[Pair, float] = {}
        rows: dict[Pair, tuple[int, ...]] = {}
        if not self._procs:
            for shard in self.shards:
                found.update(shard.distances() if self.distances_wanted else {})
                rows.update(shard.nearest_rows() if self.nearest_wanted else {})
            return found, rows, Work()
        work = Work()
        for (part, part_rows), part_work in self._receive():
            found.update(part)
            rows.update(part_rows)
            work += part_work
        return found, rows, work

    def _receive(self) -> list:
        """The next message of every worker, in shard order."""
        return [receive(conn, proc, "collision worker") for proc, conn in self._procs]


def receive(conn: Any, proc: Any, what: str) -> Any:
    """The payload of a worker's next ("ok" | "error", payload) message; WorkerFailed when the
    worker (`what`, e.g. "proof worker") sent its exception or died without an answer."""
    try:
        kind, payload = conn.recv()
    except EOFError:
        proc.join(timeout=1.0)
        raise WorkerFailed(f"{what} {proc.pid} died (exit {proc.exitcode})") from None
    if kind == "error":
        raise WorkerFailed(payload[0], detail=f"in the {what}:\n{payload[1]}")
    return payload


class _ShardSpec:
    """What a spawned worker needs to build its shard again (the scene is not picklable)."""

    def __init__(
        self, robot, padding: float, seed: int, trials: int, shortcuts: bool, pairs, tracked, closest
    ) -> None:
        self.args = (robot, padding, seed, trials, shortcuts, pairs, tracked, closest)

    @classmethod
    def of(cls, shard: PairShard) -> _ShardSpec:
        scene = shard.scene
        args = (shard.seed, shard.trials, shard.shortcuts, shard.unseen, shard.tracked, shard.keep_closest)
        return cls(scene.robot, scene.padding, *args)

    def build(self) -> PairShard:
        from marm_setup.collision.scene import CollisionScene

        robot, padding, *rest = self.args
        return PairShard(CollisionScene(robot, padding), *rest)


def _work(spec: PairShard | _ShardSpec, conn, distances: bool, nearest: bool = False) -> None:
    """A worker process: every chunk in order, then (when wanted) the distances and the
    nearest states' indices, one message each; an exception is sent as (its last line, the
    traceback)."""
    try:
        shard = spec.build() if isinstance(spec, _ShardSpec) else spec
        for index in range(shard.chunks):
            before = Work.of(shard.scene)
            seen = shard.check(index)
            conn.send(("ok", (seen, Work.of(shard.scene) - before)))
        if distances or nearest:
            before = Work.of(shard.scene)
            found = (shard.distances() if distances else {}, shard.nearest_rows() if nearest else {})
            conn.send(("ok", (found, Work.of(shard.scene) - before)))
    except BaseException as exc:  # report, then end: the parent raises WorkerFailed
        last = traceback.format_exception_only(exc)[-1].strip()
        conn.send(("error", (last, traceback.format_exc())))
    finally:
        conn.close()
