"""Find ROS packages on disk and resolve `package://`, `file://` and relative URIs.

A package is found by its `package.xml` `<name>` first (as ROS does), then by a folder of that
name under a search root (as pinocchio, yourdfpy and MuJoCo's tools resolve `package://`: pip
`share/` trees and vendor checkouts often have no or another `package.xml`). The index records
which way each package it handed out was found, for `inspect` to say.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from marm_setup import bounded_read
from marm_setup.bounded_read import FileTooLarge
from marm_setup.errors import InputError, MeshNotFound, PackageNotFound
from marm_setup.untrusted import excerpt, readable

BY_MANIFEST, BY_FOLDER = "package.xml", "folder name"
SEARCH_DEPTH = 3  # folder levels below a search root, as deep as packages are looked for


@dataclass(frozen=True, slots=True)
class PackageUse:
    """A package a robot description used: where it is and how it was found."""

    name: str
    path: str
    found_by: str  # BY_MANIFEST | BY_FOLDER


@dataclass
class PackageIndex(Mapping[str, Path]):
    """Packages by `package.xml` name, with the folder-name fallback under `roots`.

    Iterating lists the `package.xml` packages only (the folder fallback is found on demand).
    """

    manifests: dict[str, Path] = field(default_factory=dict)
    roots: tuple[tuple[Path, int], ...] = ()  # (folder, levels below it to look at)
    used: dict[str, PackageUse] = field(default_factory=dict)

    def __getitem__(self, name: str) -> Path:
        found = self.lookup(name)
        if found is None:
            raise KeyError(name)
        return found

    def __iter__(self) -> Iterator[str]:
        return iter(self.manifests)

    def __len__(self) -> int:
        return len(self.manifests)

    def __contains__(self, name: object) -> bool:
        return isinstance(name, str) and self.lookup(name) is not None

    def lookup(self, name: str) -> Path | None:
        """The package's folder (recording how it was found), or None."""
        if name in self.manifests:
            return self._use(name, self.manifests[name], BY_MANIFEST)
        for root, depth in self.roots:
            folder = _folder_below(root, name, depth)
            if folder is not None:
                return self._use(name, folder, BY_FOLDER)
        return None

    def _use(self, name: str, path: Path, how: str) -> Path:
        self.used.setdefault(name, PackageUse(name, str(path), how))
        return path


PackageMap = Mapping[str, Path]


def package_name(folder: Path) -> str | None:
    """The `<name>` in `folder/package.xml`, else None."""
    manifest = folder / "package.xml"
    if not manifest.is_file():
        return None
    try:
        data = bounded_read.read_bytes(manifest, bounded_read.XML_BYTES)
        name = etree.fromstring(data, base_url=str(manifest)).findtext("name")
    except (etree.XMLSyntaxError, OSError, FileTooLarge):
        return None
    return name.strip() if name else None


def exported_plugin_classes(packages: PackageIndex) -> frozenset[str]:
    """The plugin lookup names the `package.xml` packages of `packages` export: each
    `<export><base_package plugin="${prefix}/file.xml"/></export>` entry names a description
    file whose `<class name=...>` (else `type`) pluginlib finds the class by, whatever the
    name's prefix (pluginlib class_loader_imp.hpp getPluginXmlPaths, processXMLFile). Files
    outside their package or unreadable are skipped."""
    found: set[str] = set()
    for folder in packages.manifests.values():
        for described in _plugin_files(folder):
            found.update(_plugin_class_names(described))
    return frozenset(found)


def _plugin_files(folder: Path) -> list[Path]:
    parser = etree.XMLParser(resolve_entities=False, no_network=True)
    try:
        data = bounded_read.read_bytes(folder / "package.xml", bounded_read.XML_BYTES)
        export = etree.fromstring(data, parser).find("export")
    except (etree.XMLSyntaxError, OSError, FileTooLarge):
        return []
    out = []
    for entry in export if export is not None else ():
        plugin = entry.get("plugin") if isinstance(entry.tag, str) else None
        if plugin:
            path = Path(plugin.replace("${prefix}", str(folder))).resolve()
            if path.is_relative_to(folder.resolve()):
                out.append(path)
    return out


def _plugin_class_names(described: Path) -> list[str]:
    parser = etree.XMLParser(resolve_entities=False, no_network=True)
    try:
        root = etree.fromstring(bounded_read.read_bytes(described, bounded_read.XML_BYTES), parser)
    except (etree.XMLSyntaxError, OSError, FileTooLarge):
        return []
    classes = root.iter("class")
    return [name for c in classes if (name := c.get("name") or c.get("type"))]


def _subfolders(folder: Path) -> list[Path]:
    try:
        return sorted(c for c in folder.iterdir() if c.is_dir() and not c.name.startswith("."))
    except OSError:
        return []


def _first_visit(folder: Path, depth: int, visited: dict[tuple[int, int], int]) -> bool:
    """Whether `folder` is new to this search, or now to be searched deeper than before: a
    folder reached again through a symlink (`ln -s . loop`) is searched once, so 150 links to
    `.` cost 150 look-ups, not 150**3."""
    try:
        info = folder.stat()
    except OSError:
        return False
    key = (info.st_dev, info.st_ino)
    if visited.get(key, -1) >= depth:
        return False
    visited[key] = depth
    return True


def _packages_below(
    root: Path, depth: int = SEARCH_DEPTH, visited: dict[tuple[int, int], int] | None = None
) -> dict[str, Path]:
    """Packages at or below `root` (as ROS_PACKAGE_PATH is searched; a package is not entered;
    each folder once, however many symlinks lead to it)."""
    visited = {} if visited is None else visited
    try:  # a folder we may not read holds no package we can use: skip it, as rospack does
        if not _first_visit(root, depth, visited):
            return {}
        name = package_name(root)
        if name:
            return {name: root}
        if depth == 0 or not root.is_dir():
            return {}
        children = _subfolders(root)
    except OSError:
        return {}
    found: dict[str, Path] = {}
    for child in children:
        for pkg, path in _packages_below(child, depth - 1, visited).items():
            found.setdefault(pkg, path)
    return found


def _folder_below(root: Path, name: str, depth: int) -> Path | None:
    """`root` if it is named `name`, else the first folder named `name` below it (breadth first;
    each folder once, however many symlinks lead to it)."""
    level: list[Path] = [root]
    visited: dict[tuple[int, int], int] = {}
    for remaining in range(depth, -1, -1):
        for folder in level:
            if folder.name == name and folder.is_dir() and not _holds_packages(folder):
                return folder
        level = [c for f in level if _first_visit(f, remaining, visited) for c in _subfolders(f)]
    return None


def _holds_packages(folder: Path, depth: int = 2) -> bool:
    """`folder` has no package.xml but packages lie below it (within `depth` levels): a
    repository or workspace folder, never a package, as packages do not nest (catkin_pkg
    src/catkin_pkg/packages.py `find_package_paths`: a package.xml ends the descent)."""
    if (folder / "package.xml").is_file():
        return False
    level = _subfolders(folder)
    for _ in range(depth):
        if any((child / "package.xml").is_file() for child in level):
            return True
        level = [c for f in level for c in _subfolders(f)]
    return False


def _env_roots(environ: Mapping[str, str]) -> list[Path]:
    roots = [Path(p) for p in environ.get("ROS_PACKAGE_PATH", "").split(os.pathsep) if p]
    for prefix in environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep):
        if prefix:
            roots.append(Path(prefix) / "share")
    return roots


def find_packages(
    package_paths: Iterable[str | Path],
    near: Path | None = None,
    environ: Mapping[str, str] | None = None,
) -> PackageIndex:
    """Index packages: the packages enclosing `near` (a URDF's own `package://` is its own
    package, wherever a copy of it lies), then `--package-path`, then the env, then the
    siblings of those enclosing packages. The folder-name fallback also looks at the folders
    enclosing `near` and their children.
    """
    environ = os.environ if environ is None else environ
    for given in package_paths:
        if not Path(given).is_dir():
            raise InputError("not a directory", path=str(given), element="--package-path")
    roots = [Path(p).resolve() for p in package_paths] + [p.resolve() for p in _env_roots(environ)]
    index = PackageIndex(roots=tuple((root, SEARCH_DEPTH) for root in roots))
    for folder in list(near.resolve().parents)[:4] if near is not None else ():
        name = package_name(folder)
        if name:
            index.manifests.setdefault(name, folder)
    for root in roots:
        for pkg, path in _packages_below(root).items():
            index.manifests.setdefault(pkg, path)
    if near is not None:
        around = list(near.resolve().parents)[:4]
        for folder in around:
            name = package_name(folder)
            if name:
                index.manifests.setdefault(name, folder)
                for pkg, path in _packages_below(folder.parent, depth=2).items():
                    index.manifests.setdefault(pkg, path)
        index.roots += tuple((folder, 1) for folder in around)
    return index


def find_package(name: str, packages: PackageMap, *, path: str, element: str) -> Path:
    """The folder of package `name`, or an InputError listing where we looked."""
    found = packages.lookup(name) if isinstance(packages, PackageIndex) else packages.get(name)
    if found is not None:
        return found
    known = ", ".join(sorted(packages)) or "none"
    raise PackageNotFound(
        f"unknown package '{name}' (no package.xml or folder of that name; known packages: {known})",
        package=name,
        path=path,
        element=element,
    )


def resolve_uri(uri: str, base_dir: Path, packages: PackageMap, *, path: str, element: str) -> Path:
    """Resolve a mesh URI to an existing file, or raise MeshNotFound / PackageNotFound naming
    where we looked."""
    if uri.startswith("package:///"):
        candidate = _unnamed_package_file(uri[len("package:///") :], base_dir, packages)
    elif uri.startswith("package://"):
        pkg, _, rest = uri[len("package://") :].partition("/")
        candidate = find_package(pkg, packages, path=path, element=element) / rest
    elif uri.startswith("file://"):
        candidate = Path(uri[len("file://") :])
    else:
        candidate = Path(uri) if Path(uri).is_absolute() else base_dir / uri
    if not candidate.is_file():
        raise MeshNotFound(
            f"mesh '{uri}' not found (looked at {candidate})", uri=uri, path=path, element=element
        )
    if not readable(candidate):
        raise MeshNotFound(
            f"mesh '{excerpt(uri)}' lies outside the package: not read (--untrusted reads nothing outside it)",
            uri=uri,
            path=path,
            element=element,
        )
    return candidate.resolve()


def _unnamed_package_file(rest: str, base_dir: Path, packages: PackageMap) -> Path:
    """`package:///a/b.stl` (no package name) as pinocchio reads it (`retrieveResourcePath`: the
    path below each package directory): the first of the package search roots, then the folders
    enclosing the URDF, that holds `a/b.stl` (example-robot-data's talos_full_v2 names its
    meshes so); else the path below the first root, for the not-found message."""
    roots = [root for root, _ in packages.roots] if isinstance(packages, PackageIndex) else []
    folders = [*roots, *base_dir.resolve().parents]
    found = next((f / rest for f in folders if (f / rest).is_file()), None)
    return found if found is not None else (folders[0] if folders else base_dir) / rest


def description_file(ref: str, base: Path, package_paths: Iterable[str | Path] = ()) -> Path:
    """The robot description a setup names: `package://pkg/path` (looked up in `package_paths`
    that exist, the environment and around `base`, so a package moved into a workspace next to
    its description still finds it), else a path relative to `base` (or absolute)."""
    if not ref.startswith("package://"):
        candidate = Path(ref)
        return candidate if candidate.is_absolute() else base / candidate
    pkg, _, rest = ref[len("package://") :].partition("/")
    usable = [p for p in package_paths if Path(p).is_dir()]
    index = find_packages(usable, near=base / "marm_setup.yaml")
    return find_package(pkg, index, path=str(base / "marm_setup.yaml"), element="robot.urdf") / rest


def misspelt_package(name: str, known: Iterable[str]) -> str | None:
    """The package of `known` that `name` (a package no path holds) misspells, if any: one or two
    letters apart (inserted, dropped or changed). Then `name` is a typo, not a ROS package
    installed elsewhere; a name `known` holds is no typo."""
    names = set(known)
    if name in names:
        return None
    close = sorted((_edits(name, k), k) for k in names if abs(len(k) - len(name)) <= 2)
    return close[0][1] if close and close[0][0] <= min(2, len(name) // 4) else None


def _edits(a: str, b: str) -> int:
    """Levenshtein distance (names are short)."""
    row = list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        prev, row[0] = row[0], i
        for j, cb in enumerate(b, 1):
            prev, row[j] = row[j], min(row[j] + 1, row[j - 1] + 1, prev + (ca != cb))
    return row[-1]
