"""The witness search of a pair the branch and bound could not settle: descend its distance.

From start states (given ones first: the pair's closest states of the matrix's own trials, by
bounding-sphere gap, free since the trials drew them anyway; then an earlier round's nearest
end states and states scattered about them; with neither, the nearest-looking of DENSE random
states of the pair's box, ranked by the kinematics of its two chains alone; then the closest
box centres the branch and bound measured; then random states; seeded by the run's seed and
the pair's names), step down the distance's gradient in the box's variables until the pair is
in contact. The gradient comes from coal's nearest points: a point fixed to a link moves at
axis x (point - axis origin) per radian of a turning joint, along the axis per metre of a
sliding one, a mimic joint's by its multiplier. While the meshes' convex hulls are more than
SWITCH apart the hulls' distance is descended (far cheaper, and the meshes' own where a link
is convex); closer, the real one. Each step is a Newton step on the distance aimed AIM beyond
contact, halved until the distance shrinks; a descent ends when it no longer does, or after
STEPS steps. Aiming far beyond contact overshoots the small dips that stop a cautious
descent: on the hardest pairs measured (a Motoman base against its wrist, 4-5 variables, in
collision in about 1e-5 of the box) a witness costs 30 to 80 units instead of 500 to 1000
with a 1 mm aim. When every halved step fails, steps aimed only FINE beyond contact are
tried: a thin shape meets a mesh (a surface) only in a shell as thick as the shape, which the
halved steps (at least 4 mm beyond contact) jump through from either side, the distance on the
far side no smaller; so the descent stopped 0.02 mm short of the PR2's gripper accelerometer,
a 1 mm box, touching the other arm's wrist (the one pair a 1M-trial run sees that a default
run missed). A state within the padding goes through the matrix's own exact check, so a
witness is always a state the matrix itself finds in contact.

Descents run BATCH at a time, their forward kinematics and gradients in numpy batches; coal is
asked in a fixed order and the budget counts its queries, so the search is deterministic.
The NEAR states the descents ended nearest at are kept (`PairSearch.near`): a second round
(`proving.settle_pairs`) goes on from them.
"""

from __future__ import annotations

import itertools
import zlib
from collections.abc import Iterator
from typing import TYPE_CHECKING, Protocol

import numpy as np

from marm_setup.collision.certificates import CERT_MARGIN, RELATIVE_MARGIN

if TYPE_CHECKING:
    from marm_setup.collision.chain_kinematics import Frames
    from marm_setup.collision.meter import Meter
    from marm_setup.collision.pair_chain import PairChain
    from marm_setup.collision.scene import CollisionScene

DENSE = 2048  # descents from the DENSE_STARTS nearest-looking of DENSE random states of the
CLOSEST = 8  # pair's box, then from the CLOSEST box centres measured, then from random states
DENSE_STARTS = 24
FIRST_CUT = 128
STATES_PER_UNIT = 16  # the kinematics of a pair's two chains and the ranking, per state
NEAR = 8  # end states a search keeps, nearest first, for a second round to go on from
AROUND = 64  # states scattered about them a second round descends from next
SPREAD = 0.02  # of each variable's range: the scatter's standard deviation
BATCH = 16  # descents run together
STEPS = 10  # gradient steps per descent at most
HALVINGS = 7
AIM = 0.5  # [m] each Newton step aims this far beyond contact, then halves
FINE = np.array([1e-3, 2.5e-4, 6.25e-5])  # [m] then steps aimed this little beyond contact
SWITCH = 2e-3  # [m] hull distance beyond the padding below which the real distance is descended

Witness = tuple[tuple[str, float], ...]
Measured = tuple[float, tuple[np.ndarray, np.ndarray], bool]  # distance, nearest points, exact


class PairSearch(Protocol):
    """What the witness search needs of a pair's proof (collision/proof.py PairSearch)."""

    scene: CollisionScene
    chain: PairChain
    meter: Meter
    threshold: float
    near: list

    def check_witness(self, values: np.ndarray) -> tuple[tuple[str, float], ...]: ...


def search_witness(
    search: PairSearch, first: list[np.ndarray], closest: list[np.ndarray], seed: int, limit: int
) -> Witness:
    """A witness of `search` (a PairSearch) before its meter reaches `limit` units, or ();
    descents start from `first`, then as the module doc says (`closest`: box centres)."""
    chain = search.chain
    if not chain.dims:  # nothing moves: the branch and bound measured the one state there is
        return ()
    dense = not first and not search.near  # no trial states, no earlier round: sample the box
    starts = itertools.chain(first, _around(search, seed), _starts(search, closest, seed, dense))
    while search.meter.units < limit:
        q = np.array([next(starts) for _ in range(BATCH)])
        witness, values = descend(search, q, limit)
        if witness:
            return witness
        _keep_nearest(search, q, values)
    return ()


def _keep_nearest(search: PairSearch, q: np.ndarray, values: np.ndarray) -> None:
    """Keep the NEAR states the descents ended nearest at, as (distance, order, state)."""
    ended = [
        (float(v), len(search.near) + k, row.copy()) for k, (v, row) in enumerate(zip(values, q, strict=True))
    ]
    search.near = sorted(search.near + ended, key=lambda item: item[:2])[:NEAR]


def _around(search: PairSearch, seed: int) -> Iterator[np.ndarray]:
    """An earlier round's nearest end states, then AROUND states scattered about them (a
    normal spread of SPREAD of each variable's range, seeded)."""
    near = [state for _, _, state in search.near]
    if not near:
        return
    yield from near
    chain = search.chain
    rng = np.random.default_rng([seed, 1, zlib.crc32("\0".join(chain.pair).encode())])
    for k in range(AROUND):
        moved = near[k % len(near)] + rng.normal(0.0, SPREAD, chain.dims) * (chain.upper - chain.lower)
        yield np.clip(moved, chain.lower, chain.upper)


def _starts(search: PairSearch, closest: list[np.ndarray], seed: int, dense: bool) -> Iterator[np.ndarray]:
    """With `dense`, the nearest-looking of DENSE random states; then the closest box centres
    measured; then random states (seeded by the run's seed and the pair's names). Starting from
    the dense states first found the dual panda's rare contacts (one arm's hand against the
    other's base) in 50 of 60 tries at 1000 units a pair, from the box centres first in 46;
    the trials' own closest states, where there are 10,000, do as well at no cost."""
    chain = search.chain
    rng = np.random.default_rng([seed, zlib.crc32("\0".join(chain.pair).encode())])
    if dense:
        box = chain.lower + rng.random((DENSE, chain.dims)) * (chain.upper - chain.lower)
        dense_states = nearest_looking(chain, box)
        search.meter.units += DENSE // STATES_PER_UNIT
        yield from dense_states
    yield from closest[:CLOSEST]
    while True:
        yield chain.lower + rng.random(chain.dims) * (chain.upper - chain.lower)


def nearest_looking(chain: PairChain, q: np.ndarray) -> np.ndarray:
    """The DENSE_STARTS states of `q` whose links look nearest, nearest first: by the gap of
    balls round the links' lever balls, then, for the nearest FIRST_CUT, by the smallest gap
    between lever balls (not a bound: the balls hold a link's hull points, not its surface;
    a ranking, for the descents to start from). Kinematics of the pair's chains only."""
    frames = chain.frames(q)
    rough = _ball_gaps(chain, frames)
    rows = np.argsort(rough, kind="stable")[:FIRST_CUT]
    fine = _lever_gaps(chain, frames, rows)
    return q[rows[np.argsort(fine, kind="stable")[:DENSE_STARTS]]]


def _ball_gaps(chain: PairChain, frames: tuple[Frames, Frames]) -> np.ndarray:
    centres = []
    for levers, frame in zip(chain.levers, frames, strict=True):
        low, high = levers.points.min(axis=0), levers.points.max(axis=0)
        middle = (low + high) / 2.0
        radius = float(np.max(np.linalg.norm(levers.points - middle, axis=1) + levers.radii))
        centres.append((frame.pose[:, :3, :3] @ middle + frame.pose[:, :3, 3], radius))
    return np.linalg.norm(centres[0][0] - centres[1][0], axis=1) - centres[0][1] - centres[1][1]


def _lever_gaps(chain: PairChain, frames: tuple[Frames, Frames], rows: np.ndarray) -> np.ndarray:
    a, b = (
        (frame.pose[rows, :3, :3] @ levers.points.T).transpose(0, 2, 1) + frame.pose[rows, None, :3, 3]
        for levers, frame in zip(chain.levers, frames, strict=True)
    )
    squared = (
        np.sum(a**2, axis=2)[:, :, None] + np.sum(b**2, axis=2)[:, None, :] - 2.0 * (a @ b.transpose(0, 2, 1))
    )
    gaps = np.sqrt(np.maximum(squared, 0.0))
    gaps -= chain.levers[0].radii[None, :, None] + chain.levers[1].radii[None, None, :]
    return gaps.reshape(len(rows), -1).min(axis=1)


class _Descents:
    """The state of S descents: where each is, its distance there, its gradient, whether that
    distance is the real one (else the hulls'), and whether it still moves. The starts are
    measured in order until the meter reaches `limit` (a pair whose meshes' distance costs
    tens of units reaches it within a batch); the rest never start (inf, inactive)."""

    def __init__(self, search: PairSearch, q: np.ndarray, limit: int) -> None:
        self.q = q
        frames = search.chain.frames(q)
        batch = search.meter.batch(frames[0].pose, frames[1].pose)
        measured: list[Measured] = []
        while len(measured) < len(q) and search.meter.units < limit:
            measured.append(_measure(search, batch, len(measured)))
        count = len(measured)
        self.value = np.full(len(q), np.inf)
        self.value[:count] = [m[0] for m in measured]
        self.exact = np.zeros(len(q), dtype=bool)
        self.exact[:count] = [m[2] for m in measured]
        self.gradient = np.zeros((len(q), search.chain.dims))
        self.gradient[:count] = _gradients(frames, np.arange(count), measured, search.chain.dims)
        self.active = np.arange(len(q)) < count


def descend(search: PairSearch, q: np.ndarray, limit: int) -> tuple[Witness, np.ndarray]:
    """Descents from each row of `q` (S, m) together, each row moved to where its descent
    ended: the first witness found (or ()) and the distances there."""
    state = _Descents(search, q, limit)
    for _ in range(STEPS):
        for s in np.flatnonzero(state.active & state.exact & (state.value <= search.threshold)):
            witness = search.check_witness(state.q[s])
            if witness:
                return witness, state.value
        state.active &= np.sum(state.gradient**2, axis=1) > 1e-12
        if not state.active.any() or search.meter.units >= limit:
            break
        _step(search, state, limit)
    return (), state.value


def _step(search: PairSearch, state: _Descents, limit: int) -> None:
    """One gradient step of every active descent (its candidates' kinematics in one batch)."""
    chain = search.chain
    rows = np.flatnonzero(state.active)
    q, gradient = state.q[rows], state.gradient[rows].copy()
    # projected: a variable at a bound that the step would push past it stays there
    gradient[((q <= chain.lower) & (gradient > 0)) | ((q >= chain.upper) & (gradient < 0))] = 0.0
    norm2 = np.maximum(np.sum(gradient**2, axis=1), 1e-12)
    gap = state.value[rows] - search.scene.padding
    factors = np.concatenate(
        [((gap + AIM) / norm2)[:, None] * 0.5 ** np.arange(HALVINGS), (gap[:, None] + FINE) / norm2[:, None]],
        axis=1,
    )  # (R, T): the halved steps, then the fine ones
    tries = factors.shape[1]
    moves = q[:, None, :] - factors[:, :, None] * gradient[:, None, :]
    moves = np.clip(moves, chain.lower, chain.upper).reshape(-1, chain.dims)
    frames = chain.frames(moves)
    batch = search.meter.batch(frames[0].pose, frames[1].pose)
    floors = _floors(chain, frames)
    beyond = search.threshold + SWITCH if search.meter.hulls else -np.inf
    accepted: list[tuple[int, int]] = []
    measured: list[Measured] = []
    for i, s in enumerate(rows):
        for h in range(tries):
            if floors[i * tries + h] >= max(state.value[s], beyond):  # no nearer: see _floors
                search.meter.units += 1
                continue
            found = _measure(search, batch, i * tries + h)
            if found[0] < state.value[s]:
                state.q[s], state.value[s], state.exact[s] = moves[i * tries + h], found[0], found[2]
                accepted.append((int(s), i * tries + h))
                measured.append(found)
                break
        else:
            state.active[s] = False
        if search.meter.units >= limit:
            break
    if accepted:
        targets, at = np.array([a[0] for a in accepted]), np.array([a[1] for a in accepted])
        state.gradient[targets] = _gradients(frames, at, measured, chain.dims)


def _floors(chain: PairChain, frames: tuple[Frames, Frames]) -> np.ndarray:
    """(K,): a sure lower bound of the pair's distance, its hulls' too, at each state of
    `frames`: the gap between balls holding each link (levers.LeverPoints.ball) less coal's
    tolerance (as the proofs' certificates take it). A candidate whose floor is no nearer than
    its descent's distance (nor within SWITCH of contact, where the real distance is measured)
    would be measured and rejected: it is rejected without coal, for the unit its hull query
    costs, so the budgets, the descents and their outcomes are those of asking coal (on the
    PR2 a third of the candidates)."""
    (center_a, radius_a), (center_b, radius_b) = chain.levers[0].ball, chain.levers[1].ball
    pose_a, pose_b = frames[0].pose, frames[1].pose
    apart = (pose_a[:, :3, :3] @ center_a + pose_a[:, :3, 3]) - (
        pose_b[:, :3, :3] @ center_b + pose_b[:, :3, 3]
    )
    gap = np.sqrt(np.vecdot(apart, apart)) - radius_a - radius_b
    return gap - CERT_MARGIN - RELATIVE_MARGIN * np.abs(gap)


def _measure(search: PairSearch, batch: tuple, row: int) -> Measured:
    """The distance at state `row` of a meter's `batch`, its nearest points, and whether it is
    the real distance (else the hulls', while they are more than SWITCH apart)."""
    meter = search.meter
    distance, near_a, near_b = meter.nearest(batch, row, hulls=meter.hulls)
    exact = not meter.hulls
    if meter.hulls and distance <= search.threshold + SWITCH:
        distance, near_a, near_b = meter.nearest(batch, row, hulls=False)
        exact = True
    return distance, (near_a, near_b), exact


def _gradients(
    frames: tuple[Frames, Frames], rows: np.ndarray, measured: list[Measured], dims: int
) -> np.ndarray:
    """(R, m): the distance's gradient in the box columns at `rows`, from the nearest points."""
    near_a = np.array([m[1][0] for m in measured]).reshape(-1, 3)
    near_b = np.array([m[1][1] for m in measured]).reshape(-1, 3)
    distance = np.array([m[0] for m in measured])
    gap = near_b - near_a
    length = np.linalg.norm(gap, axis=1)
    normal = np.where((distance > 0)[:, None], gap, -gap) / np.maximum(length, 1e-12)[:, None]
    normal[length < 1e-12] = 0.0
    return frames[1].rates(rows, near_b, normal) - frames[0].rates(rows, near_a, normal)
