"""The one place a config package's YAML files are opened and parsed.

`PackageFiles` reads a file once (cached), measured by `bounded_read` before it is read, through
`safe_yaml`'s bounds and rosparam's tags,
substituting roslaunch args first where a launch file loads it with `subst_value`. A file that
cannot be read or parsed is a finding in `problems` (`yaml.parse`, `yaml.substitution`), never
an exception: each rule family runs on what could be read.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import yaml

from marm_setup.bounded_read import YAML_BYTES, FileTooLarge, read_text
from marm_setup.findings import Finding, error, warning
from marm_setup.package.rosparam import RosparamLoader
from marm_setup.package.substitution import Scope, SubstitutionError, substitute
from marm_setup.package.where import Located, Where
from marm_setup.safe_yaml import load_yaml_lines
from marm_setup.untrusted import PathEscape, SymlinkEscape, confined

IGNORED_PARTS = (".git", "__pycache__")


SYMLINK_HINT = "pass --package-path DIR to read files under DIR"
PATH_HINT = "name a file inside the package, by a relative path without '..'"


class FileProblem(Exception):
    """A file that exists but cannot be read (permissions, encoding, size)."""


class OutsidePackage(FileProblem):
    """A path that leads outside the package and the folders the user named: not read."""


class PackageFiles:
    """Reads the files of the package at `root` (relative paths), recording failures. A file is
    read only inside `root` or the `allowed` folders the user named (untrusted.confined): a
    symlink or a path leaving them is a `package.outside` warning naming it, never read."""

    def __init__(self, root: Path, problems: list[Finding], allowed: tuple[Path, ...] = ()):
        self.root = root
        self.problems = problems
        self.allowed = allowed
        self.scopes: dict[str, Scope] = {}  # files a launch file loads with subst_value
        # files a launch file reads through ReplaceString: (key, value) pairs, in order
        self.replacements: dict[str, tuple[tuple[str, str], ...]] = {}
        self._yaml: dict[str, Located | None] = {}
        self._refused: set[tuple[str, str]] = set()

    def refused(self, rel: str, file: str | None = None, element: str = "") -> bool:
        """Whether `rel` (named by `file`'s `element`, default: the file itself) leads outside
        the package and the allowed folders; the first time, a `package.outside` warning."""
        try:
            confined(self.root, rel, self.allowed, shown=file or rel, element=element)
            return False
        except PathEscape as exc:
            hint = SYMLINK_HINT if isinstance(exc, SymlinkEscape) else PATH_HINT
            if (exc.path or "", element) not in self._refused:
                self._refused.add((exc.path or "", element))
                self.problems.append(warning("package.outside", exc.path or rel, element, exc.message, hint))
            return True

    def inside_only(self, rels: Iterable[str]) -> tuple[str, ...]:
        """`rels` without those leading outside (each one a `package.outside` warning)."""
        return tuple(rel for rel in rels if not self.refused(rel))

    def path(self, rel: str) -> Path:
        return self.root / rel

    def is_file(self, rel: str) -> bool:
        return self.path(rel).is_file()

    def glob(self, pattern: str) -> list[str]:
        """Relative paths of the files matching `pattern` (sorted)."""
        return sorted(p.relative_to(self.root).as_posix() for p in self.root.glob(pattern) if p.is_file())

    def listing(self) -> tuple[str, ...]:
        """Every file of the package (relative, sorted), version control and caches left out."""
        out = []
        for p in sorted(self.root.rglob("*")):
            rel = p.relative_to(self.root).as_posix()
            if p.is_file() and not any(part in IGNORED_PARTS for part in Path(rel).parts):
                out.append(rel)
        return self.inside_only(out)

    def text(self, rel: str, limit: int = YAML_BYTES) -> str | None:
        """The file's text, None when absent; FileProblem when it cannot be read or is over
        `limit` bytes (bounded_read's bound of its kind)."""
        file = self.path(rel)
        if not file.is_file():
            return None
        if self.refused(rel):
            raise OutsidePackage(f"{rel} leads outside the package")
        try:
            return read_text(file, limit, shown=rel)
        except FileTooLarge as exc:
            raise FileProblem(exc.message) from None
        except (OSError, UnicodeDecodeError) as exc:
            raise FileProblem(str(exc)) from None

    def yaml(self, rel: str) -> Located | None:
        """The parsed YAML of `rel` (an empty file reads as `{}`), or None when absent or broken."""
        if rel not in self._yaml:
            self._yaml[rel] = self._load(rel)
        return self._yaml[rel]

    def _load(self, rel: str) -> Located | None:
        try:
            text = self.text(rel)
            if text is None:
                return None
            if rel in self.replacements:
                text = replaced(text, self.replacements[rel])
            if rel in self.scopes:
                text = substitute(text, self.scopes[rel])
            data, lines = load_yaml_lines(text, RosparamLoader)
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            where = f"line {mark.line + 1}" if mark is not None else ""
            self.problems.append(error("yaml.parse", rel, where, f"malformed YAML: {_yaml_message(exc)}"))
            return None
        except SubstitutionError as exc:
            msg = f"cannot evaluate {exc} (loaded with subst_value): its rules were skipped"
            self.problems.append(warning("yaml.substitution", rel, "", msg))
            return None
        except OutsidePackage:  # its package.outside warning says so
            return None
        except FileProblem as exc:
            self.problems.append(error("yaml.parse", rel, "", f"cannot read: {exc}"))
            return None
        return Located(Where(rel), {} if data is None else data, lines)


def replaced(text: str, pairs: tuple[tuple[str, str], ...]) -> str:
    """`text` as nav2_common's ReplaceString writes it: each line gets each (key, value) pair's
    replacement in turn (ros-navigation/navigation2 nav2_common/launch/replace_string.py
    `ReplaceString.replace`). FileProblem past the YAML files' bound, measured before each
    replacement is made."""
    out, size = [], 0
    for line in text.splitlines(keepends=True):
        for key, value in pairs:
            grown = len(line) + line.count(key) * (len(value) - len(key))
            if size + grown > YAML_BYTES:
                raise FileProblem(
                    f"its text after the launch file's ReplaceString is over {YAML_BYTES:,} bytes"
                )
            line = line.replace(key, value)
        out.append(line)
        size += len(line)
    return "".join(out)


def located_text(text: str, file: str) -> Located:
    """YAML text as a file of the package named `file` would read (rosparam's tags included);
    raises yaml.YAMLError. For a file's text at hand (tests, tools)."""
    data, lines = load_yaml_lines(text, RosparamLoader)
    return Located(Where(file), {} if data is None else data, lines)


def _yaml_message(exc: yaml.YAMLError) -> str:
    problem = getattr(exc, "problem", None)
    return str(problem) if problem else str(exc).splitlines()[0]
