"""The 3D viewer the page embeds: MeshCat's built three.js viewer, read from the installed
`meshcat` package at run time (nothing of it is copied into this repository).

`main.min.js` is one self-contained script (three.js, OrbitControls, dat.GUI) that defines the
global `MeshCat` (`MeshCat.Viewer`, `MeshCat.THREE`); the page drives it through
`viewer.handle_command(...)` and its scene tree. MeshCat's own static export replays msgpack
commands the same way.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

from marm_setup.errors import MarmError

VIEWER_JS = ("viewer", "dist", "main.min.js")


def viewer_script() -> str:
    """The text of MeshCat's viewer script, made safe to inline in a `<script>` element."""
    spec = importlib.util.find_spec("meshcat")
    origin = spec.origin if spec is not None else None
    path = Path(origin).parent.joinpath(*VIEWER_JS) if origin else None
    if path is None or not path.is_file():
        raise MarmError("MeshCat's viewer script is missing (reinstall marm-setup: pip install meshcat)")
    return inline_script(path.read_text(encoding="utf-8"))


def inline_script(text: str) -> str:
    """`text` with every `</script` (any case) written `<\\/script`, which a script reads the
    same but which cannot end the element early."""
    out, low, start = [], text.lower(), 0
    while (k := low.find("</script", start)) >= 0:
        out += [text[start:k], "<\\/"]
        start = k + 2
    return "".join(out) + text[start:]
