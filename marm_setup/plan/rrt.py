"""RRT-Connect and shortcut smoothing in a box of joint space, against a line checker.

The checker is a `LineChecker` (`planner._Checker`): `options` (max_step, max_range, budgets),
`space` (lower/upper bounds), `first_invalid(states) -> (index | None, pair | None)` and
`line_valid(q_a, q_b)`. Trees are numpy arrays grown in place; nearest neighbours by brute
force, which beats a k-d tree at the few thousand nodes these queries need.
"""

from __future__ import annotations

import time
from typing import Protocol

import numpy as np

from marm_setup.plan.space import GroupSpace, PlannerOptions


class LineChecker(Protocol):
    """Settings, the box to sample in, and collision checks of states and lines."""

    @property
    def options(self) -> PlannerOptions: ...

    @property
    def space(self) -> GroupSpace: ...

    @property
    def valid_lines(self) -> set[tuple[bytes, bytes]]: ...

    def first_invalid(self, q: np.ndarray) -> tuple[int | None, tuple[str, str] | None]: ...

    def line_valid(self, q_a: np.ndarray, q_b: np.ndarray) -> bool: ...


def interpolate(q_a: np.ndarray, q_b: np.ndarray, max_step: float) -> np.ndarray:
    """States after `q_a` up to and including `q_b`, consecutive ones at most `max_step` apart."""
    n = max(1, int(np.ceil(np.linalg.norm(q_b - q_a) / max_step)))
    s = np.arange(1, n + 1)[:, None] / n
    return q_a + s * (q_b - q_a)


class _Tree:
    """Nodes (grown by doubling) and parent indices; node 0 is the root."""

    def __init__(self, root: np.ndarray):
        self.nodes = np.empty((64, len(root)))
        self.nodes[0] = root
        self.parents = [-1]

    def __len__(self) -> int:
        return len(self.parents)

    def add(self, q: np.ndarray, parent: int) -> int:
        n = len(self.parents)
        if n == len(self.nodes):
            self.nodes = np.concatenate([self.nodes, np.empty_like(self.nodes)])
        self.nodes[n] = q
        self.parents.append(parent)
        return n

    def nearest(self, q: np.ndarray) -> int:
        diff = self.nodes[: len(self.parents)] - q
        return int(np.argmin(np.einsum("ij,ij->i", diff, diff)))

    def branch(self, i: int) -> list[np.ndarray]:
        """Nodes from `i` up to the root."""
        out = []
        while i >= 0:
            out.append(self.nodes[i].copy())
            i = self.parents[i]
        return out


def _add_along(tree: _Tree, parent: int, states: np.ndarray, count: int, every: int) -> int:
    """Add every `every`-th of the first `count` line states as a chain of nodes; last index."""
    for k in range(every - 1, count, every):
        parent = tree.add(states[k], parent)
    return parent


def _steps_per_range(checker: LineChecker, states: np.ndarray, q_from: np.ndarray) -> int:
    step = float(np.linalg.norm(states[0] - q_from))
    return max(1, int(checker.options.max_range / max(step, 1e-12)))


def _extend(checker: LineChecker, tree: _Tree, q_target: np.ndarray) -> int | None:
    """One step of at most max_range from the nearest node toward `q_target`; the new node."""
    i = tree.nearest(q_target)
    d = q_target - tree.nodes[i]
    dist = float(np.linalg.norm(d))
    if dist < 1e-12:
        return None
    q_new = tree.nodes[i] + d * min(1.0, checker.options.max_range / dist)
    if not checker.line_valid(tree.nodes[i], q_new):
        return None
    return tree.add(q_new, i)


def _connect(checker: LineChecker, tree: _Tree, q_target: np.ndarray) -> bool:
    """Grow from the nearest node straight to `q_target` as far as valid; True if reached."""
    i = tree.nearest(q_target)
    states = interpolate(tree.nodes[i], q_target, checker.options.max_step)
    bad, _ = checker.first_invalid(states)
    every = _steps_per_range(checker, states, tree.nodes[i])
    if bad is not None:
        _add_along(tree, i, states, bad, every)
        return False
    last = _add_along(tree, i, states, len(states) - 1, every)
    tree.add(states[-1], last)
    return True


def rrt_connect(
    checker: LineChecker, q_start: np.ndarray, q_goal: np.ndarray, rng: np.random.Generator, t0: float
) -> tuple[np.ndarray | None, int]:
    """(waypoints (M, n) from start to goal, iterations), or (None, iterations) over budget."""
    options, space = checker.options, checker.space
    if checker.line_valid(q_start, q_goal):
        return np.array([q_start, q_goal]), 0
    tree_a, tree_b, a_is_start = _Tree(q_start), _Tree(q_goal), True
    for it in range(1, options.max_iterations + 1):
        if time.perf_counter() - t0 > options.max_time_s:
            return None, it - 1
        q_rand = space.lower + rng.random(len(q_start)) * (space.upper - space.lower)
        new = _extend(checker, tree_a, q_rand)
        if new is not None and _connect(checker, tree_b, tree_a.nodes[new]):
            path = tree_a.branch(new)[::-1] + tree_b.branch(len(tree_b) - 1)[1:]
            return np.array(path if a_is_start else path[::-1]), it
        tree_a, tree_b, a_is_start = tree_b, tree_a, not a_is_start
    return None, options.max_iterations


def _greedy(checker: LineChecker, q_path: np.ndarray) -> np.ndarray:
    """From each kept waypoint, jump to the furthest later waypoint it sees directly."""
    out, i = [q_path[0]], 0
    while i < len(q_path) - 1:
        j = len(q_path) - 1
        while j > i + 1 and not checker.line_valid(q_path[i], q_path[j]):
            j -= 1
        out.append(q_path[j])
        i = j
    return np.array(out)


def _point_at(q_path: np.ndarray, cum: np.ndarray, s: float) -> tuple[int, np.ndarray]:
    """Segment index and point at arc length `s` along the path."""
    i = int(np.clip(np.searchsorted(cum, s, side="right") - 1, 0, len(q_path) - 2))
    seg = cum[i + 1] - cum[i]
    frac = 0.0 if seg <= 0 else (s - cum[i]) / seg
    return i, q_path[i] + frac * (q_path[i + 1] - q_path[i])


def merge_collinear(q_path: np.ndarray, tol: float = 1e-9) -> np.ndarray:
    """Drop repeated waypoints and waypoints on the straight line between their neighbours."""
    out = [q_path[0]]
    for q, q_next in zip(q_path[1:-1], q_path[2:], strict=True):
        a, b = q - out[-1], q_next - q
        na, nb = np.linalg.norm(a), np.linalg.norm(b)
        if na <= tol:
            continue
        if nb > tol and np.dot(a, b) >= na * nb * (1 - 1e-12):
            continue
        out.append(q)
    if np.linalg.norm(q_path[-1] - out[-1]) > tol or len(out) == 1:
        out.append(q_path[-1])
    else:  # the last kept waypoint is within tol of the goal: end exactly at the goal
        out[-1] = q_path[-1]
    return np.array(out)


def shortcut(checker: LineChecker, q_path: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """Greedy waypoint skipping, then random partial shortcuts; never lengthens the path.

    Random shortcuts stop after `shortcut_iterations`, or after `shortcut_patience` failures
    in a row.
    """
    q_path = _greedy(checker, merge_collinear(q_path))
    failures = 0
    for _ in range(checker.options.shortcut_iterations):
        if len(q_path) < 3 or failures >= checker.options.shortcut_patience:
            break
        cum = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(q_path, axis=0), axis=1))])
        s1, s2 = np.sort(rng.random(2) * cum[-1])
        (i1, q1), (i2, q2) = _point_at(q_path, cum, s1), _point_at(q_path, cum, s2)
        if i1 == i2 or not checker.line_valid(q1, q2):
            failures += 1
            continue
        failures = 0
        q_path = np.concatenate([q_path[: i1 + 1], [q1, q2], q_path[i2 + 1 :]])
    return merge_collinear(q_path)


def _first_bad_segment(checker: LineChecker, q_path: np.ndarray) -> int | None:
    """Index of the first segment whose own discretisation has an invalid state.

    Segments already found valid as whole lines are skipped; the rest go in one batch.
    """
    segments = [
        k
        for k in range(len(q_path) - 1)
        if (q_path[k].tobytes(), q_path[k + 1].tobytes()) not in checker.valid_lines
    ]
    if not segments:
        return None
    parts = [interpolate(q_path[k], q_path[k + 1], checker.options.max_step) for k in segments]
    bad, _ = checker.first_invalid(np.concatenate(parts))
    if bad is None:
        return None
    return segments[int(np.searchsorted(np.cumsum([len(p) for p in parts]), bad, side="right"))]


def verify_path(
    checker: LineChecker, q_path: np.ndarray, rng: np.random.Generator, t0: float, attempts: int = 5
) -> np.ndarray | None:
    """The path with every segment valid at its own discretisation, or None.

    Pieces of checked lines (tree chains, partial shortcuts, merged collinear runs) are
    re-sampled differently when they become segments of their own; a segment failing that
    is re-planned with RRT-Connect between its (valid) ends.
    """
    for _ in range(attempts):
        seg = _first_bad_segment(checker, q_path)
        if seg is None:
            return q_path
        sub, _ = rrt_connect(checker, q_path[seg], q_path[seg + 1], rng, t0)
        if sub is None:
            return None
        q_path = np.concatenate([q_path[:seg], sub, q_path[seg + 2 :]])
    return q_path if _first_bad_segment(checker, q_path) is None else None
