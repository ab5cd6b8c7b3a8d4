"""Lever balls (collision/levers.py): the merged balls hold the given ones, and the heap that
picks the widest part gives the parts the plain greedy rule gives (the spec below)."""

from __future__ import annotations

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from marm_setup.collision.levers import merged_levers


def greedy_merge(points: np.ndarray, radii: np.ndarray, most: int) -> tuple[np.ndarray, np.ndarray]:
    """The rule as first written: halve the first of the widest parts (a list in point order)
    at the median of its widest axis until there are `most` parts or only single balls."""

    def ball(rows):
        lo, hi = points[rows].min(axis=0), points[rows].max(axis=0)
        center = (lo + hi) / 2.0
        return rows, center, float(np.max(np.linalg.norm(points[rows] - center, axis=1) + radii[rows]))

    if len(points) <= most:
        return points, radii
    parts = [ball(np.arange(len(points)))]
    widths = [parts[0][2]]
    while len(parts) < most:
        widest = widths.index(max(widths))
        rows = parts[widest][0]
        if len(rows) < 2:
            break
        axis = int(np.argmax(np.ptp(points[rows], axis=0)))
        order = rows[np.argsort(points[rows, axis], kind="stable")]
        halves = [ball(order[: len(order) // 2]), ball(order[len(order) // 2 :])]
        parts[widest : widest + 1] = halves
        widths[widest : widest + 1] = [h[2] if len(h[0]) > 1 else -1.0 for h in halves]
    return np.array([p[1] for p in parts]), np.array([p[2] for p in parts])


@st.composite
def balls(draw):
    """Balls on a coarse grid (ties in widths and coordinates are common) or anywhere."""
    count = draw(st.integers(1, 120))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    grid = draw(st.booleans())
    points = rng.integers(-3, 4, size=(count, 3)).astype(float) if grid else rng.normal(size=(count, 3))
    radii = rng.integers(0, 2, size=count) * 0.5 if grid else rng.uniform(0, 0.2, size=count)
    return points, radii


@given(balls(), st.integers(1, 40))
def test_the_heap_merges_as_the_greedy_rule(given_balls, most):
    points, radii = given_balls
    merged = merged_levers(points, radii, most)
    centers, out_radii = greedy_merge(points, radii, most)
    assert np.array_equal(merged.points, centers)
    assert np.array_equal(merged.radii, out_radii)


@given(balls(), st.integers(1, 40))
def test_each_ball_lies_in_a_merged_ball(given_balls, most):
    points, radii = given_balls
    merged = merged_levers(points, radii, most)
    assert len(merged.points) <= max(most, 1) or len(merged.points) == len(points)
    apart = np.linalg.norm(points[:, None] - merged.points[None], axis=2) + radii[:, None]
    assert np.all(np.min(apart - merged.radii[None], axis=1) <= 1e-12)
