"""`marm-setup --help` stays light: no coal, trimesh, yourdfpy or scipy at import."""

from __future__ import annotations

import os
import subprocess
import sys

from typer.testing import CliRunner

from marm_setup import __version__
from marm_setup.cli.app import app
from marm_setup.cli.commands import COMMAND_SPECS
from tests.conftest import MARM_URDF

HEAVY = ("coal", "trimesh", "yourdfpy", "scipy")


def _heavy_modules_after(*argvs: list[str]) -> str:
    """Run each `marm-setup ARGV` in one fresh interpreter; the heavy modules it imported."""
    code = (
        "import sys\n"
        "from marm_setup.cli.app import app\n"
        "from typer.testing import CliRunner\n"
        f"for argv in {list(argvs)!r}:\n"
        "    CliRunner().invoke(app, argv)\n"
        f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return out.stdout.strip()


def test_help_imports_nothing_heavy():
    assert _heavy_modules_after(["--help"]) == ""


def test_every_command_help_imports_nothing_heavy():
    assert _heavy_modules_after(*([name, "--help"] for name, _, _ in COMMAND_SPECS)) == ""


def test_collisions_on_stl_meshes_loads_no_trimesh_scipy_or_renderer():
    code = (
        "import sys\n"
        "from marm_setup.cli.app import app\n"
        "from typer.testing import CliRunner\n"
        f"r = CliRunner().invoke(app, ['collisions', {str(MARM_URDF)!r}, '--trials', '200', '--jobs', '1'])\n"
        "assert r.exit_code == 0, r.output\n"
        "names = ('trimesh', 'scipy', 'jinja2', 'marm_setup.render.writer', 'marm_setup.templating')\n"
        "print(','.join(m for m in names if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_version_and_no_args():
    runner = CliRunner()
    assert runner.invoke(app, ["--version"]).stdout.strip() == f"marm-setup {__version__}"
    result = runner.invoke(app, [])
    assert "Usage" in result.output


def test_the_console_script_runs_numpy_on_one_blas_thread_unless_the_user_chose():
    code = (
        "import sys\n"
        "sys.argv = ['marm-setup', '--version']\n"
        "from marm_setup.cli.app import main\n"
        "try:\n"
        "    main()\n"
        "except SystemExit:\n"
        "    pass\n"
        "import os\n"
        "print(os.environ.get('OPENBLAS_NUM_THREADS'))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    ours = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    assert ours.stdout.split()[-1] == "1"
    chosen = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env={**env, "OPENBLAS_NUM_THREADS": "4"},
    )
    assert chosen.stdout.split()[-1] == "4"
