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
    least: int | None = None  # finished by the screen's branch and bound: the least budget giving it

    @property
    def screened_alone(self) -> bool:
        """Finished by the screen's branch and bound alone, whose run any screen budget of at
        least `least` boxes repeats step for step (proof.PairSearch.least): another run may take it."""
        return self.least is not None and self.screen[0] == self.outcome and self.outcome in OUTCOMES

    @property
    def settled(self) -> bool:
        """Finished after the trials (the pair went through them in a run without cache)."""
        return self.screen[0] not in OUTCOMES
