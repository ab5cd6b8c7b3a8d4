"""Every ROS 2 package the test suite generates, made once per session (the `ros2_packages`
fixture): the marm, every description in ../shared (skipped when absent), every synthetic
fixture, the vendor-style descriptions with their own ros2_control (tests/vendor_descriptions.py)
and the ports of the shared config packages; each for Humble and Jazzy.

`init` runs through the CLI for Humble (as a user types it); the Jazzy package is the same
setup rendered for Jazzy (init's distro changes only ros_distro), in a sibling folder at the
same depth so the setup's relative paths hold. Ports run through the CLI for each distro.

Under pytest-xdist the workers share the packages: each is made by the first worker that asks
for it (a file lock per package), the others read what it recorded. A worker's vendor
descriptions and its copies to change are its own.
"""

from __future__ import annotations

import dataclasses
import json
import shutil
from dataclasses import dataclass
from pathlib import Path

from filelock import FileLock
from typer.testing import CliRunner

from marm_setup.cli.app import app
from tests.conftest import FIXTURES, realworld, realworld2
from tests.vendor_descriptions import NAMES as VENDOR_STYLES
from tests.vendor_descriptions import write_vendor_descriptions

TRIALS = "300"
# name: (URDF under ../shared, package path roots, xacro args)
SHARED = {
    "panda_ros1": ("realworld/ros1/panda_description/urdf/panda_arm_hand.urdf.xacro", ["realworld/ros1"], []),
    "panda_ros2": ("realworld/ros2/panda_description/urdf/panda.urdf", ["realworld/ros2"], []),
    "pr2": ("realworld/ros1/pr2_description/urdf/robot.xml", ["realworld/ros1"], []),
    "ur5e": ("realworld2/universal_robot/ur_description/urdf/ur5e.xacro", ["realworld2/universal_robot"], []),
    "fanuc_cr7ia": ("realworld2/fanuc/fanuc_cr7ia_support/urdf/cr7ia.xacro", ["realworld2/fanuc"], []),
    "motoman_sda10f": (
        "realworld2/motoman/motoman_sda10f_support/urdf/sda10f.xacro",
        ["realworld2/motoman"],
        [],
    ),
    "kinova_j2n6s300": (
        "realworld2/kinova-ros/kinova_description/urdf/j2n6s300_standalone.xacro",
        ["realworld2/kinova-ros"],
        [],
    ),
    "dual_panda": (
        "realworld2/moveit_resources_master/panda_description/urdf/dual_panda.urdf.xacro",
        ["realworld2/moveit_resources_master"],
        [],
    ),
    "kinova_gen3_robotiq": (
        "realworld2/ros2_kortex/kortex_description/robots/gen3.xacro",
        ["realworld2/ros2_kortex", "realworld2/ros2_robotiq_gripper"],
        ["gripper:=robotiq_2f_85", "dof:=6"],
    ),
}
SYNTHETIC = sorted(p.stem for p in (FIXTURES / "synthetic").glob("*.urdf"))
# config packages ported to ros2: (package under ../shared, package path roots)
PORTS = {
    "panda_moveit1": ("realworld/ros1/panda_moveit_config", ["realworld/ros1"]),
    "panda_moveit2": ("realworld/ros2/panda_moveit_config", ["realworld/ros2"]),
    "ur5e": ("realworld2/universal_robot/ur5e_moveit_config", ["realworld2/universal_robot"]),
    "fanuc_cr7ia": ("realworld2/fanuc/moveit_cfgs/fanuc_cr7ia_moveit_config", ["realworld2/fanuc"]),
    "motoman_sda10f": ("realworld2/motoman/motoman_sda10f_moveit_config", ["realworld2/motoman"]),
    "kinova_j2n6s300": (
        "realworld2/kinova-ros/kinova_moveit/robot_configs/j2n6s300_moveit_config",
        ["realworld2/kinova-ros"],
    ),
    "dual_panda": (
        "realworld2/moveit_resources_master/dual_panda_moveit_config",
        ["realworld2/moveit_resources_master"],
    ),
    "kinova_gen3_robotiq": (
        "realworld2/ros2_kortex/kortex_moveit_config/kinova_gen3_6dof_robotiq_2f_85_moveit_config",
        ["realworld2/ros2_kortex", "realworld2/ros2_robotiq_gripper"],
    ),
}
# Every generated package's key: marm, shared:<name>, synthetic:<name>, vendor:<style>, port:<name>.
KEYS = (
    "marm",
    *(f"shared:{k}" for k in SHARED),
    *(f"synthetic:{k}" for k in SYNTHETIC),
    *(f"vendor:{k}" for k in VENDOR_STYLES),
    *(f"port:{k}" for k in PORTS),
)
runner = CliRunner()


def shared_path(rel: str) -> Path:
    """A path under ../shared/realworld or realworld2 (skips the test when absent)."""
    kind, _, rest = rel.partition("/")
    return realworld(*rest.split("/")) if kind == "realworld" else realworld2(*rest.split("/"))


@dataclass(frozen=True)
class Generated:
    """One generated package: where it is, the description folders it needs, the CLI's output."""

    key: str
    distro: str
    out: Path
    roots: tuple[Path, ...]
    output: str
    exit_code: int


class GeneratedPackages:
    """Packages by (key, distro), each generated on first use under `base` (shared by the
    pytest-xdist workers; `worker` names this one's own folders there)."""

    def __init__(self, base: Path, worker: str = "") -> None:
        self.base = base
        self.suffix = f"-{worker}" if worker else ""
        self._made: dict[tuple[str, str], Generated] = {}
        self._vendor: dict | None = None

    def get(self, key: str, distro: str) -> Generated:
        if (key, distro) not in self._made:
            self._made[(key, distro)] = self._shared(key, distro)
        return self._made[(key, distro)]

    def _shared(self, key: str, distro: str) -> Generated:
        """The package made once for every worker: made here unless another worker recorded it."""
        folder = self.base / distro / key.replace(":", "_")
        record = folder / "generated.json"
        folder.parent.mkdir(parents=True, exist_ok=True)
        with FileLock(f"{folder}.lock"):
            if record.is_file():
                data = json.loads(record.read_text(encoding="utf-8"))
                return Generated(
                    key,
                    distro,
                    Path(data["out"]),
                    tuple(map(Path, data["roots"])),
                    data["output"],
                    data["exit_code"],
                )
            shutil.rmtree(folder, ignore_errors=True)  # what a worker that failed here left
            made = self._make(key, distro)
            data = {"out": str(made.out), "roots": list(map(str, made.roots)), "output": made.output}
            record.write_text(json.dumps({**data, "exit_code": made.exit_code}), encoding="utf-8")
            return made

    def vendor(self, style: str):
        if self._vendor is None:
            self._vendor = write_vendor_descriptions(self.base / f"vendor{self.suffix}")
        return self._vendor[style]

    def _make(self, key: str, distro: str) -> Generated:
        kind, _, name = key.partition(":")
        out = self.base / distro / key.replace(":", "_") / "pkg"
        if kind == "port":
            return self._port(key, name, distro, out)
        if distro != "humble":
            return self._rerender(self.get(key, "humble"), distro, out)
        urdf, roots, args, extra = self._init_source(kind, name)
        paths = [a for root in roots for a in ("--package-path", str(root))]
        xacro = [a for x in args for a in ("--xacro-arg", x)]
        argv = ["init", str(urdf), "--out", str(out), "--trials", TRIALS, "--jobs", "1", "--target", "ros2"]
        argv += ["--ros-distro", distro]
        made = runner.invoke(app, [*argv, *paths, *xacro, *extra])
        assert made.exit_code == 0, made.output
        return Generated(key, distro, out, tuple(roots), made.output, made.exit_code)

    def _init_source(self, kind: str, name: str) -> tuple[Path, list[Path], list[str], list[str]]:
        """(URDF, package roots, xacro args, other init options) of an init key."""
        if kind == "marm":
            return (
                FIXTURES / "marm" / "urdf" / "marm.urdf.xacro",
                [FIXTURES / "marm"],
                [],
                [
                    "--setup",
                    str(FIXTURES / "marm" / "marm_setup.yaml"),
                ],
            )
        if kind == "shared":
            urdf, roots, args = SHARED[name]
            return shared_path(urdf), [shared_path(r) for r in roots], list(args), []
        if kind == "synthetic":
            return FIXTURES / "synthetic" / f"{name}.urdf", [], [], []
        vendor = self.vendor(name)
        return vendor.urdf, [vendor.root], list(vendor.xacro_args), []

    def _rerender(self, humble: Generated, distro: str, out: Path) -> Generated:
        from marm_setup.flows import write_package
        from marm_setup.flows.render import load_package_setup

        model, robot = load_package_setup(humble.out)
        write_package(dataclasses.replace(model, ros_distro=distro), robot, out, force=False)
        return dataclasses.replace(humble, distro=distro, out=out)

    def _port(self, key: str, name: str, distro: str, out: Path) -> Generated:
        rel, roots = PORTS[name]
        source, paths = shared_path(rel), [shared_path(r) for r in roots]
        argv = ["init", "--from-package", str(source), "--out", str(out), "--target", "ros2"]
        argv += ["--ros-distro", distro, "--no-plan", "--format", "json"]
        made = runner.invoke(app, [*argv, *(a for p in paths for a in ("--package-path", str(p)))])
        assert made.exit_code in (0, 1), made.output
        return Generated(key, distro, out, tuple(paths), made.stdout, made.exit_code)

    def copy(self, key: str, distro: str, name: str) -> Path:
        """A copy of a generated package to change, at the same depth (its setup's relative paths hold)."""
        out = self.base / f"copies{self.suffix}" / f"{name}-{distro}" / "pkg"
        shutil.rmtree(out.parent, ignore_errors=True)
        shutil.copytree(self.get(key, distro).out, out, symlinks=True)
        return out
