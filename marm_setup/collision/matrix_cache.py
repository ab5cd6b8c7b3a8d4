"""The user's matrix cache: each finished matrix computation under what it depends on, so running
`init`, `collisions` or `report` again on the same robot with the same settings computes nothing.
(The proof cache, proof_cache.py, serves proofs pair by pair; this serves the whole result.)

The key (matrix_key) covers the robot's kinematics and collision geometry
(robot/fingerprint.py: every joint, each mesh file by its bytes, a `.gltf` also by the arrays it
loads, since its buffers may sit in other files), the scene's padding, every setting of the
computation but those that change no byte of it (`--jobs`, progress, shortcuts), the source of the
code that computes it (marm_setup/collision and marm_setup/robot) and the versions of coal and
numpy. A hit is the matrix the first run computed, field for field, so what is written from it is
the same bytes. Kept in `matrices.sqlite` in the proof cache's folder (its newest KEEP results),
off with it (MARM_SETUP_CACHE=off); a cache that cannot be read or written is skipped.
"""

from __future__ import annotations

import hashlib
import json
import logging
import sqlite3
from collections.abc import Mapping
from contextlib import closing
from dataclasses import astuple
from importlib import metadata
from pathlib import Path
from typing import TYPE_CHECKING, Any

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.proof_cache import cache_dir
from marm_setup.collision.results import CollisionMatrix, PairProof, PairStats, Work

if TYPE_CHECKING:
    from marm_setup.robot import RobotModel

LOG = logging.getLogger(__name__)
FILE = "matrices.sqlite"
KEEP = 64  # results kept: a robot's few settings and tools, for the robots a user works on
UNKEYED = frozenset({"jobs", "progress", "proof_progress", "shortcuts"})  # change no byte of the result
PACKAGE = Path(__file__).resolve().parent.parent
CODE = ("collision", "robot")  # marm_setup's folders whose code the result depends on
LEANS_ON_OTHER_FILES = (".gltf",)  # mesh formats whose geometry may sit in files the URDF does not name
VERSION = "marm-setup matrix 1"  # changes with what the stored fields mean


def matrix_key(robot: RobotModel, padding: float, options: Mapping[str, Any]) -> str:
    """32 hex digits of what the matrix of `robot` with `options` depends on (the module doc)."""
    from marm_setup.robot import robot_fingerprint

    settings = sorted((name, _plain(value)) for name, value in options.items() if name not in UNKEYED)
    text = repr((VERSION, robot_fingerprint(robot), _gltf_digests(robot), float(padding), settings, _code()))
    return hashlib.sha256(text.encode()).hexdigest()[:32]


def load_matrix(key: str) -> CollisionMatrix | None:
    """The matrix stored under `key`, or None (none stored, cache off or unreadable)."""
    folder = cache_dir()
    if folder is None or not (folder / FILE).is_file():
        return None
    try:
        with closing(_connect(folder)) as db:
            row = db.execute("SELECT value FROM matrices WHERE key = ?", (key,)).fetchone()
        return None if row is None else matrix_from_json(json.loads(row[0]))
    except (sqlite3.Error, ValueError, TypeError, KeyError, IndexError) as exc:
        LOG.debug("matrix cache not read: %s", exc)
        return None


def store_matrix(key: str, matrix: CollisionMatrix) -> None:
    """Keep `matrix` under `key`, the newest KEEP results only (nothing when the cache is off)."""
    folder = cache_dir()
    if folder is None:
        return
    value = json.dumps(matrix_to_json(matrix), separators=(",", ":"))
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with closing(_connect(folder)) as db, db:
            db.execute("INSERT OR REPLACE INTO matrices (key, value) VALUES (?, ?)", (key, value))
            db.execute(
                "DELETE FROM matrices WHERE rowid NOT IN (SELECT rowid FROM matrices ORDER BY rowid DESC LIMIT ?)",
                (KEEP,),
            )
    except (OSError, sqlite3.Error) as exc:
        LOG.debug("matrix cache not written: %s", exc)


def matrix_to_json(matrix: CollisionMatrix) -> dict:
    """Every field of `matrix` as JSON values (floats keep every bit through json)."""
    return {
        "disabled": [[d.link1, d.link2, d.reason.value] for d in matrix.disabled],
        "enabled": [list(pair) for pair in matrix.enabled],
        "stats": [_stats_to_json(s) for s in matrix.stats],
        "trials": int(matrix.trials),
        "seed": int(matrix.seed),
        "min_collision_fraction": float(matrix.min_collision_fraction),
        "padding": float(matrix.padding),
        "work": [int(n) for n in astuple(matrix.work)],
        "prove": matrix.prove,
        "screened": [[a, b, outcome, int(units)] for (a, b), (outcome, units) in matrix.screened.items()],
    }


def matrix_from_json(data: dict) -> CollisionMatrix:
    """The matrix `matrix_to_json` gave `data` for."""
    return CollisionMatrix(
        disabled=tuple(DisabledPair(a, b, DisabledReason(reason)) for a, b, reason in data["disabled"]),
        enabled=tuple((a, b) for a, b in data["enabled"]),
        stats=tuple(_stats_from_json(item) for item in data["stats"]),
        trials=int(data["trials"]),
        seed=int(data["seed"]),
        min_collision_fraction=float(data["min_collision_fraction"]),
        padding=float(data["padding"]),
        work=Work(*(int(n) for n in data["work"])),
        prove=str(data["prove"]),
        screened={(a, b): (str(outcome), int(units)) for a, b, outcome, units in data["screened"]},
        stored=True,
    )


def _stats_to_json(stats: PairStats) -> list:
    proof = stats.proof
    kept = None
    if proof is not None:
        witness = [[joint, float(value)] for joint, value in proof.witness]
        second = None if proof.second is None else float(proof.second)
        kept = [proof.outcome, float(proof.proved_fraction), witness, int(proof.units), second]
    reason = None if stats.reason is None else stats.reason.value
    distance = None if stats.min_distance is None else float(stats.min_distance)
    return [
        stats.link1,
        stats.link2,
        reason,
        int(stats.hits),
        int(stats.samples),
        bool(stats.seen_colliding),
        distance,
        kept,
    ]


def _stats_from_json(item: list) -> PairStats:
    link1, link2, reason, hits, samples, seen, distance, kept = item
    proof = None
    if kept is not None:
        outcome, fraction, witness, units, second = kept
        witness = tuple((str(joint), float(value)) for joint, value in witness)
        proof = PairProof(
            outcome, float(fraction), witness, int(units), second=None if second is None else float(second)
        )
    return PairStats(
        link1,
        link2,
        None if reason is None else DisabledReason(reason),
        int(hits),
        int(samples),
        bool(seen),
        None if distance is None else float(distance),
        proof,
    )


def _plain(value: Any) -> Any:
    """A setting as plain values (an array as its list)."""
    return value.tolist() if hasattr(value, "tolist") else value


def _gltf_digests(robot: RobotModel) -> list[tuple[str, str]]:
    """(link, digest of its loaded collision arrays) of each link with a mesh in a format whose
    geometry may sit in other files."""
    from marm_setup.robot import Mesh

    links = [
        link.name
        for link in sorted(robot.links, key=lambda x: x.name)
        if any(
            isinstance(s.geometry, Mesh) and s.geometry.path.lower().endswith(LEANS_ON_OTHER_FILES)
            for s in link.collisions
        )
    ]
    if not links:
        return []
    from marm_setup.collision.proof_keys import link_geometry_digest  # imports the prover

    return [(name, link_geometry_digest(robot, name)) for name in links]


def _code() -> tuple[str, str, str]:
    """A digest of marm-setup's version and the source the matrix comes from (an install without
    its .py files still keys by version), and the coal and numpy versions."""
    from marm_setup import __version__

    digest = hashlib.sha256(__version__.encode())
    for folder in CODE:
        for path in sorted((PACKAGE / folder).glob("*.py")):
            digest.update(path.name.encode())
            digest.update(path.read_bytes())
    return digest.hexdigest(), _version("coal"), _version("numpy")


def _version(name: str) -> str:
    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


def _connect(folder: Path) -> sqlite3.Connection:
    db = sqlite3.connect(folder / FILE, timeout=10.0)
    db.execute("CREATE TABLE IF NOT EXISTS matrices (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
    return db
