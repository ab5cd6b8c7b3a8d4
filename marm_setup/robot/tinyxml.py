"""XML text as tinyxml2 reads it, for parsing with lxml: what MoveIt's parsers (srdfdom, urdfdom)
accept and libxml2 refuses."""

from __future__ import annotations

import re
from typing import TypeVar

_Text = TypeVar("_Text", str, bytes)

_COMMENT = re.compile(r"<!--(.*?)-->", re.DOTALL)
_COMMENT_BYTES = re.compile(rb"<!--(.*?)-->", re.DOTALL)


def tinyxml_comments(text: _Text) -> _Text:
    """`text` with each comment's inside blanked where libxml2 and tinyxml2 part: tinyxml2 ends
    a comment at the first `-->` and takes any `--` or a last `-` before it (tinyxml2.cpp
    l.1322-1330 at leethomason/tinyxml2@3dcad8e), which libxml2 refuses. srdfdom (src/model.cpp
    l.729-730 at moveit/srdfdom@148991a, ros2; l.708-709 at e23af6e, noetic) and urdfdom
    (urdf_parser/src/model.cpp l.97-98 at ros/urdfdom@9a1f5b4) parse with tinyxml2, so MoveIt
    reads such a file. Same length, same lines: every offset and line number stays; anything
    else malformed is still refused."""
    if isinstance(text, bytes):
        return _COMMENT_BYTES.sub(lambda m: b"<!--" + m[1].replace(b"-", b" ") + b"-->", text)
    return _COMMENT.sub(lambda m: "<!--" + m[1].replace("-", " ") + "-->", text)
