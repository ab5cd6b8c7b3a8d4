"""Lever points: a few balls whose convex hull holds a link's collision shapes, for the
displacement bounds of `collision/pair_chain.py` (the farthest a link reaches from an axis is at
one of them: distance from a line is convex), and more of them for its projections on a line
(the separating-direction bound: a projection of a convex hull is that of its points).

Mesh hull vertices and box corners (radius 0), a sphere's centre with its radius, a cylinder's
end-cap centres with its radius (a capsule holds it); then merged into at most LEVERS balls
(SUPPORT for the projections: mesh hulls have a few hundred vertices, kept nearly exact).
"""

from __future__ import annotations

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
    """At most `most` balls holding the given ones: the part whose ball is widest is halved at
    the median of its widest axis until there are `most` parts, and each part becomes one ball
    round it (fewer points make every bound cheaper, and looser only by each part's radius:
    halving the widest, not the most numerous, keeps the largest radius small: a long link's
    32 parts by count had radii up to 0.25 m, by size 0.05 m)."""
    if len(points) <= most:
        return LeverPoints(points, radii, points, radii)
    parts = [_part_ball(points, radii, np.arange(len(points)))]
    widths = [_width(parts[0])]  # per part: its radius, -1 for a single ball (not split)
    while len(parts) < most:
        widest = widths.index(max(widths))  # the first of the widest
        rows = parts[widest][0]
        if len(rows) < 2:
            break
        span = np.ptp(points[rows], axis=0)
        order = rows[np.argsort(points[rows, int(np.argmax(span))], kind="stable")]
        halves = [
            _part_ball(points, radii, half) for half in (order[: len(order) // 2], order[len(order) // 2 :])
        ]
        parts[widest : widest + 1] = halves
        widths[widest : widest + 1] = [_width(half) for half in halves]
    centers, out_radii = np.array([p[1] for p in parts]), np.array([p[2] for p in parts])
    return LeverPoints(centers, out_radii, centers, out_radii)


def _width(part: tuple[np.ndarray, np.ndarray, float]) -> float:
    return part[2] if len(part[0]) > 1 else -1.0


def _part_ball(
    points: np.ndarray, radii: np.ndarray, rows: np.ndarray
) -> tuple[np.ndarray, np.ndarray, float]:
    """(rows, centre, radius): a ball round the balls `rows`, centred on their bounding box."""
    lo, hi = points[rows].min(axis=0), points[rows].max(axis=0)
    center = (lo + hi) / 2.0
    return rows, center, float(np.max(np.linalg.norm(points[rows] - center, axis=1) + radii[rows]))


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
