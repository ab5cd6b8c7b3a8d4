"""One forked child for every `$(eval)` of a package read (issue 36: a child per expression made
5000 of them take 4 minutes).

The child is forked on the first `$(eval)` of an `eval_session` (read_package holds one) and
killed when the session ends; outside a session each evaluation has a child of its own. It is
bounded as xacro's (robot/sandbox.py): its address space (RLIMIT_AS) for its whole life, and
each evaluation by a deadline, past which it is killed (the next evaluation forks another). The
parent sends a request and answers the child's package lookups (`find` closes over the parent's
package map, an arg the launch file's scope holds) until the reply comes; each frame is
length-prefixed and bounded.
"""

from __future__ import annotations

import contextlib
import os
import pickle
import select
import signal
import struct
import time
from collections.abc import Callable, Iterator
from typing import Any

from marm_setup.robot import ChildDied, TimeLimitExceeded, kill, limit_memory, picklable

Ask = Callable[[str, str], Any]  # (what, name) -> the parent's answer: ("find", pkg), ("arg", name)
Handler = Callable[[Any, Ask], str]  # (request, ask) -> the value, in the child
FRAME_BYTES = 4 << 20  # one request or reply: a substituted text is at most 1 MiB characters
_HEADER = struct.Struct("<Q")


class EvalChild:
    """A forked child running `handler` on each request (`evaluate`), until `close`."""

    def __init__(self, handler: Handler, memory_bytes: int):
        from_parent, to_child = os.pipe()  # (read end, write end)
        from_child, to_parent = os.pipe()
        pid = os.fork()
        if pid == 0:  # child: never returns
            os.close(to_child)
            os.close(from_child)
            _serve(handler, from_parent, to_parent, memory_bytes)
        os.close(from_parent)
        os.close(to_parent)
        self.pid, self._send, self._receive = pid, to_child, from_child

    def evaluate(self, request: Any, answer: Ask, seconds: float) -> str:
        """The handler's value for `request` (its exception raised here), within `seconds`;
        `answer(what, name)` answers the child's questions."""
        deadline = time.monotonic() + seconds
        _write_frame(self._send, pickle.dumps(request))
        while True:
            kind, *rest = pickle.loads(_read_frame(self._receive, deadline, seconds))
            if kind == "ask":
                _write_frame(self._send, pickle.dumps(answer(*rest)))
                continue
            ok, value = rest
            if ok:
                return value
            raise value

    def close(self) -> None:
        for fd in (self._send, self._receive):
            with contextlib.suppress(OSError):
                os.close(fd)
        kill(self.pid)


_child: EvalChild | None = None
_sessions = 0


@contextlib.contextmanager
def eval_session() -> Iterator[None]:
    """Every `$(eval)` inside runs in one child, killed at the end (sessions may nest)."""
    global _sessions
    _sessions += 1
    try:
        yield
    finally:
        _sessions -= 1
        if _sessions == 0:
            _close()


def evaluate_in_child(
    handler: Handler, request: Any, answer: Ask, *, seconds: float, memory_bytes: int
) -> str:
    """`handler(request, ask)` in the session's child (`answer` answering what it asks) (forked now if it has none); a child
    that ran out of time or died is killed, and the next evaluation forks another."""
    global _child
    if not hasattr(os, "fork"):
        return handler(request, answer)
    if _child is None:
        _child = EvalChild(handler, memory_bytes)
    try:
        return _child.evaluate(request, answer, seconds)
    except (TimeLimitExceeded, ChildDied, OSError):
        _close()
        raise
    finally:
        if _sessions == 0:
            _close()


def _close() -> None:
    global _child
    if _child is not None:
        _child.close()
        _child = None


def _serve(handler: Handler, receive: int, send: int, memory_bytes: int) -> None:
    """The child's loop: a request in, its reply out, until the parent closes the pipe."""
    code = 0
    try:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
        limit_memory(memory_bytes)

        def ask(what: str, name: str) -> Any:
            _write_frame(send, pickle.dumps(("ask", what, name)))
            return pickle.loads(_read_frame(receive, None, 0))

        while True:
            try:
                request = pickle.loads(_read_frame(receive, None, 0))
            except ChildDied:  # the parent closed the pipe: done
                break
            try:
                reply: tuple = ("done", True, handler(request, ask))
            except Exception as exc:  # the parent decides what it means
                reply = ("done", False, picklable(exc))
            _write_frame(send, pickle.dumps(reply))
    except BaseException:
        code = 1
    finally:
        os._exit(code)


def _write_frame(fd: int, data: bytes) -> None:
    if len(data) > FRAME_BYTES:
        raise ChildDied(f"a message of {len(data):,} bytes, over {FRAME_BYTES:,}")
    view = memoryview(_HEADER.pack(len(data)) + data)
    while view:
        view = view[os.write(fd, view) :]


def _read_frame(fd: int, deadline: float | None, seconds: float) -> bytes:
    size = _HEADER.unpack(_read_exactly(fd, _HEADER.size, deadline, seconds))[0]
    if size > FRAME_BYTES:
        raise ChildDied(f"a message of {size:,} bytes, over {FRAME_BYTES:,}")
    return _read_exactly(fd, size, deadline, seconds)


def _read_exactly(fd: int, size: int, deadline: float | None, seconds: float) -> bytes:
    chunks, left = [], size
    while left:
        if deadline is not None:
            ready, _, _ = select.select([fd], [], [], max(deadline - time.monotonic(), 0))
            if not ready:
                raise TimeLimitExceeded(f"did not finish within {seconds:g} s")
        chunk = os.read(fd, min(left, 1 << 16))
        if not chunk:
            raise ChildDied("the child process died without an answer (out of memory?)")
        chunks.append(chunk)
        left -= len(chunk)
    return b"".join(chunks)
