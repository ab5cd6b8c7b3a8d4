"""`marm-setup --help` stays light: no coal, trimesh, yourdfpy or scipy at import."""

from __future__ import annotations

import subprocess
import sys

from typer.testing import CliRunner

from marm_setup import __version__
from marm_setup.cli import app

HEAVY = ("coal", "trimesh", "yourdfpy", "scipy")


def test_help_imports_nothing_heavy():
    code = (
        "import sys\n"
        "from marm_setup.cli import app\n"
        "from typer.testing import CliRunner\n"
        "CliRunner().invoke(app, ['--help'])\n"
        f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_every_command_help_imports_nothing_heavy():
    code = (
        "import sys\n"
        "from marm_setup.cli import app\n"
        "from typer.testing import CliRunner\n"
        "for cmd in ['init', 'collisions', 'render', 'validate', 'plan', 'inspect']:\n"
        "    CliRunner().invoke(app, [cmd, '--help'])\n"
        f"print(','.join(m for m in {HEAVY!r} if m in sys.modules))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""


def test_version_and_no_args():
    runner = CliRunner()
    assert runner.invoke(app, ["--version"]).stdout.strip() == f"marm-setup {__version__}"
    result = runner.invoke(app, [])
    assert "Usage" in result.output
