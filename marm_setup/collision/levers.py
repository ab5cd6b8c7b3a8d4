"""Lever points: a few balls whose convex hull holds a link's collision shapes, for the
displacement bounds of `collision/pair_chain.py` (the farthest a link reaches from an axis is at
one of them: distance from a line is convex), and more of them for its projections on a line
(the separating-direction bound: a projection of a convex hull is that of its points).

Mesh hull vertices and box corners (radius 0), a sphere's centre with its radius, a cylinder's
end-cap centres with its radius (a capsule holds it); then merged into at most LEVERS balls
(SUPPORT for the projections: mesh hulls have a few hundred vertices, kept nearly exact).
"""

from __future__ import annotations

import heapq
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

LEVERS = 32
SUPPORT = 512


@dataclass(frozen=True, eq=False)
class LeverPoints:
    """Points (n, 3) in a link's frame and radii (n,): the link lies in their balls' hull;
    `support_points` / `support_radii`: more such balls, tighter, for projections."""

    points: np.ndarray
    radii: np.ndarray
    support_points: np.ndarray
    support_radii: np.ndarray

    @cached_property
    def ball(self) -> tuple[np.ndarray, float]:
        """A ball (centre, radius) round the lever balls, centred on their bounding box
        (worked out once: every box a proof evaluates starts from it)."""
        lo = np.min(self.points - self.radii[:, None], axis=0)
        hi = np.max(self.points + self.radii[:, None], axis=0)
        center = (lo + hi) / 2.0
        return center, float(np.max(np.linalg.norm(self.points - center, axis=1) + self.radii))


def link_levers(points: np.ndarray, radii: np.ndarray) -> LeverPoints:
    """The lever balls (at most LEVERS) and support balls (at most SUPPORT) of a link whose
    shapes lie in the hull of the balls (`points`, `radii`)."""
    support = merged_levers(points, radii, SUPPORT)
    levers = merged_levers(support.points, support.radii, LEVERS)
    return LeverPoints(levers.points, levers.radii, support.points, support.radii)


def merged_levers(points: np.ndarray, radii: np.ndarray, most: int = 32) -> LeverPoints:
    """At most `most` balls holding the given ones: the part whose ball is widest (the first of
    them in point order) is halved at the median of its widest axis until there are `most`
    parts, and each part becomes one ball round it (fewer points make every bound cheaper, and
    looser only by each part's radius: halving the widest, not the most numerous, keeps the
    largest radius small: a long link's 32 parts by count had radii up to 0.25 m, by size
    0.05 m). The halving tree is built a level at a time (`_halvings`), then walked widest
    first; a part's place in point order is where its points start."""
    if len(points) <= most:
        return LeverPoints(points, radii, points, radii)
    tree = _halvings(points, radii)
    heap = [(tree.key[0], 0, 0)]  # (key, start, node)
    while len(heap) < most and tree.size[heap[0][2]] > 1:  # (a single ball is never halved)
        node = heapq.heappop(heap)[2]
        for child in (tree.lower[node], tree.lower[node] + 1):
            heapq.heappush(heap, (tree.key[child], tree.start[child], child))
    nodes = [node for _, _, node in sorted(heap, key=lambda entry: entry[1])]
    return LeverPoints(tree.center[nodes], tree.radius[nodes], tree.center[nodes], tree.radius[nodes])


@dataclass(frozen=True)
class _Halvings:
    """Every part of the halving down to single balls, node 0 the whole: its ball (`center`,
    `radius`), `key` (-radius; 1 for a single ball, never halved), where its points `start`
    in point order and how many (`size`), and its halves: nodes `lower` and `lower` + 1."""

    center: np.ndarray
    radius: np.ndarray
    key: list[float]
    start: list[int]
    size: list[int]
    lower: list[int]


def _halvings(points: np.ndarray, radii: np.ndarray) -> _Halvings:
    """The halving tree of the balls, a level at a time: a level's parts are runs of one point
    order (from `starts`), each halved at the median of its box's widest axis by one stable
    sort of the whole order, and measured together."""
    count = len(points)
    order, starts, ids = np.arange(count), np.array([0]), np.array([0])
    level = _measure(points, radii, order, starts)
    nodes = [(*level[:2], starts, np.array([count]))]  # per level: its new nodes' center, radius, start, size
    lower = np.full(2 * count - 1, -1)
    first = 1  # the next node id
    while True:
        sizes = np.diff(np.append(starts, count))
        halved = sizes > 1
        if not halved.any():
            break
        part = np.repeat(np.arange(len(starts)), sizes)
        order = order[np.lexsort((points[order, np.argmax(level[2], axis=1)[part]], part))]
        lower[ids[halved]] = first + 2 * np.arange(halved.sum())
        parent = np.repeat(np.arange(len(starts)), np.where(halved, 2, 1))
        is_half = halved[parent]
        new_ids = np.where(is_half, first + np.cumsum(is_half) - 1, ids[parent])
        starts = np.sort(np.concatenate([starts, starts[halved] + sizes[halved] // 2]))
        level = _measure(points, radii, order, starts)
        new_sizes = np.diff(np.append(starts, count))
        nodes.append((level[0][is_half], level[1][is_half], starts[is_half], new_sizes[is_half]))
        ids, first = new_ids, first + int(is_half.sum())
    center, radius, start, size = (np.concatenate(column) for column in zip(*nodes, strict=True))
    key = np.where(size > 1, -radius, 1.0)
    return _Halvings(center, radius, key.tolist(), start.tolist(), size.tolist(), lower.tolist())


def _measure(
    points: np.ndarray, radii: np.ndarray, order: np.ndarray, starts: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each run of `order` from `starts`: its box's centre, the radius of the ball there round
    its balls, its box's extent per axis (the values a part's own numpy reductions give)."""
    inside = points[order]
    lo, hi = np.minimum.reduceat(inside, starts, axis=0), np.maximum.reduceat(inside, starts, axis=0)
    center = (lo + hi) / 2.0
    part = np.repeat(np.arange(len(starts)), np.diff(np.append(starts, len(points))))
    apart = inside - center[part]
    reach = np.sqrt(np.add.reduce(apart * apart, axis=1)) + radii[order]  # norm's sum of squares
    return center, np.maximum.reduceat(reach, starts), hi - lo


def shape_levers(geom: Any, coal: Any, hull: Any) -> tuple[np.ndarray, np.ndarray]:
    """(points, radii) in a shape's frame for coal geometry `geom`; `hull`: its convex hull
    (coal Convex), or `geom` itself when it has none (a primitive, or a flat mesh)."""
    if isinstance(geom, coal.Sphere):
        return np.zeros((1, 3)), np.array([geom.radius])
    if isinstance(geom, coal.Cylinder):
        half = geom.halfLength
        return np.array([[0.0, 0.0, -half], [0.0, 0.0, half]]), np.full(2, geom.radius)
    if isinstance(geom, coal.Box):
        half = np.asarray(geom.halfSide, dtype=float)
        corners = np.array(
            [[x, y, z] for x in (-half[0], half[0]) for y in (-half[1], half[1]) for z in (-half[2], half[2])]
        )
        return corners, np.zeros(len(corners))
    vertices = np.asarray(hull.points() if hull is not geom else geom.vertices(), dtype=float)
    return vertices, np.zeros(len(vertices))
