"""The report as one HTML file: the page template, its style and script, MeshCat's viewer, and
the content as JSON, all inline (no URL anywhere: it works offline and from a mail attachment)."""

from __future__ import annotations

import json

from marm_setup.report.viewer import inline_script, viewer_script
from marm_setup.templating import render_template, templates_dir

PAGE = "report/report.html.j2"
ASSETS = ("report/report.css", "report/report.js")


def render_page(content: dict) -> str:
    """The whole page for `content` (`report.content.page_content`)."""
    style, script = (templates_dir().joinpath(name).read_text(encoding="utf-8") for name in ASSETS)
    return render_template(
        PAGE,
        title=f"marm-setup report: {content['robot']}",
        style=style,
        viewer=viewer_script(),
        data=json_for_script(content),
        script=inline_script(script),
    )


def json_for_script(content: dict) -> str:
    """`content` as JSON that can sit inside a `<script>` element: ASCII, and `<`, `>`, `&`
    escaped as \\u003c etc. (JSON.parse reads them back), keys in the order built."""
    text = json.dumps(content, ensure_ascii=True, separators=(",", ":"), allow_nan=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")
