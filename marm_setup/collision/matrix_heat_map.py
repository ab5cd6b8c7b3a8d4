"""The collision matrix as a link-by-link SVG (or HTML) heat map (`collisions --report`, the
`report` page).

Pure: data in, text out. Cells are coloured by reason; enabled (sometimes colliding) pairs are
shaded by their hit rate in the fully counted Always-round samples (matrix_summary.HIT_COUNTS).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from marm_setup.collision.matrix_summary import ENABLED, final_reasons, summary_lines
from marm_setup.collision.pairs import DisabledPair, DisabledReason
from marm_setup.collision.results import COLLIDES, PROVED, CollisionMatrix

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
    summary = summary_lines(matrix, reasons)
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
