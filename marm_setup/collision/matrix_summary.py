"""Collision-matrix reports: a JSON-ready summary and a link-by-link SVG (or HTML) heat map.

Pure: data in, text out. Cells are coloured by reason; enabled (sometimes colliding) pairs are
shaded by their hit rate in the fully counted Always-round samples.

Hit counts come from the Always rounds only (rounds of 200 samples in which every remaining
pair is checked): the Never phase stops checking a pair at its first hit, so its trials give
"seen colliding", not a count. Every output says so (HIT_COUNTS).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from marm_setup.collision.matrix import ROUND, CollisionMatrix, PairStats
from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.proof import COLLIDES, PROVED

ENABLED = "Enabled"
COLORS = {
    DisabledReason.ADJACENT: "#bdbdbd",
    DisabledReason.DEFAULT: "#9e9ac8",
    DisabledReason.ALWAYS: "#de2d26",
    DisabledReason.NEVER: "#a1d99b",
    DisabledReason.USER: "#6baed6",
}
LETTERS = {
    DisabledReason.ADJACENT: "A",
    DisabledReason.DEFAULT: "D",
    DisabledReason.ALWAYS: "X",
    DisabledReason.NEVER: "N",
    DisabledReason.USER: "U",
}
HEAT_LOW, HEAT_HIGH = (254, 230, 206), (230, 85, 13)  # enabled: 0 % -> 100 % hit rate
PROVED_FILL = "#238b45"  # Never, proved collision-free over the whole joint range
WITNESS_FILL = "#a50f15"  # enabled: a proof found the pair in contact
CELL, CHAR, PAD = 22, 7.0, 12
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
        if (a, b) not in {s.pair for s in matrix.stats}
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


@dataclass(frozen=True, slots=True)
class Cell:
    x: float
    y: float
    fill: str
    label: str
    label_fill: str
    title: str


def render_matrix_svg(
    matrix: CollisionMatrix,
    robot_name: str,
    links: Sequence[str],
    disabled: Sequence[DisabledPair] | None = None,
) -> str:
    """The heat map as SVG text; `links` in display order (e.g. tree order)."""
    from marm_setup.templating import render_template

    reasons = final_reasons(matrix, disabled)
    stats = {s.pair: s for s in matrix.stats}
    label_w = PAD + CHAR * max((len(n) for n in links), default=4)
    summary = _summary(matrix, reasons)
    top = 28 + 16 * len(summary) + 0.8 * label_w  # summary lines, then the rotated column labels
    cells = [
        _cell(a, b, i, j, label_w, top, reasons, stats)
        for i, a in enumerate(links)
        for j, b in enumerate(links)
        if i != j
    ]
    size = CELL * len(links)
    legend_y = top + size + 28
    legend = _legend(label_w, legend_y, matrix.prove != "off")
    return render_template(
        "report/collision_matrix.svg.j2",
        robot_name=robot_name,
        summary=summary,
        links=list(links),
        cells=cells,
        cell=CELL,
        left=label_w,
        top=top,
        legend=legend,
        width=max(label_w + size + 30, label_w + 100 * len(legend) + 130),
        height=legend_y + 50,
    )


def render_matrix_html(svg: str, robot_name: str) -> str:
    """The SVG inside a minimal standalone HTML page."""
    from marm_setup.templating import render_template

    body = svg.split("?>", 1)[-1].lstrip() if svg.startswith("<?xml") else svg
    return render_template("report/collision_matrix.html.j2", robot_name=robot_name, svg=body)


def _cell(a, b, i, j, left, top, reasons, stats) -> Cell:
    pair = (a, b) if a < b else (b, a)
    reason = reasons.get(pair)
    st = stats.get(pair)
    rate = st.hits / st.samples if st is not None and st.samples else None
    x, y = left + j * CELL, top + i * CELL
    proven = _proof_cell(x, y, pair, reason, st, rate)
    if proven is not None:
        return proven
    if reason is None:
        share = rate or 0.0
        fill = _mix(HEAT_LOW, HEAT_HIGH, share)
        label = f"{round(100 * share)}" if round(100 * share) >= 1 else "<1"
        return Cell(x, y, fill, label, "#fff" if share > 0.5 else "#333", _title(pair, None, st, rate))
    return Cell(x, y, COLORS[reason], LETTERS[reason], "#333", _title(pair, reason, st, rate))


def _proof_cell(x, y, pair, reason, st, rate) -> Cell | None:
    """The cell of a pair a proof decided: Never proved or unproved, or enabled by a witness."""
    proof = st.proof if st is not None else None
    if proof is None or (reason is not None and reason is not DisabledReason.NEVER):
        return None
    title = _title(pair, reason, st, rate)
    if reason is None:
        if proof.outcome != COLLIDES:
            return None
        from marm_setup.collision.proof_summary import witness_text

        return Cell(
            x,
            y,
            WITNESS_FILL,
            "W",
            "#fff",
            f"{title}, in contact at {witness_text(st, 99)} (found by a proof)",
        )
    if proof.outcome == PROVED:
        return Cell(
            x, y, PROVED_FILL, "N", "#fff", f"{title}, proved collision-free over its whole joint range"
        )
    share = int(1000 * proof.proved_fraction) / 10
    return Cell(
        x,
        y,
        COLORS[reason],
        "N?",
        "#333",
        f"{title}, unproved: proved collision-free over {share:.1f} % of its range",
    )


def _title(pair, reason, st, rate) -> str:
    text = f"{pair[0]} / {pair[1]}: {ENABLED if reason is None else reason.value}"
    if rate is not None:
        text += f", in collision in {st.hits} of {st.samples} Always-round samples ({100 * rate:.1f} %)"
    if reason is None and st is not None and not st.hits and st.seen_colliding:
        text += ", seen colliding in the trials"
    if reason is DisabledReason.NEVER and st is not None and st.min_distance is not None:
        text += f", closest {1000 * st.min_distance:.1f} mm"
    return text


def _mix(lo, hi, share: float) -> str:
    rgb = (round(a + (b - a) * share) for a, b in zip(lo, hi, strict=True))
    return "#" + "".join(f"{c:02x}" for c in rgb)


def _summary(matrix: CollisionMatrix, reasons) -> list[str]:
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


def _legend(x: float, y: float, proofs: bool = False) -> list[dict]:
    items = [(COLORS[r], f"{LETTERS[r]} {r.value}") for r in DisabledReason]
    if proofs:
        items[list(DisabledReason).index(DisabledReason.NEVER)] = (
            COLORS[DisabledReason.NEVER],
            "N? unproved",
        )
        items += [(PROVED_FILL, "N Never, proved"), (WITNESS_FILL, "W witness")]
    items.append((_mix(HEAT_LOW, HEAT_HIGH, 0.5), "% enabled: Always-round hit rate"))
    return [{"x": x + k * 100, "y": y, "fill": f, "text": t} for k, (f, t) in enumerate(items)]


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
