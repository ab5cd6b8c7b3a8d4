"""`marm-setup rules`: the catalogue of validate's rules (the registry), as text, JSON or Markdown."""

from __future__ import annotations

import enum
from typing import Annotated

import typer


class RulesFormat(str, enum.Enum):
    text = "text"
    json = "json"
    markdown = "markdown"


def rules(
    format: Annotated[
        RulesFormat, typer.Option("--format", help="text, json or markdown (docs/rules.md).")
    ] = RulesFormat.text,
) -> None:
    """List every rule validate can report: its id, severity and what MoveIt does with the defect."""
    from marm_setup.validate import rules_json, rules_markdown, rules_text

    show = {
        RulesFormat.text: rules_text,
        RulesFormat.json: rules_json,
        RulesFormat.markdown: rules_markdown,
    }[format]
    typer.echo(show(), nl=False)
