"""What a matrix computation returns: the matrix, each pair's figures and proof, the work it
did. Plain data without numpy, so a stored result (matrix_cache.py) reads back without loading
the computation, and the outputs (proof_summary.py, matrix_summary.py) format it alike."""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass, field
from typing import Any

from marm_setup.collision.pairs import DisabledPair, DisabledReason

Pair = tuple[str, str]
ROUND = 200  # samples per Always round, as MoveIt
PROVED, COLLIDES, UNPROVED = "proved", "collides", "unproved"  # a pair proof's outcomes


@dataclass(frozen=True, slots=True)
class Work:
    """What the computation did (not part of the result: it varies with --jobs and shortcuts)."""

    exact_checks: int = 0  # coal collision checks of the real geometry
    hull_checks: int = 0
    hull_rejections: int = 0  # hull checks that proved a pair apart (no exact check needed)
    certificate_queries: int = 0  # coal distance queries made for certificates
    certified: int = 0  # (state, pair) checks a certificate answered
    proof_units: int = 0  # work of the proofs, in hull-distance queries (collision/proof.py)

    @classmethod
    def of(cls, scene: Any) -> Work:
        return cls(*scene.work())

    def __add__(self, other: Work) -> Work:
        return Work(*(a + b for a, b in zip(astuple(self), astuple(other), strict=True)))

    def __sub__(self, other: Work) -> Work:
        return Work(*(a - b for a, b in zip(astuple(self), astuple(other), strict=True)))


@dataclass(frozen=True, eq=False)
class SearchState:
    """Where an unfinished branch and bound stopped, to go on from there (plain data: it goes
    to and from pool processes): its open boxes (heap items), the certified share, the closest
    centres measured, the meter's counts, the next sequence number, whether a box was too small
    to split."""

    heap: list
    certified: float
    measured: list
    units: int
    extra: tuple[int, int]
    sequence: int
    stuck: bool


@dataclass(frozen=True, slots=True)
class PairProof:
    """What the proof of one pair found; `witness`: (joint, value) in contact (collides only);
    `state`: an unproved branch and bound's, to go on with more units."""

    outcome: str
    proved_fraction: float
    witness: tuple[tuple[str, float], ...] = ()
    units: int = 0  # work done, in hull-query units
    closest: tuple[tuple[float, ...], ...] = field(default=(), compare=False, repr=False)  # centres
    state: SearchState | None = field(default=None, compare=False, repr=False)
    near: tuple = field(default=(), compare=False, repr=False)  # witness search: (distance, order, state)
    second: float | None = field(default=None, compare=False, repr=False)  # left open by the first
    # round of the witness search: where that round ended [m] (proving.settle_pairs)
    least: int | None = field(default=None, compare=False, repr=False)  # a finished branch and
    # bound's: the smallest budget that gives this very proof (proof.PairSearch.least)

    @property
    def reached(self) -> float:
        """The smallest distance [m] its witness search reached (inf: none ran)."""
        return self.near[0][0] if self.near else math.inf


@dataclass(frozen=True, slots=True)
class PairStats:
    """One candidate pair: its reason (None: enabled), hits in the fully counted Always-round
    samples (`hits` of `samples`), whether any sample showed it in collision, for Never
    pairs the smallest distance [m] measured over its closest-looking trial states, and its
    proof (None: not proved, the pair being decided before the Never phase or `prove` off)."""

    link1: str
    link2: str
    reason: DisabledReason | None
    hits: int = 0
    samples: int = 0
    seen_colliding: bool = False
    min_distance: float | None = None
    proof: PairProof | None = None

    @property
    def pair(self) -> Pair:
        return (self.link1, self.link2)


@dataclass(frozen=True)
class CollisionMatrix:
    """The result: `disabled` sorted, `enabled` the sometimes-colliding pairs, `stats` per pair."""

    disabled: tuple[DisabledPair, ...]
    enabled: tuple[Pair, ...]
    stats: tuple[PairStats, ...]
    trials: int
    seed: int
    min_collision_fraction: float
    padding: float
    work: Work = field(default=Work(), compare=False)
    prove: str = "off"
    screened: dict[Pair, tuple[str, int]] = field(default_factory=dict, compare=False)  # the screen's
    # (outcome, units) per pair it screened or knew (what the proof cache keeps with a proof)
    stored: bool = field(default=False, compare=False)  # read from the matrix cache, not computed

    @property
    def narrow_calls(self) -> int:
        """Exact coal checks, every worker process included."""
        return self.work.exact_checks

    def count(self, reason: DisabledReason) -> int:
        return sum(1 for d in self.disabled if d.reason is reason)
