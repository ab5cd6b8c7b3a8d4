"""The user's proof cache: finished pair proofs by their key (collision/proof_keys.py).

One SQLite file, `$XDG_CACHE_HOME/marm-setup/proofs.sqlite` (else `~/.cache/marm-setup/`),
written only by the user's own runs of `init` and `collisions`: a package never supplies a
proof, so this is the only place proofs are trusted from (validate skips the resample of a
Never pair only when this cache holds its proof). `MARM_SETUP_CACHE=off` turns it off;
`MARM_SETUP_CACHE=DIR` puts it in DIR.

A matrix computation (collision/cached_matrix.py) replays its own run only: every proof and
screen a run left is kept under its pair's key within that run's context
(proof_keys.run_context: every candidate pair's key, the sampled joints, the settings and the
proof budgets), and served to the very same run, which then gives the same bytes as without the
cache. Of another run's proofs a matrix takes only those the screen's branch and bound finished
alone (CachedProof.screened_alone), where its own screen budget is at least the least that
repeats that search step for step (proof.PairSearch.least; matrix._repeated): the same proof,
units included, as computing it. Any other proof depends on the budget its whole run gave it
(the pools the pairs share, the trial states its witness search starts from), so a pair proved
by a variant of the robot might stay unproved here, and taking it would change the budgets of
the others and the output with the cache's contents. Finished proofs
("proved": no state of the pair's box is in contact; "collides": a state that is) are also kept
by their pair's key alone, for validate: a proved pair needs no resampling, whatever run proved
it. Each entry keeps what the matrix needs to account for it as the run did (its units, the
screen's outcome and units, where its first witness-search round ended). A cache that cannot be
read or written is skipped: it only ever saves work.
"""

from __future__ import annotations

import hashlib
import json
import logging
import os
import sqlite3
from collections.abc import Iterable, Mapping
from contextlib import closing
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.collision.cached_proof import OUTCOMES, CachedProof

if TYPE_CHECKING:
    from marm_setup.collision.results import CollisionMatrix, PairStats
    from marm_setup.collision.scene import CollisionScene

Pair = tuple[str, str]
LOG = logging.getLogger(__name__)
FILE = "proofs.sqlite"
SEEN = "seen"  # within one run: screened unproved, then seen in collision by the trials


def cache_dir() -> Path | None:
    """The cache folder, or None when MARM_SETUP_CACHE is "off"."""
    setting = os.environ.get("MARM_SETUP_CACHE", "")
    if setting.lower() in ("off", "0", "no", "false"):
        return None
    if setting:
        return Path(setting)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "marm-setup"


def known_proofs(
    scene: CollisionScene, pairs: Iterable[Pair] | None = None, context: str | None = None
) -> dict[Pair, CachedProof]:
    """Pair -> its proof in the cache, for `pairs` (default: every candidate pair of `scene`):
    with `context` (proof_keys.run_context) what that very run left, every outcome (a matrix
    computation replays only its own run: see the module doc); without, the finished proofs of
    any run (validate's: a proved pair needs no resampling)."""
    if cache_dir() is None:
        return {}
    from marm_setup.collision.proof_keys import pair_keys

    keys = pair_keys(scene, scene.candidate_pairs if pairs is None else pairs)
    if context:
        runs = {pair: _in_run(key, context) for pair, key in keys.items()}
        found = load_proofs(runs.values())
        return {pair: found[key] for pair, key in runs.items() if key in found}
    found = load_proofs(keys.values())
    return {pair: found[key] for pair, key in keys.items() if key in found and found[key].outcome in OUTCOMES}


def run_proofs(
    scene: CollisionScene, context: str
) -> tuple[dict[Pair, CachedProof], dict[Pair, CachedProof]]:
    """For every candidate pair of `scene`, in one read: what the very run `context` left
    (known_proofs with a context), and of the others the proofs another run's screen finished
    alone (CachedProof.screened_alone), which a matrix may take where its screen repeats them."""
    if cache_dir() is None:
        return {}, {}
    from marm_setup.collision.proof_keys import pair_keys

    keys = pair_keys(scene, scene.candidate_pairs)
    runs = {pair: _in_run(key, context) for pair, key in keys.items()}
    found = load_proofs([*runs.values(), *keys.values()])
    own = {pair: found[key] for pair, key in runs.items() if key in found}
    others = {
        pair: proof
        for pair, key in keys.items()
        if pair not in own and (proof := found.get(key)) is not None and proof.screened_alone
    }
    return own, others


def remember_proofs(scene: CollisionScene, matrix: CollisionMatrix, context: str | None = None) -> None:
    """Keep the finished proofs of `matrix` (computed on `scene`) in the cache by their pair's
    key, and with `context` every proof and the screens of the pairs its trials saw in collision
    (SEEN) for that very run."""
    from marm_setup.collision.proof_keys import pair_keys

    kept = {stats.pair: proof for stats in matrix.stats if (proof := _kept(stats, matrix.screened))}
    if cache_dir() is None or not kept:
        return
    keys = pair_keys(scene, kept)
    entries = {keys[pair]: proof for pair, proof in kept.items() if proof.outcome in OUTCOMES}
    if context:
        entries |= {_in_run(keys[pair], context): proof for pair, proof in kept.items()}
    dump_proofs(entries)


def _kept(stats: PairStats, screened: Mapping[Pair, tuple[str, int]]) -> CachedProof | None:
    """What the cache keeps of one pair: its proof, or the screen of a pair seen after it."""
    proof, screen = stats.proof, screened.get(stats.pair, ("unproved", 0))
    if proof is None:
        return CachedProof(SEEN, 0.0, (), 0, screen) if stats.pair in screened else None
    return CachedProof(
        proof.outcome, proof.proved_fraction, proof.witness, proof.units, screen, proof.second, proof.least
    )


def _in_run(key: str, context: str) -> str:
    """The key of an unproved proof: its pair's key within one run's context."""
    return hashlib.sha256(f"{key} {context}".encode()).hexdigest()[:32]


def load_proofs(keys: Iterable[str]) -> dict[str, CachedProof]:
    """Key -> its cached proof, for the keys the cache holds (none when it is off or unreadable)."""
    folder = cache_dir()
    wanted = sorted(set(keys))
    if folder is None or not wanted or not (folder / FILE).is_file():
        return {}
    found: dict[str, CachedProof] = {}
    try:
        with closing(_connect(folder)) as db:
            for start in range(0, len(wanted), 500):
                part = wanted[start : start + 500]
                marks = ",".join("?" * len(part))
                rows = db.execute(f"SELECT key, value FROM proofs WHERE key IN ({marks})", part)
                found.update((key, proof) for key, value in rows if (proof := _parsed(value)) is not None)
    except sqlite3.Error as exc:
        LOG.debug("proof cache not read: %s", exc)
        return {}
    return found


def dump_proofs(proofs: Mapping[str, CachedProof]) -> None:
    """Add `proofs` (key -> finished proof) to the cache (nothing when it is off or unwritable)."""
    folder = cache_dir()
    if folder is None or not proofs:
        return
    rows = [(key, json.dumps(_fields(proof))) for key, proof in sorted(proofs.items())]
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with closing(_connect(folder)) as db, db:
            db.executemany("INSERT OR REPLACE INTO proofs (key, value) VALUES (?, ?)", rows)
    except (OSError, sqlite3.Error) as exc:
        LOG.debug("proof cache not written: %s", exc)


def _connect(folder: Path) -> sqlite3.Connection:
    db = sqlite3.connect(folder / FILE, timeout=10.0)
    db.execute("CREATE TABLE IF NOT EXISTS proofs (key TEXT PRIMARY KEY, value TEXT NOT NULL)")
    return db


def _fields(proof: CachedProof) -> dict:
    return {
        "outcome": proof.outcome,
        "fraction": proof.fraction,
        "witness": [list(item) for item in proof.witness],
        "units": proof.units,
        "screen": list(proof.screen),
        "second": proof.second,
        "least": proof.least,
    }


def _parsed(value: str) -> CachedProof | None:
    """A cached proof from its JSON, or None when it is not one."""
    try:
        data = json.loads(value)
        proof = CachedProof(
            str(data["outcome"]),
            float(data["fraction"]),
            tuple((str(joint), float(v)) for joint, v in data["witness"]),
            int(data["units"]),
            (str(data["screen"][0]), int(data["screen"][1])),
            None if data.get("second") is None else float(data["second"]),
            None if data.get("least") is None else int(data["least"]),
        )
    except (ValueError, TypeError, KeyError, IndexError):
        return None
    return proof if proof.outcome in (*OUTCOMES, "unproved", SEEN) else None
