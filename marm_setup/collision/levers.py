"""Lever points: a few balls whose convex hull holds a link's collision shapes, for the
displacement bounds of `collision/pair_chain.py` (the farthest a link reaches from an axis is at
one of them: distance from a line is convex).

Mesh hull vertices and box corners (radius 0), a sphere's centre with its radius, a cylinder's
end-cap centres with its radius (a capsule holds it); then merged into at most 32 balls.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass(frozen=True, eq=False)
class LeverPoints:
    """Points (n, 3) in a link's frame and radii (n,): the link lies in their balls' hull."""

    points: np.ndarray
    radii: np.ndarray


def merged_levers(points: np.ndarray, radii: np.ndarray, most: int = 32) -> LeverPoints:
    """At most `most` balls holding the given ones: the set is halved at the median of its
    widest axis until each part is small enough, and each part becomes one ball round it
    (fewer points make every bound cheaper, and looser only by each part's size)."""
    if len(points) <= most:
        return LeverPoints(points, radii)
    parts = [np.arange(len(points))]
    while len(parts) < most:
        widest = max(range(len(parts)), key=lambda i: (len(parts[i]), -i))
        if len(parts[widest]) < 2:
            break
        rows = parts.pop(widest)
        span = np.ptp(points[rows], axis=0)
        order = rows[np.argsort(points[rows, int(np.argmax(span))], kind="stable")]
        parts[widest:widest] = [order[: len(order) // 2], order[len(order) // 2 :]]
    centers, out_radii = [], []
    for rows in parts:
        lo, hi = points[rows].min(axis=0), points[rows].max(axis=0)
        center = (lo + hi) / 2.0
        centers.append(center)
        out_radii.append(float(np.max(np.linalg.norm(points[rows] - center, axis=1) + radii[rows])))
    return LeverPoints(np.array(centers), np.array(out_radii))


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
