"""A finished proof as the user's proof cache keeps it (collision/proof_cache.py reads and
writes them; collision/matrix.py takes them as known proofs)."""

from __future__ import annotations

from dataclasses import dataclass

OUTCOMES = ("proved", "collides")


@dataclass(frozen=True, slots=True)
class CachedProof:
    """A finished proof as the cache keeps it: `screen` is (outcome, units) of the screen
    before the trials ("unproved": the proof went on after them); `second` where the first
    round of its witness search ended, when that round left it open."""

    outcome: str
    fraction: float
    witness: tuple[tuple[str, float], ...]
    units: int
    screen: tuple[str, int]
    second: float | None = None  # left open by the first witness-search round: where it ended [m]

    @property
    def settled(self) -> bool:
        """Finished after the trials (the pair went through them in a run without cache)."""
        return self.screen[0] not in OUTCOMES
