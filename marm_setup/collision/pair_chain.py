"""PairChain: the kinematics of one link pair over boxes of its joints' values.

Links `a` and `b` have lowest common ancestor `c`. In `c`'s frame the pose of `a` depends only
on the joints on the chain c -> a, that of `b` only on c -> b (joints above `c` move both
rigidly and never change their distance). The pair's *box* is the product of the bounds of the
variables (active joints; a mimic joint counts as its leader) that drive those joints.

For a batch of boxes `evaluate` gives, at each box's centre, the poses of `a` and `b` in `c`'s
frame and two sound bounds over the whole box (the proof in `collision/proof.py` uses both):

- **displacement**: an upper bound on how far any point of `a` (`b`) moves, in `c`'s frame,
  between the centre and any state of the box. Move from the centre to a state one joint at a
  time, the joint nearest the link first. Turning revolute joint i by at most h moves a point
  at distance rho from its axis along an arc whose chord is 2 rho sin(h/2) (2 rho for h >= pi);
  a prismatic joint moves it by h (unit axis). While joint i turns, the joints above it sit at
  the centre, so its axis is where the centre puts it; the joints below have moved, but each
  point is within the displacement E of those joints of where the centre puts it, so rho is
  at most (largest distance of the link's hull points at the centre from the axis) + E. The
  displacements add up along the way (triangle inequality). A mimic joint moves by
  |multiplier| times its leader's half-width.
- **balls**: a ball (centre, radius) in `c`'s frame holding every point of `a` (`b`) at every
  state of the box. It starts as a ball round the link's hull points and is carried up the
  chain: a revolute joint sweeping it over an arc of half-angle h <= pi/2 moves its centre to
  the chord's midpoint and adds rho sin h to its radius (every point of the arc is within
  rho sin h of that midpoint); over a wider arc the centre goes onto the axis and the radius
  grows by rho; a prismatic joint adds h.

So distance(q) >= distance(centre) - E_a - E_b for every q of the box, and the balls' gap is a
lower bound too. Geometry enters as *lever points* with radii: each link's shapes lie in the
union of balls (point, radius) -- mesh hull vertices and box corners with radius 0, a sphere's
centre with its radius, a cylinder's end-cap centres with its radius (a capsule holds it) --
whose convex hull holds the link. The largest distance from a line over such a set is at one
of its points (distance from a line is convex), plus that point's radius.

- **separating direction**: a turning joint moves a point perpendicular to its axis, so along a
  direction u it moves it by at most its displacement bound times |sin| of the angle between u
  and the axis (a sliding joint: times |cos|). So the gap between the two links' projections on
  u, less those shares, is a lower bound of the distance over the box. With u a turning axis of
  the path, joints parallel to it cost nothing: two links of a planar chain (a UR arm's
  shoulder, elbow and wrist joints) whose projections on the common axis are apart are proved
  in one box, however far they swing in the plane.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision.chain_kinematics import (
    MOVING,
    ChainKinematics,
    Frames,
    Step,
    chain_kinematics,
    folded,
)
from marm_setup.collision.levers import LeverPoints
from marm_setup.robot import Joint, RobotModel, origin_matrix

if TYPE_CHECKING:
    from marm_setup.collision.scene import CollisionScene


@dataclass(frozen=True, eq=False)
class BoxBounds:
    """Bounds of a pair over K boxes: both links' frames at the centres (in the common
    ancestor's frame), the displacement bound [m] of the best pivot and its share per box
    column (where to split), the best pivot's gap between the swept balls [m], and the best
    gap between the links' projections on a turning axis of the path, less what the box can
    move them along it [m]: each a lower bound of the distance over the box."""

    frames: tuple[Frames, Frames]
    motion: np.ndarray  # (K,)
    shares: np.ndarray  # (K, m)
    ball_gap: np.ndarray  # (K,)
    axis_gap: np.ndarray  # (K,) the separating-direction bound (see `_axis_gap`)


@dataclass(frozen=True, eq=False)
class PairChain:
    """The chains of a pair and its box: `columns` index the robot's active joints."""

    pair: tuple[str, str]
    columns: np.ndarray  # (m,) sorted active-joint columns
    lower: np.ndarray  # (m,)
    upper: np.ndarray  # (m,)
    kinematics: tuple[ChainKinematics, ChainKinematics]  # c -> a, c -> b
    levers: tuple[LeverPoints, LeverPoints]

    @property
    def dims(self) -> int:
        return len(self.columns)

    def box_values(self, q: np.ndarray) -> np.ndarray:
        """The box's variables (K, m) at robot states `q` (K, active joints): a turning joint's
        value beyond the box (its range was folded to one turn) taken a whole turn back."""
        values = q[:, self.columns]
        return np.where(values > self.upper, self.lower + np.mod(values - self.lower, 2.0 * np.pi), values)

    def frames(self, q: np.ndarray) -> tuple[Frames, Frames]:
        """Both links' frames at the states `q` (K, m) of the box's variables."""
        return self.kinematics[0].frames(q), self.kinematics[1].frames(q)

    def evaluate(self, centers: np.ndarray, halves: np.ndarray, enough: float = np.inf) -> BoxBounds:
        """Bounds of the pair over the boxes `centers` +- `halves` (K, m); a box whose balls'
        gap exceeds `enough` [m] is decided: its displacement bound, shares (0) and axis gap
        (-inf) are not worked out."""
        frames = self.frames(centers)
        path = _path(frames)
        half = np.abs(path.multipliers) * halves[:, path.columns]  # (K, n) per path joint
        balls_a, balls_b = _balls(path, self.levers, frames, half)
        apart = balls_a[0] - balls_b[0]
        ball_gap = (np.sqrt(np.vecdot(apart, apart)) - balls_a[1] - balls_b[1]).max(axis=1)
        count = len(centers)
        motion, shares, axis_gap = np.zeros(count), np.zeros(halves.shape), np.full(count, -np.inf)
        open_rows = np.flatnonzero(ball_gap <= enough)  # each row's arithmetic is its own
        if open_rows.size:
            rows = slice(None) if open_rows.size == count else open_rows
            some = _rows(path, rows), (frames[0].pose[rows], frames[1].pose[rows])
            motion[rows], shares[rows], axis_gap[rows] = self._moved(*some, half[rows])
        return BoxBounds(frames, motion, shares, ball_gap, axis_gap)

    def _moved(
        self, path: _Path, poses: tuple[np.ndarray, np.ndarray], half: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """At K states of the path: the best pivot's displacement bound (K,), its share per box
        column (K, m), and the axis gap (K,)."""
        moved_a, moved_b = _displacements(path, self.levers, poses, half)
        # pivot k: the path's first k joints move a, the others move b
        before_a = np.concatenate([np.zeros((len(half), 1)), np.cumsum(moved_a, axis=1)], axis=1)
        after_b = np.concatenate(
            [np.cumsum(moved_b[:, ::-1], axis=1)[:, ::-1], np.zeros((len(half), 1))], axis=1
        )
        totals = before_a + after_b  # (K, n + 1)
        best = np.argmin(totals, axis=1)
        on_a = np.arange(path.count)[None, :] < best[:, None]
        per_joint = np.where(on_a, moved_a, moved_b)
        shares = np.zeros((len(half), self.dims))
        for i, column in enumerate(path.columns):  # a column may drive several joints (mimic)
            shares[:, column] += per_joint[:, i]
        axis_gap = _axis_gap(path.axes, path.turning, poses, self.levers, (moved_a, moved_b))
        return totals[np.arange(len(half)), best], shares, axis_gap


def pair_chains(scene: CollisionScene, pairs: Sequence[tuple[str, str]]) -> dict[tuple[str, str], PairChain]:
    """Pair -> its PairChain, for the pairs of a CollisionScene `scene` (each chain from an
    ancestor to a link built once: on the PR2, 640 pairs have 1,280 chains, 200 of them apart)."""
    levers = {link: scene.lever_points(link) for pair in pairs for link in pair}
    sides: dict = {}
    return {pair: pair_chain(scene.robot, pair, levers, sides) for pair in pairs}


def pair_chain(
    robot: RobotModel, pair: tuple[str, str], levers: Mapping[str, LeverPoints], sides: dict | None = None
) -> PairChain:
    """The PairChain of `pair` (both links need lever points); `sides`: the chains built so far
    for pairs of the same robot, by (ancestor, link)."""
    a, b = pair
    common = _common_ancestor(robot, a, b)
    memo = {} if sides is None else sides
    chains = [_side(robot, common, link, memo) for link in pair]
    leaders = np.array(sorted({int(c) for chain in chains for c in chain.columns}), dtype=np.intp)
    position = np.full(len(robot.active_joints), -1, dtype=np.intp)
    position[leaders] = np.arange(len(leaders))
    joints = robot.active_joints
    lower = np.array([joints[c].bounds[0] for c in leaders], dtype=float)
    upper = np.array([joints[c].bounds[1] for c in leaders], dtype=float)
    kinematics = (chains[0].placed(position, len(leaders)), chains[1].placed(position, len(leaders)))
    upper = np.minimum(upper, lower + _periods(kinematics, len(leaders)))
    return PairChain(pair, leaders, lower, upper, kinematics, (levers[a], levers[b]))


def _side(robot: RobotModel, common: str, link: str, memo: dict) -> ChainKinematics:
    """The chain from `common` down to `link`, its columns the robot's active joints (memo)."""
    if (common, link) not in memo:
        active = {name: i for i, name in enumerate(robot.active_joint_names)}
        steps = folded([_step(j, active) for j in robot.chain(common, link) or ()])
        memo[(common, link)] = chain_kinematics(steps)
    return memo[(common, link)]


def _periods(kinematics: tuple[ChainKinematics, ...], count: int) -> np.ndarray:
    """Per box column, 2 pi when every joint it drives turns (multiplier +-1), else inf: a
    turning joint's poses repeat every 2 pi, so a wider range holds no pose a 2 pi window lacks."""
    periodic = np.ones(count, dtype=bool)  # (the proved fraction is that of the window)
    for chain in kinematics:
        for column, turning, multiplier in zip(chain.columns, chain.turning, chain.multipliers, strict=True):
            periodic[column] &= bool(turning) and abs(multiplier) == 1.0
    return np.where(periodic, 2.0 * np.pi, np.inf)


def _step(joint: Joint, active: Mapping[str, int]) -> Step:
    """One joint as a Step, its column the active joint that drives it (a mimic's leader)."""
    origin = origin_matrix(joint.origin)
    if joint.type not in MOVING:
        return Step(origin, "fixed", np.zeros(3), -1)
    leader, multiplier, offset = _leader(joint)
    axis = np.asarray(joint.axis, dtype=float)
    norm = np.linalg.norm(axis)
    axis = axis / norm if norm > 0 else np.array([1.0, 0.0, 0.0])  # as kinematics._unit
    kind = "prismatic" if joint.type == "prismatic" else "revolute"
    return Step(origin, kind, axis, active[leader], multiplier, offset)


def _leader(joint: Joint) -> tuple[str, float, float]:
    if joint.mimic is None:
        return joint.name, 1.0, 0.0
    return joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset


def _common_ancestor(robot: RobotModel, a: str, b: str) -> str:
    above_b = {b, *(j.parent for j in robot.path_to_root(b))}
    return next(x for x in (a, *(j.parent for j in robot.path_to_root(a))) if x in above_b)


@dataclass(frozen=True, eq=False)
class _Path:
    """The moving joints on the path from `a` to `b` (a's chain upwards, then b's chain
    downwards) at K states: axis lines in the common ancestor's frame, columns, multipliers."""

    origins: np.ndarray  # (K, n, 3)
    axes: np.ndarray  # (K, n, 3)
    columns: np.ndarray  # (n,)
    multipliers: np.ndarray  # (n,)
    turning: np.ndarray  # (n,)

    @property
    def count(self) -> int:
        return len(self.columns)


def _path(frames: tuple[Frames, Frames]) -> _Path:
    up, down = frames[0], frames[1]
    return _Path(
        np.concatenate([up.origins[:, ::-1], down.origins], axis=1),
        np.concatenate([up.axes[:, ::-1], down.axes], axis=1),
        np.concatenate([up.columns[::-1], down.columns]),
        np.concatenate([up.multipliers[::-1], down.multipliers]),
        np.concatenate([up.turning[::-1], down.turning]),
    )


def _rows(path: _Path, rows: slice | np.ndarray) -> _Path:
    """`path` at the states `rows` only."""
    return _Path(path.origins[rows], path.axes[rows], path.columns, path.multipliers, path.turning)


def _balls(
    path: _Path, levers: tuple[LeverPoints, LeverPoints], frames: tuple[Frames, Frames], half: np.ndarray
) -> tuple[tuple[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]:
    """Each link's ball swept by the joints on its side of each pivot k (k = how many path
    joints move a; see the module doc), nearest it first (a forward, b backward), as centres
    (K, n + 1, 3) and radii (K, n + 1), in path order. The two links go through one loop,
    stacked (side, K, ...) in the order each meets the joints: numpy calls per joint, not per box."""
    count, n = len(half), path.count
    halves = np.stack([half, half[:, ::-1]])  # (2, K, n), in each side's order
    turning = np.stack([path.turning, path.turning[::-1]])[:, None, :]  # (2, 1, n)
    origins = np.stack([path.origins, path.origins[:, ::-1]])  # (2, K, n, 3)
    axes = np.stack([path.axes, path.axes[:, ::-1]])
    keep, grow = _sweep_factors(halves, turning)
    slide = np.where(turning, 0.0, halves)  # a sliding joint moves every point by its half
    centers, radii = np.zeros((2, count, n + 1, 3)), np.zeros((2, count, n + 1))
    for side, (levers_side, frame) in enumerate(zip(levers, frames, strict=True)):
        center, radius = ball_round(levers_side)
        centers[side, :, 0], radii[side, :, 0] = frame.pose[:, :3, :3] @ center + frame.pose[:, :3, 3], radius
    for t in range(n):
        offset = centers[:, :, t] - origins[:, :, t]
        radial = offset - np.vecdot(offset, axes[:, :, t])[..., None] * axes[:, :, t]
        centers[:, :, t + 1] = centers[:, :, t] - radial * keep[:, :, t, None]
        grown = np.sqrt(np.vecdot(radial, radial)) * grow[:, :, t]
        radii[:, :, t + 1] = radii[:, :, t] + grown + slide[:, :, t]
    return (centers[0], radii[0]), (centers[1][:, ::-1], radii[1][:, ::-1])  # back in path order


def _displacements(
    path: _Path,
    levers: tuple[LeverPoints, LeverPoints],
    poses: tuple[np.ndarray, np.ndarray],
    half: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Each link's displacement bound per path joint (K, n) in path order, the joints moving it
    nearest it first (see the module doc); both links in one loop, as `_balls`."""
    count, n = len(half), path.count
    reach = np.stack([_reach(poses[0], levers[0], path), _reach(poses[1], levers[1], path)[:, ::-1]])
    halves = np.stack([half, half[:, ::-1]])  # (2, K, n), in each side's order
    turning = np.stack([path.turning, path.turning[::-1]])[:, None, :]  # (2, 1, n)
    chord = 2.0 * np.sin(np.minimum(halves, np.pi) / 2.0)  # per unit of distance from the axis
    slide = np.where(turning, 0.0, halves)  # a sliding joint moves every point by its half
    moved, total = np.zeros((2, count, n)), np.zeros((2, count))
    for t in range(n):
        moved[:, :, t] = np.where(turning[:, :, t], (reach[:, :, t] + total) * chord[:, :, t], slide[:, :, t])
        total = total + moved[:, :, t]
    return moved[0], moved[1][:, ::-1]


def _sweep_factors(half: np.ndarray, turning: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per turning joint, how a ball swept over +- half moves (see the module doc): the share
    1 - cos h of its offset from the axis its centre moves towards the axis by (all of it
    beyond pi/2), and the growth of its radius per unit of that offset (sin h; 1 beyond pi/2);
    both 0 for a sliding joint."""
    narrow = half <= np.pi / 2.0
    keep = np.where(narrow, 1.0 - np.cos(half), 1.0)
    grow = np.where(narrow, np.sin(np.minimum(half, np.pi / 2.0)), 1.0)
    return np.where(turning, keep, 0.0), np.where(turning, grow, 0.0)


def _reach(pose: np.ndarray, levers: LeverPoints, path: _Path) -> np.ndarray:
    """(K, n): the largest distance of the link's lever balls from each path joint's axis,
    worked out in the link's frame (the axes moved there: two matrix products)."""
    rotation, translation = pose[:, :3, :3], pose[:, :3, 3]
    origins = (path.origins - translation[:, None, :]) @ rotation  # rows: R^T v
    axes = path.axes @ rotation
    points = levers.points
    along = _times_points(axes, points) - np.vecdot(origins, axes)[..., None]  # (K, n, P)
    squared = (
        np.sum(points**2, axis=1)
        - 2.0 * _times_points(origins, points)
        + np.vecdot(origins, origins)[..., None]
    ) - along**2
    return (np.sqrt(np.maximum(squared, 0.0)) + levers.radii).max(axis=2)


def _times_points(rows: np.ndarray, points: np.ndarray) -> np.ndarray:
    """(K, n, P): each row (K, n, 3) dotted with each point (P, 3), as a stack of small matrix
    products (one (K n, 3) x (3, P) product would go to a multithreaded BLAS, which costs far
    more CPU time on a busy machine)."""
    return rows @ points.T


def _axis_gap(
    axes: np.ndarray,
    turning: np.ndarray,
    poses: tuple[np.ndarray, np.ndarray],
    levers: tuple[LeverPoints, LeverPoints],
    moved: tuple[np.ndarray, np.ndarray],
) -> np.ndarray:
    """(K,): the separating-direction bound (see the module doc) over the turning axes' directions
    u at the centre: the gap between the links' projections on u, less what each joint can move
    a point along u (its displacement bound times |sin| of its axis' angle to u when it turns,
    times |cos| when it slides), for the best pivot; -inf when no joint turns. The path's joints
    at K states: `axes` (K, n, 3), `turning` (n,); the links' poses (K, 4, 4) and each path
    joint's displacement bound of each link (K, n)."""
    if not turning.any():
        return np.full(len(axes), -np.inf)
    directions = axes[:, turning]  # (K, D, 3)
    low_a, high_a = _projection(poses[0], levers[0], directions)
    low_b, high_b = _projection(poses[1], levers[1], directions)
    gap = np.maximum(low_b - high_a, low_a - high_b)  # (K, D)
    cosine = axes @ directions.transpose(0, 2, 1)  # (K, n, D)
    along = np.where(turning[None, :, None], np.sqrt(np.maximum(0.0, 1.0 - cosine**2)), np.abs(cosine))
    shrink_a, shrink_b = moved[0][..., None] * along, moved[1][..., None] * along  # (K, n, D)
    zeros = np.zeros((len(gap), 1, gap.shape[1]))
    before_a = np.concatenate([zeros, np.cumsum(shrink_a, axis=1)], axis=1)
    after_b = np.concatenate([np.cumsum(shrink_b[:, ::-1], axis=1)[:, ::-1], zeros], axis=1)
    return (gap - (before_a + after_b).min(axis=1)).max(axis=1)


def _projection(
    pose: np.ndarray, levers: LeverPoints, directions: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """(K, D) lowest and highest projections of the link's support balls on `directions` (the
    balls' centres projected in the link's frame, in one matrix product; then moved)."""
    local = directions @ pose[:, :3, :3]  # rows: R^T u
    offset = np.vecdot(directions, pose[:, None, :3, 3])
    points, radii = levers.support_points, levers.support_radii
    along = _times_points(local, points)
    if not radii.any():  # hull vertices: no radii to add
        return along.min(axis=2) + offset, along.max(axis=2) + offset
    return (along - radii).min(axis=2) + offset, (along + radii).max(axis=2) + offset


def swept_ball(
    center: np.ndarray, radius: float, origin: np.ndarray, axis: np.ndarray, half: float
) -> tuple[np.ndarray, float]:
    """One ball (centre (3,), radius) swept round the axis line over +- half."""
    new_center, new_radius = _swept(
        center[None], np.array([radius]), origin[None], axis[None], np.array([half])
    )
    return new_center[0], float(new_radius[0])


def _swept(center, radius, origin, axis, half):
    """Ball (center, radius) swept round the axis line over +- half (see the module doc)."""
    foot = origin + np.sum((center - origin) * axis, axis=1)[:, None] * axis
    rho = np.linalg.norm(center - foot, axis=1)
    narrow = half <= np.pi / 2.0
    new_center = np.where(narrow[:, None], foot + (center - foot) * np.cos(half)[:, None], foot)
    return new_center, radius + np.where(narrow, rho * np.sin(np.minimum(half, np.pi / 2.0)), rho)


def ball_round(levers: LeverPoints) -> tuple[np.ndarray, float]:
    """A ball round the lever points' balls (centred on their bounding box)."""
    return levers.ball
