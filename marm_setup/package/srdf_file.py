"""The SRDF: read once (a `.srdf.xacro` expanded by xacro with its args first) into the setup
model's `Srdf`, plus what only the XML shows (pairs written twice, passive joints inside a group)."""

from __future__ import annotations

import dataclasses
import os
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from marm_setup.errors import InputError, MarmError, remedy
from marm_setup.findings import Finding, error, warning
from marm_setup.untrusted import CodeNotRun

if TYPE_CHECKING:
    from lxml import etree

    from marm_setup.setup import Srdf


@dataclass(frozen=True, slots=True)
class NestedPassiveJoint:
    """A `<passive_joint>` inside a `<group>` (srdfdom reads them only under `<robot>`)."""

    group: str
    joint: str


@dataclass(frozen=True)
class SrdfFile:
    """The chosen SRDF: its path (relative to the package), its xacro args, the parsed `srdf`
    (None when unreadable) and its (expanded) text."""

    path: str
    xacro_args: tuple[tuple[str, str], ...] = ()
    srdf: Srdf | None = None
    text: str | None = None
    duplicate_pairs: tuple[tuple[str, str, int], ...] = ()  # (link1, link2, times written)
    nested_passive_joints: tuple[NestedPassiveJoint, ...] = ()
    skipped_groups: frozenset[str] = frozenset()  # groups srdfdom leaves out (their finding says why)
    xacro_declared: frozenset[str] | None = None  # the args a .srdf.xacro takes; None for a plain SRDF


def read_srdf_file(
    root: Path,
    rel: str,
    paths: tuple[Path, ...],
    problems: list[Finding],
    args: dict[str, str],
    unread: tuple[str, ...] = (),
    built: tuple[tuple[str, str], ...] = (),
) -> SrdfFile:
    """The SRDF at `rel`; what cannot be read becomes findings in `problems` (`srdf.parse`,
    `srdf.unsupported`; `srdf.runtime-arg` when its xacro needs one of the `unread` args, whose
    value only the launch file's run time gives, or one of the `built` args, whose value only
    the package's CMake build gives)."""
    from marm_setup.setup import parse_srdf_document

    xacro_args = tuple(sorted(args.items()))
    skipped: list[InputError] = []
    try:
        text, declared = _srdf_text(root / rel, rel, paths, args)
        srdf, xml = parse_srdf_document(text, rel, skipped)
    except CodeNotRun:  # --untrusted: its xacro did not run (the summary says so)
        return SrdfFile(rel, xacro_args)
    except MarmError as exc:
        problems.append(_unreadable(rel, exc, unread, built))
        return SrdfFile(rel, xacro_args)
    problems += [_skipped_element(rel, exc) for exc in skipped]
    gone = frozenset(_group_name(exc.element or "") for exc in skipped) - {None}
    return SrdfFile(
        rel,
        xacro_args,
        _without_groups(srdf, gone),  # type: ignore[arg-type]
        text,
        _duplicate_pairs(xml),
        _nested_passive_joints(xml),
        gone,  # type: ignore[arg-type]
        declared,
    )


def _unreadable(
    rel: str, exc: MarmError, unread: tuple[str, ...], built: tuple[tuple[str, str], ...] = ()
) -> Finding:
    """An SRDF that does not expand: an error, unless what it lacks is an arg the launch file
    passes a value validate cannot read (then the run time has it: a warning), or one the
    package's build gives it from a CMake variable (`xacro_add_files(... REMAP name:=${var})`,
    package.cmake_xacro: the installed SRDF has it, a warning too)."""
    from marm_setup.package.launch_python import undefined_unread_arg

    cmake = undefined_unread_arg(exc.message, tuple(name for name, _ in built))
    if cmake is not None:
        msg = (
            f"not read: its xacro needs {cmake}:=, which the package's build gives it "
            f"(CMakeLists.txt xacro_add_files REMAP {cmake}:={dict(built)[cmake]}) from a value validate "
            "does not know"
        )
        return warning(
            "srdf.runtime-arg", rel, exc.element or "", msg, f"pass --xacro-arg {cmake}:=VALUE to read it"
        )
    arg = undefined_unread_arg(exc.message, unread)
    if arg is None:
        return error("srdf.parse", rel, exc.element or "", exc.message, remedy(exc.needs))
    msg = (
        f"not read: its xacro needs {arg}:=, which the launch file sets from a value only the run time gives"
    )
    return warning(
        "srdf.runtime-arg", rel, exc.element or "", msg, f"pass --xacro-arg {arg}:=VALUE to read it"
    )


def _srdf_text(
    file: Path, rel: str, paths: tuple[Path, ...], args: dict[str, str]
) -> tuple[str, frozenset[str] | None]:
    """The SRDF's text (a `.srdf.xacro` expanded) and the xacro args it takes (None: plain)."""
    if not rel.endswith(".xacro"):
        from marm_setup.bounded_read import XML_BYTES, read_text

        try:
            return read_text(file, XML_BYTES, shown=rel), None
        except (OSError, UnicodeDecodeError) as exc:
            raise InputError(f"cannot read: {exc}", path=rel) from None
    from marm_setup.setup import expand_srdf_xacro

    out = expand_srdf_xacro(file, args, paths, shown=rel)
    return out.xml, frozenset(out.declared)


def _skipped_element(rel: str, exc: InputError) -> Finding:
    """An SRDF element left out: srdfdom also skips one missing an attribute (logging an error);
    a form srdfdom reads but this validator does not model is only not checked. A virtual joint
    srdfdom skips (srdfdom src/model.cpp `loadVirtualJoints`) leaves MoveIt its default: a fixed
    root joint (moveit/moveit `moveit_core/robot_model/src/robot_model.cpp` l.972-976,
    "Assuming fixed joint"), and MoveIt plans: a warning."""
    if "not supported" in exc.message:
        return warning("srdf.unsupported", rel, exc.element or "", f"not checked: {exc.message}")
    if (exc.element or "").split("[", 1)[0] == "virtual_joint":
        msg = f"{exc.message} (srdfdom skips this element: MoveIt assumes a fixed root joint)"
        return warning("srdf.parse", rel, exc.element or "", msg)
    return error("srdf.parse", rel, exc.element or "", f"{exc.message} (srdfdom skips this element)")


def _group_name(element: str) -> str | None:
    return element[len("group[") : -1] if element.startswith("group[") and element.endswith("]") else None


def _without_groups(srdf: Srdf, gone: frozenset[str]) -> Srdf:
    """Poses and end effectors of a group left out are left out too (no cascade of 'unknown group')."""
    if not gone:
        return srdf
    return dataclasses.replace(
        srdf,
        group_states=tuple(s for s in srdf.group_states if s.group not in gone),
        end_effectors=tuple(
            e for e in srdf.end_effectors if e.group not in gone and e.parent_group not in gone
        ),
    )


def _duplicate_pairs(root: etree._Element) -> tuple[tuple[str, str, int], ...]:
    from marm_setup.collision import link_pair

    counts = Counter(
        link_pair(e.get("link1", ""), e.get("link2", "")) for e in root.iterchildren("disable_collisions")
    )
    return tuple((a, b, n) for (a, b), n in sorted(counts.items()) if n > 1)


def _nested_passive_joints(root: etree._Element) -> tuple[NestedPassiveJoint, ...]:
    return tuple(
        NestedPassiveJoint(group.get("name", ""), elem.get("name", ""))
        for group in root.iterchildren("group")
        for elem in group.iterchildren("passive_joint")
    )


def srdf_robot_name(root: Path, rel: str | None) -> str | None:
    """The `<robot name>` of the SRDF (what MoveItConfigsBuilder and launch files pair a URDF by)."""
    if rel is None:
        return None
    from lxml import etree

    from marm_setup.bounded_read import XML_BYTES

    try:
        with open(root / rel, "rb") as stream:  # closed also when the first element returns
            if os.fstat(stream.fileno()).st_size > XML_BYTES:
                return None  # reading the SRDF says so
            for _event, elem in etree.iterparse(stream, events=("start",)):
                return elem.get("name") or None
    except (etree.XMLSyntaxError, OSError):
        return None
    return None


FIND_PREFIXES = ("$(find ", "$(find-pkg-share ")


def srdf_includes(root: Path, rel: str) -> tuple[str, ...]:
    """The package-relative paths a `.srdf.xacro` includes (`xacro:include filename`, relative to
    its folder or `$(find pkg)/...`, taken as this package's); none for a plain SRDF, an
    unreadable one, or a filename built from args."""
    if not rel.endswith(".xacro"):
        return ()
    from lxml import etree

    from marm_setup.bounded_read import XML_BYTES

    try:
        if os.path.getsize(root / rel) > XML_BYTES:
            return ()
        tree = etree.parse(str(root / rel), etree.XMLParser(resolve_entities=False, no_network=True))
    except (etree.XMLSyntaxError, OSError):
        return ()
    names = (
        elem.get("filename", "")
        for elem in tree.iter()
        if isinstance(elem.tag, str) and elem.tag.endswith("}include") and "xacro" in elem.tag
    )
    return tuple(path for name in names if (path := _included_path(rel, name)) is not None)


def _included_path(rel: str, name: str) -> str | None:
    for prefix in FIND_PREFIXES:
        if name.startswith(prefix) and ")/" in name:
            name = name.split(")/", 1)[1]
            break
    else:
        name = os.path.join(os.path.dirname(rel), name)
    if "$(" in name or "${" in name:
        return None
    return os.path.normpath(name).replace(os.sep, "/")
