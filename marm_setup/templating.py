"""Render config files from Jinja2 templates into memory (pure: no disk writes).

Templates live in `templates/` (checkout) or `marm_setup/templates/` (installed wheel). Each
output file has one template at a mirrored path; the per-target file lists below say which.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import jinja2
import yaml

from marm_setup.errors import MarmError
from marm_setup.safe_yaml import load_yaml


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


# Plain scalars a YAML 1.2 reader (yaml-cpp in ROS 2, rclpy's PyYAML reads 1.1) takes for
# something other than a string: numbers (`1e3`, `0x1F`, `.5`), bools, null, infinities.
_YAML12_NOT_STRING = re.compile(
    r"[-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?|0x[0-9a-fA-F]+|0o[0-7]+|[-+]?\.(inf|Inf|INF)"
    r"|\.(nan|NaN|NAN)|true|True|TRUE|false|False|FALSE|null|Null|NULL|~",
)


def yaml_str(value: object) -> str:
    """A one-line YAML scalar that parses back as the same string, in YAML 1.1 and 1.2 alike.

    PyYAML's emitter chooses plain or quoted style (`on`, `a: b`, `#x` get quoted); anything it
    would spread over lines, and plain text YAML 1.2 reads as a number or bool, is double-quoted
    with escapes instead. The result is checked by parsing it back.
    """
    text = str(value)
    dumped = yaml.safe_dump([text], default_flow_style=True, width=2**30, allow_unicode=True)
    out = dumped.strip()[1:-1]
    if not out.isprintable() or (out == text and _YAML12_NOT_STRING.fullmatch(text)):
        out = _double_quoted(text)
    if load_yaml(f"[{out}]") != [text]:
        raise ValueError(f"cannot write {text!r} as a YAML string")
    return out


def _double_quoted(text: str) -> str:
    """A YAML double-quoted scalar: printable characters as they are, the rest as escapes."""
    out = []
    for c in text:
        code = ord(c)
        if c in '"\\':
            out.append("\\" + c)
        elif c.isprintable():
            out.append(c)
        else:
            out.append(
                f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}" if code < 0x10000 else f"\\U{code:08x}"
            )
    return '"' + "".join(out) + '"'


def py_repr(value: object) -> str:
    """A Python literal of a string (for generated scripts): `repr`, never a code fragment;
    double-quoted where that needs no escape (the style ruff and black write)."""
    literal = repr(str(value))
    if literal.startswith("'") and '"' not in literal:
        literal = f'"{literal[1:-1]}"'  # repr single-quotes only text without ' (or with both)
    return literal


def xml_comment(value: object) -> str:
    """Text safe inside an XML comment: no `--` and no trailing `-` (XML 1.0 §2.5)."""
    text = str(value)
    while "--" in text:
        text = text.replace("--", "- -")
    return text + " " if text.endswith("-") else text


def xacro_text(value: object) -> str:
    """Text xacro leaves as it is: xacro evaluates `${...}` and `$(...)` in text and attributes
    and reads `$${` / `$$(` as the literal `${` / `$(` (xacro __init__.py, eval_text's
    DOLLAR_DOLLAR_BRACE), so each run of '$' before '{' or '(' gets one more. XML escaping is the
    template's (autoescape)."""
    return re.sub(r"(\$+)(?=[{(])", r"$\1", str(value))


def yaml_bool(value: bool) -> str:
    return "true" if value else "false"


def yaml_scalar(value: str | bool | int | float) -> str:
    """A parameter value as YAML of its own type: a string, a bool, an int, a float (`1.0`)."""
    if isinstance(value, str):
        return yaml_str(value)
    if isinstance(value, bool):
        return yaml_bool(value)
    return str(value) if isinstance(value, int) else fmt_float(value)


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
    env.filters.update(
        fmt_float=fmt_float,
        yaml_str=yaml_str,
        yaml_bool=yaml_bool,
        yaml_scalar=yaml_scalar,
        py_repr=py_repr,
        xml_comment=xml_comment,
        xacro_text=xacro_text,
    )
    return env


def render_template(name: str, **context: object) -> str:
    """Render one template; the result always ends with exactly one newline."""
    text = environment().get_template(name).render(**context)
    return text.rstrip("\n") + "\n"
