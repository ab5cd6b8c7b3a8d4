"""Docstrings, comments and docs name our modules by path (`collision/proof.py`) or dotted
(`marm_setup.collision.proof`): each one named must exist, so a rename cannot leave a stale
pointer behind."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PACKAGE = ROOT / "marm_setup"
SUBPACKAGES = sorted(p.name for p in PACKAGE.iterdir() if (p / "__init__.py").is_file())
PATH = re.compile(r"(?<![\w./-])(?:marm_setup/)?((?:" + "|".join(SUBPACKAGES) + r")/[\w/]+\.py)\b")
DOTTED = re.compile(r"(?<![\w.])marm_setup((?:\.\w+)+)")  # not `pkg.marm_setup.author`


def _texts() -> list[Path]:
    found = [*PACKAGE.rglob("*.py"), *(ROOT / "tests").rglob("*.py"), *(ROOT / "benchmarks").rglob("*.py")]
    found += [*ROOT.glob("*.md"), *(ROOT / "docs").rglob("*.md"), ROOT / "Makefile", ROOT / "pyproject.toml"]
    here = Path(__file__).resolve()
    return [p for p in found if p.is_file() and "goldens" not in p.parts and p != here]


def _dotted_exists(parts: list[str]) -> bool:
    """marm_setup.a.b.c names a package, a module, or an attribute of one."""
    here = PACKAGE
    for depth, part in enumerate(parts):
        if (here / part / "__init__.py").is_file():
            here = here / part
        elif (here / f"{part}.py").is_file():
            return True
        else:
            return depth > 0  # an attribute of the package reached (marm_setup.yaml is a file name)
    return True


def stale_references() -> list[str]:
    out = []
    for path in _texts():
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            where = f"{path.relative_to(ROOT)}:{number}"
            out += [f"{where}: {m[1]}" for m in PATH.finditer(line) if not (PACKAGE / m[1]).is_file()]
            out += [
                f"{where}: marm_setup{m[1]}"
                for m in DOTTED.finditer(line)
                if not m[1].startswith(".yaml") and not _dotted_exists(m[1].strip(".").split("."))
            ]
    return out


def test_every_module_named_exists():
    assert stale_references() == []


def test_a_stale_name_is_found(tmp_path):
    assert not _dotted_exists(["no_such_package", "module"])
    assert _dotted_exists(["collision", "proof"]) and _dotted_exists(["collision", "proof", "PairSearch"])
    assert PATH.search("see `collision/no_such_module.py`")[1] == "collision/no_such_module.py"
    assert not (PACKAGE / "collision/no_such_module.py").is_file()
