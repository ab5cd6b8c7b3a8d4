"""Per-pair distance certificates: one exact distance proves a whole neighbourhood collision-free.

The bound (a Lipschitz bound of a pair's distance in its joint values). Let links `a` and `b`
have lowest common ancestor `c`. In `c`'s frame the pose of `a` depends only on the joints on
the chain c -> a, that of `b` only on the chain c -> b; nothing else changes their distance.
Move from configuration q to q' one joint at a time. Turning revolute joint j by dq moves every
point p below it along an arc of length |dq| * dist(p, axis_j); sliding prismatic joint j by dq
moves it by |dq| (unit axis). If every point of a's geometry moves by at most e_a and every
point of b's by at most e_b, their distance changes by at most e_a + e_b. Hence

    distance(q') >= distance(q) - sum_j |dq_j| * r_j

over the joints j of both chains, where r_j is, for a revolute joint, an upper bound on the
distance from j's axis to any point of the geometry it moves (over every value of the joints
between j and that geometry), and 1 for a prismatic joint. A mimic joint moves by
multiplier * d(leader), so its |multiplier| * r_j adds to its leader's weight. `r_j` is
computed without sampling: the geometry's hull points (every collision shape lies in their
convex hull) give the exact value for the nearest moving joint; above it a ball (centre,
radius) holding every reachable point is carried up the chain: a revolute joint sweeps the
centre round its axis (ball: centre projected on the axis, radius + the centre's distance to
the axis), a prismatic joint slides it over its range (radius + half the range), a fixed
origin moves it rigidly. Then r_j = distance(centre, axis_j) + radius.

So when coal measures distance d at a sample, every sample whose weighted joint distance
`sum_v w_v |q_v - q'_v|` is below d - padding - CERT_MARGIN is collision-free under the
padding: it needs no exact check. CERT_MARGIN covers coal's distance tolerance.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from marm_setup.robot import Joint, RobotModel, origin_matrix

CERT_MARGIN = 1e-5  # [m] kept below every certified distance (coal's GJK tolerance is 1e-6)
RELATIVE_MARGIN = 1e-5  # coal's GJK stops within a relative 1e-6 of the distance (VDB criterion)
MOVING = ("revolute", "continuous", "prismatic")


@dataclass(frozen=True, eq=False)
class PairMotion:
    """How far a pair's geometries can move relative to each other: `bound(q, q2)` [m] is an
    upper bound on the change of their distance between configurations q and q2."""

    cols: np.ndarray  # (m,) columns of q (active joints) on the pair's path
    weights: np.ndarray  # (m,) [m/rad] or [m/m], per column

    def bound(self, q: np.ndarray, q2: np.ndarray) -> np.ndarray:
        """Bound between rows of `q` (N, n_active) and one configuration `q2` (n_active,)."""
        return np.abs(q[..., self.cols] - q2[self.cols]) @ self.weights


def pair_motions(
    robot: RobotModel,
    points: Mapping[str, np.ndarray],
    pairs: Sequence[tuple[str, str]],
    memo: dict | None = None,
) -> tuple[PairMotion, ...]:
    """A PairMotion per pair; `points[link]` holds link-frame points whose hull holds its shapes
    (`memo`: a dict kept between calls to reuse the levers of (ancestor, link) chains)."""
    columns = {name: i for i, name in enumerate(robot.active_joint_names)}
    memo = {} if memo is None else memo
    ancestors = {link: _ancestors(robot, link) for pair in pairs for link in pair}
    out = []
    for a, b in pairs:
        common = next(x for x in ancestors[a] if x in set(ancestors[b]))
        weights: dict[int, float] = {}
        for link in (a, b):
            if (common, link) not in memo:
                memo[common, link] = joint_levers(robot, common, link, points[link])
            for joint, lever in memo[common, link]:
                leader, multiplier = _leader(joint)
                col = columns[leader]
                weights[col] = weights.get(col, 0.0) + abs(multiplier) * lever
        cols = np.array(sorted(weights), dtype=np.intp)
        out.append(PairMotion(cols, np.array([weights[c] for c in cols], dtype=float)))
    return tuple(out)


def joint_levers(
    robot: RobotModel, ancestor: str, link: str, points: np.ndarray
) -> list[tuple[Joint, float]]:
    """(joint, r_j) for each moving joint from `ancestor` down to `link` (see the module doc)."""
    chain = robot.chain(ancestor, link) or ()
    out: list[tuple[Joint, float]] = []
    exact = np.asarray(points, dtype=float)  # link-frame points until the first moving joint
    center, radius = None, 0.0
    for joint in reversed(chain):
        if joint.type in MOVING:
            axis = _axis(joint)
            if joint.type == "prismatic":
                lever = 1.0
            elif center is None:
                lever = float(np.max(_off_axis(exact, axis), initial=0.0))
            else:
                lever = float(_off_axis(center, axis)) + radius
            out.append((joint, lever))
            if center is None:
                center, radius = _ball(exact)
            center, radius = _swept(joint, axis, center, radius, robot)
        transform = origin_matrix(joint.origin)
        if center is None:
            exact = exact @ transform[:3, :3].T + transform[:3, 3]
        else:
            center = transform[:3, :3] @ center + transform[:3, 3]
    return out


def _swept(joint: Joint, axis: np.ndarray, center: np.ndarray, radius: float, robot: RobotModel):
    """A ball holding the ball (center, radius) moved by every value of `joint`."""
    if joint.type == "prismatic":
        lo, hi = _value_range(joint, robot)
        return center + axis * (lo + hi) / 2.0, radius + (hi - lo) / 2.0
    on_axis = (center @ axis) * axis
    return on_axis, radius + float(np.linalg.norm(center - on_axis))


def _value_range(joint: Joint, robot: RobotModel) -> tuple[float, float]:
    """The values a (possibly mimic) joint takes while its leader stays within its bounds."""
    leader, multiplier = _leader(joint)
    lo, hi = robot.joint(leader).bounds
    offset = joint.mimic.offset if joint.mimic is not None else 0.0
    ends = sorted((multiplier * lo + offset, multiplier * hi + offset))
    return ends[0], ends[1]


def _leader(joint: Joint) -> tuple[str, float]:
    if joint.mimic is None:
        return joint.name, 1.0
    return joint.mimic.joint, joint.mimic.multiplier


def _axis(joint: Joint) -> np.ndarray:
    vec = np.asarray(joint.axis, dtype=float)
    norm = np.linalg.norm(vec)
    return vec / norm if norm > 0 else np.array([1.0, 0.0, 0.0])  # as kinematics._unit


def _off_axis(points: np.ndarray, axis: np.ndarray) -> np.ndarray:
    """Distance of points (..., 3) from the line through the origin along unit `axis`."""
    along = points @ axis
    return np.linalg.norm(points - np.multiply.outer(along, axis), axis=-1)


def _ball(points: np.ndarray) -> tuple[np.ndarray, float]:
    lo, hi = points.min(axis=0), points.max(axis=0)
    center = (lo + hi) / 2.0
    return center, float(np.max(np.linalg.norm(points - center, axis=1)))


def _ancestors(robot: RobotModel, link: str) -> list[str]:
    """`link`, its parent, ... up to the root."""
    return [link, *(joint.parent for joint in robot.path_to_root(link))]


class BallStore:
    """Certified balls of one pair: centres (k, m) in its path columns, radii (k,) [m]."""

    def __init__(self, motion: PairMotion) -> None:
        self.motion = motion
        self._centers: list[np.ndarray] = []
        self._radii: list[float] = []
        self._stacked: tuple[np.ndarray, np.ndarray] | None = None

    def __len__(self) -> int:
        return len(self._radii)

    def add(self, q: np.ndarray, radius: float) -> None:
        self._centers.append(np.asarray(q, dtype=float)[self.motion.cols])
        self._radii.append(radius)
        self._stacked = None

    def covers(self, q: np.ndarray) -> np.ndarray:
        """Boolean per row of `q` (N, n_active): inside some ball (proven collision-free)."""
        if not self._radii or not len(q):
            return np.zeros(len(q), dtype=bool)
        if self._stacked is None:
            self._stacked = (np.array(self._centers), np.array(self._radii))
        centers, radii = self._stacked
        sub, weights = q[:, self.motion.cols], self.motion.weights
        out = np.zeros(len(q), dtype=bool)
        for start in range(0, len(centers), 256):  # bounded memory: N x 256 x m at a time
            gaps = np.abs(sub[:, None, :] - centers[None, start : start + 256]) @ weights
            out |= np.any(gaps < radii[start : start + 256], axis=1)
        return out
