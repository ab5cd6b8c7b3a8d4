"""The MoveIt Setup Assistant's self-collision algorithm re-implemented with pinocchio and coal:
the reference `bench_proofs.py` compares `marm-setup collisions` with (run as its own process).

Run: `.venv/bin/python benchmarks/setup_assistant_reference.py ROBOT.urdf [--package-dir DIR ...]
[--trials 10000] [--seed 0]`; prints the disabled pairs per reason, one `reason link1 link2` line each.

compute_default_collisions.cpp's phases, as DESIGN.md section 3 states them: Adjacent (parent
and child links through a joint, through geometry-less links), Default (in collision at the
zero/mid-range state), Always (in collision in >= 95 % of a round of 200 random states; rounds
until one adds nothing), Never (never in collision in `trials` random states). Every remaining
pair is checked in every state with pinocchio's computeCollisions (coal narrow phase, its own
bounding-volume tests), as the Setup Assistant checks the whole robot per state.
"""

from __future__ import annotations

import argparse
import itertools

import numpy as np
import pinocchio as pin

ROUND = 200
FRACTION = 0.95


def link_pairs(model, geom_model) -> dict[tuple[str, str], list[int]]:
    """Link pair (sorted names) -> its collision pair indices (one per pair of geometries),
    every pair of geometries of different links added to `geom_model`."""
    owner = [model.frames[g.parentFrame].name for g in geom_model.geometryObjects]
    pairs: dict[tuple[str, str], list[int]] = {}
    for i, j in itertools.combinations(range(len(owner)), 2):
        if owner[i] != owner[j]:
            geom_model.addCollisionPair(pin.CollisionPair(i, j))
            key = (owner[i], owner[j]) if owner[i] < owner[j] else (owner[j], owner[i])
            pairs.setdefault(key, []).append(len(geom_model.collisionPairs) - 1)
    return pairs


def adjacent(model, geometry_links: set[str]) -> set[tuple[str, str]]:
    """Each link with geometry and its nearest ancestor with geometry (links without geometry
    are transparent, as in the Setup Assistant)."""
    out = set()
    for link in geometry_links:
        index = model.frames[model.getFrameId(link)].parentFrame
        while index > 0:
            frame = model.frames[index]
            if frame.type == pin.FrameType.BODY and frame.name in geometry_links:
                out.add((link, frame.name) if link < frame.name else (frame.name, link))
                break
            index = frame.parentFrame
    return out


def checking(geom_data, pairs: dict[tuple[str, str], list[int]], count: int) -> None:
    """Only the collision pairs of `pairs` active (the disabled ones are not checked, as under
    the Setup Assistant's allowed collision matrix)."""
    active = {k for ids in pairs.values() for k in ids}
    for k in range(count):
        if k in active:
            geom_data.activateCollisionPair(k)
        else:
            geom_data.deactivateCollisionPair(k)


def colliding(model, data, geom_model, geom_data, q, pairs) -> set[tuple[str, str]]:
    pin.computeCollisions(model, data, geom_model, geom_data, q, False)
    results = geom_data.collisionResults
    return {pair for pair, ids in pairs.items() if any(results[k].isCollision() for k in ids)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("urdf")
    parser.add_argument("--package-dir", action="append", default=[])
    parser.add_argument("--trials", type=int, default=10000)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    model = pin.buildModelFromUrdf(args.urdf)
    geom_model = pin.buildGeomFromUrdf(model, args.urdf, pin.COLLISION, package_dirs=args.package_dir)
    pairs = link_pairs(model, geom_model)
    data, geom_data = model.createData(), pin.GeometryData(geom_model)
    links = {link for pair in pairs for link in pair}
    reasons = dict.fromkeys(adjacent(model, links) & set(pairs), "Adjacent")
    if model.nq != model.nv:
        raise SystemExit("continuous joints: not supported by this reference")
    lower, upper = model.lowerPositionLimit.copy(), model.upperPositionLimit.copy()
    zero = np.where((lower <= 0) & (upper >= 0), 0.0, (lower + upper) / 2)
    open_pairs = {p: ids for p, ids in pairs.items() if p not in reasons}
    checking(geom_data, open_pairs, len(geom_model.collisionPairs))
    reasons.update(dict.fromkeys(colliding(model, data, geom_model, geom_data, zero, open_pairs), "Default"))
    rng = np.random.default_rng(args.seed)
    while True:
        open_pairs = {p: ids for p, ids in pairs.items() if p not in reasons}
        hits = dict.fromkeys(open_pairs, 0)
        checking(geom_data, open_pairs, len(geom_model.collisionPairs))
        for _ in range(ROUND):
            q = lower + rng.random(len(lower)) * (upper - lower)
            for pair in colliding(model, data, geom_model, geom_data, q, open_pairs):
                hits[pair] += 1
        always = {p for p, n in hits.items() if n >= FRACTION * ROUND}
        reasons.update(dict.fromkeys(always, "Always"))
        if not always:
            break
    open_pairs = {p: ids for p, ids in pairs.items() if p not in reasons}
    seen: set[tuple[str, str]] = set()
    checking(geom_data, open_pairs, len(geom_model.collisionPairs))
    for _ in range(args.trials):
        q = lower + rng.random(len(lower)) * (upper - lower)
        seen |= colliding(model, data, geom_model, geom_data, q, open_pairs)
    reasons.update(dict.fromkeys((p for p in open_pairs if p not in seen), "Never"))
    for pair, reason in sorted(reasons.items()):
        print(reason, *pair)


if __name__ == "__main__":
    main()
