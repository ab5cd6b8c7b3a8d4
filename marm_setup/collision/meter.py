"""A pair's coal distance queries counted in work units (a proof's budget is units, never time)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from marm_setup.collision.scene import CollisionScene

EXACT_UNITS = 10  # an exact mesh distance costs about 10 to 40 hull distances
PROBE = 8  # exact queries beyond the hulls tried before their use is judged by what they certify


class Meter:
    """Coal distance queries of one pair, in work units, and whether exact queries beyond the
    hulls still pay (they are tried while at least 1 in PROBE certifies what the hull did not)."""

    def __init__(self, scene: CollisionScene, pair_id: int) -> None:
        self.scene, self.pair_id = scene, pair_id
        self.hulls = scene.has_hulls(pair_id)
        self.units = 0
        self.extra_tries = 0
        self.extra_wins = 0
        self._plans = (scene.distance_plan(pair_id, False), scene.distance_plan(pair_id, True))

    def hull(self, pose_a: np.ndarray, pose_b: np.ndarray) -> float:
        """The distance [m] of the meshes' convex hulls (see CollisionScene.shape_distance)."""
        self.units += 1
        return self.scene.closest(self._plans[True], pose_a, pose_b)[0]

    def exact(self, pose_a: np.ndarray, pose_b: np.ndarray) -> float:
        """The distance [m] of the pair's shapes."""
        self.units += EXACT_UNITS if self.hulls else 1
        return self.scene.closest(self._plans[False], pose_a, pose_b)[0]

    def batch(self, poses_a: np.ndarray, poses_b: np.ndarray) -> tuple:
        """The pair at K states (its links' poses (K, 4, 4)), for `nearest`; the distance
        plans are laid out for them when first asked (collision/scene.py `posed`)."""
        return poses_a, poses_b, {}

    def nearest(self, batch: tuple, row: int, hulls: bool) -> tuple[float, np.ndarray, np.ndarray]:
        """The distance [m] and nearest points of the pair's shapes at state `row` of a
        `batch`, `hulls`: of their hulls."""
        self.units += 1 if hulls or not self.hulls else EXACT_UNITS
        poses_a, poses_b, posed = batch
        if hulls not in posed:
            posed[hulls] = self.scene.posed(self._plans[hulls], poses_a, poses_b)
        return self.scene.closest_at(posed[hulls], row, points=True)

    def extra_pays(self) -> bool:
        return self.extra_tries < PROBE or self.extra_wins * PROBE >= self.extra_tries
