"""A MoveIt repository read at one ref through git (a bare mirror or a checkout): file text,
the commit, and the line a literal first occurs on (what a table row cites)."""

from __future__ import annotations

import subprocess
from dataclasses import dataclass
from pathlib import Path


class SourceError(Exception):
    """A file or a cited literal missing at the pinned ref: the tables would cite nothing."""


@dataclass(frozen=True, slots=True)
class GitRef:
    """One ref (`jazzy`, `noetic-devel`) of the git repository at `repo`."""

    repo: Path
    ref: str

    def _git(self, *args: str) -> str:
        done = subprocess.run(
            ["git", "-C", str(self.repo), *args], capture_output=True, text=True, check=False
        )
        if done.returncode != 0:
            raise SourceError(f"git {' '.join(args)}: {done.stderr.strip()}")
        return done.stdout

    def commit(self) -> str:
        return self._git("rev-parse", f"{self.ref}^{{commit}}").strip()

    def blob(self, path: str) -> str:
        """The object id of `path` (equal ids: byte-identical files)."""
        return self._git("rev-parse", f"{self.ref}:{path}").strip()

    def text(self, path: str) -> str:
        return self._git("show", f"{self.ref}:{path}")

    def files(self, suffix: str) -> list[str]:
        """Every path of the tree ending in `suffix`, sorted."""
        out = self._git("ls-tree", "-r", "--name-only", self.ref).splitlines()
        return sorted(p for p in out if p.endswith(suffix))

    def line_of(self, path: str, literal: str) -> int:
        """The 1-based line where `literal` first occurs in `path` (SourceError: nowhere)."""
        for number, line in enumerate(self.text(path).splitlines(), 1):
            if literal in line:
                return number
        raise SourceError(f"{self.ref}:{path}: no line holds {literal!r}")
