"""`validate` over every published package a folder holds, as a new user types it: for each
MoveIt config package (a folder with package.xml whose name ends in moveit_config or config),
the robot and SRDF it loaded and where from, its errors by rule, and the exit code; then the
same with the folder as --package-path. Prints one line per package and run, then totals.

Run: .venv/bin/python benchmarks/sweep_validate.py [FOLDER ...]   (default: ../shared/realworld*)
A count to compare before -> after a change to validate (false errors are read off the rules).
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared"
CLI = [sys.executable, "-m", "marm_setup.cli.app"]


def config_packages(folder: Path) -> list[Path]:
    """MoveIt config packages below `folder` (a package.xml beside a config/ with an SRDF)."""
    found = {p.parent for p in folder.rglob("package.xml") if _is_config(p.parent)}
    return sorted(found)


def _is_config(pkg: Path) -> bool:
    return (
        any(pkg.glob("config/*.srdf*")) or any(pkg.glob("srdf/*.srdf*")) or any(pkg.glob("config/*/*.srdf*"))
    )


def run(pkg: Path, paths: tuple[Path, ...]) -> dict:
    args = [*CLI, "validate", str(pkg), "--no-plan", "--format", "json"]
    for folder in paths:
        args += ["--package-path", str(folder)]
    start = time.perf_counter()
    done = subprocess.run(args, capture_output=True, text=True, timeout=900, check=False)
    seconds = time.perf_counter() - start
    try:
        doc = json.loads(done.stdout)
    except json.JSONDecodeError:
        return {"exit": done.returncode, "seconds": seconds, "crash": done.stderr.strip()[-200:]}
    return {"exit": done.returncode, "seconds": seconds, **doc}


def line(name: str, how: str, result: dict) -> str:
    if "crash" in result:
        return f"{name:48} {how:6} exit {result['exit']}  {result['crash']}"
    checked = result.get("validated", {})
    errors = Counter(f["rule"] for f in result.get("findings", []) if f["severity"] == "error")
    robot = checked.get("robot") or "-"
    origin = checked.get("urdf_origin", "")
    return (
        f"{name:48} {how:6} exit {result['exit']} {result['seconds']:5.1f}s robot {robot:18} "
        f"from {origin[:50]:50} errors {dict(errors)}"
    )


def main(folders: list[Path]) -> None:
    totals: Counter = Counter()
    for folder in folders:
        for pkg in config_packages(folder):
            name = pkg.relative_to(folder.parent).as_posix()
            for how, paths in (("bare", ()), ("paths", (folder,))):
                result = run(pkg, paths)
                print(line(name, how, result), flush=True)
                totals[f"{how} runs"] += 1
                totals[f"{how} exit 2"] += result["exit"] == 2
                totals[f"{how} robot not loaded"] += not (result.get("validated") or {}).get("robot")
                totals[f"{how} errors"] += sum(f["severity"] == "error" for f in result.get("findings", []))
    print(", ".join(f"{k}: {v}" for k, v in sorted(totals.items())))


if __name__ == "__main__":
    given = [Path(a).resolve() for a in sys.argv[1:]]
    main(given or sorted(p for p in SHARED.glob("realworld*") if p.is_dir()))
