"""What the proofs found, as reports show it: JSON fields per pair, summary lines, SRDF notes.

JSON, per candidate pair (`collisions --format json`):
- `proof`: "proved" (collision-free over its whole joint range), "collides" (a proof found it
  in contact: enabled), "unproved" (the budget ran out: Never by MoveIt's sampling rule), or
  null (no proof: decided before the Never phase, seen colliding in the trials, or --prove off);
- `proved_fraction`: the share of the pair's joint box proved collision-free (1.0 when proved);
- `witness`: {joint: value} of the pair's joints at a state in contact (collides only); the
  matrix's own exact check finds the pair in contact there (other joints at their default);
- `hit_bound`: for a Never pair, an upper bound on its collision probability in a random state:
  0 when proved; else the smaller of 1 - proved_fraction (certain) and 3/trials (95 %).
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable, Mapping

from marm_setup.collision.pairs import DisabledReason, UnprovedPair
from marm_setup.collision.results import COLLIDES, PROVED, UNPROVED, CollisionMatrix, PairStats

OUTCOMES = (PROVED, COLLIDES, UNPROVED)
WITNESS_SHOWN = 4  # joints of a witness in a summary line (the JSON has them all)


def unproved_pairs(matrix: CollisionMatrix) -> tuple[UnprovedPair, ...]:
    """The Never pairs whose proof did not finish, sorted."""
    return tuple(
        sorted(
            UnprovedPair(s.link1, s.link2, round(float(s.proof.proved_fraction), 4))
            for s in matrix.stats
            if s.reason is DisabledReason.NEVER and s.proof is not None and s.proof.outcome == UNPROVED
        )
    )


def proof_key(
    fingerprint: str, prove: str, never: Iterable[tuple[str, str]], unproved: Iterable[tuple[str, str]]
) -> str:
    """16 hex digits tying a matrix's proofs to the robot they were made for (its
    `robot_fingerprint`), the prove mode and the Never and unproved pairs: validate trusts the
    proved pairs of a setup file only while its key matches the robot it reads."""
    text = repr((fingerprint, prove, sorted(never), sorted(unproved)))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def unproved_notes(matrix: CollisionMatrix) -> dict[tuple[str, str], str]:
    """Pair -> the SRDF note of each unproved Never pair."""
    return {u.pair: u.note(matrix.trials) for u in unproved_pairs(matrix)}


def outcome_counts(stats: Iterable[PairStats]) -> dict[str, int]:
    """Pairs per proof outcome, every outcome listed."""
    found = [s.proof.outcome for s in stats if s.proof is not None]
    return {outcome: found.count(outcome) for outcome in OUTCOMES}


def proof_fields(stats: PairStats, reason: DisabledReason | None, trials: int) -> dict:
    """The JSON fields of one pair (see the module doc)."""
    proof = stats.proof
    fields: dict = {"proof": None, "proved_fraction": None, "witness": None, "hit_bound": None}
    if proof is not None:
        fields.update(proof=proof.outcome, proved_fraction=round(proof.proved_fraction, 4))
        if proof.outcome == COLLIDES:
            fields["witness"] = dict(proof.witness)
    if reason is DisabledReason.NEVER:
        fields["hit_bound"] = hit_bound(
            proof.proved_fraction if proof else 0.0, proof is not None and proof.outcome == PROVED, trials
        )
    return fields


def hit_bound(proved_fraction: float, proved: bool, trials: int) -> float | None:
    """Upper bound on a Never pair's collision probability (see the module doc)."""
    if proved:
        return 0.0
    bounds = [1.0 - proved_fraction] + ([3.0 / trials] if trials else [])
    return round(min(bounds), 6)


def proof_lines(matrix: CollisionMatrix, reasons: Mapping) -> list[str]:
    """The summary's lines on the proofs (none when --prove is off)."""
    if matrix.prove == "off":
        return []
    never = [s for s in matrix.stats if reasons.get(s.pair) is DisabledReason.NEVER]
    proved = [s for s in never if _proved(s)]
    unproved = [s for s in never if not _proved(s)]  # one pass each: linear in the pairs
    found = [
        s
        for s in matrix.stats
        if s.proof is not None and s.proof.outcome == COLLIDES and reasons.get(s.pair) is None
    ]
    lines = [
        f"proof (--prove {matrix.prove}): {len(proved)} of {len(never)} Never pairs proved collision-free "
        f"over their whole joint range; {len(unproved)} unproved (Never by MoveIt's sampling rule)"
        + (":" if unproved else "")
    ]
    lines += [f"  {s.link1} / {s.link2}  (proved over {_share(s)} of its range)" for s in unproved]
    if found:
        lines.append(f"enabled by a proof (in contact at a state the trials missed) {len(found)}:")
        lines += [f"  {s.link1} / {s.link2}  at {witness_text(s)}" for s in found]
    return lines


def _proved(stats: PairStats) -> bool:
    return stats.proof is not None and stats.proof.outcome == PROVED


def witness_text(stats: PairStats, shown: int = WITNESS_SHOWN) -> str:
    """`joint=value, ...` of a witness (at most `shown` joints, then how many more)."""
    items = stats.proof.witness if stats.proof is not None else ()
    text = ", ".join(f"{joint}={value:.4f}" for joint, value in items[:shown])
    return text + (f" (+{len(items) - shown} more)" if len(items) > shown else "")


def _share(stats: PairStats) -> str:
    fraction = stats.proof.proved_fraction if stats.proof is not None else 0.0
    return f"{int(1000 * fraction) / 10:.1f} %"
