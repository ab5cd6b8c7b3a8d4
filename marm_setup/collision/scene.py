"""CollisionScene: coal geometry for every link with collision shapes, built once per robot.

The only module that imports coal (and, through `meshes`, trimesh). Checks run on batches of
configurations: batched numpy FK, then two vectorised conservative filters (bounding spheres,
then oriented boxes by the separating-axis test) so that only pairs that may touch reach the
coal narrow phase.

Mesh geometry becomes a coal BVH (`BVHModelOBBRSS`), which is a *surface*, as in MoveIt's
FCL: a shape entirely inside a mesh, not touching its triangles, does not collide with it.

`collide(..., hulls=True)` first tests the convex hulls of the meshes (primitives as they
are): a surface lies inside its hull, so hulls apart (by more than the padding) proves the
surfaces apart; only touching hulls go on to the exact mesh check.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from marm_setup.collision.pairs import link_pair
from marm_setup.robot import (
    Box,
    CollisionShape,
    Cylinder,
    Mesh,
    RobotModel,
    Sphere,
    check_robot_triangles,
    forward_kinematics,
    link_index,
    load_mesh,
    origin_matrix,
)

if TYPE_CHECKING:
    from marm_setup.collision.levers import LeverPoints

Pair = tuple[str, str]
_EPS = 1e-9
PAIR_BATCH = 1 << 18  # (state, pair) entries filtered at once: temporaries of tens of MB at most
HULL_MARGIN = 1e-5  # [m] added to the padding of hull tests (coal's GJK tolerance is 1e-6)


@dataclass(frozen=True, eq=False)
class _Bounds:
    """Link-frame bounding volumes of all links, row per geometry link: a box and the sphere
    around it share `center`."""

    center: np.ndarray  # (L, 3)
    sphere_radius: np.ndarray  # (L,)
    box_half: np.ndarray  # (L, 3)


class CollisionScene:
    """Coal objects and bounding volumes for `robot`; `padding` [m] pads every link."""

    def __init__(self, robot: RobotModel, padding: float = 0.0):
        import coal

        self._coal = coal
        self.robot = robot
        self.padding = float(padding)
        self.links: tuple[str, ...] = robot.geometry_links
        self.candidate_pairs: tuple[Pair, ...] = tuple(itertools.combinations(self.links, 2))
        self._pair_ids = {pair: i for i, pair in enumerate(self.candidate_pairs)}
        row = {name: i for i, name in enumerate(self.links)}
        self._pair_a = np.array([row[a] for a, _ in self.candidate_pairs], dtype=np.intp)
        self._pair_b = np.array([row[b] for _, b in self.candidate_pairs], dtype=np.intp)
        fk_index = link_index(robot)
        self._fk_rows = np.array([fk_index[name] for name in self.links], dtype=np.intp)
        check_robot_triangles(robot)  # the whole robot's meshes bounded before any BVH is built
        bvh_cache: dict = {}  # one BVH per mesh file and scale
        built = [_link_shapes(robot, name, coal, bvh_cache) for name in self.links]
        self._shapes: tuple[tuple[tuple[object, np.ndarray], ...], ...] = tuple(s for s, _ in built)
        points = [p for _, p in built]
        self.link_points: dict[str, np.ndarray] = dict(zip(self.links, points, strict=True))
        self._bounds = _bounds(points)
        # break_distance 0: coal breaks bounding volumes down below max(security_margin,
        # break_distance) only to refine a distance lower bound we never read (its default 1 mm
        # made a pair 1 mm apart cost ~50 % more); the verdict is security_margin's alone
        # (coal collision_data.h, CollisionRequest), so the matrix is the same (tested)
        self._request = coal.CollisionRequest()
        self._request.security_margin = self.padding
        self._request.break_distance = 0.0
        self._hull_request = coal.CollisionRequest()
        self._hull_request.security_margin = self.padding + HULL_MARGIN
        self._hull_request.break_distance = 0.0
        self._result = coal.CollisionResult()
        self._distance_request = coal.DistanceRequest()
        # hull distances are read only where positive (a lower bound that certifies, or a
        # descent's step while the hulls are apart): overlapping hulls need no penetration
        # depth (EPA, about 10 us a query), coal's unsigned distance (0) says as much
        self._hull_distance_request = coal.DistanceRequest()
        self._hull_distance_request.enable_signed_distance = False
        for request in (
            self._request,
            self._hull_request,
            self._distance_request,
            self._hull_distance_request,
        ):
            _same_start(request, coal)
        self._distance_result = coal.DistanceResult()
        self._distance_solvers: dict[tuple[int, int], object] = {}  # keyed by the geometries' ids
        self._plans: dict[tuple[int, bool], tuple] = {}  # (pair, hulls) -> its distance functors
        self._hulls: dict[int, tuple | None] = {}  # link row -> hull shapes (None: no mesh)
        self._hull_cache: dict = {}  # one hull per mesh BVH
        self._tf = (coal.Transform3s(), coal.Transform3s())
        self._solvers: dict[tuple[int, int, int, int], object] = {}
        self._ids_cache: dict[tuple[Pair, ...], np.ndarray] = {}
        self._levers: dict[str, LeverPoints] = {}
        self.narrow_calls = 0  # exact coal checks of the real geometry
        self.hull_checks = 0
        self.hull_rejections = 0  # hull checks that proved a pair apart
        self.certificate_queries = 0  # distance queries made for certificates (collision/prover.py)
        self.certified = 0  # states proven collision-free by a certificate

    # -- public API ----------------------------------------------------------------------------
    def enabled_pairs(self, disabled: Iterable[tuple[str, str]]) -> tuple[Pair, ...]:
        """Candidate pairs minus `disabled` (what MoveIt checks at run time under an SRDF)."""
        off = {link_pair(a, b) for a, b in disabled}
        return tuple(p for p in self.candidate_pairs if p not in off)

    def pair_ids(self, pairs: Sequence[tuple[str, str]]) -> np.ndarray:
        """Indices of `pairs` (any order inside a pair) into `candidate_pairs`."""
        key = tuple(pairs)
        ids = self._ids_cache.get(key)
        if ids is None:
            try:
                ids = np.array([self._pair_ids[link_pair(a, b)] for a, b in key], dtype=np.intp)
            except KeyError as exc:
                raise ValueError(f"not a candidate pair (both links need geometry): {exc}") from None
            if len(self._ids_cache) > 64:
                self._ids_cache.clear()
            self._ids_cache[key] = ids
        return ids

    def link_poses(self, q: np.ndarray, pair_id: int | None = None) -> np.ndarray:
        """World poses (N, L, 4, 4) of the geometry links (`self.links` order); with `pair_id`,
        those of that pair's two links only, the same values (the others zero: `collide`
        reads the pair's)."""
        rows = None if pair_id is None else self._fk_rows[[self._pair_a[pair_id], self._pair_b[pair_id]]]
        return forward_kinematics(self.robot, q, rows)[:, self._fk_rows]

    def pair_batches(self, states: int, pairs: int) -> list[slice]:
        """Consecutive slices of `pairs` pairs to filter together over `states` states, so that no
        batch holds more than PAIR_BATCH (state, pair) entries (a 1000-link chain has 500,500
        pairs: all at once over a 200-state round took 7 GB)."""
        step = max(1, PAIR_BATCH // max(states, 1))
        return [slice(start, start + step) for start in range(0, pairs, step)]

    def first_collisions(self, q: np.ndarray, pairs: Sequence[tuple[str, str]]) -> list[Pair | None]:
        """Per configuration, the first pair of `pairs` (in order) in collision, or None."""
        pairs = tuple(pairs)
        ids = self.pair_ids(pairs)
        poses = self.link_poses(q)
        centers = self.link_centers(poses)
        out: list[Pair | None] = [None] * len(poses)
        open_rows = list(range(len(poses)))
        for part in self.pair_batches(len(poses), len(ids)):
            maybe = self.maybe_colliding(poses, ids[part], self.sphere_gaps(poses, ids[part], centers))
            for n in open_rows:
                hit = next(
                    (k for k in np.flatnonzero(maybe[n]) if self.collide(poses[n], ids[part][k])), None
                )
                out[n] = None if hit is None else link_pair(*pairs[part][hit])
            open_rows = [n for n in open_rows if out[n] is None]
            if not open_rows:
                break
        return out

    def collision_counts(
        self,
        poses: np.ndarray,
        ids: np.ndarray,
        hulls: bool = False,
        opened: np.ndarray | None = None,
        seconds: np.ndarray | None = None,
    ) -> np.ndarray:
        """How many of the configurations in `poses` have each pair of `ids` in collision.
        `opened` / `seconds` (arrays per pair), when given, add up the states that reached the
        exact check and the seconds those checks took (the hulls built before: their one-time
        qhull would be charged to the first state of each pair)."""
        counts = np.zeros(len(ids), dtype=np.int64)
        if seconds is not None and hulls:
            for row in {int(r) for r in (*self._pair_a[ids], *self._pair_b[ids])}:
                self._hull_shapes(row)
        centers = self.link_centers(poses)
        for part in self.pair_batches(len(poses), len(ids)):
            maybe = self.maybe_colliding(poses, ids[part], self.sphere_gaps(poses, ids[part], centers))
            for n, k in zip(*np.nonzero(maybe), strict=True):
                started = time.perf_counter()
                counts[part.start + k] += self.collide(poses[n], ids[part.start + k], hulls)
                if seconds is not None:
                    seconds[part.start + k] += time.perf_counter() - started
            if opened is not None:
                opened[part] += maybe.sum(axis=0)
        return counts

    def work(self) -> tuple[int, int, int, int, int]:
        """Counters: exact checks, hull checks, hull rejections, certificate queries, certified."""
        return (self.narrow_calls, self.hull_checks, self.hull_rejections,
                self.certificate_queries, self.certified)  # fmt: skip

    # -- filters -------------------------------------------------------------------------------
    def link_centers(self, poses: np.ndarray) -> np.ndarray:
        """(N, L, 3) world centres of the links' bounding spheres (for `sphere_gaps`)."""
        rot, trans = poses[..., :3, :3], poses[..., :3, 3]
        return np.einsum("nlij,lj->nli", rot, self._bounds.center) + trans

    def sphere_gaps(
        self, poses: np.ndarray, ids: np.ndarray, centers: np.ndarray | None = None
    ) -> np.ndarray:
        """(N, P) distance between bounding spheres minus padding; > 0 means cannot collide.
        `centers`: `link_centers(poses)`, when the caller has them (it filters in batches)."""
        b = self._bounds
        centers = self.link_centers(poses) if centers is None else centers
        a_rows, b_rows = self._pair_a[ids], self._pair_b[ids]
        dist = np.linalg.norm(centers[:, a_rows] - centers[:, b_rows], axis=-1)
        return dist - b.sphere_radius[a_rows] - b.sphere_radius[b_rows] - self.padding

    def maybe_colliding(
        self, poses: np.ndarray, ids: np.ndarray, gaps: np.ndarray | None = None
    ) -> np.ndarray:
        """(N, P) False where bounding spheres or oriented boxes prove a pair apart."""
        maybe = (self.sphere_gaps(poses, ids) if gaps is None else gaps) <= _EPS
        n_idx, k_idx = np.nonzero(maybe)
        if len(n_idx):
            a_rows, b_rows = self._pair_a[ids[k_idx]], self._pair_b[ids[k_idx]]
            maybe[n_idx, k_idx] = self._boxes_overlap(
                poses[n_idx, a_rows], poses[n_idx, b_rows], a_rows, b_rows
            )
        return maybe

    def _boxes_overlap(self, pose_a, pose_b, a_rows, b_rows) -> np.ndarray:
        """Separating-axis test of the padded link boxes, one row per (pose_a, pose_b)."""
        b, pad = self._bounds, self.padding / 2.0 + _EPS
        rot_a, rot_b = pose_a[:, :3, :3], pose_b[:, :3, :3]
        ca = np.einsum("mij,mj->mi", rot_a, b.center[a_rows]) + pose_a[:, :3, 3]
        cb = np.einsum("mij,mj->mi", rot_b, b.center[b_rows]) + pose_b[:, :3, 3]
        ea, eb = b.box_half[a_rows] + pad, b.box_half[b_rows] + pad
        r = np.einsum("mki,mkj->mij", rot_a, rot_b)
        t = np.einsum("mki,mk->mi", rot_a, cb - ca)
        abs_r = np.abs(r) + 1e-12
        apart = np.any(np.abs(t) > ea + np.einsum("mij,mj->mi", abs_r, eb), axis=1)
        t_b = np.einsum("mij,mi->mj", r, t)
        apart |= np.any(np.abs(t_b) > np.einsum("mij,mi->mj", abs_r, ea) + eb, axis=1)
        for i, j in itertools.product(range(3), range(3)):
            i1, i2, j1, j2 = (i + 1) % 3, (i + 2) % 3, (j + 1) % 3, (j + 2) % 3
            ra = ea[:, i1] * abs_r[:, i2, j] + ea[:, i2] * abs_r[:, i1, j]
            rb = eb[:, j1] * abs_r[:, i, j2] + eb[:, j2] * abs_r[:, i, j1]
            apart |= np.abs(t[:, i2] * r[:, i1, j] - t[:, i1] * r[:, i2, j]) > ra + rb
        return ~apart

    # -- narrow phase --------------------------------------------------------------------------
    def collide(self, poses: np.ndarray, pair_id: int, hulls: bool = False) -> bool:
        """Exact (coal) check of candidate pair `pair_id` at one configuration's link poses;
        `hulls`: first try to prove it apart with the meshes' convex hulls (same answer)."""
        a, b = int(self._pair_a[pair_id]), int(self._pair_b[pair_id])
        if hulls and self._hulls_apart(poses, a, b):
            return False
        tf_a, tf_b = self._tf
        for (ia, (_, la)), (ib, (_, lb)) in itertools.product(
            enumerate(self._shapes[a]), enumerate(self._shapes[b])
        ):
            _set(tf_a, poses[a], la)
            _set(tf_b, poses[b], lb)
            self._result.clear()
            self.narrow_calls += 1
            if self._solver(a, ia, b, ib)(tf_a, tf_b, self._request, self._result):
                return True
        return False

    def hulls_apart(self, poses: np.ndarray, pair_id: int) -> bool:
        """The hull test alone: True proves the pair apart (see `collide(hulls=True)`)."""
        a, b = int(self._pair_a[pair_id]), int(self._pair_b[pair_id])
        return self._hulls_apart(poses, a, b)

    def has_hulls(self, pair_id: int) -> bool:
        """Whether either link of the pair has a mesh (with a convex hull)."""
        a, b = int(self._pair_a[pair_id]), int(self._pair_b[pair_id])
        return self._hull_shapes(a) is not None or self._hull_shapes(b) is not None

    def pair_triangles(self, pair_id: int) -> tuple[int, int]:
        """Each link's mesh triangles (a primitive counts 1): what an exact distance costs."""
        rows = (int(self._pair_a[pair_id]), int(self._pair_b[pair_id]))
        count = [sum(getattr(geom, "num_tris", 1) for geom, _ in self._shapes[row]) for row in rows]
        return count[0], count[1]

    def hull_distance(self, poses: np.ndarray, pair_id: int) -> float:
        """A lower bound [m] on the pair's distance: that of the meshes' convex hulls (GJK, much
        cheaper than mesh distance); the exact distance for a pair of primitives."""
        a, b = int(self._pair_a[pair_id]), int(self._pair_b[pair_id])
        self.hull_checks += 1
        best = self.closest(self.distance_plan(pair_id, True), poses[a], poses[b])[0]
        self.hull_rejections += bool(best > self.padding + HULL_MARGIN)
        return best

    def _hulls_apart(self, poses: np.ndarray, a: int, b: int) -> bool:
        """True when the convex hulls (padded) of links a and b cannot touch; False when they
        may, or when neither link has a mesh (its shapes are their own hulls)."""
        hull_a, hull_b = self._hull_shapes(a), self._hull_shapes(b)
        if hull_a is None and hull_b is None:
            return False
        tf_a, tf_b = self._tf
        self.hull_checks += 1
        for (ga, la), (gb, lb) in itertools.product(hull_a or self._shapes[a], hull_b or self._shapes[b]):
            _set(tf_a, poses[a], la)
            _set(tf_b, poses[b], lb)
            self._result.clear()
            if self._coal.collide(ga, tf_a, gb, tf_b, self._hull_request, self._result):
                return False
        self.hull_rejections += 1
        return True

    def _hull_shapes(self, row: int):
        """The link's shapes with each mesh replaced by its convex hull; None without meshes."""
        if row not in self._hulls:
            shapes = self._shapes[row]
            hulls = [(self._hull(geom), local) for geom, local in shapes]
            has_mesh = any(h is not g for (h, _), (g, _) in zip(hulls, shapes, strict=True))
            self._hulls[row] = tuple(hulls) if has_mesh else None
        return self._hulls[row]

    def _hull(self, geom):
        """coal's convex hull of a BVH mesh (cached per mesh); other geometry as it is."""
        if not isinstance(geom, self._coal.BVHModelOBBRSS):
            return geom
        key = id(geom)
        if key not in self._hull_cache:
            vertices = _distinct_rows(np.asarray(geom.vertices(), dtype=float))
            hull = None
            if _solid(vertices):  # coal's qhull call crashes the process on flat point sets
                points = self._coal.StdVec_Vec3s()
                points.extend(list(vertices))
                try:
                    hull = self._coal.ConvexBase.convexHull(points, True, None)
                except RuntimeError:  # e.g. "Too many neighbors" on a dense mesh: no hull test
                    hull = None
            self._hull_cache[key] = hull
        return self._hull_cache[key] or geom

    def distance(self, poses: np.ndarray, pair_id: int) -> float:
        """Smallest distance [m] between the pair's shapes (0 or less when touching)."""
        a, b = int(self._pair_a[pair_id]), int(self._pair_b[pair_id])
        return self.closest(self.distance_plan(pair_id, False), poses[a], poses[b])[0]

    def shape_distance(
        self, pair_id: int, pose_a: np.ndarray, pose_b: np.ndarray, hulls: bool = False
    ) -> float:
        """Smallest distance [m] between the pair's shapes with its links at `pose_a`, `pose_b`
        (any common frame); `hulls`: of the meshes' convex hulls (a lower bound)."""
        return self.closest(self.distance_plan(pair_id, hulls), pose_a, pose_b)[0]

    def nearest_points(
        self, pair_id: int, pose_a: np.ndarray, pose_b: np.ndarray, hulls: bool = False
    ) -> tuple[float, np.ndarray, np.ndarray]:
        """The pair's distance [m] at `pose_a`, `pose_b` and its nearest points on each link
        (in the poses' frame); `hulls`: of the meshes' convex hulls."""
        return self.closest(self.distance_plan(pair_id, hulls), pose_a, pose_b, points=True)

    def lever_points(self, link: str) -> LeverPoints:
        """Balls (points in the link's frame, radii) whose convex hull holds the link's shapes
        (`collision/levers.py`), computed once per link."""
        from marm_setup.collision.levers import link_levers, shape_levers

        if link not in self._levers:
            points, radii = [], []
            for geom, local in self._shapes[self.links.index(link)]:
                p, r = shape_levers(geom, self._coal, self._hull(geom))
                points.append(p if local is None else p @ local[:3, :3].T + local[:3, 3])
                radii.append(r)
            self._levers[link] = link_levers(np.concatenate(points), np.concatenate(radii))
        return self._levers[link]

    def distance_plan(self, pair_id: int, hulls: bool) -> tuple:
        """The pair's distance request and its (coal distance functor, link-from-shape pose of
        a, of b) per pair of its shapes (of the meshes' convex hulls when `hulls`), built once:
        a proof asks tens of thousands of distances of the same pair."""
        plan = self._plans.get((pair_id, hulls))
        if plan is None:
            a, b = int(self._pair_a[pair_id]), int(self._pair_b[pair_id])
            shapes_a, shapes_b = self._shapes[a], self._shapes[b]
            if hulls:
                shapes_a, shapes_b = self._hull_shapes(a) or shapes_a, self._hull_shapes(b) or shapes_b
            request = self._hull_distance_request if hulls else self._distance_request
            shapes = itertools.product(shapes_a, shapes_b)
            plan = (request, tuple((self._distance_solver(ga, gb), la, lb) for (ga, la), (gb, lb) in shapes))
            self._plans[(pair_id, hulls)] = plan
        return plan

    def closest(self, plan: tuple, pose_a: np.ndarray, pose_b: np.ndarray, points: bool = False):
        """(distance, nearest point on a, on b) of the closest pair of shapes of a
        `distance_plan`, its links at `pose_a`, `pose_b` (any common frame); the points are
        read only when `points` (else zeros)."""
        tf_a, tf_b = self._tf
        request, solvers = plan
        best: tuple = (np.inf, None)
        for solve, local_a, local_b in solvers:
            _set(tf_a, pose_a, local_a)
            _set(tf_b, pose_b, local_b)
            best = self._nearer(best, solve, request, points)
        return best if len(best) == 3 else (best[0], np.zeros(3), np.zeros(3))

    def posed(self, plan: tuple, poses_a: np.ndarray, poses_b: np.ndarray) -> tuple:
        """A `distance_plan` at K poses of its links (K, 4, 4) each: per pair of shapes, their
        rotations and translations laid out as coal reads them (for `closest_at`: a proof's
        descents measure hundreds of states of a batch one by one)."""
        request, solvers = plan
        out = []
        for solve, local_a, local_b in solvers:
            shape_a = poses_a if local_a is None else poses_a @ local_a
            shape_b = poses_b if local_b is None else poses_b @ local_b
            rotations = (np.ascontiguousarray(shape_a[:, :3, :3]), np.ascontiguousarray(shape_b[:, :3, :3]))
            shifts = (np.ascontiguousarray(shape_a[:, :3, 3]), np.ascontiguousarray(shape_b[:, :3, 3]))
            out.append((solve, rotations, shifts))
        return request, tuple(out)

    def closest_at(self, posed: tuple, row: int, points: bool = False):
        """`closest` at state `row` of a `posed` plan."""
        tf_a, tf_b = self._tf
        request, solvers = posed
        best: tuple = (np.inf, None)
        for solve, (rotation_a, rotation_b), (shift_a, shift_b) in solvers:
            tf_a.setTransform(rotation_a[row], shift_a[row])
            tf_b.setTransform(rotation_b[row], shift_b[row])
            best = self._nearer(best, solve, request, points)
        return best if len(best) == 3 else (best[0], np.zeros(3), np.zeros(3))

    def _nearer(self, best: tuple, solve, request, points: bool) -> tuple:
        """`best` ((distance, nearest points...) so far) or the distance of coal functor `solve`
        at the transforms set, whichever is smaller; the points are read only when `points`."""
        result = self._distance_result
        result.clear()
        request.cached_gjk_guess, request.cached_support_func_guess = _GUESS, _HINT  # _same_start
        solve(*self._tf, request, result)
        distance = float(result.min_distance)
        if distance >= best[0]:
            return best
        if not points:
            return (distance, None)
        # (coal returns copies of the points: the result's next query leaves them be)
        return distance, result.getNearestPoint1(), result.getNearestPoint2()

    def _distance_solver(self, geom_a, geom_b):
        key = (id(geom_a), id(geom_b))
        solver = self._distance_solvers.get(key)
        if solver is None:
            solver = self._distance_solvers[key] = self._coal.ComputeDistance(geom_a, geom_b)
        return solver

    def _solver(self, a: int, ia: int, b: int, ib: int):
        key = (a, ia, b, ib)
        solver = self._solvers.get(key)
        if solver is None:
            solver = self._coal.ComputeCollision(self._shapes[a][ia][0], self._shapes[b][ib][0])
            self._solvers[key] = solver
        return solver


_GUESS = np.array([1.0, 0.0, 0.0])  # coal's default first direction
_HINT = np.zeros(2, dtype=np.int32)


def _same_start(request, coal) -> None:
    """Every GJK run of `request` starts from the same guess and support hint: left at its
    default, a coal functor starts from where its previous query ended, so a distance (within
    coal's tolerance, 1e-8 m on the PR2's hulls) and what a proof decides from it would depend
    on which pairs and states the process measured before (its --jobs share, the proof cache);
    a distance functor changes the guess and hint as it runs, so distance queries set those two
    again before each run."""
    request.gjk_initial_guess = coal.GJKInitialGuess.CachedGuess
    request.cached_gjk_guess = _GUESS
    request.cached_support_func_guess = _HINT


def _set(tf, pose: np.ndarray, local: np.ndarray | None) -> None:
    """Set coal transform `tf` to `pose @ local` (local None: identity)."""
    if local is not None:
        pose = pose @ local
    tf.setTransform(pose[:3, :3], pose[:3, 3])


def _link_shapes(robot: RobotModel, name: str, coal, bvh_cache: dict):
    """((coal geometry, link-from-shape 4x4 or None), ...) and link-frame hull points of `name`."""
    shapes, points = [], []
    for i, shape in enumerate(robot.link(name).collisions):
        element = f"link[{name}]/collision[{i}]"
        geom, local_points = _coal_geometry(shape, coal, robot.source, element, bvh_cache)
        local = origin_matrix(shape.origin)
        points.append(local_points @ local[:3, :3].T + local[:3, 3])
        shapes.append((geom, None if np.allclose(local, np.eye(4)) else local))
    return tuple(shapes), np.concatenate(points)


def _coal_geometry(shape: CollisionShape, coal, shown: str, element: str, bvh_cache: dict):
    """A coal geometry for one URDF shape and points whose hull contains it (shape frame)."""
    geom = shape.geometry
    if isinstance(geom, Box):
        half = np.asarray(geom.size) / 2.0
        return coal.Box(*geom.size), _corners(half)
    if isinstance(geom, Cylinder):
        half = np.array([geom.radius, geom.radius, geom.length / 2.0])
        return coal.Cylinder(geom.radius, geom.length), _corners(half)
    if isinstance(geom, Sphere):
        return coal.Sphere(geom.radius), _corners(np.full(3, geom.radius))
    if isinstance(geom, Mesh):
        mesh = load_mesh(geom.path, geom.scale, shown=shown, element=f"{element}/mesh")
        key = (geom.path, geom.scale)
        if key not in bvh_cache:
            bvh_cache[key] = _bvh(mesh, coal)
        return bvh_cache[key], np.asarray(mesh.vertices)
    raise TypeError(f"unknown geometry {geom!r}")


def _distinct_rows(points: np.ndarray) -> np.ndarray:
    """The distinct rows of `points` in first-seen order: an STL triangle soup repeats each
    vertex about six times, and qhull's time grows with the points it is given (xarm7's 123k
    corners are 21k points: its hulls 52 -> 20 ms)."""
    rows = np.ascontiguousarray(points, dtype=float)
    _, first = np.unique(
        rows.view(np.dtype((np.void, rows.itemsize * rows.shape[1]))).ravel(), return_index=True
    )
    return rows[np.sort(first)]


def _solid(points: np.ndarray) -> bool:
    """At least 4 points spanning 3-D (thinnest extent > 1e-4 of the largest)."""
    if len(points) < 4:
        return False
    spread = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    return bool(spread[0] > 0 and spread[-1] > 1e-4 * spread[0])


def _corners(half: np.ndarray) -> np.ndarray:
    return np.array(list(itertools.product(*((-h, h) for h in half))))


def _bvh(mesh, coal):
    model = coal.BVHModelOBBRSS()
    model.beginModel(len(mesh.faces), len(mesh.vertices))
    model.addVertices(np.ascontiguousarray(mesh.vertices, dtype=float))
    model.addTriangles(np.ascontiguousarray(mesh.faces, dtype=np.int32))
    model.endModel()
    return model


def _bounds(points: Sequence[np.ndarray]) -> _Bounds:
    """Bounding sphere (centred on the box) and link-frame box of each link's hull points."""
    lo = np.array([p.min(axis=0) for p in points]).reshape(-1, 3)
    hi = np.array([p.max(axis=0) for p in points]).reshape(-1, 3)
    center = (lo + hi) / 2.0
    radius = np.array([np.linalg.norm(p - c, axis=1).max() for p, c in zip(points, center, strict=True)])
    return _Bounds(center, radius, (hi - lo) / 2.0)
