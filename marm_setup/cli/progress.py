"""The sampling progress bar of `collisions` and `init`, and what a denser run would cost."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from rich.progress import Progress, TaskID


class SamplingProgress:
    """A context manager: `callback(done, total)` for compute_collision_matrix, drawn as a rich
    bar on stderr when it is a TTY and `enabled` (not with --format json), and timed so
    `denser_seconds` can extrapolate."""

    def __init__(self, enabled: bool = True) -> None:
        self.enabled = enabled
        self.started = time.perf_counter()
        self.marks: list[tuple[float, int]] = []  # (time, trials done) at each progress call
        self._bar: Progress | None = None
        self._task: TaskID | None = None

    def __enter__(self) -> SamplingProgress:
        self.started = time.perf_counter()
        return self

    def __exit__(self, *exc: object) -> None:
        self.finished = time.perf_counter()
        if self._bar is not None:
            self._bar.stop()

    def __call__(self, done: int, total: int) -> None:
        self.marks.append((time.perf_counter(), done))
        if self._bar is None and self.enabled and sys.stderr.isatty():
            self._start_bar()
        if self._bar is not None and self._task is not None:
            self._bar.update(self._task, completed=done, total=total)

    def _start_bar(self) -> None:
        """The bar appears with the first sampling step (init does other work before)."""
        bar = _bar()
        self._bar, self._task = bar, bar.add_task("sampling", total=None)

    def denser_seconds(self, factor: int = 10) -> float | None:
        """Seconds a run with `factor` times the trials would take: this run plus the extra
        trials at the rate of this run's second half (its steady state, once early chunks
        have found the sometimes-colliding pairs)."""
        if len(self.marks) < 2 or self.marks[-1][1] <= 0:
            return None
        end_time, total = self.marks[-1]
        half_time, half = next((t, d) for t, d in self.marks if d >= total // 2 or (t, d) == self.marks[-1])
        if half >= total:
            half_time, half = self.marks[0]
        rate = (end_time - half_time) / max(total - half, 1)
        return (self.finished - self.started) + rate * total * (factor - 1)


class StageProgress:
    """A context manager: `callback(stage, done, total)` drawn as one rich bar on stderr (its
    label the current stage), only when stderr is a terminal and `enabled`; nothing otherwise,
    so pipes and `--format json` get no extra output."""

    def __init__(self, enabled: bool = True) -> None:
        self.enabled = enabled and sys.stderr.isatty()
        self._bar: Progress | None = None
        self._tasks: dict[str, TaskID] = {}

    def __enter__(self) -> StageProgress:
        return self

    def __exit__(self, *exc: object) -> None:
        if self._bar is not None:
            self._bar.stop()

    def __call__(self, stage: str, done: int, total: int) -> None:
        if not self.enabled:
            return
        if self._bar is None:
            self._bar = _bar()
        if stage not in self._tasks:
            self._tasks[stage] = self._bar.add_task(stage, total=total or None)
        self._bar.update(self._tasks[stage], completed=done, total=total or None)

    def stage(self, stage: str) -> Callable[[int, int], None]:
        """`callback(done, total)` for one stage."""
        return lambda done, total: self(stage, done, total)


def _bar() -> Progress:
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TaskProgressColumn, TextColumn, TimeRemainingColumn

    columns = (TextColumn("{task.description}"), BarColumn(), TaskProgressColumn(), TimeRemainingColumn())
    bar = Progress(*columns, console=Console(stderr=True), transient=True)
    bar.start()
    return bar
