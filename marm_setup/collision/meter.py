"""A pair's coal distance queries counted in work units (a proof's budget is units, never time).

A unit is about one hull distance (GJK on two convex hulls, a few microseconds). An exact mesh
distance costs far more, and more the larger the meshes: on the PR2, 0.05 ms for a small box
against a 1,000-triangle mesh, 0.3 to 1.4 ms for two meshes of 100 to 1,900 triangles nested
within millimetres of each other: 50 to 250 hull queries, 0.3 to 1.5 us times the square root
of the product of their triangle counts. The branch and bound charges it EXACT_UNITS (its
per-pair budgets were sized to that, and the proofs it completes need one exact query or none);
the witness search, which descends the real distance for hundreds of queries on the pairs whose
hulls touch, charges it by its meshes: sqrt(n_a n_b) / TRIANGLES_PER_UNIT units, at least
EXACT_UNITS (still below what they cost: with / 8 a PR2 seed lost a contact the others find).
Counts of triangles, never time: the outcome stays the same on any machine.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from marm_setup.collision.scene import CollisionScene

EXACT_UNITS = 10  # the branch and bound's charge for an exact mesh distance
TRIANGLES_PER_UNIT = 16  # the witness search's: sqrt(n_a n_b) / this, at least EXACT_UNITS
PROBES = 1  # exact queries beyond the hulls a branch and bound tries before judging their pay
PAYS = 8  # then they go on while at least 1 in PAYS certifies what the hull did not (on the
# PR2, 3,300 such queries in a default run, 8 probes a pair, certified 7 boxes and completed
# no proof; with 1 probe the PR2, panda and marm outcomes are the same)


class Meter:
    """Coal distance queries of one pair, in work units, and whether exact queries beyond the
    hulls still pay (see PROBES, PAYS)."""

    def __init__(self, scene: CollisionScene, pair_id: int) -> None:
        self.scene, self.pair_id = scene, pair_id
        self.hulls = scene.has_hulls(pair_id)
        self.units = 0
        self.extra_tries = 0
        self.extra_wins = 0
        self._plans = (scene.distance_plan(pair_id, False), scene.distance_plan(pair_id, True))
        self._descent_exact = descent_units(*scene.pair_triangles(pair_id)) if self.hulls else 1

    def batch(self, poses_a: np.ndarray, poses_b: np.ndarray) -> tuple:
        """The pair at K states (its links' poses (K, 4, 4)), for the queries below; the
        distance plans are laid out for them when first asked (collision/scene.py `posed`)."""
        return poses_a, poses_b, {}

    def hull(self, batch: tuple, row: int) -> float:
        """The distance [m] of the meshes' convex hulls at state `row` of a `batch`."""
        self.units += 1
        return self._closest(batch, row, True, False)[0]

    def exact(self, batch: tuple, row: int) -> float:
        """The distance [m] of the pair's shapes at state `row` of a `batch` (the branch and
        bound's)."""
        self.units += EXACT_UNITS if self.hulls else 1
        return self._closest(batch, row, False, False)[0]

    def nearest(self, batch: tuple, row: int, hulls: bool) -> tuple[float, np.ndarray, np.ndarray]:
        """The distance [m] and nearest points of the pair's shapes at state `row` of a
        `batch`, `hulls`: of their hulls (the witness search's)."""
        self.units += 1 if hulls else self._descent_exact
        return self._closest(batch, row, hulls, True)

    def _closest(self, batch: tuple, row: int, hulls: bool, points: bool) -> tuple:
        poses_a, poses_b, posed = batch
        if hulls not in posed:
            posed[hulls] = self.scene.posed(self._plans[hulls], poses_a, poses_b)
        return self.scene.closest_at(posed[hulls], row, points)

    def extra_pays(self) -> bool:
        return self.extra_tries < PROBES or self.extra_wins * PAYS >= self.extra_tries


def descent_units(triangles_a: int, triangles_b: int) -> int:
    """The witness search's charge for an exact distance of meshes of so many triangles."""
    return max(EXACT_UNITS, math.ceil(math.sqrt(triangles_a * triangles_b) / TRIANGLES_PER_UNIT))
