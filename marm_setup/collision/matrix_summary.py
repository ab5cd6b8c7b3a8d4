"""The collision matrix summed up: a JSON-ready description (`collisions --format json`) and the
summary lines (`collisions`, the heat map's caption in matrix_heat_map.py).

Pure: data in, text out.

Hit counts come from the Always rounds only (rounds of 200 samples in which every remaining
pair is checked): the Never phase stops checking a pair at its first hit, so its trials give
"seen colliding", not a count. Every output says so (HIT_COUNTS).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.results import ROUND, CollisionMatrix, PairStats

ENABLED = "Enabled"
HIT_COUNTS = (
    "hits/samples count the Always-round samples only (every pair checked in each); the Never "
    "trials stop checking a pair at its first hit, so they add no counts, only seen_colliding"
)


def final_reasons(matrix: CollisionMatrix, disabled: Iterable[DisabledPair] | None = None) -> dict:
    """Pair -> reason (None: enabled), from `disabled` (e.g. after merging User pairs) or the matrix."""
    chosen = matrix.disabled if disabled is None else disabled
    return {d.pair: d.reason for d in chosen}


def describe_matrix(
    matrix: CollisionMatrix, robot_name: str, disabled: Sequence[DisabledPair] | None = None
) -> dict:
    """Everything about the matrix as plain data (for `--format json`), pairs sorted."""
    from marm_setup.collision.proof_summary import outcome_counts

    reasons = final_reasons(matrix, disabled)
    counts = reason_counts(reasons)
    pairs = [_pair_dict(s, reasons.get(s.pair), matrix.trials) for s in matrix.stats]
    checked = {s.pair for s in matrix.stats}
    pairs += [
        {
            "link1": a,
            "link2": b,
            "reason": r.value,
            "hits": None,
            "samples": None,
            "seen_colliding": None,
            "min_distance": None,
            "proof": None,
            "proved_fraction": None,
            "witness": None,
            "hit_bound": None,
        }
        for (a, b), r in sorted(reasons.items())
        if (a, b) not in checked
    ]
    counts[ENABLED] = sum(1 for p in pairs if p["reason"] is None)
    return {
        "robot": robot_name,
        "trials": matrix.trials,
        "seed": matrix.seed,
        "min_collision_fraction": matrix.min_collision_fraction,
        "padding": matrix.padding,
        "never_bound_95": never_bound(matrix.trials),
        "hit_counts": HIT_COUNTS,
        "counts": counts,
        "prove": matrix.prove,
        "proofs": outcome_counts(matrix.stats),
        "pairs": sorted(pairs, key=lambda p: (p["link1"], p["link2"])),
    }


def reason_counts(reasons: dict) -> dict[str, int]:
    """Disabled pairs per reason, in MoveIt's order (every reason listed, zeros included)."""
    return {r.value: sum(1 for v in reasons.values() if v is r) for r in DisabledReason}


def never_bound(trials: int) -> float | None:
    """95 % upper bound on a Never pair's collision probability (rule of three): 3/N."""
    return 3.0 / trials if trials else None


def _pair_dict(stats: PairStats, reason: DisabledReason | None, trials: int) -> dict:
    from marm_setup.collision.proof_summary import proof_fields

    distance = None if stats.min_distance is None else round(stats.min_distance, 6)
    sampled = stats.samples > 0 or stats.reason in (None, DisabledReason.NEVER)  # else never checked
    return {
        "link1": stats.link1,
        "link2": stats.link2,
        "reason": None if reason is None else reason.value,
        "hits": stats.hits,
        "samples": stats.samples,
        "seen_colliding": stats.seen_colliding if sampled else None,
        "min_distance": distance if reason is DisabledReason.NEVER else None,
        **proof_fields(stats, reason, trials),
    }


def summary_lines(matrix: CollisionMatrix, reasons: dict) -> list[str]:
    """The heat map's caption: the proofs' first lines, then the counts and the sampling."""
    from marm_setup.collision.proof_summary import proof_lines

    counts = ", ".join(f"{reason} {n}" for reason, n in reason_counts(reasons).items())
    enabled = sum(1 for s in matrix.stats if reasons.get(s.pair) is None)
    bound = never_bound(matrix.trials)
    proofs = [line for line in proof_lines(matrix, reasons) if not line.startswith(" ")][:2]
    return [*proofs, *_base_summary(matrix, counts, enabled, bound)]


def _base_summary(matrix: CollisionMatrix, counts: str, enabled: int, bound: float | None) -> list[str]:
    return [
        f"{len(matrix.stats)} candidate pairs; disabled: {counts}; enabled (sometimes colliding): {enabled}",
        f"{matrix.trials} trials, seed {matrix.seed}, Always at >= {matrix.min_collision_fraction:g}"
        + (f"; a Never pair collides with p < {bound:.2g} (95 %)" if bound else ""),
        "hit rates: Always-round samples only (the trials stop checking a pair at its first hit)",
    ]


def format_summary(
    matrix: CollisionMatrix,
    robot_name: str,
    disabled: Sequence[DisabledPair],
    seconds: float,
    denser_seconds: float | None = None,
) -> str:
    """The text summary `marm-setup collisions` prints (`denser_seconds`: a 10x denser run)."""
    reasons = final_reasons(matrix, disabled)
    counts = ", ".join(f"{reason} {n}" for reason, n in reason_counts(reasons).items())
    enabled = [s for s in matrix.stats if reasons.get(s.pair) is None]
    lines = [
        f"robot {robot_name}: {len(matrix.stats)} candidate pairs (links with collision geometry)",
        f"disabled {len(reasons)}: {counts}",
        f"enabled (seen colliding, checked at run time) {len(enabled)}, "
        "with hits/samples of the Always rounds (the trials stop at a pair's first hit):",
    ]
    for s in enabled:
        hits = f"{s.hits}/{s.samples}" if s.samples else ""
        seen = "seen in trials" if not s.hits and s.seen_colliding else ""
        found = "found by a proof" if not s.hits and not s.seen_colliding else ""
        lines.append(f"  {s.link1} / {s.link2}  ({', '.join(x for x in (hits, seen, found) if x)})")
    lines.append(
        f"{matrix.trials} trials, seed {matrix.seed}, Always at >= {matrix.min_collision_fraction:g} "
        f"of a {ROUND}-sample round, padding {matrix.padding:g} m, {seconds:.2f} s"
        + (
            " (an earlier run's stored result; MARM_SETUP_CACHE=off computes it again)"
            if matrix.stored
            else ""
        )
    )
    if matrix.trials:
        lines.append(
            f"Never is statistical: with {matrix.trials} trials and no hit, a pair's collision "
            f"probability is below 3/N = {never_bound(matrix.trials):.2g} (95 % confidence)"
        )
    from marm_setup.collision.proof_summary import proof_lines

    lines += proof_lines(matrix, reasons)
    if denser_seconds is not None:
        lines.append(
            f"a 10x denser run (--trials {_count_text(10 * matrix.trials)}, bound "
            f"{never_bound(10 * matrix.trials):.2g}) would take about {denser_seconds:.0f} s here"
        )
    return "\n".join(lines)


def _count_text(n: int) -> str:
    """100000 -> '100k', 1000000 -> '1M' (as --trials accepts); other counts as digits."""
    for suffix, scale in (("M", 1_000_000), ("k", 1_000)):
        if n % scale == 0:
            return f"{n // scale}{suffix}"
    return str(n)
