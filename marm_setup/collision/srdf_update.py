"""SRDF `disable_collisions` output: a minimal SRDF, or an in-place update of an existing one.

An update edits the text, not a re-serialised tree: every byte outside the replaced
`<disable_collisions>` lines stays as it was (comments, groups, attribute order, indentation).
Entries whose reason is `User` (or not one we compute) are kept where they are; with `keep`,
every existing entry is kept and only new pairs are added. A Never pair whose proof did not
finish gets a note (an XML comment on the line before it); a replaced entry's note goes with it.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from html import escape, unescape
from pathlib import Path

from lxml import etree

from marm_setup import bounded_read
from marm_setup.collision.pairs import UNPROVED_MARK, DisabledPair, DisabledReason
from marm_setup.errors import InputError
from marm_setup.robot import tinyxml_comments, xml_syntax_message

COMPUTED = frozenset(
    {DisabledReason.ADJACENT, DisabledReason.DEFAULT, DisabledReason.ALWAYS, DisabledReason.NEVER}
)
# A whole `<disable_collisions .../>` (or with an empty end tag); quoted attribute values may
# hold `>` and `/>`.
_ELEMENT = re.compile(
    r"<disable_collisions\b(?:\s+[^\s=/>]+\s*=\s*(?:\"[^\"]*\"|'[^']*'))*\s*(?:/>|>\s*</disable_collisions\s*>)"
)
# Text that is not markup of the document tree: comments, CDATA, processing instructions, the DTD.
_HIDDEN = re.compile(r"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|<!DOCTYPE(?:[^\[>]|\[.*?\])*>", re.S)


@dataclass(frozen=True, slots=True)
class SrdfEntry:
    """One `<disable_collisions>` in an SRDF: `start`/`end` offsets in the text, its raw reason."""

    start: int
    end: int
    link1: str
    link2: str
    reason: str

    @property
    def pair(self) -> DisabledPair:
        """As a DisabledPair; a reason we do not compute counts as `User` (never recomputed)."""
        try:
            reason = DisabledReason(self.reason)
        except ValueError:
            reason = DisabledReason.USER
        return DisabledPair.of(self.link1, self.link2, reason)


Notes = Mapping[tuple[str, str], str]


def render_minimal_srdf(robot_name: str, disabled: Iterable[DisabledPair], notes: Notes | None = None) -> str:
    """`<robot name>` with the sorted `disable_collisions` entries (`notes`: pair -> comment)."""
    from marm_setup.templating import render_template

    return render_template(
        "collision/disable_collisions.srdf.j2",
        robot_name=robot_name,
        disabled=sorted(disabled),
        notes=dict(notes or {}),
    )


def read_srdf_entries(text: str, *, shown: str) -> list[SrdfEntry]:
    """The `disable_collisions` entries of SRDF `text`, in document order.

    Offsets come from the text (outside comments, CDATA, processing instructions and the DTD);
    link names and reasons from lxml's tree, so entity references read as the parser reads them.
    """
    try:
        data = tinyxml_comments(text).encode("utf-8")  # as srdfdom reads it; offsets kept
        root = etree.fromstring(data, etree.XMLParser(remove_comments=True))
    except etree.XMLSyntaxError as exc:
        raise InputError(
            f"malformed XML: {xml_syntax_message(exc)}", path=shown, element=f"line {exc.lineno}"
        ) from None
    if root.tag != "robot":
        raise InputError(f"root element is <{root.tag!s}>, expected <robot>", path=shown)
    elements = root.findall("disable_collisions")
    matches = list(_element_matches(text))
    lines = _line_numbers(text, [m.start() for m in matches])
    if len(matches) != len(elements) or any(
        not _same_element(el, m, n) for el, m, n in zip(elements, matches, lines, strict=False)
    ):
        raise InputError(
            "disable_collisions elements in an unexpected form (nested, or with content); cannot edit in place",
            path=shown,
        )
    entries = []
    for match, el, line in zip(matches, elements, lines, strict=True):
        link1, link2 = el.get("link1"), el.get("link2")
        if not link1 or not link2:
            raise InputError("disable_collisions needs link1 and link2", path=shown, element=f"line {line}")
        entries.append(SrdfEntry(match.start(), match.end(), link1, link2, el.get("reason", "")))
    return entries


def update_srdf(
    text: str, disabled: Sequence[DisabledPair], *, keep: bool = False, shown: str, notes: Notes | None = None
) -> tuple[str, tuple[DisabledPair, ...]]:
    """SRDF `text` with its computed entries replaced by `disabled`; also the final disabled set.

    Kept entries (`User`, unknown reasons, or all with `keep`) stay byte for byte; a kept pair
    wins over a computed one. New entries go, sorted, where the first removed entry was (else
    before `</robot>`), one per line with that entry's indentation, each after its note if
    `notes` (pair -> comment text) has one; a removed entry's note is removed with it.
    """
    notes = notes or {}
    entries = read_srdf_entries(text, shown=shown)
    kept = [e for e in entries if keep or e.pair.reason not in COMPUTED]
    kept_pairs = {e.pair.pair for e in kept}
    new = sorted(d for d in {d.pair: d for d in disabled}.values() if d.pair not in kept_pairs)
    kept_ids = {id(e) for e in kept}
    removed = [e for e in entries if id(e) not in kept_ids]
    newline = "\r\n" if "\r\n" in text else "\n"
    anchor, indent = _anchor(text, removed, entries, shown)
    block = "".join(
        (f"{indent}<!-- {notes[d.pair]} -->{newline}" if d.pair in notes else "")
        + f'{indent}<disable_collisions link1="{escape(d.link1)}" link2="{escape(d.link2)}" '
        f'reason="{d.reason.value}"/>{newline}'
        for d in new
    )
    edits = [(*_with_note(text, *_line_span(text, e)), "") for e in removed]
    if edits and edits[0][0] == anchor:
        edits[0] = (edits[0][0], edits[0][1], block)
    else:
        edits.append((anchor, anchor, block if anchor == 0 or text[anchor - 1] == "\n" else newline + block))
    return _apply_edits(text, edits), tuple(sorted([e.pair for e in kept] + new))


def _apply_edits(text: str, edits: list[tuple[int, int, str]]) -> str:
    """`text` with each (start, end, replacement) span replaced; spans do not overlap. One pass
    (slicing the whole text once per edit was quadratic: 100,000 entries took minutes)."""
    pieces, at = [], 0
    for start, end, replacement in sorted(edits):
        pieces += [text[at:start], replacement]
        at = end
    pieces.append(text[at:])
    return "".join(pieces)


_ATTRIBUTE = re.compile(r"""\s([^\s=/>]+)\s*=\s*(?:"([^"]*)"|'([^']*)')""")


def _same_element(el, match: re.Match, line: int) -> bool:
    """The tree's element `el` is the one `match` found on `line`: the same line, or past line
    65534, where libxml2 (2.14) may report one more (65535 is its 16-bit "big line" marker),
    the next line and the same attributes."""
    if el.sourceline == line:
        return True
    if line < 65535 or el.sourceline != line + 1:
        return False
    found = {m[1]: unescape(m[2] if m[2] is not None else m[3]) for m in _ATTRIBUTE.finditer(match.group(0))}
    return found == dict(el.attrib)


def _line_numbers(text: str, offsets: list[int]) -> list[int]:
    """The 1-based line of each offset (ascending), counting each newline once (linear time)."""
    lines, line, at = [], 1, 0
    for offset in offsets:
        line += text.count("\n", at, offset)
        at = offset
        lines.append(line)
    return lines


def masked(text: str) -> str:
    """`text` with comments, CDATA, processing instructions and the DTD blanked (same offsets)."""
    return _HIDDEN.sub(lambda m: re.sub(r"[^\n]", " ", m.group(0)), text)


def _element_matches(text: str):
    """Regex matches of disable_collisions elements in the document tree's own markup."""
    return _ELEMENT.finditer(masked(text))


def _line_span(text: str, entry: SrdfEntry) -> tuple[int, int]:
    """The span to delete for `entry`: its whole line when it is alone on it, else the element."""
    line_start = text.rfind("\n", 0, entry.start) + 1
    line_end = text.find("\n", entry.end)
    line_end = len(text) if line_end < 0 else line_end + 1
    if text[line_start : entry.start].strip() or text[entry.end : line_end].strip():
        return entry.start, entry.end
    return line_start, line_end


def _with_note(text: str, start: int, end: int) -> tuple[int, int]:
    """The span of an entry's line, widened to the line before when that line is our note."""
    if start == 0 or text[start - 1] != "\n":
        return start, end
    before = text.rfind("\n", 0, start - 1) + 1
    line = text[before:start].strip()
    if line.startswith(f"<!-- {UNPROVED_MARK}") and line.endswith("-->") and line.count("-->") == 1:
        return before, end
    return start, end


def _anchor(text: str, removed: list[SrdfEntry], entries: list[SrdfEntry], shown: str) -> tuple[int, str]:
    """Where new entries go (a line start) and their indentation."""
    if removed:
        start = _with_note(text, *_line_span(text, removed[0]))[0]
        return start, _indent_at(text, removed[0].start)
    close = masked(text).rfind("</robot")  # the root's end tag, not one in a comment after it
    if close < 0:
        raise InputError(
            "<robot/> has no end tag to add disable_collisions before; write <robot ...></robot>", path=shown
        )
    line_start = text.rfind("\n", 0, close) + 1
    if text[line_start:close].strip():  # `</robot>` shares its line: start a new one
        return close, ""
    if entries:
        return line_start, _indent_at(text, entries[-1].start)
    child = re.search(r"\n([ \t]+)<", text)
    return line_start, child.group(1) if child else "  "


def _indent_at(text: str, offset: int) -> str:
    line_start = text.rfind("\n", 0, offset) + 1
    prefix = text[line_start:offset]
    return prefix if not prefix.strip() else ""


def load_srdf_text(path: Path, *, shown: str) -> str:
    """The SRDF at `path` as text (UTF-8, line endings untouched)."""
    try:
        return bounded_read.read_text(path, bounded_read.XML_BYTES, shown=shown)
    except FileNotFoundError:
        raise InputError("file not found", path=shown) from None
    except IsADirectoryError:
        raise InputError("is a folder; expected an SRDF file", path=shown) from None
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte {exc.start})", path=shown) from None
    except OSError as exc:
        raise InputError(f"cannot read: {exc.strerror or exc}", path=shown) from None
