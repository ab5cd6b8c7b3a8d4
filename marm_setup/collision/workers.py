"""Workers: the trial chunks and the Never distances, in this process or in `jobs` processes.

Chunks come back in chunk order whoever ran them, so the result does not depend on `jobs`.
Each result carries the work its process did, so the counts add up under --jobs too.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from marm_setup.collision.trials import Pair, TrialChecker, Work

if TYPE_CHECKING:
    from concurrent.futures import ProcessPoolExecutor

_CHECKER: TrialChecker | None = None  # the checker of a worker process (fork or _init_worker)


class Workers:
    """A context manager over a TrialChecker: `chunks` and `distances` run serially when
    `jobs` is 1, else in a process pool (forked workers inherit the built scene)."""

    def __init__(self, checker: TrialChecker, jobs: int) -> None:
        self.checker, self.jobs = checker, jobs
        self._pool: ProcessPoolExecutor | None = None

    def __enter__(self) -> Workers:
        if self.jobs > 1 and self.checker.chunks > 1:
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            global _CHECKER
            fork = "fork" in multiprocessing.get_all_start_methods()
            _CHECKER = self.checker if fork else None
            scene, c = self.checker.scene, self.checker
            self._pool = ProcessPoolExecutor(
                self.jobs,
                mp_context=multiprocessing.get_context("fork" if fork else "spawn"),
                initializer=_init_worker,
                initargs=(scene.robot, scene.padding, c.seed, c.trials, c.shortcuts, c.jobs),
            )
        return self

    def __exit__(self, *exc) -> None:
        global _CHECKER
        if self._pool is not None:
            self._pool.shutdown(cancel_futures=True)
        _CHECKER = None

    def chunks(self, pairs: tuple[Pair, ...]) -> Iterator[tuple[set, dict, Work]]:
        """(seen, closest, work of other processes) per chunk, in chunk order. Serially, a pair
        seen in a chunk is not checked in later ones."""
        if self._pool is None or not pairs:
            unseen = pairs
            for index in range(self.checker.chunks):
                seen, closest = self.checker.check(index, unseen)
                unseen = tuple(p for p in unseen if p not in seen)
                yield seen, closest, Work()
            return
        yield from self._pool.map(_worker_chunk, [(i, pairs) for i in range(self.checker.chunks)])

    def distances(self, items: list[tuple[Pair, list[int]]]) -> tuple[dict[Pair, float], Work]:
        """TrialChecker.distances over `items`, split among the workers."""
        if self._pool is None or len(items) < 2:
            return self.checker.distances(items), Work()
        size = -(-len(items) // (4 * self.jobs))
        out: dict[Pair, float] = {}
        work = Work()
        for part, part_work in self._pool.map(
            _worker_distances, [items[i : i + size] for i in range(0, len(items), size)]
        ):
            out.update(part)
            work += part_work
        return out, work


def _init_worker(robot, padding: float, seed: int, trials: int, shortcuts: bool, jobs: int) -> None:
    global _CHECKER
    if _CHECKER is None:
        from marm_setup.collision.scene import CollisionScene

        _CHECKER = TrialChecker(CollisionScene(robot, padding), seed, trials, shortcuts, jobs)


def _checker() -> TrialChecker:
    assert _CHECKER is not None, "a worker process without its checker"
    return _CHECKER


def _worker_chunk(args):
    checker = _checker()
    before = Work.of(checker.scene)
    seen, closest = checker.check(*args)
    return seen, closest, Work.of(checker.scene) - before


def _worker_distances(items):
    checker = _checker()
    before = Work.of(checker.scene)
    return checker.distances(items), Work.of(checker.scene) - before
