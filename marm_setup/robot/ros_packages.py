"""Find ROS packages on disk and resolve `package://`, `file://` and relative URIs."""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path

from lxml import etree

from marm_setup.errors import InputError, MeshNotFound, PackageNotFound

PackageMap = Mapping[str, Path]


def package_name(folder: Path) -> str | None:
    """The `<name>` in `folder/package.xml`, else None."""
    manifest = folder / "package.xml"
    if not manifest.is_file():
        return None
    try:
        name = etree.parse(str(manifest)).findtext("name")
    except (etree.XMLSyntaxError, OSError):
        return None
    return name.strip() if name else None


def _packages_below(root: Path, depth: int = 3) -> dict[str, Path]:
    """Packages at or below `root` (as ROS_PACKAGE_PATH is searched; a package is not entered)."""
    try:  # a folder we may not read holds no package we can use: skip it, as rospack does
        name = package_name(root)
        if name:
            return {name: root}
        if depth == 0 or not root.is_dir():
            return {}
        children = sorted(c for c in root.iterdir() if c.is_dir() and not c.name.startswith("."))
    except OSError:
        return {}
    found: dict[str, Path] = {}
    for child in children:
        for pkg, path in _packages_below(child, depth - 1).items():
            found.setdefault(pkg, path)
    return found


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
) -> dict[str, Path]:
    """Map package names to folders: `--package-path` first, then the env, then around `near`.

    Around `near` (a URDF): every enclosing folder holding a `package.xml`, and its siblings.
    """
    environ = os.environ if environ is None else environ
    found: dict[str, Path] = {}
    for given in package_paths:
        if not Path(given).is_dir():
            raise InputError("not a directory", path=str(given), element="--package-path")
    roots = [Path(p) for p in package_paths] + _env_roots(environ)
    for root in roots:
        for pkg, path in _packages_below(root.resolve()).items():
            found.setdefault(pkg, path)
    if near is not None:
        for folder in list(near.resolve().parents)[:4]:
            name = package_name(folder)
            if name:
                found.setdefault(name, folder)
                for pkg, path in _packages_below(folder.parent, depth=2).items():
                    found.setdefault(pkg, path)
    return found


def find_package(name: str, packages: PackageMap, *, path: str, element: str) -> Path:
    """The folder of package `name`, or an InputError listing where we looked."""
    if name in packages:
        return packages[name]
    known = ", ".join(sorted(packages)) or "none"
    raise PackageNotFound(
        f"unknown package '{name}' (known packages: {known}; add --package-path DIR)",
        package=name,
        path=path,
        element=element,
    )


def resolve_uri(uri: str, base_dir: Path, packages: PackageMap, *, path: str, element: str) -> Path:
    """Resolve a mesh URI to an existing file, or raise MeshNotFound / PackageNotFound naming
    where we looked."""
    if uri.startswith("package://"):
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
    return candidate.resolve()
