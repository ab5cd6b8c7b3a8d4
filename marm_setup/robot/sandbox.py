"""Run a function in a forked child with a time and memory limit (for xacro).

Why a process and not a guarded evaluator: xacro evaluates `${...}` as Python (`eval`), so no
check of the expression text bounds the work (`10**10**8`, `'a' * 10**10`, a comprehension over
`range(10**12)`), and a big-integer power runs in C where no signal interrupts it. A forked child
sees the same modules and package map as the parent, cannot leave xacro's module globals dirty,
and can be killed. Where fork is unavailable the function runs in-process (unbounded).
"""

from __future__ import annotations

import os
import pickle
import resource
import select
import signal
import time
from collections.abc import Callable
from typing import TypeVar

T = TypeVar("T")


class TimeLimitExceeded(Exception):
    """The child did not finish in time and was killed."""


class ChildDied(Exception):
    """The child ended without sending a result (killed by the memory limit or a signal)."""


def run_limited(fn: Callable[[], T], *, seconds: float, memory_bytes: int) -> T:
    """`fn()` in a child process; its return value or its exception (both pickled) come back."""
    if not hasattr(os, "fork"):
        return fn()
    read_fd, write_fd = os.pipe()
    pid = os.fork()
    if pid == 0:  # child: never returns
        os.close(read_fd)
        _child(fn, write_fd, memory_bytes)
    os.close(write_fd)
    try:
        data = _read_all(read_fd, pid, seconds)
    except BaseException:
        kill(pid)
        raise
    finally:
        os.close(read_fd)
    if not data:
        raise ChildDied("the child process died without an answer (out of memory?)")
    ok, value = pickle.loads(data)
    if ok:
        return value
    raise value


def _child(fn: Callable, write_fd: int, memory_bytes: int) -> None:
    code = 0
    try:
        limit_memory(memory_bytes)
        try:
            payload = pickle.dumps((True, fn()))
        except BaseException as exc:  # everything goes back to the parent, which decides
            payload = pickle.dumps((False, picklable(exc)))
        with os.fdopen(write_fd, "wb") as out:
            out.write(payload)
    except BaseException:
        code = 1
    finally:
        os._exit(code)


def limit_memory(memory_bytes: int) -> None:
    """This process's address space at most `memory_bytes` (never above its hard limit)."""
    _soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    limit = memory_bytes if hard == resource.RLIM_INFINITY else min(memory_bytes, hard)
    resource.setrlimit(resource.RLIMIT_AS, (limit, hard))


def picklable(exc: BaseException) -> BaseException:
    """`exc` when it survives pickling (to go back to the parent), else a RuntimeError saying it."""
    try:
        pickle.loads(pickle.dumps(exc))
        return exc
    except Exception:
        return RuntimeError(f"{type(exc).__name__}: {exc}")


def _read_all(fd: int, pid: int, seconds: float) -> bytes:
    chunks: list[bytes] = []
    deadline = time.monotonic() + seconds
    while True:
        left = deadline - time.monotonic()
        ready, _, _ = select.select([fd], [], [], max(left, 0))
        if not ready:
            kill(pid)
            raise TimeLimitExceeded(f"did not finish within {seconds:g} s")
        chunk = os.read(fd, 1 << 16)
        if not chunk:
            os.waitpid(pid, 0)
            return b"".join(chunks)
        chunks.append(chunk)


def kill(pid: int) -> None:
    """SIGKILL the child `pid` and reap it (gone already: nothing)."""
    try:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    except (ProcessLookupError, ChildProcessError):
        pass
