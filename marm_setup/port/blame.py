"""A port's setup check failure, named where the source package says the value (issue 36).

`check_setup` names a key of the new marm_setup.yaml (`author.email`,
`joint_limits[j].max_velocity`); a port reads each key from a file of the source package and
its report item says which (`PortItem.source`, `file: element`). The error names that file and
element, not the SRDF the whole setup was once blamed on (a bad `.setup_assistant` author email
was reported as `config/x.srdf: author.email`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable

from marm_setup.errors import InputError
from marm_setup.port.port_log import PortItem

# (source file, setup key) -> the source's own field, `{}` the item's element: the author is
# one report item ("author") read from two fields
FIELDS = {
    (".setup_assistant", "author.name"): "moveit_setup_assistant_config.{}.author_name",
    (".setup_assistant", "author.email"): "moveit_setup_assistant_config.{}.author_email",
    ("package.xml", "author.name"): "maintainer",
    ("package.xml", "author.email"): "maintainer@email",
}


def blamed_on_source(
    exc: InputError, items: Iterable[PortItem], user_path: Callable[[str], str]
) -> InputError:
    """`exc` (naming a setup key as its element) naming instead the source file and element the
    port carried that key from, the key kept in the message; `exc` itself when no item says."""
    key = exc.element or ""
    item = _item_of(key, items)
    if item is None:
        return exc
    file, _, element = item.source.partition(": ")
    field = FIELDS.get((file, key))
    where = field.format(element) if field else element
    return InputError(
        f"{exc.message} (ported as marm_setup.yaml's {key})", path=user_path(file), element=where or None
    )


def _item_of(key: str, items: Iterable[PortItem]) -> PortItem | None:
    """The carried or changed item whose setting is `key` or holds it (`author` holds
    `author.email`), the most specific one."""
    found = [
        i
        for i in items
        if i.status in ("carried", "changed")
        and i.source
        and (key == i.setting or key.startswith((f"{i.setting}.", f"{i.setting}[")))
    ]
    return max(found, key=lambda i: len(i.setting), default=None)
