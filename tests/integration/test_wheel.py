"""The wheel as a user gets it: templates inside, and every command working without test extras.

`installed` builds the wheel and installs it, dependencies resolved by pip from the configured
index, into a venv of its own: a module the library imports at run time but pyproject.toml lists
only as an extra fails here with ModuleNotFoundError. The venv is cached under .venv/ keyed on
the wheel's exact runtime dependency list and Python version, so it is rebuilt from scratch whenever the
dependencies change (and on a fresh machine); a cached one is re-checked with `pip check`.
"""

from __future__ import annotations

import hashlib
import json
import os
import shutil
import subprocess
import sys
import zipfile
from dataclasses import dataclass
from pathlib import Path

import pytest

from tests.conftest import MARM_URDF, ROOT

MARM_SPEC = ROOT / "fixtures" / "marm" / "marm_setup.yaml"
# Test-only distributions: none may be importable in the user's venv.
TEST_ONLY = ("pytest", "hypothesis", "yourdfpy", "pinocchio", "scipy")

# One worker runs the module (`--dist loadgroup`): the wheel is built and installed once, and no
# two workers' session fixtures pip-install into the cached venv at once (a race that left it
# without its bin/marm-setup).
pytestmark = [pytest.mark.wheel, pytest.mark.xdist_group("wheel")]


@pytest.fixture(scope="session")
def wheel(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("wheel")
    cmd = [
        sys.executable,
        "-m",
        "pip",
        "wheel",
        "--quiet",
        "--no-deps",
        "--no-build-isolation",
        "-w",
        str(out),
    ]
    _run([*cmd, str(ROOT)])
    return next(out.glob("marm_setup-*.whl"))


@dataclass(frozen=True)
class Installed:
    """A venv holding the wheel and its runtime dependencies only; `workdir` is outside the checkout."""

    python: Path
    script: Path
    workdir: Path

    def run(self, *args: str | Path, ok: int = 0) -> subprocess.CompletedProcess[str]:
        """Run `marm-setup args` in `workdir`; fail with its output unless it exits `ok`."""
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
        out = subprocess.run(
            [str(self.script), *map(str, args)], cwd=self.workdir, env=env, capture_output=True, text=True
        )
        assert out.returncode == ok, f"exit {out.returncode}\n{out.stdout}\n{out.stderr}"
        assert "Traceback" not in out.stderr, out.stderr
        return out


@pytest.fixture(scope="session")
def installed(wheel, tmp_path_factory) -> Installed:
    venv = _venv_for(wheel, tmp_path_factory)
    python = venv / "bin" / "python"
    pip = [sys.executable, "-m", "pip", "--python", str(python)]
    if python.exists():  # cached: same dependencies; replace marm-setup, then check they still hold
        _run([*pip, "install", "--quiet", "--force-reinstall", "--no-deps", str(wheel)])
        _run([*pip, "check"])
    else:
        shutil.rmtree(venv, ignore_errors=True)
        _run([sys.executable, "-m", "venv", "--without-pip", str(venv)])
        _run([*pip, "install", "--quiet", str(wheel)])
    return Installed(python, venv / "bin" / "marm-setup", tmp_path_factory.mktemp("user"))


def _venv_for(wheel: Path, tmp_path_factory) -> Path:
    """The venv folder for this wheel's dependency list: under .venv/ when it exists, else per run."""
    meta = next(n for n in zipfile.ZipFile(wheel).namelist() if n.endswith(".dist-info/METADATA"))
    requires = sorted(
        line
        for line in zipfile.ZipFile(wheel).read(meta).decode().splitlines()
        if line.startswith("Requires-Dist:") and "extra ==" not in line  # runtime requirements only
    )
    key = hashlib.sha256("\n".join([sys.version, *requires]).encode()).hexdigest()[:16]
    cache = ROOT / ".venv"
    if not cache.is_dir():
        return tmp_path_factory.mktemp("venv") / key
    for stale in cache.glob("wheel-test-*"):
        if stale.name != f"wheel-test-{key}":
            shutil.rmtree(stale, ignore_errors=True)
    return cache / f"wheel-test-{key}"


def _run(cmd: list[str]) -> None:
    out = subprocess.run(cmd, capture_output=True, text=True)
    assert out.returncode == 0, f"{' '.join(cmd)}\n{out.stdout}\n{out.stderr}"


def test_wheel_contains_every_template(wheel):
    names = set(zipfile.ZipFile(wheel).namelist())
    templates = sorted(p.relative_to(ROOT).as_posix() for p in (ROOT / "templates").rglob("*") if p.is_file())
    assert templates, "no templates in the checkout"
    missing = [t for t in templates if f"marm_setup/{t}" not in names]
    assert not missing


def test_installed_package_is_the_wheel_without_test_extras(installed):
    code = (
        "import importlib.util, marm_setup.templating as t; print(t.templates_dir()); "
        f"print(sorted(m for m in {TEST_ONLY!r} if importlib.util.find_spec(m)))"
    )
    out = subprocess.run(
        [str(installed.python), "-c", code], cwd=installed.workdir, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    templates, importable = out.stdout.splitlines()
    site = Path(templates).parent.parent
    assert site.name == "site-packages" and Path(templates) == site / "marm_setup" / "templates"
    assert importable == "[]"


@pytest.fixture(scope="session")
def ros1_package(installed) -> Path:
    """`init` on the marm fixture with its SPEC (the demo's package), in the user's venv."""
    out = installed.workdir / "marm_moveit_config"
    installed.run(
        "init", MARM_URDF, "--out", out, "--setup", MARM_SPEC, "--target", "ros1", "--trials", "300"
    )
    assert (out / "config" / "marm.srdf").is_file()
    return out


def test_inspect(installed):
    assert "joint1" in installed.run("inspect", MARM_URDF).stdout


def test_init_ros2_infers_a_setup(installed):
    out = installed.workdir / "inferred"
    installed.run("init", MARM_URDF, "--out", out, "--trials", "200")
    assert (out / "config" / "moveit.yaml").is_file()


def test_collisions(installed):
    srdf = installed.workdir / "matrix.srdf"
    installed.run("collisions", MARM_URDF, "--trials", "200", "--output", srdf)
    assert "disable_collisions" in srdf.read_text(encoding="utf-8")


def test_render(installed, ros1_package):
    *files, summary = installed.run("render", ros1_package).stdout.splitlines()
    assert files and all(line.startswith("unchanged ") for line in files)
    assert summary.startswith("0 create,") and summary.endswith(" 0 update, 0 conflict")


def test_validate_with_planning(installed, ros1_package):
    report = json.loads(installed.run("validate", ros1_package, "--format", "json").stdout)
    assert report["errors"] == 0 and report["validated"]["planned_pairs"] > 0


def test_report(installed, ros1_package):
    """The page needs MeshCat's viewer script from the user's site-packages (read at run time)."""
    page = installed.workdir / "report.html"
    out = installed.run("report", ros1_package, "-o", page, "--trials", "300")
    assert out.stdout.startswith(f"wrote {page}") and "MeshCat" in page.read_text(encoding="utf-8")


def test_mesh_decimation(installed):
    """Decimation needs fast-simplification (trimesh's quadric decimation), never imported by name."""
    code = (
        "import trimesh; from marm_setup.report.geometry import _decimated; "
        "print(len(_decimated(trimesh.creation.icosphere(subdivisions=4), 1000).faces) <= 1000)"
    )
    out = subprocess.run([str(installed.python), "-c", code], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"


def test_plan(installed, ros1_package):
    trajectory = installed.workdir / "home_to_forward.yaml"
    installed.run(
        "plan", ros1_package, "--group", "arm", "--from", "home", "--to", "forward", "--output", trajectory
    )
    assert "time_from_start" in trajectory.read_text(encoding="utf-8")


def test_collada_meshes_load(installed, tmp_path):
    """A .dae needs pycollada (trimesh's Collada loader): a runtime dependency, though never imported by name."""
    code = (
        "import trimesh, sys; from marm_setup.robot.meshes import load_mesh; "
        "open(sys.argv[1], 'wb').write(trimesh.exchange.dae.export_collada(trimesh.creation.box())); "
        "print(len(load_mesh(sys.argv[1]).faces))"
    )
    dae = tmp_path / "box.dae"
    out = subprocess.run([str(installed.python), "-c", code, str(dae)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "12"
