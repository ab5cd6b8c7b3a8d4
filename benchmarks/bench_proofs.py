"""Benchmark: what the proofs cost (issue 34), side by side in one run, as whole processes.

Run: `.venv/bin/python benchmarks/bench_proofs.py [--trials 10000] [--runs 3] [--robot panda|pr2|xarm7 ...]`.

CPU seconds (user + system, the process and its workers, from getrusage) of
`marm-setup collisions URDF --trials N --format json`, per robot:
- default (`--prove on`) against `--prove off` (sampling alone), both without the proof cache;
- default against the pin+coal reference of the Setup Assistant's algorithm
  (`setup_assistant_reference.py`; panda and xarm7: it takes no continuous joints);
- a first run into an empty proof cache against a re-run with it (MARM_SETUP_CACHE), and
  whether their outputs are the same bytes;
- the panda only: a variant (the arm on a cart, a box under panda_link0) with the cache the
  panda's first run left against the variant with an empty cache, and whether their outputs
  are the same bytes (the proofs the screen finished are taken across runs).
With `--against-1m JSON` (the PR2's `collisions --trials 1000000 --prove off --format json`,
about 13 min of CPU), also the PR2's default run at seeds 0, 1 and 2 against it: the Never pairs
the 1M-state run sees in contact (misses) and the proved pairs it sees (unsound proofs).
The panda and the PR2 come from ../shared/realworld; the xarm7 from example-robot-data
(`pip install example-robot-data`; skipped when absent). Medians of --runs (the PR2: one run).
"""

from __future__ import annotations

import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
REALWORLD = ROOT.parent / "shared" / "realworld" / "ros1"
ERD = Path(sys.prefix) / "lib" / f"python{sys.version_info[0]}.{sys.version_info[1]}" / "site-packages"
ERD = ERD / "cmeel.prefix" / "share"
ROBOTS = {  # name -> (URDF, package path)
    "panda": (REALWORLD / "panda_description/urdf/panda_arm_hand.urdf.xacro", REALWORLD),
    "pr2": (REALWORLD / "pr2_description/urdf/robot.xml", REALWORLD),
    "xarm7": (ERD / "example-robot-data/robots/xarm_description/urdf/xarm7.urdf", ERD),
}
REFERENCE = Path(__file__).resolve().parent / "setup_assistant_reference.py"


def cpu(argv: list[str], env: dict[str, str]) -> tuple[float, bytes]:
    """CPU seconds [s] of the process `argv` and its children, and its stdout."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    done = subprocess.run(argv, check=True, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime, done.stdout


def plain_urdf(path: Path, packages: Path, folder: Path) -> Path:
    """The robot as a plain URDF file (xacro expanded) for the reference."""
    if path.suffix != ".xacro":
        return path
    from marm_setup.robot.ros_packages import find_packages
    from marm_setup.robot.xacro_expand import run_xacro

    out = folder / f"{path.stem}.urdf"
    found = find_packages([packages], near=path)
    text = run_xacro(path, {}, found, shown=str(path)).xml
    text = re.sub(r"package://([^/]+)/", lambda m: f"file://{found[m.group(1)]}/", text)  # as we resolve them
    out.write_text(text, encoding="utf-8")
    return out


def bench(name: str, args, folder: Path) -> None:
    urdf, packages = ROBOTS[name]
    command = [sys.executable, "-m", "marm_setup", "collisions", str(urdf), "--package-path", str(packages)]
    command += ["--trials", str(args.trials), "--format", "json"]
    off_env = dict(os.environ, MARM_SETUP_CACHE="off")
    runs = 1 if name == "pr2" else args.runs
    reference = None
    if name != "pr2":
        plain = plain_urdf(urdf, packages, folder)
        reference = [sys.executable, str(REFERENCE), str(plain), "--package-dir", str(packages)]
        reference += ["--trials", str(args.trials)]
    rows: dict[str, list[float]] = {"on": [], "off": [], "reference": [], "first": [], "cached": []}
    same = True
    for run in range(runs):
        rows["on"].append(cpu([*command, "--prove", "on"], off_env)[0])
        rows["off"].append(cpu([*command, "--prove", "off"], off_env)[0])
        if reference is not None:
            rows["reference"].append(cpu(reference, off_env)[0])
        cache_env = dict(os.environ, MARM_SETUP_CACHE=str(folder / f"cache-{name}-{run}"))
        first, first_out = cpu(command, cache_env)
        cached, cached_out = cpu(command, cache_env)
        rows["first"].append(first)
        rows["cached"].append(cached)
        same = same and first_out == cached_out
    med = {key: statistics.median(values) for key, values in rows.items() if values}
    print(f"{name}: {args.trials} trials, CPU seconds, median of {runs}")
    print(
        f"  default {med['on']:6.2f}   --prove off {med['off']:6.2f}   ratio {med['on'] / med['off']:4.2f}"
        + (
            f"   | pin+coal reference {med['reference']:6.2f}   default/reference {med['on'] / med['reference']:4.2f}"
            f"   off/reference {med['off'] / med['reference']:4.2f}"
            if "reference" in med
            else ""
        )
    )
    print(
        f"  first run {med['first']:6.2f}   cached re-run {med['cached']:6.2f}"
        f"   ratio {med['cached'] / med['first']:4.2f}   same output bytes: {same}"
    )
    if name == "panda":
        variant(command, runs, folder)


CART = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="panda">
  <xacro:include filename="{urdf}"/>
  <link name="cart"><collision><origin xyz="0 0 -0.25"/><geometry><box size="0.6 0.5 0.5"/></geometry></collision></link>
  <joint name="cart_joint" type="fixed"><parent link="cart"/><child link="panda_link0"/></joint>
</robot>
"""


def variant(command: list[str], runs: int, folder: Path) -> None:
    """The panda on a cart with the panda's proof cache (copied fresh each run) against an empty one."""
    import shutil

    cart = folder / "panda_on_a_cart.urdf.xacro"
    cart.write_text(CART.format(urdf=command[4]), encoding="utf-8")
    argv = [*command[:4], str(cart), *command[5:]]
    rows: dict[str, list[float]] = {"empty": [], "taken": []}
    same = True
    for run in range(runs):
        panda_cache = folder / f"cache-variant-{run}"
        cpu(command, dict(os.environ, MARM_SETUP_CACHE=str(panda_cache)))
        (panda_cache / "matrices.sqlite").unlink(missing_ok=True)
        empty, empty_out = cpu(argv, dict(os.environ, MARM_SETUP_CACHE=str(folder / f"cache-empty-{run}")))
        taken, taken_out = cpu(argv, dict(os.environ, MARM_SETUP_CACHE=str(panda_cache)))
        shutil.rmtree(panda_cache)
        rows["empty"].append(empty)
        rows["taken"].append(taken)
        same = same and empty_out == taken_out
    med = {key: statistics.median(values) for key, values in rows.items()}
    print(
        f"  variant on a cart: empty cache {med['empty']:6.2f}   the panda's cache {med['taken']:6.2f}"
        f"   ratio {med['taken'] / med['empty']:4.2f}   same output bytes: {same}"
    )


def against_1m(path: Path, trials: int) -> None:
    """The PR2's default runs at seeds 0, 1, 2 against a 1M-state run's pairs seen in contact."""
    import json

    seen = {(p["link1"], p["link2"]) for p in json.loads(path.read_text())["pairs"] if p["seen_colliding"]}
    urdf, packages = ROBOTS["pr2"]
    env = dict(os.environ, MARM_SETUP_CACHE="off")
    for seed in (0, 1, 2):
        command = [
            sys.executable,
            "-m",
            "marm_setup",
            "collisions",
            str(urdf),
            "--package-path",
            str(packages),
        ]
        command += ["--trials", str(trials), "--seed", str(seed), "--format", "json"]
        pairs = json.loads(cpu(command, env)[1])["pairs"]
        never = {(p["link1"], p["link2"]) for p in pairs if p["reason"] == "Never"}
        proved = {(p["link1"], p["link2"]) for p in pairs if p["proof"] == "proved"}
        print(
            f"pr2 seed {seed}: {len(never)} Never, {len(proved)} proved; Never pairs the 1M-state run "
            f"sees in contact: {len(never & seen)} {sorted(never & seen)}; proved pairs it sees: {len(proved & seen)}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=10000)
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--robot", choices=sorted(ROBOTS), action="append")
    parser.add_argument("--against-1m", type=Path, metavar="JSON", help="the PR2's 1M-state run (see above)")
    args = parser.parse_args()
    # bytecode as an installed package has it (an editable install in a PYTHONDONTWRITEBYTECODE
    # shell would compile marm_setup in every process measured)
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(ROOT / "marm_setup")], check=True)
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs")
    with tempfile.TemporaryDirectory(prefix="bench-proofs-") as tmp:
        for name in args.robot or ["panda", "xarm7", "pr2"]:
            if not ROBOTS[name][0].exists():
                print(f"{name}: {ROBOTS[name][0]} not present, skipped")
                continue
            bench(name, args, Path(tmp))
    if args.against_1m is not None:
        against_1m(args.against_1m, args.trials)


if __name__ == "__main__":
    main()
