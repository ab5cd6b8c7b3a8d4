"""Render config files from Jinja2 templates into memory (pure: no disk writes).

Templates live in `templates/` (checkout) or `marm_setup/templates/` (installed wheel). Each
output file has one template at a mirrored path; the per-target file lists below say which.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import jinja2
import yaml

from marm_setup.errors import MarmError


@dataclass(frozen=True, slots=True)
class RenderedFile:
    """One generated file: `path` relative to the package root, `content` ending in a newline."""

    path: str
    content: str


def templates_dir() -> Path:
    """The templates folder, installed (inside the package) or in a checkout."""
    here = Path(__file__).resolve().parent
    for candidate in (here / "templates", here.parent / "templates"):
        if candidate.is_dir():
            return candidate
    raise MarmError("templates folder not found (broken install?)", path=str(here))


def fmt_float(value: float) -> str:
    """Stable float text: shortest round-trip repr, always with a decimal point (YAML 1.1, which
    rosparam's PyYAML speaks, reads `1e-05` as a string but `1.0e-05` as a float), no -0."""
    value = float(value)
    if value == 0.0:
        return "0.0"
    if math.isinf(value) or math.isnan(value):
        raise ValueError(f"cannot render {value}")
    mantissa, e, exponent = repr(value).partition("e")
    if "." not in mantissa:
        mantissa += ".0"
    return f"{mantissa}{e}{exponent}"


def yaml_str(value: object) -> str:
    """A YAML scalar that parses back as the same string (quotes `on`, `1e3`, `null`, ...)."""
    text = str(value)
    dumped = yaml.safe_dump(text, default_flow_style=True, width=10**6).strip()
    return dumped.removesuffix("\n...").removesuffix("...").strip()


def yaml_bool(value: bool) -> str:
    return "true" if value else "false"


@lru_cache(maxsize=1)
def environment() -> jinja2.Environment:
    """The one Jinja environment: strict undefined, XML autoescape for .xml/.srdf/.launch."""
    env = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir())),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=jinja2.select_autoescape(
            enabled_extensions=("xml.j2", "srdf.j2", "launch.j2", "xacro.j2", "svg.j2"),
            default_for_string=False,
            default=False,
        ),
    )
    env.filters.update(fmt_float=fmt_float, yaml_str=yaml_str, yaml_bool=yaml_bool)
    return env


def render_template(name: str, **context: object) -> str:
    """Render one template; the result always ends with exactly one newline."""
    text = environment().get_template(name).render(**context)
    return text.rstrip("\n") + "\n"
