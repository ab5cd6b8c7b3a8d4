"""Progress on stderr: the sampling bar of `collisions` and `init` (and the proofs: pairs
proved, in contact, left) with the estimate of a long run (said up front, and past a bound run only with --yes) and what a denser run would cost,
and the staged bar of validate's planning."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from marm_setup.cli.common import echo_err
from marm_setup.errors import InputError

if TYPE_CHECKING:
    from rich.progress import Progress, TaskID

SAY_SECONDS = 60.0  # [s] a sampling estimate above this is said on stderr before the run goes on
CONFIRM_SECONDS = 30 * 60.0  # [s] above this the run needs --yes
MEASURE_SECONDS = 1.0  # [s] of sampling the estimate is made from (at least one chunk)


class SamplingProgress:
    """A context manager: `callback(done, total)` for compute_collision_matrix, drawn as a rich
    bar on stderr when it is a TTY and `enabled` (not with --format json), and timed so
    `denser_seconds` can extrapolate.

    After MEASURE_SECONDS of sampling (or its first chunk, if that takes longer) the whole run
    is estimated at the rate of the chunks after the first (which is slower: start-up, and the
    sometimes-colliding pairs still being found): past SAY_SECONDS the estimate is one stderr
    line, past CONFIRM_SECONDS the run stops there (an InputError naming `--trials`) unless
    `confirmed` (--yes)."""

    def __init__(
        self, enabled: bool = True, *, confirmed: bool = False, say: Callable[[str], None] = echo_err
    ) -> None:
        self.enabled = enabled
        self.started = time.perf_counter()
        self.marks: list[tuple[float, int]] = []  # (time, trials done) at each progress call
        self.confirmed = confirmed
        self._estimated = False
        self._say = say
        self._bar: Progress | None = None
        self._task: TaskID | None = None
        self._proof_task: TaskID | None = None
        self.proof_counts: tuple[int, int, int] | None = None  # the last proofs(...) told

    def __enter__(self) -> SamplingProgress:
        self.started = time.perf_counter()
        return self

    def __exit__(self, *exc: object) -> None:
        self.finished = time.perf_counter()
        if self._bar is not None:
            self._bar.stop()

    def __call__(self, done: int, total: int) -> None:
        self.marks.append((time.perf_counter(), done))
        if done and not self._estimated and self.marks[-1][0] - self.marks[0][0] >= MEASURE_SECONDS:
            self._estimated = True
            self._estimate(done, total)
        if self._bar is None and self.enabled and sys.stderr.isatty():
            self._start_bar()
        if self._bar is not None and self._task is not None:
            self._bar.update(self._task, completed=done, total=total)

    def proofs(self, proved: int, in_contact: int, left: int) -> None:
        """The proofs so far (compute_collision_matrix's `proof_progress`), as a second line
        of the bar: pairs proved collision-free, found in contact, left in the current stage."""
        self.proof_counts = (proved, in_contact, left)
        if self._bar is None and self.enabled and sys.stderr.isatty():
            self._start_bar()
        if self._bar is None:
            return
        text = f"proving: {proved} proved, {in_contact} in contact, {left} left"
        if self._proof_task is None:
            self._proof_task = self._bar.add_task(text, total=None)
        self._bar.update(self._proof_task, description=text)

    def _estimate(self, done: int, total: int) -> None:
        """Say how long the whole sampling will take, and stop a run past CONFIRM_SECONDS
        without --yes; `done` trials are checked, the first progress mark is the start."""
        if done >= total:
            return
        start, now = self.marks[0][0], self.marks[-1][0]
        took = now - start
        first_time, first_done = next((t, d) for t, d in self.marks if d)
        if done > first_done:  # the steady rate, after the first chunk
            seconds = took + (now - first_time) / (done - first_done) * (total - done)
        else:
            seconds = took * total / done
        if seconds <= SAY_SECONDS:
            return
        if seconds > CONFIRM_SECONDS and not self.confirmed:
            raise InputError(
                f"{total:,} trials would take about {duration(seconds)} here (the first {done:,} took "
                f"{duration(took)}): pass --yes to run them, or fewer --trials",
                element="--trials",
            )
        self._tell(f"sampling {total:,} trials: about {duration(seconds)} here (from the first {done:,})")

    def _tell(self, line: str) -> None:
        """Say `line` on its own line: above the bar while one is drawn (rich moves the bar down),
        never written into it."""
        if self._bar is None:
            self._say(line)
            return
        self._bar.console.print(line, markup=False, highlight=False, soft_wrap=True)

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


def duration(seconds: float) -> str:
    """`0.04 s`, `45 s`, `12 min`, `3.5 h`, `4 days`: a rough length of time for a person."""
    if seconds < 1:
        return f"{seconds:.2g} s"
    for unit, size, limit in (("s", 1, 120), ("min", 60, 120 * 60), ("h", 3600, 72 * 3600)):
        if seconds < limit:
            return f"{seconds / size:.2g} {unit}" if seconds / size < 10 else f"{seconds / size:.0f} {unit}"
    return f"{seconds / 86400:.0f} days"
